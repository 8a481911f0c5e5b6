// The benchmark inputs of deltamesh-gen that are polygons must be valid
// closed polygons: checked here on the smooth polygon of the benchmarks.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "deltamesh-gen/generators.hpp"
#include "deltamesh/triangulate.hpp"
#include "deltamesh/validate.hpp"

namespace {

using namespace deltamesh;

TEST(Generators, SmoothPolygonIsAClosedRingOnItsCurve) {
  const std::size_t n = 2000;
  const Pslg g = gen::generate(gen::Kind::Smooth, n, /*seed, unused*/ 5);
  EXPECT_EQ(g.first_index, 1);  // numbered from 1 in the file
  ASSERT_EQ(g.points.size(), n);
  ASSERT_EQ(g.segments.size(), n);
  EXPECT_TRUE(g.holes.empty());
  std::vector<int> degree(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    // Segment i joins i and i+1; the last closes the ring at vertex 0.
    EXPECT_EQ(g.segments[i].a, i);
    EXPECT_EQ(g.segments[i].b, (i + 1) % n);
    ++degree[g.segments[i].a];
    ++degree[g.segments[i].b];
    const double t = 2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(n);
    const double r = 0.7 + 0.2 * std::sin(7.0 * t) + 0.05 * std::sin(53.0 * t);
    EXPECT_NEAR(std::hypot(g.points[i].x, g.points[i].y), r, 1e-12);
    EXPECT_NEAR(std::atan2(g.points[i].y, g.points[i].x), std::remainder(t, 2.0 * std::numbers::pi), 1e-12);
  }
  for (std::size_t v = 0; v < n; ++v) EXPECT_EQ(degree[v], 2) << v;
  EXPECT_TRUE(gen::is_polygon_kind(gen::Kind::Smooth));
}

TEST(Generators, SmoothPolygonMeshesToItsOwnArea) {
  const Pslg g = gen::smooth_polygon(3000);
  TriangulateStats st;
  const Mesh mesh = triangulate(g, {}, &st);
  CheckOptions co;
  co.convex_hull = false;  // carved to the (non-convex) polygon
  co.pslg = &g;
  const CheckReport report = check(mesh, co);
  EXPECT_TRUE(report.ok()) << report.summary();
  EXPECT_EQ(report.segments_checked, g.segments.size());
  // Simple polygon, no Steiner points: n - 2 triangles whose areas add up
  // to the ring's shoelace area.
  EXPECT_EQ(mesh.num_triangles(), g.points.size() - 2);
  double ring = 0.0, tris = 0.0;
  for (std::size_t i = 0; i < g.points.size(); ++i) {
    const Point& a = g.points[i];
    const Point& b = g.points[(i + 1) % g.points.size()];
    ring += a.x * b.y - a.y * b.x;
  }
  for (TriId t = 0; t < mesh.num_triangle_slots(); ++t) {
    if (!mesh.is_real(t)) continue;
    const auto v = mesh.triangle(t);
    const Point &a = mesh.point(v[0]), &b = mesh.point(v[1]), &c = mesh.point(v[2]);
    tris += (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  }
  EXPECT_GT(ring, 0.0);  // counter-clockwise
  EXPECT_NEAR(tris, ring, 1e-9 * ring);
}

}  // namespace
