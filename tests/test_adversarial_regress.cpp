// Regression inputs found by fuzzing (tests/regress/): one test per input,
// named after what it exposed. A test whose bug is not fixed yet is skipped
// with GTEST_SKIP naming the bug; remove the skip with the fix.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>
#include <regex>
#include <string>
#include <utility>
#include <vector>

#include "deltamesh/adapt.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/pipeline.hpp"
#include "deltamesh/refine.hpp"
#include "deltamesh/switches.hpp"
#include "deltamesh/triangle_io.hpp"
#include "deltamesh/triangulate.hpp"
#include "deltamesh/validate.hpp"
#include "test_adversarial_util.hpp"
#include "mesh/editor.hpp"

namespace dm = deltamesh;

namespace {

std::string regress(const std::string& name) {
  return (std::filesystem::path(DELTAMESH_SOURCE_DIR) / "tests" / "regress" / name).string();
}

// Input vertices that are in no triangle, although they are the first copy
// of their point, and later copies that are in one.
std::vector<std::string> copies_misused(const dm::Mesh& m, const dm::Pslg& g) {
  std::map<std::pair<double, double>, dm::VertexId> first;
  std::vector<char> used(m.num_vertices(), 0);
  for (dm::TriId t = 0; t < m.num_triangle_slots(); ++t)
    if (m.is_real(t))
      for (const dm::VertexId v : m.triangle(t)) used[v] = 1;
  std::vector<std::string> bad;
  for (std::size_t i = 0; i < g.points.size(); ++i) {
    const auto [it, is_first] = first.emplace(std::make_pair(g.points[i].x, g.points[i].y), i);
    if (is_first && !used[i]) bad.push_back("first copy " + std::to_string(i) + " unused");
    if (!is_first && used[i]) bad.push_back("copy " + std::to_string(i) + " of " + std::to_string(it->second) + " used");
  }
  return bad;
}

}  // namespace

TEST(Regress, DuplicatePointsKeepTheFirstCopyWithSegments) {
  const dm::Pslg g = dm::read_node(regress("duplicates_first_copy_not_kept_without_p.node"));
  dm::TriangulateOptions opt;
  opt.use_segments = true;
  opt.domain.keep_convex_hull = true;
  const dm::Mesh m = dm::triangulate(g, opt);
  EXPECT_TRUE(dm::check(m, {.convex_hull = false}).ok());
  EXPECT_EQ(copies_misused(m, g), std::vector<std::string>{});
}

TEST(Regress, DuplicatePointsKeepTheFirstCopyWithoutSegments) {
  // Bug: triangulate() without segments (the CLI without -p) keeps whichever
  // copy of equal points the Delaunay step inserted first (its BRIO/Hilbert
  // order), not the first in input order as the CDT does (cdt.cpp
  // relabels) and delaunay.hpp's DelaunayStats::duplicates describes. The
  // output (and -j) then carries a later copy's id, marker and attributes.
  const dm::Pslg g = dm::read_node(regress("duplicates_first_copy_not_kept_without_p.node"));
  dm::TriangulateOptions opt;
  opt.use_segments = false;
  const dm::Mesh m = dm::triangulate(g, opt);
  EXPECT_TRUE(dm::check(m).ok());
  EXPECT_EQ(copies_misused(m, g), std::vector<std::string>{});
}

TEST(Regress, RefineWithoutSmallAngleProtectionAtTinyScaleStaysDelaunay) {
  const dm::Pslg g = dm::read_poly(regress("refine_tiny_scale_conforming_not_delaunay.poly"));
  dm::TriangulateOptions topt;
  topt.method = dm::CdtMethod::Lifting;
  topt.strict = true;
  topt.domain.fill = dm::FillRule::EvenOdd;
  topt.domain.keep_convex_hull = true;
  topt.domain.ignore_holes = true;
  topt.domain.regional_attributes = true;
  topt.domain.regional_area_bounds = true;
  dm::Mesh m = dm::triangulate(g, topt);
  ASSERT_TRUE(dm::check(m, {.convex_hull = false}).ok());
  dm::RefineOptions ro;
  ro.min_angle_deg = 20;
  ro.steiner = dm::SteinerRule::Circumcenter;
  ro.encroachment = dm::EncroachmentRule::DiametralLens;
  ro.conforming_delaunay = true;
  ro.small_angle_protection = false;
  ro.max_steiner = 3000;
  ro.time_limit_seconds = 10;
  const dm::RefineStats st = dm::refine(m, ro);
  EXPECT_FALSE(st.time_exhausted) << st.summary();
  const dm::CheckReport rep = dm::check(m, {.convex_hull = false});
  EXPECT_TRUE(rep.ok()) << rep.summary();
}

TEST(Regress, SplitCavityTakesTheFarTriangleOnlyByExactIncircle) {
  // Exposed: a segment split's cavity took both triangles of the segment
  // unconditionally. The rounded split point lay off the segment's line and
  // outside the far triangle's circumcircle, which left edges not locally
  // Delaunay (edges 11-317 and 11-320 at budgets 320 and 330, with
  // small-angle protection off, off-centres or circumcentres alike).
  const dm::Pslg g = dm::read_poly(regress("refine_no_small_angle_protection_not_delaunay.poly"));
  dm::TriangulateOptions topt;
  topt.domain.keep_convex_hull = true;
  const dm::Mesh base = dm::triangulate(g, topt);
  for (const std::size_t budget : {std::size_t{313}, std::size_t{320}, std::size_t{330}, std::size_t{1000}})
    for (const dm::SteinerRule rule : {dm::SteinerRule::Offcenter, dm::SteinerRule::Circumcenter}) {
      SCOPED_TRACE(budget);
      dm::Mesh m = base;
      dm::RefineOptions ro;
      ro.min_angle_deg = 20;
      ro.steiner = rule;
      ro.small_angle_protection = false;
      ro.max_steiner = budget;
      const dm::RefineStats st = dm::refine(m, ro);
      const dm::CheckReport rep = dm::check(m, {.convex_hull = false});
      EXPECT_TRUE(rep.ok()) << rep.summary() << "\n" << st.summary();
    }
}

TEST(Regress, SplitCavityNearlyCoincidentVerticesAreaBoundStaysDelaunay) {
  // Exposed: the same far-triangle shortcut with a vertex within ulps of a
  // segment and a hull edge within ulps of it: refining for an area bound
  // only ended with edge 4-72 not locally Delaunay (4-60 at budget 56).
  const dm::Pslg g = dm::read_poly(regress("refine_area_bound_near_coincident_not_delaunay.poly"));
  dm::TriangulateOptions topt;
  topt.method = dm::CdtMethod::Lawson;
  topt.domain.keep_convex_hull = true;
  const dm::Mesh base = dm::triangulate(g, topt);
  ASSERT_TRUE(dm::check(base, {.convex_hull = false}).ok());
  for (const std::size_t budget : {std::size_t{56}, std::size_t{3000}}) {
    SCOPED_TRACE(budget);
    dm::Mesh m = base;
    dm::RefineOptions ro;
    ro.min_angle_deg = 0;
    ro.max_area = 1.0 / 64;  // the bounding box [0.5, 1.5]^2, / 64
    ro.steiner = dm::SteinerRule::Offcenter;
    ro.encroachment = dm::EncroachmentRule::DiametralCircle;
    ro.max_steiner = budget;
    const dm::RefineStats st = dm::refine(m, ro);
    const dm::CheckReport rep = dm::check(m, {.convex_hull = false});
    EXPECT_TRUE(rep.ok()) << rep.summary();
    EXPECT_TRUE(!st.complete || st.too_large == 0) << st.summary();
  }
}

TEST(Regress, RefineReportsTrianglesLeftTooLargeAtPrecisionAsIncomplete) {
  // Exposed by the same input: no split of the segments within ulps of each
  // other fits, so 4 triangles stay above the area bound, and refinement
  // said "complete".
  const dm::Pslg g = dm::read_poly(regress("refine_area_bound_near_coincident_not_delaunay.poly"));
  dm::TriangulateOptions topt;
  topt.method = dm::CdtMethod::Lawson;
  topt.domain.keep_convex_hull = true;
  dm::Mesh m = dm::triangulate(g, topt);
  dm::RefineOptions ro;
  ro.min_angle_deg = 0;
  ro.max_area = 1.0 / 64;
  ro.encroachment = dm::EncroachmentRule::DiametralCircle;
  const dm::RefineStats st = dm::refine(m, ro);
  EXPECT_TRUE(dm::check(m, {.convex_hull = false}).ok());
  EXPECT_FALSE(st.budget_exhausted || st.time_exhausted) << st.summary();
  EXPECT_GT(st.too_large_precision, 0u) << st.summary();
  EXPECT_LE(st.too_large_precision, st.too_large) << st.summary();
  EXPECT_FALSE(st.complete) << st.summary();
  EXPECT_NE(st.summary().find("at the precision of doubles"), std::string::npos) << st.summary();
}

class RegressCli : public dm::test::TempDirTest {};

TEST_F(RegressCli, TrianglesLeftTooLargeAtPrecisionReportedByStatsAndExitCode) {
  std::filesystem::copy_file(regress("refine_area_bound_near_coincident_not_delaunay.poly"), path("a.poly"));
  const dm::test::CliResult r = run("-pc --cdt=lawson -a0.015625 --encroachment=circle -V --stats=json a.poly");
  EXPECT_EQ(r.code, 3) << r.err;
  const std::regex warning("bounds not met: [1-9][0-9]* triangles above their size bound \\([1-9][0-9]* at the "
                           "precision of doubles\\)");
  EXPECT_TRUE(std::regex_search(r.err, warning)) << r.err;
  EXPECT_NE(r.out.find("\"complete\":false,\"budget_exhausted\":false"), std::string::npos) << r.out;
  EXPECT_TRUE(std::regex_search(r.out, std::regex("\"too_large\":[1-9][0-9]*,\"too_large_precision\":[1-9]"))) << r.out;
  // -V's report goes to stderr: stdout holds the JSON alone.
  EXPECT_TRUE(std::regex_search(r.err, std::regex("\n    at the precision of doubles: [1-9]"))) << r.err;
  EXPECT_EQ(r.out.front(), '{') << r.out;
  EXPECT_TRUE(exists("a.1.ele"));
}

TEST(Regress, RefineReservesNoMoreThanTheBudgetAllows) {
  // Exposed: with a regional area bound of 9.5e-7 on a domain of area ~50
  // refine() reserved room for ~10^8 triangles up front (1.3 GB), although
  // the budget of 20 Steiner points allows 40 more triangles.
  const dm::Pslg g = dm::read_poly(regress("refine_area_bound_reserve_huge_allocation.poly"));
  dm::TriangulateOptions topt;
  topt.method = dm::CdtMethod::Lawson;
  topt.domain.fill = dm::FillRule::EvenOdd;
  topt.domain.keep_convex_hull = true;
  topt.domain.ignore_holes = true;
  topt.domain.regional_area_bounds = true;
  dm::Mesh m = dm::triangulate(g, topt);
  ASSERT_TRUE(m.has_triangle_area_bounds());
  const std::size_t before = m.num_triangle_slots();
  dm::RefineOptions ro;
  ro.encroachment = dm::EncroachmentRule::DiametralCircle;
  ro.max_steiner = 20;
  const dm::RefineStats st = dm::refine(m, ro);
  EXPECT_TRUE(st.budget_exhausted) << st.summary();
  EXPECT_TRUE(dm::check(m, {.convex_hull = false}).ok());
  EXPECT_LE(deltamesh::detail::MeshEditor(m).triangle_vertices().capacity(), 3 * (before + 2 * 20 + 64));
  EXPECT_LE(deltamesh::detail::MeshEditor(m).points().capacity(), m.num_vertices() + 64);
}

TEST(Regress, RefineBoundarySplitPointStaysInsideItsPiece) {
  // Exposed: a boundary segment's midpoint rounded outside its piece of the
  // domain and into another piece touching it within ulps (crossing
  // segments, even-odd fill): the fans at vertex 28 overlapped.
  const dm::Pslg g = dm::read_poly(regress("refine_boundary_split_point_in_neighbouring_piece.poly"));
  dm::TriangulateOptions topt;
  topt.method = dm::CdtMethod::Lawson;
  topt.domain.fill = dm::FillRule::EvenOdd;
  const dm::Mesh base = dm::triangulate(g, topt);
  ASSERT_TRUE(dm::check(base, {.convex_hull = false}).ok());
  for (const std::size_t budget : {std::size_t{5}, std::size_t{20}, std::size_t{300}, dm::kAutomaticBudget}) {
    SCOPED_TRACE(budget);
    dm::Mesh m = base;
    dm::RefineOptions ro;
    ro.min_angle_deg = 33;
    ro.max_area = 5.0625;
    ro.encroachment = dm::EncroachmentRule::DiametralCircle;
    ro.max_steiner = budget;
    const dm::RefineStats st = dm::refine(m, ro);
    const dm::CheckReport rep = dm::check(m, {.convex_hull = false});
    EXPECT_TRUE(rep.ok()) << rep.summary() << "\n" << st.summary();
  }
}

TEST(Regress, RefineFinishAfterABudgetStopIsLinear) {
  // Exposed: after a budget stop, finish() asked the decision procedure
  // again why each bad triangle was left; on points on a circle every
  // Steiner point's cavity is the whole mesh, so that took seconds (3000
  // points: ~5 s) for a refinement stopped at once.
  const int n = 3000;
  std::vector<dm::Point> pts;
  for (int i = 0; i < n; ++i)
    pts.push_back({std::cos(2 * std::numbers::pi * i / n), std::sin(2 * std::numbers::pi * i / n)});
  dm::Pslg g;
  g.points = pts;
  dm::TriangulateOptions topt;
  topt.use_segments = false;
  topt.domain.keep_convex_hull = true;
  dm::Mesh m = dm::triangulate(g, topt);
  dm::RefineOptions ro;
  ro.min_angle_deg = 20;
  ro.max_steiner = 0;
  const dm::RefineStats st = dm::refine(m, ro);
  EXPECT_TRUE(st.budget_exhausted);
  EXPECT_GT(st.below_budget, std::size_t{n / 2}) << st.summary();
  // No time assertion (timed unit tests flake on a loaded 2-core CI): the
  // linear finish() is 0.3 s here against ~5 s before, see the commit log.
  EXPECT_TRUE(dm::check(m, {.convex_hull = false}).ok());
}

TEST(Regress, CdtRepeatedSegmentFollowsItsBentChain) {
  // Exposed: a segment given again after its first copy was split at
  // rounded crossing vertices crossed that (ulp-bent) chain in the middle of
  // a piece, adding vertices without end: a non-Delaunay edge, or an
  // InputError ("more vertices added at segment crossings ...").
  const dm::Pslg full = dm::read_poly(regress("cdt_repeated_segment_crosses_bent_chain.poly"));
  for (const std::size_t nseg : {std::size_t{8}, full.segments.size()})
    for (const dm::CdtMethod method :
         {dm::CdtMethod::Fast, dm::CdtMethod::Ct, dm::CdtMethod::Lawson, dm::CdtMethod::Lifting})
      for (const bool hull : {false, true}) {
        SCOPED_TRACE(std::to_string(nseg) + " segments, " + std::string(dm::to_string(method)) +
                     (hull ? ", -c" : ""));
        dm::Pslg g = full;
        g.segments.resize(nseg);
        dm::TriangulateOptions topt;
        topt.method = method;
        topt.domain.keep_convex_hull = hull;
        dm::Mesh m;
        ASSERT_NO_THROW(m = dm::triangulate(g, topt));
        // Three segments cross pairwise at most three times.
        EXPECT_LE(m.num_vertices(), g.points.size() + 3);
        dm::CheckOptions co;
        co.convex_hull = false;
        co.delaunay = method != dm::CdtMethod::Ct;
        if (hull) co.pslg = &g;
        const dm::CheckReport rep = dm::check(m, co);
        EXPECT_TRUE(rep.ok()) << rep.summary();
      }
}

// 122 bunched lines crossing near the origin (fuzz_hubs): a segment piece
// whose cavity Fast cannot retriangulate (a chain with holes) went to the
// lifting map, whose coordinates spanned more than 2^80, which went back to
// Fast, without end (a stack overflow under Fast and Lifting).
TEST(Regress, CdtFallbacksOfFastAndLiftingEnd) {
  const dm::Pslg g = dm::read_poly(regress("cdt_fast_lifting_fallbacks_call_each_other.poly"));
  for (const dm::CdtMethod method :
       {dm::CdtMethod::Fast, dm::CdtMethod::Ct, dm::CdtMethod::Lawson, dm::CdtMethod::Lifting}) {
    SCOPED_TRACE(std::string(dm::to_string(method)));
    dm::TriangulateOptions topt;
    topt.method = method;
    dm::TriangulateStats st;
    dm::Mesh m;
    ASSERT_NO_THROW(m = dm::triangulate(g, topt, &st));
    dm::CheckOptions co;
    co.convex_hull = false;
    co.delaunay = method != dm::CdtMethod::Ct;
    co.pslg = &g;
    const dm::CheckReport rep = dm::check(m, co);
    EXPECT_TRUE(rep.ok()) << rep.summary();
  }
}

namespace {

// The regression input above under `method`, carved and with -c.
void check_ring_crossings(dm::CdtMethod method) {
  const dm::Pslg g = dm::read_poly(regress("cdt_ring_crossings_converge_not_delaunay.poly"));
  for (const bool hull : {false, true}) {
    SCOPED_TRACE(std::string(dm::to_string(method)) + (hull ? ", -c" : ""));
    dm::TriangulateOptions topt;
    topt.method = method;
    topt.domain.keep_convex_hull = hull;
    dm::Mesh m;
    try {
      m = dm::triangulate(g, topt);
    } catch (const dm::InputError& e) {
      // Refusing a numerically hopeless input is allowed; a wrong mesh is not.
      EXPECT_EQ(std::string(e.what()).find("internal error"), std::string::npos) << e.what();
      continue;
    }
    dm::CheckOptions co;
    co.convex_hull = false;
    if (hull) co.pslg = &g;
    const dm::CheckReport rep = dm::check(m, co);
    EXPECT_TRUE(rep.ok()) << rep.summary();
  }
}

}  // namespace

TEST(Regress, CdtRingCrossingsStayDelaunayFast) {
  // Exposed (fuzz_insert_segments, in the triangulation it starts from): a
  // self-crossing ring of ulp-perturbed points far from the origin gets a
  // run of rounded crossing vertices converging on one point (24-59), and
  // --cdt=fast leaves edge 26-24 not locally Delaunay (vertex 25, on the
  // constrained chain 24-25-26, is inside the circumcircle across it).
  // Fixed by constrained Lawson flips after the fast method when crossings
  // added vertices.
  check_ring_crossings(dm::CdtMethod::Fast);
}

TEST(Regress, CdtRingCrossingsStayDelaunayOtherMethods) {
  // The same input: Lawson and Lifting give the CDT.
  check_ring_crossings(dm::CdtMethod::Lawson);
  check_ring_crossings(dm::CdtMethod::Lifting);
}

TEST(Regress, AdaptSteinerBudgetCoversTheRefinementAfterSmoothing) {
  // Exposed by fuzz_adapt: after smoothing, adapt() refines again for the
  // triangles smoothing left outside the bounds, and that refinement got
  // max_steiner (and the time limit) again: 379 Steiner points under a
  // budget of 200 here (179 before smoothing, 200 after).
  const dm::Pslg g = dm::read_poly(regress("adapt_refinement_after_smoothing_exceeds_budget.poly"));
  dm::TriangulateOptions topt;
  topt.method = dm::CdtMethod::Lifting;
  topt.domain.keep_convex_hull = true;
  dm::Mesh m = dm::triangulate(g, topt);
  dm::RefineOptions ro;
  ro.min_angle_deg = 30;
  // 300 (the file's 400 before refinement's scale-free order, issue 20:
  // then adapt's first refinement took the whole budget and the one after
  // smoothing never ran).
  ro.max_steiner = 300;
  dm::refine(m, ro);
  ASSERT_TRUE(dm::check(m, {.convex_hull = false}).ok());
  dm::AdaptOptions ao;
  ao.refine.min_angle_deg = 25;
  // 600 (200 before precision was measured by rounding alone, issue 20: the
  // file's ulp-sized features now take refinement further, and with 200 the
  // first refinement took the whole budget).
  ao.refine.max_steiner = 600;
  ao.smooth_passes = 3;
  const dm::AdaptStats st = dm::adapt(m, [](double, double) { return 1e12; }, ao);
  const dm::CheckReport rep = dm::check(m, {.convex_hull = false});
  EXPECT_TRUE(rep.ok()) << rep.summary();
  EXPECT_GT(st.removed, 100u) << st.summary();
  EXPECT_GT(st.resplit, 0u) << st.summary();  // the refinement after smoothing ran
  EXPECT_LE(st.inserted, ao.refine.max_steiner) << st.summary();
  EXPECT_EQ(st.inserted, st.refine.steiner_points);
  EXPECT_FALSE(st.complete) << st.summary();
}

TEST(Regress, SubnormalInputWithAHoleMeshesInAFrame) {
  // Exposed (fuzz_adapt): three points with subnormal coordinates, two
  // segments and a hole point. constrained_triangulation()'s classic path
  // let delaunay() frame the points on its own and then located the hole in
  // the subnormal coordinates: InternalError "visibility_walk: point
  // location met a degenerate triangle". And check() ran the predicates on
  // the subnormal triangle (products underflow): "not counter-clockwise".
  const dm::Pslg g = dm::read_poly(regress("cdt_subnormal_points_hole_point_walk.poly"));
  for (const dm::CdtMethod method : {dm::CdtMethod::Fast, dm::CdtMethod::Lawson, dm::CdtMethod::Lifting})
    for (const bool hull : {false, true}) {
      SCOPED_TRACE(std::string(dm::to_string(method)) + (hull ? " hull" : ""));
      dm::TriangulateOptions topt;
      topt.method = method;
      topt.domain.keep_convex_hull = hull;
      const dm::Mesh m = dm::triangulate(g, topt);
      const dm::CheckReport rep = dm::check(m, {.convex_hull = false});
      EXPECT_TRUE(rep.ok()) << rep.summary();
      // No segment closes a region: only the hull keeps the triangle, with
      // the input's coordinates bit for bit.
      EXPECT_EQ(m.num_triangles(), hull ? 1u : 0u);
      for (dm::VertexId v = 0; v < 3 && hull; ++v) EXPECT_EQ(m.point(v), g.points[v]);
    }
}

TEST(Regress, RefineKeepsSegmentChainsBesideAFarHullVertex) {
  // fuzz_mesh (fuzz6): one or two hull vertices at 5.2e64 or 7.6e109, the
  // rest within 5 of the origin. refine() frames such a mesh; its frame put
  // the small coordinates at the predicates' 2^-200, where split points near
  // zero were rounded to 0, off their segments, from the fifth Steiner point
  // on. Every input failed at both budgets before the fix.
  for (const char* name :
       {"refine_segment_chain_beside_far_hull_vertex.poly", "refine_segment_chain_two_far_hull_vertices.poly",
        "refine_segment_chain_far_hull_vertex_below.poly", "refine_segment_chain_far_hull_vertex_huge_seed.poly"}) {
    SCOPED_TRACE(name);
    const dm::Pslg g = dm::read_poly(regress(name));
    dm::TriangulateOptions topt;
    topt.method = dm::CdtMethod::Fast;
    topt.strict = true;
    topt.domain.keep_convex_hull = true;
    topt.domain.ignore_holes = true;
    topt.domain.regional_attributes = true;
    const dm::Mesh base = dm::triangulate(g, topt);
    ASSERT_TRUE(dm::check(base, {.convex_hull = false, .pslg = &g}).ok());
    for (const std::size_t budget : {std::size_t{5}, std::size_t{20}}) {
      SCOPED_TRACE(budget);
      dm::Mesh m = base;
      dm::RefineOptions ro;
      ro.min_angle_deg = 33;
      ro.encroachment = dm::EncroachmentRule::DiametralCircle;
      ro.max_steiner = budget;
      const dm::RefineStats st = dm::refine(m, ro);
      EXPECT_EQ(st.steiner_points, budget);  // (the bug showed from the fifth on)
      const dm::CheckReport rep = dm::check(m, {.convex_hull = false, .pslg = &g});
      EXPECT_TRUE(rep.ok()) << rep.summary();
    }
    // The CLI framed the same way and made the same wrong points; its -C
    // checks the segments only before carving, so it did not show them.
    dm::RunInput in;
    in.pslg = g;
    const dm::Plan plan =
        dm::parse_arguments({"-pcOAq33", "--encroachment=circle", "--strict", "-S20", "x"}).plan;
    const dm::RunResult r = dm::run(plan, std::move(in));
    EXPECT_EQ(r.stats.refine.steiner_points, 20u);
    const dm::CheckReport rep = dm::check(r.mesh, {.convex_hull = false, .pslg = &g});
    EXPECT_TRUE(rep.ok()) << rep.summary();
  }
}
