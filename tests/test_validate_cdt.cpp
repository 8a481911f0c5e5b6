// The validator's PSLG check: every segment must be a chain of constrained
// edges. It must accept what constrained_triangulation produces and catch
// a segment that is missing, unconstrained or bent through a vertex off it.
#include <gtest/gtest.h>

#include <string>

#include "deltamesh-gen/generators.hpp"
#include "deltamesh/cdt.hpp"
#include "deltamesh/delaunay.hpp"
#include "deltamesh/validate.hpp"

using namespace deltamesh;

namespace {

CheckReport check_with(const Mesh& m, const Pslg& g, bool delaunay = true) {
  CheckOptions o;
  o.pslg = &g;
  o.delaunay = delaunay;
  return check(m, o);
}

bool mentions(const CheckReport& r, const std::string& text) {
  for (const std::string& p : r.problems)
    if (p.find(text) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST(ValidateSegments, AcceptsAConstrainedTriangulation) {
  const Pslg g = gen::star_polygon(2000, 4);
  const Mesh m = constrained_triangulation(g);
  const CheckReport r = check_with(m, g);
  EXPECT_TRUE(r.ok()) << r.summary();
  EXPECT_EQ(r.segments_checked, g.segments.size());
  EXPECT_NE(r.summary().find("2000 segments present"), std::string::npos) << r.summary();
}

TEST(ValidateSegments, AcceptsACompactedMesh) {
  // Without ghost triangles, hull edges have a single half-edge.
  Pslg g = gen::star_polygon(500, 2);
  g.segments.push_back({0, 250, 0});
  Mesh m = constrained_triangulation(g);
  m.compact();
  const CheckReport r = check_with(m, g);
  EXPECT_TRUE(r.ok()) << r.summary();
  EXPECT_EQ(r.segments_checked, g.segments.size());
}

TEST(ValidateSegments, AnUnconstrainedEdgeIsNotASegment) {
  // A Delaunay triangulation has the edge but nothing is constrained.
  Pslg g;
  g.points = {{0, 0}, {2, 0}, {1, 1}, {1, -1.5}};
  const Mesh m = delaunay(g.points);
  ASSERT_NE(m.find_edge(0, 3), kNone);
  g.segments = {{0, 3, 0}};
  const CheckReport r = check_with(m, g);
  EXPECT_FALSE(r.ok());
  EXPECT_TRUE(mentions(r, "segment 0 (0-3) is not a chain of constrained edges")) << r.summary();
}

TEST(ValidateSegments, AMissingSegmentIsReported) {
  // Kite: the Delaunay diagonal is 2-3; segment 0-1 is not an edge.
  Pslg g;
  g.points = {{0, 0}, {4, 0}, {2, 1}, {2, -1}};
  g.segments = {{2, 3, 0}};
  const Mesh m = constrained_triangulation(g);
  EXPECT_TRUE(check_with(m, g).ok());
  Pslg other = g;
  other.segments = {{2, 3, 0}, {0, 1, 0}};
  const CheckReport r = check_with(m, other);
  EXPECT_FALSE(r.ok());
  EXPECT_TRUE(mentions(r, "segment 1 (0-1)")) << r.summary();
}

TEST(ValidateSegments, ABentChainIsNotTheSegment) {
  // Constrained 0-1 and 1-2 with 1 off the line 0-2: not a chain for 0-2.
  Pslg g;
  g.points = {{0, 0}, {1, 0.25}, {2, 0}, {1, 2}, {1, -2}};
  g.segments = {{0, 1, 0}, {1, 2, 0}};
  const Mesh m = constrained_triangulation(g);
  ASSERT_TRUE(check_with(m, g).ok());
  Pslg other = g;
  other.segments = {{0, 2, 0}};
  EXPECT_FALSE(check_with(m, other).ok());
}

TEST(ValidateSegments, ChainsThroughVerticesOnTheSegment) {
  Pslg g;
  g.points = {{0, 0}, {1, 0}, {2, 0}, {3, 0}, {1.5, 1}, {1.5, -1}};
  g.segments = {{0, 3, 0}};
  const Mesh m = constrained_triangulation(g);
  EXPECT_TRUE(check_with(m, g).ok());
  // The chain is constrained; its pieces are segments too, in either direction.
  Pslg pieces = g;
  pieces.segments = {{2, 1, 0}, {3, 2, 0}, {0, 2, 0}};
  EXPECT_TRUE(check_with(m, pieces).ok()) << check_with(m, pieces).summary();
}

TEST(ValidateSegments, DuplicateEndpointsAndZeroLength) {
  Pslg g;
  g.points = {{0, 0}, {2, 0}, {1, 1}, {1, -1}, {2, 0}};
  g.segments = {{0, 4, 0}, {4, 1, 0}, {2, 3, 0}};
  const Mesh m = constrained_triangulation(g);
  const CheckReport r = check_with(m, g);
  EXPECT_TRUE(r.ok()) << r.summary();
  EXPECT_EQ(r.segments_checked, 2u);  // 4-1 has zero length
}

TEST(ValidateSegments, EndpointOutOfRange) {
  Pslg g;
  g.points = {{0, 0}, {2, 0}, {1, 1}};
  const Mesh m = delaunay(g.points);
  g.segments = {{0, 7, 0}};
  const CheckReport r = check_with(m, g);
  EXPECT_TRUE(mentions(r, "segment 0 refers to vertex 7")) << r.summary();
}

TEST(ValidateSegments, CrossingsBendChainsWithinRoundingDistance) {
  // Segments whose crossings are rounded: the chains bend by a rounding
  // error at the new vertices and are still accepted.
  Pslg g;
  gen::Rng rng(11);
  g.points = gen::uniform_points(200, 11);
  for (int i = 0; i < 80; ++i) {
    const auto a = static_cast<VertexId>(rng.below(200)), b = static_cast<VertexId>(rng.below(200));
    if (a != b) g.segments.push_back({a, b, 0});
  }
  CdtStats st;
  const Mesh m = constrained_triangulation(g, {}, &st);
  EXPECT_GT(st.intersections, 100u);
  const CheckReport r = check_with(m, g);
  EXPECT_TRUE(r.ok()) << r.summary();
}
