// The data structure's operations on small hand-made meshes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <ranges>
#include <set>
#include <utility>
#include <vector>

#include "deltamesh/delaunay.hpp"
#include "deltamesh/mesh.hpp"
#include "deltamesh/validate.hpp"
#include "mesh/editor.hpp"

using namespace deltamesh;

namespace {

// Unit square split along 0-2: triangles (0,1,2), (0,2,3), compacted.
Mesh square() {
  Mesh m;
  m.add_vertex({0, 0});
  m.add_vertex({1, 0});
  m.add_vertex({1, 1});
  m.add_vertex({0, 1});
  const TriId a = m.add_triangle(0, 1, 2);
  const TriId b = m.add_triangle(0, 2, 3);
  m.link(3 * a + 2, 3 * b + 0);  // 2->0 with 0->2
  m.compact();
  return m;
}

CheckOptions no_delaunay() {
  CheckOptions o;
  o.delaunay = false;
  return o;
}

}  // namespace

TEST(Mesh, CompactSetsBoundaryOutEdges) {
  const Mesh m = square();
  EXPECT_EQ(m.num_triangles(), 2u);
  EXPECT_TRUE(check(m).ok()) << check(m).summary();
  for (VertexId v = 0; v < 4; ++v) {
    const HalfEdgeId e = m.out_edge(v);
    ASSERT_NE(e, kNone);
    EXPECT_EQ(m.origin(e), v);
    EXPECT_EQ(m.rotate_cw(e), kNone) << "out-edge of boundary vertex " << v << " is not the most clockwise";
  }
}

TEST(Mesh, RotaryTraversalAndFindEdge) {
  const Mesh m = square();
  std::vector<VertexId> around0;
  m.for_each_out_edge(0, [&](HalfEdgeId e) {
    around0.push_back(m.dest(e));
    return true;
  });
  EXPECT_EQ(around0, (std::vector<VertexId>{1, 2}));
  EXPECT_NE(m.find_edge(0, 2), kNone);
  EXPECT_NE(m.find_edge(2, 0), kNone);
  EXPECT_EQ(m.find_edge(1, 3), kNone);
}

TEST(Mesh, FlipTurnsTheDiagonal) {
  Mesh m = square();
  const HalfEdgeId e = m.find_edge(0, 2);
  const HalfEdgeId cd = m.flip(e);
  EXPECT_EQ(m.num_triangles(), 2u);
  EXPECT_TRUE((m.origin(cd) == 1 && m.dest(cd) == 3) || (m.origin(cd) == 3 && m.dest(cd) == 1));
  EXPECT_EQ(m.find_edge(0, 2), kNone);
  EXPECT_NE(m.find_edge(1, 3), kNone);
  EXPECT_TRUE(check(m).ok()) << check(m).summary();
}

TEST(Mesh, FlipKeepsConstraintFlagsOnOuterEdges) {
  Mesh m = square();
  const HalfEdgeId e01 = m.find_edge(0, 1);
  m.set_edge_flags(e01, kConstrained);
  m.flip(m.find_edge(0, 2));
  EXPECT_TRUE(m.is_constrained(m.find_edge(0, 1)));
  EXPECT_FALSE(m.is_constrained(m.find_edge(1, 3) != kNone ? m.find_edge(1, 3) : m.find_edge(3, 1)));
}

TEST(Mesh, SplitTriangleAndEdge) {
  Mesh m = square();
  const VertexId p = m.add_vertex({0.75, 0.25});
  const HalfEdgeId r = m.split_triangle(0, p);
  EXPECT_EQ(m.origin(r), p);
  EXPECT_EQ(m.num_triangles(), 4u);
  EXPECT_TRUE(check(m, no_delaunay()).ok()) << check(m, no_delaunay()).summary();
  // Split the interior diagonal 0-2 and a boundary edge 2-3.
  const VertexId q = m.add_vertex({0.5, 0.5});
  m.split_edge(m.find_edge(0, 2), q);
  EXPECT_EQ(m.num_triangles(), 6u);
  const VertexId s = m.add_vertex({0.5, 1.0});
  m.split_edge(m.find_edge(2, 3), s);
  EXPECT_EQ(m.num_triangles(), 7u);
  const CheckReport rep = check(m, no_delaunay());
  EXPECT_TRUE(rep.ok()) << rep.summary();
  EXPECT_EQ(m.rotate_cw(m.out_edge(s)), kNone);
}

TEST(Mesh, ValidatorCatchesBrokenMeshes) {
  {  // clockwise triangle
    Mesh m;
    m.add_vertex({0, 0});
    m.add_vertex({1, 0});
    m.add_vertex({0, 1});
    m.add_triangle(0, 2, 1);
    m.compact();
    EXPECT_FALSE(check(m).ok());
  }
  {  // asymmetric twins
    Mesh m = square();
    deltamesh::detail::MeshEditor(m).twins()[0] = 4;
    EXPECT_FALSE(check(m).ok());
  }
  {  // non-Delaunay diagonal: a long thin quad split the wrong way
    Mesh m;
    m.add_vertex({0, 0});
    m.add_vertex({10, -1});
    m.add_vertex({20, 0});
    m.add_vertex({10, 1});
    const TriId a = m.add_triangle(0, 1, 2);
    const TriId b = m.add_triangle(0, 2, 3);
    m.link(3 * a + 2, 3 * b);
    m.compact();
    const CheckReport r = check(m);
    EXPECT_FALSE(r.ok());
    EXPECT_NE(r.summary().find("Delaunay"), std::string::npos);
    EXPECT_TRUE(check(m, no_delaunay()).ok());
  }
  {  // non-convex boundary
    Mesh m;
    m.add_vertex({0, 0});
    m.add_vertex({2, 0});
    m.add_vertex({1, 0.2});
    m.add_vertex({1, 2});
    const TriId a = m.add_triangle(0, 2, 3);
    const TriId b = m.add_triangle(2, 1, 3);
    m.link(3 * a + 1, 3 * b + 2);
    m.compact();
    CheckOptions o = no_delaunay();
    EXPECT_FALSE(check(m, o).ok());
    o.convex_hull = false;
    EXPECT_TRUE(check(m, o).ok()) << check(m, o).summary();
  }
  {  // out-edge of a vertex pointing elsewhere
    Mesh m = square();
    deltamesh::detail::MeshEditor(m).out_edges()[1] = m.out_edge(3);
    EXPECT_FALSE(check(m).ok());
  }
}

TEST(Mesh, LocateReportsEveryKind) {
  DelaunayOptions opt;
  opt.keep_ghosts = true;
  const std::vector<Point> pts = {{0, 0}, {2, 0}, {2, 2}, {0, 2}, {1, 1}};
  const Mesh m = delaunay(pts, opt);
  EXPECT_EQ(m.locate({0.5, 0.2}).kind, Location::Kind::InTriangle);
  const Location on_vertex = m.locate({2, 2});
  EXPECT_EQ(on_vertex.kind, Location::Kind::OnVertex);
  EXPECT_EQ(on_vertex.vertex, 2u);
  const Location on_edge = m.locate({1, 0});
  EXPECT_EQ(on_edge.kind, Location::Kind::OnEdge);
  EXPECT_EQ(std::min(m.origin(on_edge.edge), m.dest(on_edge.edge)), 0u);
  const Location out = m.locate({5, 1});
  EXPECT_EQ(out.kind, Location::Kind::Outside);
  EXPECT_TRUE(m.is_ghost(out.tri));
}

TEST(Mesh, MemoryAccounting) {
  const Mesh m = square();
  EXPECT_GE(m.memory_bytes(), 4 * sizeof(Point) + 6 * 2 * sizeof(std::uint32_t));
}

TEST(Mesh, MarkersFollowEdgesThroughFlipsAndSplits) {
  Mesh m = square();
  m.constrain_edge(m.find_edge(0, 1), 7);
  m.constrain_edge(m.find_edge(1, 2), 9);
  m.flip(m.find_edge(0, 2));
  EXPECT_EQ(m.edge_marker(m.find_edge(0, 1)), 7);
  EXPECT_EQ(m.edge_marker(m.find_edge(1, 2)), 9);
  const VertexId p = m.add_vertex({0.5, 0.0});
  m.split_edge(m.find_edge(0, 1), p);
  EXPECT_EQ(m.edge_marker(m.find_edge(0, p)), 7);
  EXPECT_EQ(m.edge_marker(m.find_edge(p, 1)), 7);
  EXPECT_TRUE(m.is_constrained(m.find_edge(p, 1)));
  const VertexId q = m.add_vertex({0.6, 0.6});
  const Location loc = m.locate(m.point(q));
  ASSERT_EQ(loc.kind, Location::Kind::InTriangle);
  m.split_triangle(loc.tri, q);
  EXPECT_EQ(m.edge_marker(m.find_edge(1, 2)), 9);
  EXPECT_TRUE(check(m, no_delaunay()).ok()) << check(m, no_delaunay()).summary();
}

TEST(Mesh, ValidatorAcceptsAPinchVertexWithOneFanPerBoundaryEdge) {
  // Two triangles meeting only at vertex 0 (as where two holes touch).
  Mesh m;
  m.add_vertex({0, 0});
  m.add_vertex({1, -1});
  m.add_vertex({1, 1});
  m.add_vertex({-1, 1});
  m.add_vertex({-1, -1});
  m.add_triangle(0, 1, 2);
  m.add_triangle(0, 3, 4);
  m.compact();
  CheckOptions o;
  o.convex_hull = false;
  const CheckReport r = check(m, o);
  EXPECT_TRUE(r.ok()) << r.summary();
  // A third triangle overlapping the first one's fan is still caught.
  Mesh bad;
  bad.add_vertex({0, 0});
  bad.add_vertex({1, -1});
  bad.add_vertex({1, 1});
  bad.add_vertex({2, 0.5});
  bad.add_triangle(0, 1, 2);
  bad.add_triangle(0, 1, 3);
  bad.compact();
  EXPECT_FALSE(check(bad, o).ok());
}

// The ranges skip dead and ghost slots, name each edge once, and agree with
// Euler's formula for a triangulation of a convex point set.
TEST(Mesh, RangesVisitRealTrianglesEdgesAndBoundaryOnce) {
  static_assert(std::ranges::forward_range<decltype(std::declval<const Mesh&>().triangles())>);
  std::vector<Point> pts;
  std::uint32_t s = 12345;
  for (int i = 0; i < 200; ++i) {
    s = s * 1664525u + 1013904223u;
    const double x = (s >> 8) / double(1 << 24);
    s = s * 1664525u + 1013904223u;
    pts.push_back({x, (s >> 8) / double(1 << 24)});
  }
  for (const bool ghosts : {false, true}) {
    DelaunayOptions opt;
    opt.keep_ghosts = ghosts;
    Mesh m = delaunay(pts, opt);
    CheckOptions co;
    ASSERT_TRUE(check(m, co).ok()) << check(m, co).summary();
    std::vector<TriId> by_hand;
    for (TriId t = 0; t < m.num_triangle_slots(); ++t)
      if (m.is_real(t)) by_hand.push_back(t);
    const std::vector<TriId> ranged(m.triangles().begin(), m.triangles().end());
    EXPECT_EQ(ranged, by_hand);
    EXPECT_EQ(ranged.size(), m.num_triangles());

    std::set<std::pair<VertexId, VertexId>> edges, from_triangles, boundary;
    for (HalfEdgeId e : m.edges())
      EXPECT_TRUE(edges.insert(std::minmax(m.origin(e), m.dest(e))).second) << "edge named twice";
    for (TriId t : m.triangles())
      for (HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e) from_triangles.insert(std::minmax(m.origin(e), m.dest(e)));
    EXPECT_EQ(edges, from_triangles);
    for (HalfEdgeId e : m.boundary_edges()) boundary.insert(std::minmax(m.origin(e), m.dest(e)));
    // Euler for a triangulated convex polygon with V vertices, h on the hull:
    // E = 3V - 3 - h and T = 2V - 2 - h.
    const std::size_t V = m.num_vertices(), h = boundary.size();
    EXPECT_EQ(edges.size(), 3 * V - 3 - h);
    EXPECT_EQ(m.num_triangles(), 2 * V - 2 - h);
    EXPECT_EQ(std::ranges::distance(m.vertices()), static_cast<std::ptrdiff_t>(V));
  }
}
