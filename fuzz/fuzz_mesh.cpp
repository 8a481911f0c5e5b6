// libFuzzer target: random bytes -> a small PSLG -> triangulate (every CDT
// method, fill rule and domain option) -> deltamesh::check; then quality
// refinement under a Steiner budget and a time limit -> check again (bounds
// up to 40°).
//
// A bug is: a crash or sanitizer report; an exception that is not one of the
// library's typed errors, or an InternalError (a broken invariant);
// a mesh the validator rejects; an input vertex moved; a vertex of a point
// set missing from its Delaunay triangulation; an input segment not present
// as a chain of constrained edges when nothing was carved away; after
// refinement, any of these, an edge that is not locally Delaunay, counts
// that do not add up, or "complete" with a triangle above its area bound,
// a triangle left by a budget, or more triangles below the angle bound than
// refinement reports.
#include <fuzzer/FuzzedDataProvider.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "deltamesh/errors.hpp"
#include "deltamesh/pslg.hpp"
#include "deltamesh/triangulate.hpp"
#include "deltamesh/validate.hpp"
#ifdef DELTAMESH_FUZZ_HAVE_REFINE
#include "deltamesh/refine.hpp"
#endif
#include "fuzz_util.hpp"
#include "pslg_bytes.hpp"

namespace dm = deltamesh;
namespace fz = deltamesh::fuzz;

namespace {

constexpr std::size_t kMaxPoints = 40;
constexpr std::size_t kMaxSegments = 40;

// How coordinates are made from bytes. Small integer grids give exact
// collinearities, duplicates and cocircular points; scaled grids move them
// across magnitudes; ulp-perturbed grids give nearly coincident and nearly
// collinear points; raw doubles give NaN, infinities, huge and subnormal
// values (which must be rejected with an InputError).
enum class CoordMode : std::uint8_t { Grid, ScaledGrid, Perturbed, Raw, kCount };

struct CoordMaker {
  CoordMode mode = CoordMode::Grid;
  double scale = 1.0;
  double offset_x = 0.0, offset_y = 0.0;
  int grid = 8;

  void init(FuzzedDataProvider& in) {
    mode = static_cast<CoordMode>(in.ConsumeIntegralInRange<int>(0, static_cast<int>(CoordMode::kCount) - 1));
    grid = in.ConsumeIntegralInRange<int>(1, 64);
    if (mode == CoordMode::ScaledGrid || mode == CoordMode::Perturbed) {
      scale = std::ldexp(1.0, in.ConsumeIntegralInRange<int>(-190, 180));
      // An offset far from the grid's size makes the points nearly coincident
      // relative to their magnitude.
      const int shift = in.ConsumeIntegralInRange<int>(0, 60);
      offset_x = in.ConsumeBool() ? std::ldexp(scale, shift) : 0.0;
      offset_y = in.ConsumeBool() ? -std::ldexp(scale, shift / 2) : 0.0;
    }
  }

  double coord(FuzzedDataProvider& in, double offset) const {
    switch (mode) {
      case CoordMode::Grid:
        return in.ConsumeIntegralInRange<int>(0, grid);
      case CoordMode::ScaledGrid:
        return offset + scale * in.ConsumeIntegralInRange<int>(0, grid);
      case CoordMode::Perturbed: {
        double v = offset + scale * in.ConsumeIntegralInRange<int>(0, grid);
        const int ulps = in.ConsumeIntegralInRange<int>(-3, 3);
        for (int k = 0; k < std::abs(ulps); ++k) v = std::nextafter(v, ulps > 0 ? INFINITY : -INFINITY);
        return v;
      }
      default: {
        // Raw bits most of the time, otherwise a plain value, so that a raw
        // input is not rejected at its first coordinate every time.
        if (in.ConsumeIntegralInRange<int>(0, 3) != 0) return in.ConsumeIntegralInRange<int>(-4, 4);
        const std::uint64_t bits = in.ConsumeIntegral<std::uint64_t>();
        double v;
        std::memcpy(&v, &bits, sizeof v);
        return v;
      }
    }
  }

  dm::Point point(FuzzedDataProvider& in) const {
    const double x = coord(in, offset_x);
    const double y = coord(in, offset_y);
    return {x, y};
  }
};

std::string describe(const dm::Pslg& g) {
  std::string s = std::to_string(g.points.size()) + " points, " + std::to_string(g.segments.size()) + " segments, " +
                  std::to_string(g.holes.size()) + " holes, " + std::to_string(g.regions.size()) + " regions";
  return s;
}

// segments: also let the validator check that every input segment is a
// chain of constrained edges (only when nothing was carved away).
void check_mesh(const dm::Mesh& mesh, const dm::Pslg& g, bool delaunay, bool convex, bool segments,
                const char* stage) {
  dm::CheckOptions co;
  co.delaunay = delaunay;
  co.convex_hull = convex;
  if (segments) co.pslg = &g;
  const dm::CheckReport rep = dm::check(mesh, co);
  if (!rep.ok()) fz::fail(std::string(stage) + ": the validator rejects the mesh of " + describe(g) + ": " + rep.summary());
  DELTAMESH_FUZZ_CHECK(mesh.num_vertices() >= g.points.size(), stage);
  for (std::size_t i = 0; i < g.points.size(); ++i)
    DELTAMESH_FUZZ_CHECK(mesh.point(static_cast<dm::VertexId>(i)) == g.points[i],
                         std::string(stage) + ": input vertex " + std::to_string(i) + " moved");
}

// For each input vertex, its first copy (segments use it).
std::vector<dm::VertexId> first_copies(const dm::Pslg& g) {
  std::map<std::pair<double, double>, dm::VertexId> seen;
  std::vector<dm::VertexId> first(g.points.size());
  for (std::size_t i = 0; i < g.points.size(); ++i) {
    // +0.0 turns -0 into 0: the two compare equal as coordinates.
    const auto key = std::make_pair(g.points[i].x + 0.0, g.points[i].y + 0.0);
    first[i] = seen.emplace(key, static_cast<dm::VertexId>(i)).first->second;
  }
  return first;
}

// Every point of a point set is in its Delaunay triangulation: of equal
// points exactly one copy, the first in input order
// (tests/test_adversarial_regress.cpp DuplicatePointsKeepTheFirstCopy*).
void check_all_vertices_used(const dm::Mesh& mesh, const dm::Pslg& g) {
  const std::vector<dm::VertexId> first = first_copies(g);
  std::vector<int> used(mesh.num_vertices(), 0);
  for (dm::TriId t = 0; t < mesh.num_triangle_slots(); ++t) {
    if (!mesh.is_real(t)) continue;
    for (const dm::VertexId v : mesh.triangle(t)) used[v] = 1;
  }
  std::vector<int> copies_used(g.points.size(), 0);
  for (std::size_t i = 0; i < g.points.size(); ++i) copies_used[first[i]] += used[i];
  for (std::size_t i = 0; i < g.points.size(); ++i) {
    if (first[i] == i && copies_used[i] != 1)
      fz::fail("point " + std::to_string(i) + " of " + describe(g) + " is in " + std::to_string(copies_used[i]) +
               " copies in the triangulation");
    if (first[i] == i && !used[i])
      fz::fail("point " + std::to_string(i) + " of " + describe(g) + ": a later copy is used, not the first");
  }
}

// Every input segment of nonzero length joins its endpoints by a path of
// constrained edges whose vertices stay within the segment's bounding box
// (split points are rounded, so "on the segment" is not exact).
void check_segments_present(const dm::Mesh& mesh, const dm::Pslg& g, const char* stage) {
  const std::vector<dm::VertexId> first = first_copies(g);
  std::vector<std::vector<dm::VertexId>> adj(mesh.num_vertices());
  for (dm::TriId t = 0; t < mesh.num_triangle_slots(); ++t) {
    if (!mesh.is_real(t)) continue;
    for (dm::HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e) {
      if (!mesh.is_constrained(e)) continue;
      adj[mesh.origin(e)].push_back(mesh.dest(e));
      adj[mesh.dest(e)].push_back(mesh.origin(e));
    }
  }
  std::vector<std::uint32_t> stamp(mesh.num_vertices(), 0);
  std::uint32_t round = 0;
  for (std::size_t si = 0; si < g.segments.size(); ++si) {
    const dm::VertexId a = first[g.segments[si].a], b = first[g.segments[si].b];
    if (a == b) continue;  // zero length: ignored
    const dm::Point pa = g.points[a], pb = g.points[b];
    const double extent = std::max({std::fabs(pa.x), std::fabs(pa.y), std::fabs(pb.x), std::fabs(pb.y)});
    const double tol = 1e-9 * extent;
    const double lox = std::min(pa.x, pb.x) - tol, hix = std::max(pa.x, pb.x) + tol;
    const double loy = std::min(pa.y, pb.y) - tol, hiy = std::max(pa.y, pb.y) + tol;
    ++round;
    std::vector<dm::VertexId> stack{a};
    stamp[a] = round;
    bool found = false;
    while (!stack.empty() && !found) {
      const dm::VertexId v = stack.back();
      stack.pop_back();
      for (const dm::VertexId w : adj[v]) {
        if (stamp[w] == round) continue;
        const dm::Point& p = mesh.point(w);
        if (p.x < lox || p.x > hix || p.y < loy || p.y > hiy) continue;
        if (w == b) {
          found = true;
          break;
        }
        stamp[w] = round;
        stack.push_back(w);
      }
    }
    if (!found)
      fz::fail(std::string(stage) + ": segment " + std::to_string(si) + " (" + std::to_string(a) + "-" +
               std::to_string(b) + ") of " + describe(g) + " is not a chain of constrained edges");
  }
}

#ifdef DELTAMESH_FUZZ_HAVE_REFINE
// What refine() reports against the mesh: its counts add up, and a
// "complete" refinement leaves no triangle above its area bound. Angles and
// areas are recomputed here with a little slack (1e-9 relative) so that a
// triangle at its bound up to rounding is not a bug.
void check_refine_stats(const dm::Mesh& mesh, const dm::RefineOptions& ro, const dm::RefineStats& rs,
                        const dm::Pslg& g) {
  const std::string what = rs.summary() + " on " + describe(g);
  DELTAMESH_FUZZ_CHECK(rs.steiner_points <= ro.max_steiner, what);
  DELTAMESH_FUZZ_CHECK(mesh.num_vertices() == rs.input_vertices + rs.steiner_points, what);
  DELTAMESH_FUZZ_CHECK(!(rs.budget_exhausted || rs.time_exhausted) || !rs.complete, what);
  DELTAMESH_FUZZ_CHECK(rs.below_bound == rs.below_small_input_angle + rs.below_segment_protected + rs.below_budget +
                                             rs.below_out_of_reach + rs.below_precision,
                       what);
  DELTAMESH_FUZZ_CHECK(rs.too_large_precision <= rs.too_large, what);
  if (rs.complete) {
    DELTAMESH_FUZZ_CHECK(rs.too_large == 0 && rs.below_budget == 0 && rs.below_segment_protected == 0 &&
                             rs.below_precision == 0,
                         what);
  } else {
    // Incomplete says why (RefineStats::complete's one rule): a budget,
    // triangles left too large, or below the angle bound where -Y/-YY
    // forbids the split or at the precision of doubles.
    DELTAMESH_FUZZ_CHECK(rs.budget_exhausted || rs.time_exhausted || rs.too_large > 0 ||
                             rs.below_segment_protected > 0 || rs.below_precision > 0,
                         what);
  }
  const double sin_bound = std::sin(ro.min_angle_deg * (1 - 1e-9) * 3.14159265358979323846 / 180);
  std::size_t below = 0;
  for (dm::TriId t = 0; t < mesh.num_triangle_slots(); ++t) {
    if (!mesh.is_real(t)) continue;
    const auto v = mesh.triangle(t);
    const dm::Point& a = mesh.point(v[0]);
    const dm::Point& b = mesh.point(v[1]);
    const dm::Point& c = mesh.point(v[2]);
    const double cross = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    const double l0 = (b.x - a.x) * (b.x - a.x) + (b.y - a.y) * (b.y - a.y);
    const double l1 = (c.x - b.x) * (c.x - b.x) + (c.y - b.y) * (c.y - b.y);
    const double l2 = (a.x - c.x) * (a.x - c.x) + (a.y - c.y) * (a.y - c.y);
    // sin of the smallest angle = cross / (product of the two longer edges).
    const double lo = std::min({l0, l1, l2});
    const double den = lo == l0 ? l1 * l2 : (lo == l1 ? l0 * l2 : l0 * l1);
    if (ro.min_angle_deg > 0 && cross * cross < sin_bound * sin_bound * den) ++below;
    if (!rs.complete) continue;
    double bound = ro.max_area;
    const double tb = ro.use_triangle_area_bounds ? mesh.triangle_area_bound(t) : -1.0;
    if (tb > 0 && (bound <= 0 || tb < bound)) bound = tb;
    if (bound > 0 && 0.5 * cross > bound * (1 + 1e-9))
      fz::fail("refine: complete, but triangle " + std::to_string(t) + " has area " + std::to_string(0.5 * cross) +
               " above its bound " + std::to_string(bound) + ": " + what);
  }
  DELTAMESH_FUZZ_CHECK(below <= rs.below_bound, std::to_string(below) + " triangles below the bound: " + what);
}
#endif

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);

  // FuzzedDataProvider reads integers from the end of the input backwards:
  // the options are the last bytes, the geometry comes before them.
  const std::uint8_t f1 = in.ConsumeIntegral<std::uint8_t>();
  const std::uint8_t f2 = in.ConsumeIntegral<std::uint8_t>();
  dm::TriangulateOptions topt;
  topt.use_segments = (f1 & 1) != 0;
  static constexpr dm::CdtMethod kMethods[] = {dm::CdtMethod::Fast, dm::CdtMethod::Ct, dm::CdtMethod::Lawson,
                                               dm::CdtMethod::Lifting};
  topt.method = kMethods[(f1 >> 1) & 3];
  topt.strict = (f1 & 8) != 0;
  topt.domain.fill = (f1 & 16) ? dm::FillRule::EvenOdd : dm::FillRule::Holes;
  topt.domain.keep_convex_hull = (f1 & 32) != 0;
  topt.domain.ignore_holes = (f1 & 64) != 0;
  topt.domain.regional_attributes = (f1 & 128) != 0;
  topt.domain.regional_area_bounds = (f2 & 1) != 0;

  CoordMaker coords;
  coords.init(in);
  dm::Pslg g;
  const std::size_t n = in.ConsumeIntegralInRange<std::size_t>(0, kMaxPoints);
  const std::size_t ns = in.ConsumeIntegralInRange<std::size_t>(0, kMaxSegments);
  const std::size_t nh = in.ConsumeIntegralInRange<std::size_t>(0, 3);
  const std::size_t nr = in.ConsumeIntegralInRange<std::size_t>(0, 3);
  for (std::size_t i = 0; i < n; ++i) g.points.push_back(coords.point(in));
  if (n > 0) {
    for (std::size_t i = 0; i < ns; ++i) {
      dm::Segment s;
      // Now and then an endpoint out of range (an InputError).
      s.a = in.ConsumeIntegralInRange<dm::VertexId>(0, static_cast<dm::VertexId>(n - (f2 & 2 ? 0 : 1)));
      s.b = in.ConsumeIntegralInRange<dm::VertexId>(0, static_cast<dm::VertexId>(n - 1));
      s.marker = in.ConsumeIntegralInRange<int>(-2, 3);
      g.segments.push_back(s);
    }
  }
  for (std::size_t i = 0; i < nh; ++i) g.holes.push_back(coords.point(in));
  for (std::size_t i = 0; i < nr; ++i) {
    dm::RegionSeed r;
    r.p = coords.point(in);
    r.attribute = in.ConsumeIntegralInRange<int>(-3, 3);
    r.max_area = in.ConsumeBool() ? -1.0 : std::ldexp(1.0, in.ConsumeIntegralInRange<int>(-20, 20));
    g.regions.push_back(r);
  }
  if (f2 & 4) {  // vertex markers and one attribute per vertex
    for (std::size_t i = 0; i < n; ++i) g.point_markers.push_back(static_cast<int>(i % 3));
    g.num_point_attributes = 1;
    for (std::size_t i = 0; i < n; ++i) g.point_attributes.push_back(static_cast<double>(i));
  }

  static const bool verbose = std::getenv("DELTAMESH_FUZZ_VERBOSE") != nullptr;
  if (verbose) {
    std::fprintf(stderr, "--- options: use_segments=%d method=%s strict=%d fill=%s keep_convex_hull=%d "
                         "ignore_holes=%d regional_attributes=%d regional_area_bounds=%d\n--- input.poly:\n%s",
                 topt.use_segments, std::string(dm::to_string(topt.method)).c_str(), topt.strict,
                 topt.domain.fill == dm::FillRule::EvenOdd ? "evenodd" : "holes", topt.domain.keep_convex_hull,
                 topt.domain.ignore_holes, topt.domain.regional_attributes, topt.domain.regional_area_bounds,
                 fz::to_poly(g).c_str());
  }

  dm::Mesh mesh;
  dm::TriangulateStats stats;
  try {
    mesh = dm::triangulate(g, topt, &stats);
  } catch (const dm::InputError& e) {
    return 0;  // bad input, reported as such
  } catch (...) {
    fz::unexpected_exception("triangulate");
  }

  if (verbose)
    std::fprintf(stderr, "--- triangulate result: %zu vertices, %zu triangles\n", mesh.num_vertices(),
                 mesh.num_triangles());
  // Ct is a constrained triangulation, not always Delaunay. A carved domain
  // need not be convex.
  const bool delaunay = !topt.use_segments || topt.method != dm::CdtMethod::Ct;
  const bool convex = !topt.use_segments;
  const bool nothing_carved = topt.use_segments && topt.domain.keep_convex_hull &&
                              topt.domain.fill == dm::FillRule::Holes && (g.holes.empty() || topt.domain.ignore_holes);
  check_mesh(mesh, g, delaunay, convex, nothing_carved, "triangulate");
  if (!topt.use_segments) check_all_vertices_used(mesh, g);
  if (nothing_carved) check_segments_present(mesh, g, "triangulate");

#ifdef DELTAMESH_FUZZ_HAVE_REFINE
  // Refinement assumes a constrained Delaunay triangulation.
  if (!delaunay || mesh.num_triangles() == 0) return 0;
  dm::RefineOptions ropt;
  static constexpr double kAngles[] = {0.0, 20.0, 28.0, 33.0};
  ropt.min_angle_deg = kAngles[(f2 >> 3) & 3];
  if (f2 & 32) {
    // An area bound a fraction of the bounding box's area.
    double lox = INFINITY, hix = -INFINITY, loy = INFINITY, hiy = -INFINITY;
    for (const dm::Point& p : g.points) {
      lox = std::min(lox, p.x), hix = std::max(hix, p.x);
      loy = std::min(loy, p.y), hiy = std::max(hiy, p.y);
    }
    ropt.max_area = (hix - lox) * (hiy - loy) / 64.0;
  }
  ropt.encroachment = (f2 & 128) ? dm::EncroachmentRule::DiametralLens : dm::EncroachmentRule::DiametralCircle;
  const std::uint8_t f3 = in.ConsumeIntegral<std::uint8_t>();
  ropt.steiner = (f2 & 64)   ? dm::SteinerRule::Circumcenter
                 : (f3 & 64) ? dm::SteinerRule::Offcenter
                             : dm::SteinerRule::Best;
  static constexpr dm::SegmentSplitting kSplitting[] = {dm::SegmentSplitting::All, dm::SegmentSplitting::All,
                                                        dm::SegmentSplitting::InteriorOnly,
                                                        dm::SegmentSplitting::None};
  ropt.segment_splitting = kSplitting[f3 & 3];
  ropt.conforming_delaunay = (f3 & 4) != 0;
  ropt.small_angle_protection = (f3 & 8) == 0;
  static constexpr std::size_t kBudgets[] = {20, 300, 3000, 3000};
  ropt.max_steiner = kBudgets[(f3 >> 4) & 3];
  ropt.time_limit_seconds = 2.0;
  if ((f3 & 128) && ropt.min_angle_deg == 33.0) ropt.min_angle_deg = 40.0;  // beyond 34°: the staged refinement
  if (verbose)
    std::fprintf(stderr,
                 "--- refine: min_angle=%g max_area=%g steiner=%s encroachment=%s splitting=%d conforming=%d "
                 "small_angle_protection=%d max_steiner=%zu\n",
                 ropt.min_angle_deg, ropt.max_area, std::string(dm::to_string(ropt.steiner)).c_str(),
                 std::string(dm::to_string(ropt.encroachment)).c_str(), static_cast<int>(ropt.segment_splitting),
                 ropt.conforming_delaunay, ropt.small_angle_protection, ropt.max_steiner);
  dm::RefineStats rs;
  try {
    rs = dm::refine(mesh, ropt);
  } catch (...) {
    fz::unexpected_exception("refine");
  }
  if (verbose) std::fprintf(stderr, "--- refine result: %s\n", rs.summary().c_str());
  // Split points on hull edges are rounded: the hull of a refined mesh is
  // convex only up to rounding, so convexity is not checked exactly. The
  // Delaunay property (unconstrained edges locally Delaunay) always is.
  check_mesh(mesh, g, true, false, nothing_carved, "refine");
  if (nothing_carved) check_segments_present(mesh, g, "refine");
  check_refine_stats(mesh, ropt, rs, g);
#endif
  return 0;
}
