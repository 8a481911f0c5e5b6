// The mesh layer's shared kernels (src/mesh): point location with each edge
// order, the straight walks (along a segment, towards a point), constrained Lawson legalization, the
// Bowyer-Watson cavity, the carry of per-half-edge data, the edge and vertex
// marker rules, and invariant failures typed as InternalError.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "core/angles.hpp"
#include "deltamesh/delaunay.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/mesh.hpp"
#include "deltamesh/predicates.hpp"
#include "deltamesh/validate.hpp"
#include "algo/insertion.hpp"
#include "mesh/cavity.hpp"
#include "mesh/edge_rules.hpp"
#include "mesh/legalize.hpp"
#include "mesh/locate.hpp"
#include "mesh/editor.hpp"

using namespace deltamesh;

namespace {

// A long thin quadrilateral (0,0), (10,-1), (20,0), (10,1) split along the
// long diagonal 0-2 (not Delaunay), compacted.
Mesh thin_quad() {
  Mesh m;
  m.add_vertex({0, 0});
  m.add_vertex({10, -1});
  m.add_vertex({20, 0});
  m.add_vertex({10, 1});
  const TriId a = m.add_triangle(0, 1, 2);
  const TriId b = m.add_triangle(0, 2, 3);
  m.link(3 * a + 2, 3 * b + 0);
  m.compact();
  return m;
}

std::vector<Point> random_points(std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Point> pts(n);
  for (Point& p : pts) p = {u(rng), u(rng)};
  return pts;
}

// The real triangle strictly containing p, by brute force.
TriId containing(const Mesh& m, const Point& p) {
  for (TriId t = 0; t < m.num_triangle_slots(); ++t) {
    if (!m.is_real(t)) continue;
    const auto v = m.triangle(t);
    if (orient2d(m.point(v[0]), m.point(v[1]), p) > 0 && orient2d(m.point(v[1]), m.point(v[2]), p) > 0 &&
        orient2d(m.point(v[2]), m.point(v[0]), p) > 0)
      return t;
  }
  return kNone;
}

}  // namespace

TEST(MeshKernels, ALocationWalkOnADegenerateTriangleIsAnInternalError) {
  // A deliberately broken mesh (three collinear corners): the walk finds p on
  // all three edges but at no corner, which no valid mesh allows.
  Mesh m;
  m.add_vertex({0, 0});
  m.add_vertex({1, 0});
  m.add_vertex({2, 0});
  m.add_triangle(0, 1, 2);
  m.compact();
  EXPECT_FALSE(check(m).ok());
  try {
    m.locate({0.5, 0});
    FAIL() << "locate on a degenerate triangle returned";
  } catch (const InternalError& e) {
    EXPECT_EQ(e.where(), "visibility_walk");
  } catch (const InputError&) {
    FAIL() << "a broken invariant was reported as bad input";
  }
}

TEST(MeshKernels, EveryEdgeOrderFindsTheContainingTriangle) {
  DelaunayOptions opt;
  opt.keep_ghosts = true;
  const Mesh m = delaunay(random_points(400, 7), opt);
  ASSERT_TRUE(check(m).ok());
  const VertexId* tv = m.triangle_vertices().data();
  std::vector<HalfEdgeId> twins(m.triangle_vertices().size());
  for (HalfEdgeId e = 0; e < twins.size(); ++e) twins[e] = m.twin(e);
  const Point* pts = m.points().data();
  TriId start = 0;
  while (!m.is_real(start)) ++start;
  std::uint64_t state = 12345;
  for (Point p : random_points(200, 8)) {
    p = {0.2 + 0.6 * p.x, 0.2 + 0.6 * p.y};  // well inside the hull
    const TriId want = containing(m, p);
    ASSERT_NE(want, kNone);
    const auto fixed = detail::visibility_walk(tv, twins.data(), pts, p, start, detail::FixedEdgeOrder{});
    const auto rotation =
        detail::visibility_walk(tv, twins.data(), pts, p, start, detail::RandomRotationOrder{99});
    const auto pair = detail::visibility_walk(tv, twins.data(), pts, p, start, detail::RandomPairOrder{state});
    for (const auto& w : {fixed, rotation, pair}) {
      EXPECT_EQ(w.loc.kind, Location::Kind::InTriangle);
      EXPECT_EQ(w.loc.tri, want);
      EXPECT_GE(w.steps, 1u);
    }
  }
  // A point outside the hull ends at a ghost whose hull edge it sees from
  // outside: left of the ghost's half-edge, right of the real one.
  const auto out = detail::visibility_walk(tv, twins.data(), pts, {3, 0.5}, start, detail::FixedEdgeOrder{});
  ASSERT_EQ(out.loc.kind, Location::Kind::Outside);
  ASSERT_TRUE(m.is_ghost(out.loc.tri));
  EXPECT_GT(orient2d(m.point(m.origin(out.loc.edge)), m.point(m.dest(out.loc.edge)), {3, 0.5}), 0);
  EXPECT_FALSE(m.is_ghost(tri_of(m.twin(out.loc.edge))));
}

TEST(MeshKernels, TheSegmentWalkCrossesExactlyTheEdgesTheSegmentCrosses) {
  DelaunayOptions opt;
  opt.keep_ghosts = true;
  Mesh m = delaunay(random_points(300, 3), opt);
  ASSERT_TRUE(check(m).ok());
  const VertexId a = 0, b = 1;
  const Point pa = m.point(a), pb = m.point(b);
  // Brute force: edges of real triangles whose ends lie strictly on
  // opposite sides of line ab and whose line separates a from b.
  std::size_t expected = 0;
  for_each_edge(m, [&](HalfEdgeId e, bool) {
    const Point& p = m.point(m.origin(e));
    const Point& q = m.point(m.dest(e));
    const double op = orient2d(pa, pb, p), oq = orient2d(pa, pb, q);
    const double oa = orient2d(p, q, pa), ob = orient2d(p, q, pb);
    if (op * oq < 0 && oa * ob < 0) ++expected;
  });
  ASSERT_GT(expected, 0u);  // a and b are not neighbours in this triangulation

  const VertexId* tv = m.triangle_vertices().data();
  std::vector<HalfEdgeId> twins(m.triangle_vertices().size());
  for (HalfEdgeId e = 0; e < twins.size(); ++e) twins[e] = m.twin(e);
  const Point* pts = m.points().data();
  const std::size_t limit = twins.size() + 3;
  const detail::SegmentExit ex = detail::segment_exit(tv, twins.data(), pts, m.out_edge(a), pa, pa, pb, limit);
  ASSERT_EQ(ex.kind, detail::SegmentExit::Kind::Enters);
  std::vector<HalfEdgeId> crossed;
  const detail::SegmentWalk w = detail::walk_segment(
      tv, twins.data(), pts, pa, pb, b, ex.edge,
      [&](HalfEdgeId h) {
        crossed.push_back(h);
        return true;
      },
      limit);
  EXPECT_EQ(w.kind, detail::SegmentWalk::Kind::Reached);
  EXPECT_EQ(crossed.size(), expected);
  for (HalfEdgeId h : crossed) {  // each runs from the right of ab to its left
    EXPECT_LT(orient2d(pa, pb, m.point(m.origin(h))), 0);
    EXPECT_GT(orient2d(pa, pb, m.point(m.dest(h))), 0);
  }
  // A caller's refusal (a constraint) stops the walk at that edge.
  const HalfEdgeId wall = crossed[crossed.size() / 2];
  const detail::SegmentWalk stopped = detail::walk_segment(
      tv, twins.data(), pts, pa, pb, b, ex.edge, [&](HalfEdgeId h) { return h != wall; }, limit);
  EXPECT_EQ(stopped.kind, detail::SegmentWalk::Kind::Stopped);
  EXPECT_EQ(stopped.edge, wall);
}

TEST(MeshKernels, TheWalkToAPointEndsInItsTriangleOrAtTheFirstEdgeItMayNotCross) {
  Mesh m = delaunay(random_points(300, 5));  // compacted: hull edges have no twins
  ASSERT_TRUE(check(m).ok());
  const VertexId* tv = m.triangle_vertices().data();
  std::vector<HalfEdgeId> twins(m.triangle_vertices().size());
  for (HalfEdgeId e = 0; e < twins.size(); ++e) twins[e] = m.twin(e);
  const Point* pts = m.points().data();
  const auto in_closed = [&](TriId t, const Point& p) {
    const auto v = m.triangle(t);
    return orient2d(m.point(v[0]), m.point(v[1]), p) >= 0 && orient2d(m.point(v[1]), m.point(v[2]), p) >= 0 &&
           orient2d(m.point(v[2]), m.point(v[0]), p) >= 0;
  };
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-0.2, 1.2);  // some targets beyond the hull
  std::size_t reached = 0, left_mesh = 0, walls = 0, on_vertex = 0;
  for (int k = 0; k < 400; ++k) {
    const TriId t = static_cast<TriId>(rng() % m.num_triangle_slots());
    const auto v = m.triangle(t);
    const Point o{(m.point(v[0]).x + m.point(v[1]).x + m.point(v[2]).x) / 3,
                  (m.point(v[0]).y + m.point(v[1]).y + m.point(v[2]).y) / 3};
    Point c{u(rng), u(rng)};
    if (k % 10 == 0) c = m.point(static_cast<VertexId>(rng() % m.num_vertices()));  // exactly on a vertex
    if (in_closed(t, c)) continue;  // the walk starts by leaving t
    const HalfEdgeId exit = detail::line_exit(tv, pts, t, o, c);
    ASSERT_NE(exit, kNone);
    ASSERT_EQ(tri_of(exit), t);
    EXPECT_LT(orient2d(o, c, m.point(m.origin(exit))), 0);
    EXPECT_GE(orient2d(o, c, m.point(m.dest(exit))), 0);
    std::vector<HalfEdgeId> crossed;
    const auto open = [&](HalfEdgeId h) {
      if (twins[h] == kNone) return false;
      crossed.push_back(h);
      return true;
    };
    detail::PointTarget target{c};
    const detail::SegmentWalk w = detail::walk_line(tv, twins.data(), pts, o, c, target, exit, open, twins.size());
    for (HalfEdgeId h : crossed) {  // each separates o (before it) from c (beyond it)
      EXPECT_GT(orient2d(m.point(m.origin(h)), m.point(m.dest(h)), o), 0);
      EXPECT_LT(orient2d(m.point(m.origin(h)), m.point(m.dest(h)), c), 0);
    }
    if (w.kind == detail::SegmentWalk::Kind::Reached) {
      ++reached;
      const TriId at = tri_of(w.edge);
      EXPECT_TRUE(in_closed(at, c));
      EXPECT_EQ(target.side, orient2d(m.point(m.origin(w.edge)), m.point(m.dest(w.edge)), c));
      const auto a = m.triangle(at);
      if (k % 10 == 0) {
        EXPECT_TRUE(c == m.point(a[0]) || c == m.point(a[1]) || c == m.point(a[2]));
        ++on_vertex;
      } else {
        EXPECT_EQ(at, containing(m, c));
      }
      // A caller's refusal (a constraint) on the way stops the walk there.
      if (!crossed.empty()) {
        const HalfEdgeId wall = crossed[crossed.size() / 2];
        detail::PointTarget again{c};
        const detail::SegmentWalk s = detail::walk_line(
            tv, twins.data(), pts, o, c, again, exit, [&](HalfEdgeId h) { return h != wall; }, twins.size());
        EXPECT_EQ(s.kind, detail::SegmentWalk::Kind::Stopped);
        EXPECT_EQ(s.edge, wall);
        ++walls;
      }
    } else {
      // Stopped at the hull: c lies beyond that hull edge, outside the mesh.
      ASSERT_EQ(w.kind, detail::SegmentWalk::Kind::Stopped);
      EXPECT_EQ(twins[w.edge], kNone);
      EXPECT_LT(orient2d(m.point(m.origin(w.edge)), m.point(m.dest(w.edge)), c), 0);
      EXPECT_EQ(containing(m, c), kNone);
      ++left_mesh;
    }
  }
  EXPECT_GT(reached, 50u);
  EXPECT_GT(left_mesh, 20u);
  EXPECT_GT(walls, 20u);
  EXPECT_GT(on_vertex, 10u);
}

TEST(MeshKernels, ConstrainedLawsonFlipsAllButConstrainedEdges) {
  Mesh m = thin_quad();
  CheckOptions opt;
  ASSERT_FALSE(check(m, opt).ok());  // the long diagonal is not locally Delaunay
  EXPECT_EQ(detail::constrained_lawson_flips(m), 1u);
  EXPECT_TRUE(check(m, opt).ok());
  EXPECT_NE(m.find_edge(1, 3), kNone);

  Mesh c = thin_quad();
  c.constrain_edge(c.find_edge(0, 2), 4);
  EXPECT_EQ(detail::constrained_lawson_flips(c), 0u);
  EXPECT_TRUE(check(c, opt).ok());  // constrained Delaunay: the segment is kept
  EXPECT_NE(c.find_edge(0, 2), kNone);
}

TEST(MeshKernels, LegalizationOnRawArraysMatchesTheMeshOperations) {
  // The same insertion legalized through Mesh::flip and through the raw
  // arrays (flags, markers and out-edges carried) gives the same mesh.
  DelaunayOptions opt;
  opt.keep_ghosts = true;
  const std::vector<Point> pts = random_points(200, 11);
  Mesh base = delaunay(pts, opt);
  base.constrain_edge(base.out_edge(5), 7);  // a segment the flips must keep
  const Point p{0.5, 0.5};
  const Location loc = base.locate(p);
  ASSERT_EQ(loc.kind, Location::Kind::InTriangle);
  auto split = [&](Mesh& m, std::vector<HalfEdgeId>& stack) {
    const VertexId v = m.add_vertex(p);
    const HalfEdgeId r = m.split_triangle(loc.tri, v);  // v -> first corner, in slot loc.tri
    stack = {r - 2, m.twin(r - 1) - 2, m.twin(r) - 1};
    return v;
  };
  Mesh a = base, b = base;
  std::vector<HalfEdgeId> sa, sb;
  const VertexId va = split(a, sa), vb = split(b, sb);
  detail::MeshTopology ta(a);
  const std::size_t flips_a = detail::legalize_around_vertex(ta, va, sa).flips;
  detail::RawTopology<detail::kCarryFlags | detail::kCarryMarkers | detail::kCarryOutEdges> tb(
      detail::MeshArrays::of(b));
  const std::size_t flips_b = detail::legalize_around_vertex(tb, vb, sb).flips;
  EXPECT_GT(flips_a, 0u);
  EXPECT_EQ(flips_a, flips_b);
  EXPECT_TRUE(std::equal(a.triangle_vertices().begin(), a.triangle_vertices().end(), b.triangle_vertices().begin()));
  EXPECT_EQ(deltamesh::detail::MeshEditor(a).edge_markers(), deltamesh::detail::MeshEditor(b).edge_markers());
  EXPECT_EQ(deltamesh::detail::MeshEditor(a).edge_flags(), deltamesh::detail::MeshEditor(b).edge_flags());
  EXPECT_EQ(deltamesh::detail::MeshEditor(a).out_edges(), deltamesh::detail::MeshEditor(b).out_edges());
  EXPECT_TRUE(check(a).ok());
}

TEST(MeshKernels, AnArrayCarriedBesideTheMeshMovesLikeItsMarkers) {
  // Delaunay insertions through DelaunayInserter carrying a copy of the
  // markers (a CDT builder's segment ids): after splits and flips the copy
  // equals the mesh's own markers, edge for edge.
  DelaunayOptions opt;
  opt.keep_ghosts = true;
  Mesh m = delaunay(random_points(300, 5), opt);
  std::vector<HalfEdgeId> segments;
  for (HalfEdgeId e : m.edges()) segments.push_back(e);
  for (std::size_t i = 0; i < segments.size(); i += 97) m.constrain_edge(segments[i], static_cast<int>(i + 1));
  const VertexId sa = m.origin(segments[97]), sb = m.dest(segments[97]);
  std::vector<int> carried = detail::MeshEditor(m).edge_markers();
  detail::DelaunayInserter inserter(m, &carried);
  std::size_t flips = 0;
  for (const Point& p : random_points(200, 6)) {
    inserter.insert_point(p, 0);
    flips = inserter.flips();
  }
  // A point on a constrained edge splits it: both halves keep the marker.
  const HalfEdgeId s = m.find_edge(sa, sb);  // (flips around it moved it to other slots)
  ASSERT_NE(s, kNone);
  ASSERT_EQ(m.edge_marker(s), 98);
  const Point mid{0.5 * (m.point(m.origin(s)).x + m.point(m.dest(s)).x),
                  0.5 * (m.point(m.origin(s)).y + m.point(m.dest(s)).y)};
  inserter.insert_point(mid, tri_of(s));
  EXPECT_GT(flips, 0u);
  EXPECT_EQ(carried, detail::MeshEditor(m).edge_markers());
  EXPECT_TRUE(check(m).ok());
}

TEST(MeshKernels, TheCavityIsEveryTriangleWhoseCircleHoldsThePointAndItsFanIsDelaunay) {
  Mesh m = delaunay(random_points(400, 21));
  detail::MeshEditor(m).edge_flags().assign(m.triangle_vertices().size(), 0);
  for (const Point& p : random_points(20, 22)) {
    const TriId seed = containing(m, p);
    if (seed == kNone) continue;  // outside the hull
    detail::CavitySet cavity;
    std::vector<HalfEdgeId> stack{3 * seed + 2, 3 * seed + 1, 3 * seed};
    std::vector<HalfEdgeId> boundary;
    cavity.begin();
    cavity.add(seed);
    ASSERT_TRUE(detail::grow_cavity(detail::MeshArrays::of(m), p, cavity, stack,
                                    [&](HalfEdgeId e) { boundary.push_back(e); }));
    // Find: by brute force, the real triangles whose circumcircle holds p.
    std::vector<TriId> expected;
    for (TriId t = 0; t < m.num_triangle_slots(); ++t) {
      const auto v = m.triangle(t);
      if (m.is_real(t) && incircle(m.point(v[0]), m.point(v[1]), m.point(v[2]), p) > 0) expected.push_back(t);
    }
    std::vector<TriId> got = cavity.tris();
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, expected);
    ASSERT_EQ(boundary.size(), got.size() + 2);  // a point inside: a closed fan
    for (std::size_t i = 0; i < boundary.size(); ++i) {
      EXPECT_GT(orient2d(m.point(m.origin(boundary[i])), m.point(m.dest(boundary[i])), p), 0);
      EXPECT_EQ(m.dest(boundary[i]), m.origin(boundary[(i + 1) % boundary.size()]));  // counter-clockwise
    }
    // Commit: the fan into the cavity's slots and two new ones.
    struct Edge {
      VertexId a, b;
      HalfEdgeId outer;
    };
    std::vector<Edge> edges;
    for (HalfEdgeId e : boundary) edges.push_back({m.origin(e), m.dest(e), m.twin(e)});
    const VertexId v = m.add_vertex(p);
    std::vector<TriId> fan = cavity.tris();
    while (fan.size() < edges.size()) fan.push_back(m.add_triangle(v, v, v));
    detail::MeshEditor(m).edge_flags().resize(m.triangle_vertices().size(), 0);
    const detail::MeshArrays a = detail::MeshArrays::of(m);
    for (std::size_t i = 0; i < edges.size(); ++i) {
      detail::write_fan_triangle<detail::kCarryFlags>(a, fan[i], v, edges[i].a, edges[i].b, edges[i].outer, 0, 0);
      HalfEdgeId& out = detail::MeshEditor(m).out_edges()[edges[i].a];
      if (cavity.contains(tri_of(out))) out = 3 * fan[i] + 1;  // (cavity: the old slots)
    }
    detail::link_spokes(a.tw, fan.data(), 0, fan.size(), /*closed=*/true);
    detail::MeshEditor(m).out_edges()[v] = 3 * fan[0];
    ASSERT_TRUE(check(m).ok()) << "after inserting (" << p.x << ", " << p.y << ")";
  }
}

TEST(MeshKernels, EdgeAndVertexMarkerRules) {
  // Square (0,0), (1,0), (1,1), (0,1) with diagonal 0-2.
  Mesh m;
  m.add_vertex({0, 0});
  m.add_vertex({1, 0});
  m.add_vertex({1, 1});
  m.add_vertex({0, 1});
  const TriId t0 = m.add_triangle(0, 1, 2);
  const TriId t1 = m.add_triangle(0, 2, 3);
  m.link(3 * t0 + 2, 3 * t1 + 0);
  m.compact();
  ASSERT_TRUE(check(m, CheckOptions{.delaunay = false}).ok());
  const HalfEdgeId diag = m.find_edge(0, 2), bottom = m.find_edge(0, 1), right = m.find_edge(1, 2);
  auto marker = [&](HalfEdgeId e) { return edge_output_marker(m, e, real_twin(m, e)); };
  EXPECT_EQ(real_twin(m, bottom), kNone);
  EXPECT_EQ(marker(bottom), 1);  // boundary without a segment marker
  EXPECT_EQ(marker(diag), 0);    // interior edge
  EXPECT_FALSE(is_segment_edge(m, diag));
  m.constrain_edge(diag, 0);
  EXPECT_TRUE(is_segment_edge(m, m.twin(diag)));
  EXPECT_EQ(marker(diag), 0);  // interior segment with marker 0
  m.constrain_edge(diag, 5);
  EXPECT_EQ(marker(diag), 5);
  EXPECT_EQ(marker(m.twin(diag)), 5);
  m.constrain_edge(right, 3);
  EXPECT_EQ(marker(right), 3);  // a boundary segment's nonzero marker wins over 1

  std::size_t edges = 0, boundary = 0;
  for_each_edge(m, [&](HalfEdgeId, bool b) {
    ++edges;
    boundary += b;
  });
  EXPECT_EQ(edges, 5u);
  EXPECT_EQ(boundary, 4u);

  // Vertex markers: the input's where given, else 1 on the boundary.
  m.add_vertex({0.5, 2});  // in no triangle: neither given nor on the boundary
  m.vertex_markers() = {7, 0};
  const std::vector<std::uint8_t> on = boundary_vertices(m);
  EXPECT_EQ(vertex_output_marker(m, 0, on), 7);
  EXPECT_EQ(vertex_output_marker(m, 1, on), 0);
  EXPECT_EQ(vertex_output_marker(m, 2, on), 1);
  EXPECT_EQ(vertex_output_marker(m, 4, on), 0);

  EXPECT_EQ(edge_key(3, 9), edge_key(9, 3));
  EXPECT_LT(edge_key(1, 9), edge_key(2, 3));
}

TEST(MeshKernels, AngleMeasures) {
  const Point a{0, 0}, b{1, 0}, c{0, 1};
  EXPECT_NEAR(angle_at_deg(a, b, c), 90.0, 1e-12);
  EXPECT_NEAR(smallest_angle_deg(a, b, c), 45.0, 1e-12);
  EXPECT_NEAR(min_angle_deg(a, b, c), 45.0, 1e-12);
  const Point d{3, 0.001};
  EXPECT_NEAR(smallest_angle_deg(a, b, d), min_angle_deg(a, b, d), 1e-9);
  EXPECT_EQ(smallest_angle_deg(a, a, a), 0.0);
}
