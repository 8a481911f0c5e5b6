// Vertex smoothing (adapt.hpp: smooth(), AdaptOptions::smooth_passes, the
// CLI's --smooth): the mesh stays a valid constrained Delaunay
// triangulation of the same domain, fixed vertices keep their coordinates,
// the smallest angle never drops, the mean smallest angle rises, and the
// size guards hold.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "deltamesh/adapt.hpp"
#include "deltamesh/refine.hpp"
#include "deltamesh/triangle_io.hpp"
#include "deltamesh/triangulate.hpp"
#include "deltamesh/validate.hpp"
#include "test_adversarial_util.hpp"
#include "test_refine_util.hpp"

namespace dm = deltamesh;

namespace {

// The unit square (marker 1) with the square hole [0.4,0.6]^2 (marker 2), an
// interior segment from (0.1,0.2) to (0.3,0.8) (marker 3) and a lone
// interior point (0.8, 0.2).
dm::Pslg domain() {
  dm::Pslg g;
  g.points = {{0, 0},     {1, 0},     {1, 1},     {0, 1},     {0.4, 0.4}, {0.6, 0.4},
              {0.6, 0.6}, {0.4, 0.6}, {0.1, 0.2}, {0.3, 0.8}, {0.8, 0.2}};
  for (dm::VertexId i = 0; i < 4; ++i) g.segments.push_back({i, (i + 1) % 4, 1});
  for (dm::VertexId i = 0; i < 4; ++i) g.segments.push_back({4 + i, 4 + (i + 1) % 4, 2});
  g.segments.push_back({8, 9, 3});
  g.holes.push_back({0.5, 0.5});
  return g;
}

dm::Mesh refined(const dm::Pslg& g, double angle, double max_area) {
  dm::TriangulateOptions o;
  dm::RefineOptions r;
  r.min_angle_deg = angle;
  r.max_area = max_area;
  o.refine = r;
  return dm::triangulate(g, o);
}


double tri_min_angle(const dm::Mesh& m, dm::TriId t) {
  const auto v = m.triangle(t);
  double lo = 180;
  for (int i = 0; i < 3; ++i) {
    const dm::Point &a = m.point(v[i]), &b = m.point(v[(i + 1) % 3]), &c = m.point(v[(i + 2) % 3]);
    const double ux = b.x - a.x, uy = b.y - a.y, wx = c.x - a.x, wy = c.y - a.y;
    lo = std::min(lo, std::atan2(std::fabs(ux * wy - uy * wx), ux * wx + uy * wy) * 180 / std::numbers::pi);
  }
  return lo;
}

double mean_min_angle(const dm::Mesh& m) {
  double s = 0;
  std::size_t n = 0;
  for (dm::TriId t = 0; t < m.num_triangle_slots(); ++t)
    if (m.is_real(t)) {
      s += tri_min_angle(m, t);
      ++n;
    }
  return s / double(n);
}


// Vertices on a constrained edge or the boundary.
std::vector<char> on_segments(const dm::Mesh& m) {
  std::vector<char> fixed(m.num_vertices(), 0);
  for (dm::HalfEdgeId e = 0; e < m.triangle_vertices().size(); ++e)
    if (m.is_real(dm::tri_of(e)) && (m.is_constrained(e) || m.twin(e) == dm::kNone)) {
      fixed[m.origin(e)] = 1;
      fixed[m.dest(e)] = 1;
    }
  return fixed;
}

// Worst longest edge / h(centroid) over the triangles.
double worst_size(const dm::Mesh& m, const dm::SizeField& h) {
  double w = 0;
  for (dm::TriId t = 0; t < m.num_triangle_slots(); ++t) {
    if (!m.is_real(t)) continue;
    const auto v = m.triangle(t);
    const dm::Point &a = m.point(v[0]), &b = m.point(v[1]), &c = m.point(v[2]);
    const double len = std::max({std::hypot(a.x - b.x, a.y - b.y), std::hypot(b.x - c.x, b.y - c.y),
                                 std::hypot(c.x - a.x, c.y - a.y)});
    w = std::max(w, len / h((a.x + b.x + c.x) / 3, (a.y + b.y + c.y) / 3));
  }
  return w;
}

TEST(Smooth, KeepsAValidCdtRaisesTheMeanAngleAndFixesSegmentVertices) {
  const dm::Pslg g = domain();
  dm::Mesh m = refined(g, 30, 5e-4);
  dm::test::expect_valid_with_pslg(m, g);
  const dm::Mesh before = m;
  const double lo = dm::test::min_angle_deg(m), mean = mean_min_angle(m), a = dm::test::covered_area(m);
  ASSERT_GE(lo, 30.0 - 1e-9);
  dm::SmoothOptions so;
  so.protect_first = g.points.size();
  const dm::SmoothStats st = dm::smooth(m, so);
  dm::test::expect_valid_with_pslg(m, g);
  EXPECT_EQ(m.num_triangles(), before.num_triangles());
  EXPECT_EQ(st.passes, 3u);
  EXPECT_GT(st.moved, m.num_vertices() / 2) << st.summary();
  EXPECT_GE(dm::test::min_angle_deg(m), lo - 1e-9) << st.summary();
  // Measured 47.5 -> 50.5 degrees.
  EXPECT_GT(mean_min_angle(m), mean + 1.5) << st.summary();
  EXPECT_NEAR(st.mean_min_angle_after, mean_min_angle(m), 1e-9);
  EXPECT_NEAR(dm::test::covered_area(m), a, 1e-12);
  // Segment, boundary and input vertices (the lone point 10 too) stay where
  // they were, exactly; only the others moved.
  const std::vector<char> fixed = on_segments(before);
  std::size_t moved = 0;
  for (dm::VertexId v = 0; v < m.num_vertices(); ++v) {
    const bool same = m.point(v).x == before.point(v).x && m.point(v).y == before.point(v).y;
    if (fixed[v] || v < g.points.size())
      EXPECT_TRUE(same) << v;
    else
      moved += !same;
  }
  EXPECT_GT(moved, (m.num_vertices() - g.points.size()) / 2);
}

TEST(Smooth, ProtectedAndMarkedVerticesStay) {
  const dm::Pslg g = domain();
  dm::Mesh m = refined(g, 25, 1e-3);
  const std::size_t protect = m.num_vertices() / 2;
  // A free vertex above `protect` with a marker of its own.
  const std::vector<char> fixed = on_segments(m);
  dm::VertexId marked = dm::kNone;
  for (dm::VertexId v = static_cast<dm::VertexId>(protect); v < m.num_vertices() && marked == dm::kNone; ++v)
    if (!fixed[v]) marked = v;
  ASSERT_NE(marked, dm::kNone);
  m.vertex_markers().resize(m.num_vertices(), 0);
  m.vertex_markers()[marked] = 9;
  const dm::Mesh before = m;
  dm::SmoothOptions so;
  so.protect_first = protect;
  const dm::SmoothStats st = dm::smooth(m, so);
  dm::test::expect_valid_with_pslg(m, g);
  EXPECT_GT(st.moved, 0u);
  std::size_t moved_above = 0;
  for (dm::VertexId v = 0; v < m.num_vertices(); ++v) {
    const bool same = m.point(v).x == before.point(v).x && m.point(v).y == before.point(v).y;
    if (v < protect || v == marked || fixed[v])
      EXPECT_TRUE(same) << v;
    else
      moved_above += !same;
  }
  EXPECT_GT(moved_above, 0u);
  // Without protection the lower half moves too (the test can fail).
  dm::Mesh free_mesh = before;
  dm::smooth(free_mesh);
  std::size_t moved_below = 0;
  for (dm::VertexId v = 0; v < protect; ++v)
    moved_below += free_mesh.point(v).x != before.point(v).x || free_mesh.point(v).y != before.point(v).y;
  EXPECT_GT(moved_below, 0u);
}

TEST(Smooth, BothTargetsKeepTheGuards) {
  const dm::Pslg g = domain();
  for (const dm::SmoothTarget target : {dm::SmoothTarget::Laplacian, dm::SmoothTarget::Odt}) {
    dm::Mesh m = refined(g, 30, 1e-3);
    const double lo = dm::test::min_angle_deg(m), mean = mean_min_angle(m);
    dm::SmoothOptions so;
    so.target = target;
    so.passes = 5;
    so.protect_first = g.points.size();
    const dm::SmoothStats st = dm::smooth(m, so);
    dm::test::expect_valid_with_pslg(m, g);
    EXPECT_GE(dm::test::min_angle_deg(m), lo - 1e-9);
    EXPECT_GT(mean_min_angle(m), mean) << st.summary();
    EXPECT_NEAR(dm::test::covered_area(m), 1.0 - 0.04, 1e-12);
  }
}

TEST(Smooth, AnAngleFloorLetsStarsGiveWayAboveIt) {
  const dm::Pslg g = domain();
  const dm::Mesh base = refined(g, 30, 1e-3);
  dm::SmoothOptions so;
  so.protect_first = g.points.size();
  dm::Mesh strict = base, floored = base;
  const dm::SmoothStats a = dm::smooth(strict, so);
  so.min_angle_deg = 30;
  const dm::SmoothStats b = dm::smooth(floored, so);
  dm::test::expect_valid_with_pslg(floored, g);
  // Stars may lose angle above 30 degrees, never below.
  EXPECT_GE(dm::test::min_angle_deg(floored), 30.0 - 1e-9);
  EXPECT_GT(b.moved, a.moved) << a.summary() << "\n" << b.summary();
  EXPECT_LT(b.rejected, a.rejected);
}

dm::SizeField ramp() {
  return [](double x, double) { return 0.01 + 0.19 * std::clamp(x, 0.0, 1.0); };
}

TEST(Smooth, ASizeFieldIsRespected) {
  const dm::Pslg g = domain();
  const dm::SizeField h = ramp();
  dm::Mesh m = refined(g, 30, 5e-5);
  dm::AdaptOptions a;
  a.refine.min_angle_deg = 30;
  a.smooth_passes = 0;
  a.coarsen.protect_first = g.points.size();
  ASSERT_TRUE(dm::adapt(m, h, a).complete);
  const dm::Mesh before = m;
  const double w = worst_size(m, h);
  ASSERT_LE(w, 1.0 + 1e-12);
  dm::SmoothOptions so;
  so.h = h;
  so.protect_first = g.points.size();
  const dm::SmoothStats st = dm::smooth(m, so);
  dm::test::expect_valid_with_pslg(m, g);
  EXPECT_GT(st.moved, 100u);
  EXPECT_LE(worst_size(m, h), std::max(1.0, w) + 1e-12) << st.summary();
  // Unguarded, the moves make some triangle too large for h: the guard
  // matters here.
  dm::Mesh unguarded = before;
  so.h = nullptr;
  dm::smooth(unguarded, so);
  EXPECT_GT(worst_size(unguarded, h), 1.0);
}

TEST(Smooth, AdaptSmoothsAndStillMeetsTheRefineBound) {
  const dm::Pslg g = domain();
  const dm::SizeField h = ramp();
  const dm::Mesh fine = refined(g, 30, 2e-4);
  double mean[2] = {0, 0};
  for (int passes : {0, 2}) {
    dm::Mesh m = fine;
    dm::AdaptOptions a;
    a.refine.min_angle_deg = 30;
    a.smooth_passes = passes;
    a.coarsen.protect_first = g.points.size();
    const dm::AdaptStats st = dm::adapt(m, h, a);
    dm::test::expect_valid_with_pslg(m, g);
    EXPECT_TRUE(st.complete) << st.refine.summary();
    EXPECT_EQ(st.smooth.passes, std::size_t(passes));
    EXPECT_GE(dm::test::min_angle_deg(m), 30.0 - 1e-9);
    EXPECT_LE(worst_size(m, h), 1.0 + 1e-12);
    EXPECT_NEAR(dm::test::covered_area(m), 1.0 - 0.04, 1e-12);
    mean[passes != 0] = mean_min_angle(m);
  }
  EXPECT_GT(mean[1], mean[0] + 1.0) << mean[0] << " -> " << mean[1];
}

// ---- the command line: --smooth[=N] ----

class SmoothCli : public dm::test::TempDirTest {
 protected:
  dm::Pslg box() const {
    write("box.poly",
          "8 2 0 1\n1 0 0 1\n2 1 0 1\n3 1 1 1\n4 0 1 1\n5 0.4 0.4 2\n6 0.6 0.4 2\n7 0.6 0.6 2\n8 0.4 0.6 2\n"
          "8 1\n1 1 2 1\n2 2 3 1\n3 3 4 1\n4 4 1 1\n5 5 6 2\n6 6 7 2\n7 7 8 2\n8 8 5 2\n1\n1 0.5 0.5\n");
    return dm::read_poly(path("box.poly"));
  }
  dm::Mesh read(const std::string& base, const dm::Pslg& g) const {
    dm::Pslg out = dm::read_node(path(base + ".node"));
    const dm::EleData ele = dm::read_ele(path(base + ".ele"), out.first_index);
    out.segments = g.segments;
    return dm::mesh_from_triangles(out, ele.triangles, ele.num_attributes, ele.attributes);
  }
};

TEST_F(SmoothCli, SmoothsAQualityMeshAndARefinedOne) {
  const dm::Pslg g = box();
  dm::test::CliResult r = run("-pq30a0.001C box");
  ASSERT_EQ(r.code, 0) << r.err;
  const dm::Mesh plain = read("box.1", g);
  r = run("-pq30a0.001C --smooth=2 --output s.node --output s.ele box");
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("Smoothed:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Check: mesh is valid"), std::string::npos) << r.out;
  const dm::Mesh s = read("s", g);
  dm::test::expect_valid_with_pslg(s, g);
  EXPECT_GE(dm::test::min_angle_deg(s), 30.0 - 1e-9);
  EXPECT_NEAR(dm::test::covered_area(s), 0.96, 1e-12);
  for (dm::VertexId v = 0; v < 8; ++v) EXPECT_EQ(s.point(v).x, g.points[v].x);
  EXPECT_GT(mean_min_angle(s), mean_min_angle(plain) + 1.0);
  // Every triangle still meets -a.
  for (dm::TriId t = 0; t < s.num_triangle_slots(); ++t) {
    const auto v = s.triangle(t);
    const dm::Point &p = s.point(v[0]), &q = s.point(v[1]), &w = s.point(v[2]);
    EXPECT_LE(0.5 * ((q.x - p.x) * (w.y - p.y) - (q.y - p.y) * (w.x - p.x)), 0.001 * (1 + 1e-12));
  }
  // -r --smooth on the output: box.2, valid, still at least 30 degrees.
  r = run("-rpC --smooth box.1");
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("Smoothed:"), std::string::npos) << r.out;
  const dm::Mesh s2 = read("box.2", g);
  dm::test::expect_valid_with_pslg(s2, g);
  EXPECT_GE(dm::test::min_angle_deg(s2), 30.0 - 1e-9);
  EXPECT_GT(mean_min_angle(s2), mean_min_angle(plain));
}

TEST_F(SmoothCli, BadCountsAndDAreUsageErrors) {
  box();
  for (const char* args : {"-pq --smooth=x box", "-pq --smooth=-1 box", "-pq --smooth= box", "-pqD --smooth box"}) {
    const dm::test::CliResult r = run(args);
    EXPECT_EQ(r.code, 1) << args << "\n" << r.err;
    EXPECT_NE(r.err.find("--smooth"), std::string::npos) << r.err;
    EXPECT_FALSE(exists("box.1.node")) << args;
  }
}

}  // namespace

// The refinement after smoothing has only what the first refinement left of
// its Steiner budget: with none left it inserts nothing, and the counts stay
// within the budget.
TEST(Smooth, RefinementAfterSmoothingStaysWithinTheBudget) {
  // examples/plate.poly at -pq30a0.002 --smooth: smoothing leaves one
  // triangle outside the bounds (measured), which the refinement after it splits.
  const dm::Pslg g = dm::read_poly(DELTAMESH_SOURCE_DIR "/examples/plate.poly");
  dm::Mesh m = dm::triangulate(g);
  dm::RefineOptions r;
  r.min_angle_deg = 30;
  r.max_area = 0.002;
  dm::RefineStats st = dm::refine(m, r);
  ASSERT_TRUE(st.complete) << st.summary();
  ASSERT_GT(st.steiner_points, 100u);
  dm::SmoothOptions so;
  so.passes = 3;
  so.max_area = r.max_area;
  so.protect_first = g.points.size();
  {
    // Control: with budget to spare, the refinement after smoothing does
    // insert points on this mesh (so the budget below is what stops it).
    dm::Mesh copy = m;
    dm::RefineStats control = st;
    std::size_t added = 0;
    dm::smooth_refined(copy, so, r, control, &added);
    EXPECT_GT(added, 0u);
  }
  r.max_steiner = st.steiner_points;  // all of it used already
  std::size_t resplit = 99;
  const std::size_t before = m.num_vertices();
  dm::smooth_refined(m, so, r, st, &resplit);
  EXPECT_EQ(resplit, 0u);
  EXPECT_EQ(m.num_vertices(), before);
  EXPECT_LE(st.steiner_points, r.max_steiner);
  dm::test::expect_valid_with_pslg(m, g);
}
