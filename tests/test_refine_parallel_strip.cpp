// The last pass of refinement in parts on a strip around the cuts
// (src/algo/refine/strip.cpp): where it finishes the mesh, the mesh meets
// the sequential run's bounds and about its size, validated; where it does
// not (small input angles), the mesh is the whole-mesh pass's, as without
// the strip; a strip written back and then refused leaves a mesh the
// whole-mesh pass finishes; and the same mesh comes back run after run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "algo/refine_parallel.hpp"
#include "deltamesh-gen/generators.hpp"
#include "deltamesh/triangulate.hpp"
#include "deltamesh/validate.hpp"
#include "support/mesh_extremes.hpp"

namespace dm = deltamesh;
using Strip = dm::detail::LastPassReport::Strip;

namespace {

using dm::test::carved_cdt;

void expect_valid(const dm::Mesh& m, const dm::Pslg& g, const std::string& what) {
  dm::CheckOptions co;
  co.convex_hull = false;
  co.pslg = &g;
  const dm::CheckReport r = dm::check(m, co);
  EXPECT_TRUE(r.ok()) << what << ": " << r.summary();
}

struct Case {
  const char* name;
  dm::Pslg pslg;
  double angle, area;
};

std::vector<Case> cases() {
  std::vector<Case> c;
  c.push_back({"square-hole q30", dm::gen::square_with_hole(64), 30, 5e-5});
  // Graded along a fine boundary: the strip grows where it left triangles bad.
  c.push_back({"smooth q33", dm::gen::smooth_polygon(2000), 33, 5e-5});
  return c;
}

dm::RefineOptions options(const Case& c, unsigned threads) {
  dm::RefineOptions o;
  o.min_angle_deg = c.angle;
  o.max_area = c.area;
  o.threads = threads;
  return o;
}

}  // namespace

// Kept on both inputs (no small input angles: nothing stays bad), and the
// mesh has the sequential run's bounds, its size within 3%, and the
// Steiner count of its vertices.
TEST(ParallelRefineStrip, FinishesTheMeshWhereItCan) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    dm::Mesh seq = carved_cdt(c.pslg);
    ASSERT_TRUE(dm::refine(seq, options(c, 1)).complete);
    dm::Mesh par = carved_cdt(c.pslg);
    dm::detail::LastPassReport report;
    const std::optional<dm::RefineStats> st = dm::detail::refine_in_parts(par, options(c, 2), 2, &report);
    ASSERT_TRUE(st.has_value());
    EXPECT_TRUE(report.strip_kept);
    EXPECT_GT(report.strip_triangles, 0u);
    EXPECT_LT(report.strip_triangles, par.num_triangles() / 4);
    EXPECT_TRUE(st->complete) << st->summary();
    EXPECT_EQ(st->below_bound, 0u);
    EXPECT_EQ(st->too_large, 0u);
    const dm::test::MeshExtremes x = dm::test::extremes(par);
    const double smallest = x.smallest_angle_deg, largest = x.largest_area;
    EXPECT_GE(smallest, c.angle - 1e-9);
    EXPECT_LE(largest, c.area * (1 + 1e-12));
    EXPECT_NEAR(double(par.num_triangles()) / double(seq.num_triangles()), 1.0, 0.03)
        << par.num_triangles() << " vs " << seq.num_triangles();
    EXPECT_EQ(st->steiner_points, par.num_vertices() - c.pslg.points.size());
    expect_valid(par, c.pslg, c.name);
  }
}

// A strip written back and then refused (as when a flip across its outer
// edges makes a bad triangle): the whole-mesh pass finishes that mesh.
TEST(ParallelRefineStrip, WholePassFinishesARefusedStrip) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    dm::Mesh m = carved_cdt(c.pslg);
    dm::detail::LastPassReport report;
    report.strip = Strip::Refuse;
    const std::optional<dm::RefineStats> st = dm::detail::refine_in_parts(m, options(c, 2), 2, &report);
    ASSERT_TRUE(st.has_value());
    EXPECT_FALSE(report.strip_kept);
    EXPECT_GT(report.strip_triangles, 0u);
    EXPECT_TRUE(st->complete) << st->summary();
    const dm::test::MeshExtremes x = dm::test::extremes(m);
    const double smallest = x.smallest_angle_deg, largest = x.largest_area;
    EXPECT_GE(smallest, c.angle - 1e-9);
    EXPECT_LE(largest, c.area * (1 + 1e-12));
    EXPECT_EQ(st->steiner_points, m.num_vertices() - c.pslg.points.size());
    expect_valid(m, c.pslg, c.name);
  }
}

// With small input angles the strip cannot leave every triangle good: it is
// not written back, and the mesh and statistics are the whole-mesh pass's
// on the stitched mesh, exactly.
TEST(ParallelRefineStrip, NotWrittenBackChangesNothing) {
  for (const int marker : {0, 3}) {
    SCOPED_TRACE(marker);
    dm::Pslg g = dm::gen::star_polygon(300, 5);
    for (dm::Segment& s : g.segments) s.marker = marker;
    dm::RefineOptions o;
    o.min_angle_deg = 33;
    o.max_area = 1e-4;
    o.threads = 2;
    dm::Mesh tried = carved_cdt(g), never = carved_cdt(g);
    dm::detail::LastPassReport report, none;
    none.strip = Strip::Never;
    const std::optional<dm::RefineStats> st = dm::detail::refine_in_parts(tried, o, 2, &report);
    const std::optional<dm::RefineStats> st_none = dm::detail::refine_in_parts(never, o, 2, &none);
    ASSERT_TRUE(st && st_none);
    EXPECT_GT(report.strip_triangles, 0u);
    EXPECT_FALSE(report.strip_kept);
    EXPECT_EQ(none.strip_triangles, 0u);
    ASSERT_GT(st->below_small_input_angle, 0u);
    EXPECT_EQ(st->summary(), st_none->summary());
    EXPECT_TRUE(std::ranges::equal(tried.triangle_vertices(), never.triangle_vertices()));
    EXPECT_EQ(tried.num_vertices(), never.num_vertices());
    expect_valid(tried, g, "star");
  }
}

// The strip kept: every array the same run after run, with segment markers
// (carried through the strip and its write-back).
TEST(ParallelRefineStrip, SameMeshRunAfterRun) {
  dm::Pslg g = dm::gen::square_with_hole(64);
  for (dm::Segment& s : g.segments) s.marker = 5;
  const Case c{"square-hole q30", g, 30, 1e-4};
  dm::Mesh first = carved_cdt(g);
  dm::detail::LastPassReport report;
  ASSERT_TRUE(dm::detail::refine_in_parts(first, options(c, 2), 2, &report).has_value());
  ASSERT_TRUE(report.strip_kept);
  expect_valid(first, g, "first run");
  ASSERT_TRUE(first.has_edge_markers());
  for (dm::HalfEdgeId e = 0; e < first.triangle_vertices().size(); ++e)
    EXPECT_EQ(first.edge_marker(e), first.is_constrained(e) ? 5 : 0) << e;
  for (int run = 0; run < 2; ++run) {
    dm::Mesh again = carved_cdt(g);
    ASSERT_TRUE(dm::detail::refine_in_parts(again, options(c, 2), 2).has_value());
    EXPECT_TRUE(std::ranges::equal(first.triangle_vertices(), again.triangle_vertices())) << run;
    ASSERT_EQ(first.num_vertices(), again.num_vertices());
    for (dm::VertexId v = 0; v < first.num_vertices(); ++v) {
      EXPECT_EQ(first.point(v).x, again.point(v).x);
      EXPECT_EQ(first.point(v).y, again.point(v).y);
      EXPECT_EQ(first.out_edge(v), again.out_edge(v));
    }
    for (dm::HalfEdgeId e = 0; e < first.triangle_vertices().size(); ++e) {
      EXPECT_EQ(first.twin(e), again.twin(e));
      EXPECT_EQ(first.edge_flags(e), again.edge_flags(e));
      EXPECT_EQ(first.edge_marker(e), again.edge_marker(e));
    }
  }
}
