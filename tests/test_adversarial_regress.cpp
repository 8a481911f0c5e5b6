// Regression inputs found by fuzzing (tests/regress/): one test per input,
// named after what it exposed. A test whose bug is not fixed yet is skipped
// with GTEST_SKIP naming the bug; remove the skip with the fix.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "deltamesh/errors.hpp"
#include "deltamesh/refine.hpp"
#include "deltamesh/triangle_io.hpp"
#include "deltamesh/triangulate.hpp"
#include "deltamesh/validate.hpp"
#include "test_adversarial_util.hpp"

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
  GTEST_SKIP() << "bug: Delaunay path keeps a later copy of duplicate points (reported; fix in delaunay.cpp or "
                  "triangulate.cpp, then remove this skip)";
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

TEST(Regress, RefineWithoutSmallAngleProtectionLeavesNonDelaunayEdges) {
  // Bug: with small_angle_protection off, refinement around the small
  // angles at a segment crossing (budget 320 here) leaves unconstrained
  // edges that are not locally Delaunay; further insertions hide it again.
  GTEST_SKIP() << "bug: refine() with small_angle_protection = false leaves non-locally-Delaunay edges "
                  "(edge 11-317 of refine_no_small_angle_protection_not_delaunay.poly at budget 320; reported)";
  const dm::Pslg g = dm::read_poly(regress("refine_no_small_angle_protection_not_delaunay.poly"));
  dm::TriangulateOptions topt;
  topt.domain.keep_convex_hull = true;
  const dm::Mesh base = dm::triangulate(g, topt);
  for (const std::size_t budget : {std::size_t{320}, std::size_t{330}})
    for (const dm::SteinerRule rule : {dm::SteinerRule::Offcenter, dm::SteinerRule::Circumcenter}) {
      SCOPED_TRACE(budget);
      dm::Mesh m = base;
      dm::RefineOptions ro;
      ro.min_angle_deg = 20;
      ro.steiner = rule;
      ro.small_angle_protection = false;
      ro.max_steiner = budget;
      dm::refine(m, ro);
      const dm::CheckReport rep = dm::check(m, {.convex_hull = false});
      EXPECT_TRUE(rep.ok()) << rep.summary();
    }
}

TEST(Regress, RefineAreaBoundNearlyCoincidentVerticesLeavesNonDelaunayEdge) {
  // Bug: a vertex within a few ulps of a segment (and another pair of
  // vertices ulps apart); refining for an area bound only splits segments
  // down to the precision floor and ends with a non-locally-Delaunay edge,
  // reporting the refinement complete while 4 triangles are too large.
  GTEST_SKIP() << "bug: refine() for an area bound near nearly coincident vertices leaves a non-locally-Delaunay "
                  "edge (refine_area_bound_near_coincident_not_delaunay.poly; reported)";
  const dm::Pslg g = dm::read_poly(regress("refine_area_bound_near_coincident_not_delaunay.poly"));
  dm::TriangulateOptions topt;
  topt.method = dm::CdtMethod::Lawson;
  topt.domain.keep_convex_hull = true;
  dm::Mesh m = dm::triangulate(g, topt);
  ASSERT_TRUE(dm::check(m, {.convex_hull = false}).ok());
  dm::RefineOptions ro;
  ro.min_angle_deg = 0;
  ro.max_area = 1.0 / 64;  // the bounding box [0.5, 1.5]^2, / 64
  ro.steiner = dm::SteinerRule::Offcenter;
  ro.encroachment = dm::EncroachmentRule::DiametralCircle;
  ro.max_steiner = 3000;
  const dm::RefineStats st = dm::refine(m, ro);
  const dm::CheckReport rep = dm::check(m, {.convex_hull = false});
  EXPECT_TRUE(rep.ok()) << rep.summary();
  EXPECT_TRUE(!st.complete || st.too_large == 0) << st.summary();
}
