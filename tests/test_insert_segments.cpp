// Segments inserted into finished meshes (insert_segments, Triangle's -r -p),
// constrained Lawson flips (make_constrained_delaunay) and holes/regions on
// a finished mesh (carve_mesh). Every mesh goes through the validator, with
// the segments it must hold.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "deltamesh/domain.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/insert_segments.hpp"
#include "deltamesh/refine.hpp"
#include "deltamesh/triangulate.hpp"
#include "deltamesh/validate.hpp"
#include "mesh/editor.hpp"

using namespace deltamesh;

namespace {

// Valid, and (delaunay) constrained Delaunay; with `segments`, each one a
// chain of constrained edges.
void expect_valid(const Mesh& m, bool delaunay, const std::vector<Segment>& segments = {}) {
  Pslg g;
  g.points.assign(m.points().begin(), m.points().end());
  g.segments = segments;
  CheckOptions opt;
  opt.convex_hull = false;
  opt.delaunay = delaunay;
  opt.pslg = &g;
  const CheckReport r = check(m, opt);
  EXPECT_TRUE(r.ok()) << r.summary();
  EXPECT_EQ(r.segments_checked, segments.size());
  EXPECT_TRUE(m.compacted());
}

double area(const Mesh& m) {
  double s = 0;
  for (TriId t = 0; t < m.num_triangle_slots(); ++t) {
    const auto v = m.triangle(t);
    const Point &a = m.point(v[0]), &b = m.point(v[1]), &c = m.point(v[2]);
    s += 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
  }
  return s;
}

std::vector<std::array<VertexId, 3>> triangles(const Mesh& m) {
  std::vector<std::array<VertexId, 3>> t;
  for (TriId i = 0; i < m.num_triangle_slots(); ++i) t.push_back(m.triangle(i));
  return t;
}

std::size_t constrained_edges(const Mesh& m) {
  std::size_t n = 0;
  for (HalfEdgeId e = 0; e < m.triangle_vertices().size(); ++e)
    if (m.is_constrained(e) && (m.twin(e) == kNone || e < m.twin(e))) ++n;
  return n;
}

// A grid of (k+1)^2 vertices on [0,k]^2 with the square (lo, hi)^2 cut out
// as a hole (its ring of segments kept, marker 2) and the outer boundary as
// segments (marker 1): a carved CDT, the way -p leaves it.
struct Ring {
  Pslg g;
  Mesh mesh;
  int k;
  VertexId at(int x, int y) const { return static_cast<VertexId>(y * (k + 1) + x); }
};

Ring ring(int k, int lo, int hi) {
  Ring r;
  r.k = k;
  for (int y = 0; y <= k; ++y)
    for (int x = 0; x <= k; ++x) r.g.points.push_back({double(x), double(y)});
  auto loop = [&](int a, int b, int marker) {
    for (int i = a; i < b; ++i) {
      r.g.segments.push_back({r.at(i, a), r.at(i + 1, a), marker});
      r.g.segments.push_back({r.at(b, i), r.at(b, i + 1), marker});
      r.g.segments.push_back({r.at(i + 1, b), r.at(i, b), marker});
      r.g.segments.push_back({r.at(a, i + 1), r.at(a, i), marker});
    }
  };
  loop(0, k, 1);
  loop(lo, hi, 2);
  r.g.holes.push_back({(lo + hi) / 2.0 + 0.25, (lo + hi) / 2.0 + 0.25});
  r.mesh = triangulate(r.g);
  return r;
}

// ---------------------------------------------------------------------------

TEST(InsertSegments, InteriorSegmentThroughTheRing) {
  Ring r = ring(8, 3, 5);
  const Mesh before = r.mesh;
  const std::size_t boundary = [&] {
    std::size_t n = 0;
    for (HalfEdgeId e = 0; e < before.triangle_vertices().size(); ++e) n += before.twin(e) == kNone;
    return n;
  }();
  // (0,1) to (7,2): crosses many triangles below the hole, through no vertex.
  const std::vector<Segment> s = {{r.at(0, 1), r.at(7, 2), 5}};
  InsertSegmentsStats st;
  insert_segments(r.mesh, s, {}, &st);
  std::vector<Segment> all = r.g.segments;
  all.push_back(s[0]);
  expect_valid(r.mesh, true, all);
  EXPECT_EQ(st.inserted, 1u);
  EXPECT_EQ(st.already_present, 0u);
  EXPECT_EQ(st.vertices_added, 0u);
  EXPECT_EQ(r.mesh.num_vertices(), before.num_vertices());
  EXPECT_EQ(r.mesh.num_triangles(), before.num_triangles());  // same vertices, same domain
  EXPECT_DOUBLE_EQ(area(r.mesh), 64.0 - 4.0);
  std::size_t boundary_after = 0;
  for (HalfEdgeId e = 0; e < r.mesh.triangle_vertices().size(); ++e) boundary_after += r.mesh.twin(e) == kNone;
  EXPECT_EQ(boundary_after, boundary);
  EXPECT_EQ(constrained_edges(r.mesh), constrained_edges(before) + 1);
  // The segment is a single edge carrying marker 5; its ends keep their
  // markers (1: boundary segments), an interior vertex on it would take 5.
  const HalfEdgeId e = r.mesh.find_edge(r.at(0, 1), r.at(7, 2));
  ASSERT_NE(e, kNone);
  EXPECT_EQ(r.mesh.edge_marker(e), 5);
  // Inserting it again changes nothing.
  const auto tris = triangles(r.mesh);
  insert_segments(r.mesh, s, {}, &st);
  EXPECT_EQ(st.already_present, 1u);
  EXPECT_EQ(triangles(r.mesh), tris);
}

TEST(InsertSegments, SplitAtVerticesOnIt) {
  Ring r = ring(8, 3, 5);
  // (0,0) to (6,2) passes exactly through (3,1).
  const std::vector<Segment> s = {{r.at(0, 0), r.at(6, 2), 0}};
  InsertSegmentsStats st;
  insert_segments(r.mesh, s, {}, &st);
  std::vector<Segment> all = r.g.segments;
  all.push_back(s[0]);
  expect_valid(r.mesh, true, all);
  EXPECT_GE(st.cdt.vertices_on_segments, 1u);
  EXPECT_NE(r.mesh.find_edge(r.at(0, 0), r.at(3, 1)), kNone);
  EXPECT_NE(r.mesh.find_edge(r.at(3, 1), r.at(6, 2)), kNone);
  EXPECT_EQ(st.vertices_added, 0u);
}

TEST(InsertSegments, CrossingASegmentAddsAVertex) {
  Ring r = ring(8, 3, 5);
  // First an interior segment, then one crossing it.
  const std::vector<Segment> first = {{r.at(0, 1), r.at(8, 1), 4}};
  insert_segments(r.mesh, first);
  const std::size_t nv = r.mesh.num_vertices();
  const std::vector<Segment> second = {{r.at(1, 0), r.at(2, 3), 6}};  // crosses y = 1 at x = 4/3
  InsertSegmentsStats st;
  insert_segments(r.mesh, second, {}, &st);
  std::vector<Segment> all = r.g.segments;
  all.push_back(first[0]);
  all.push_back(second[0]);
  expect_valid(r.mesh, true, all);
  EXPECT_EQ(st.vertices_added, 1u);
  EXPECT_EQ(st.cdt.intersections, 1u);
  ASSERT_EQ(r.mesh.num_vertices(), nv + 1);
  const Point p = r.mesh.point(static_cast<VertexId>(nv));
  EXPECT_NEAR(p.x, 4.0 / 3.0, 1e-12);
  EXPECT_EQ(p.y, 1.0);
  // The new vertex lies on both: it takes the lower-numbered nonzero marker
  // it meets first (finish_vertex_markers: one of 4 and 6).
  ASSERT_EQ(r.mesh.vertex_markers().size(), nv + 1);
  const int m = r.mesh.vertex_markers()[nv];
  EXPECT_TRUE(m == 4 || m == 6) << m;

  // --strict: the crossing is an error naming the given segment, and
  // nothing changes.
  Ring s = ring(8, 3, 5);
  insert_segments(s.mesh, first);
  const auto tris = triangles(s.mesh);
  InsertSegmentsOptions strict;
  strict.strict = true;
  try {
    insert_segments(s.mesh, second, strict);
    ADD_FAILURE() << "no SegmentError";
  } catch (const SegmentError& e) {
    EXPECT_EQ(e.segment(), 0u);
    EXPECT_NE(e.problem().find("crosses a segment of the mesh"), std::string::npos) << e.what();
  }
  EXPECT_EQ(triangles(s.mesh), tris);
  // Two given segments that cross: IntersectingSegments names both.
  const std::vector<Segment> pair = {{r.at(0, 7), r.at(8, 7), 0}, {r.at(1, 6), r.at(2, 8), 0}};
  EXPECT_THROW(insert_segments(s.mesh, pair, strict), IntersectingSegments);
}

TEST(InsertSegments, SegmentsLeavingTheMeshAreErrors) {
  Ring r = ring(8, 3, 5);
  const auto tris = triangles(r.mesh);
  auto expect_error = [&](const Segment& s, const char* what) {
    const std::vector<Segment> list = {{r.at(0, 1), r.at(7, 2), 0}, s};  // the good one must not go in either
    try {
      insert_segments(r.mesh, list);
      ADD_FAILURE() << "no SegmentError for " << what;
    } catch (const SegmentError& e) {
      EXPECT_EQ(e.segment(), 1u);
      EXPECT_NE(e.problem().find(what), std::string::npos) << e.what();
    }
    EXPECT_EQ(triangles(r.mesh), tris);
  };
  expect_error({r.at(0, 0), r.at(8, 8), 0}, "leaves the mesh");  // through the hole
  expect_error({r.at(3, 4), r.at(5, 4), 0}, "leaves the mesh");  // across it, between two of its vertices
  expect_error({r.at(0, 0), r.at(999, 0), 0}, "does not exist");
  // An endpoint in no triangle: a vertex added in the hole.
  Pslg g = r.g;
  g.points.push_back({4.1, 4.2});
  Mesh m = triangulate(g);
  ASSERT_EQ(m.num_vertices(), r.mesh.num_vertices() + 1);
  EXPECT_THROW(insert_segments(m, std::vector<Segment>{{r.at(0, 0), static_cast<VertexId>(g.points.size() - 1), 0}}),
               SegmentError);
  // Along the hole's boundary is inside (its closure): fine.
  const std::vector<Segment> along = {{r.at(3, 3), r.at(5, 3), 0}};
  insert_segments(r.mesh, along);
  EXPECT_EQ(triangles(r.mesh), tris);
}

// A non-convex domain: an L. A segment across the notch between two of its
// boundary vertices leaves it; the boundary stays unconstrained (no -p
// segments for it), except where a segment runs along it.
TEST(InsertSegments, NonConvexMeshWithoutBoundarySegments) {
  Pslg g;
  for (int y = 0; y <= 4; ++y)
    for (int x = 0; x <= 4; ++x)
      if (x <= 2 || y <= 2) g.points.push_back({double(x), double(y)});
  auto id = [&](double x, double y) {
    for (VertexId i = 0; i < g.points.size(); ++i)
      if (g.points[i] == Point{x, y}) return i;
    return kNone;
  };
  const std::vector<Point> outline = {{0, 0}, {4, 0}, {4, 2}, {2, 2}, {2, 4}, {0, 4}};
  Pslg poly = g;
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const Point a = outline[i], b = outline[(i + 1) % outline.size()];
    // Unit steps along the outline.
    const int n = static_cast<int>(std::abs(b.x - a.x) + std::abs(b.y - a.y));
    for (int s = 0; s < n; ++s)
      poly.segments.push_back({id(a.x + (b.x - a.x) * s / n, a.y + (b.y - a.y) * s / n),
                               id(a.x + (b.x - a.x) * (s + 1) / n, a.y + (b.y - a.y) * (s + 1) / n), 0});
  }
  Mesh m = triangulate(poly);
  // Forget the segments: a mesh as another tool would give it.
  deltamesh::detail::MeshEditor(m).edge_flags().clear();
  deltamesh::detail::MeshEditor(m).edge_markers().clear();
  ASSERT_EQ(constrained_edges(m), 0u);
  const auto tris = triangles(m);
  EXPECT_THROW(insert_segments(m, std::vector<Segment>{{id(4, 2), id(2, 4), 0}}), SegmentError);  // the notch
  EXPECT_THROW(insert_segments(m, std::vector<Segment>{{id(3, 2), id(2, 3), 0}}), SegmentError);
  EXPECT_EQ(triangles(m), tris);
  // Inside: from the corner (0,0) to the reflex corner's neighbour (3,1),
  // and one along the boundary (constrained there, the rest stays free).
  const std::vector<Segment> s = {{id(0, 0), id(3, 1), 3}, {id(0, 4), id(0, 2), 8}};
  InsertSegmentsStats st;
  insert_segments(m, s, {}, &st);
  expect_valid(m, true, s);
  EXPECT_EQ(st.inserted, 1u);
  EXPECT_EQ(st.already_present, 1u);
  EXPECT_DOUBLE_EQ(area(m), 12.0);
  EXPECT_EQ(constrained_edges(m), 3u);  // (0,0)-(3,1) one edge, (0,4)-(0,2) two
}

// A fan from one corner of a convex polygon on a circle-ish curve is far
// from Delaunay. With options.delaunay the result is the CDT; without, only
// the crossed triangles change.
TEST(InsertSegments, NonDelaunayMesh) {
  Pslg g;
  const int n = 24;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * 3.14159265358979 * i / n;
    g.points.push_back({std::round(1000 * std::cos(a)) / 100, std::round(1000 * std::sin(0.9 * a + 0.1)) / 100});
  }
  std::vector<VertexId> fan;
  for (int i = 1; i + 1 < n; ++i) fan.insert(fan.end(), {0, VertexId(i), VertexId(i + 1)});
  Mesh base = mesh_from_triangles(g, fan);
  ASSERT_EQ(base.num_triangles(), std::size_t(n - 2));
  {
    CheckOptions co;
    co.convex_hull = false;
    ASSERT_FALSE(check(base, co).ok());  // not Delaunay
  }
  const std::vector<Segment> s = {{3, 17, 0}};
  Mesh a = base;
  InsertSegmentsOptions keep;
  keep.delaunay = false;
  insert_segments(a, s, keep);
  expect_valid(a, false, s);
  // Fan triangles (0, i, i+1) wholly on one side of 3-17 are still there.
  std::size_t kept = 0;
  for (const auto& t : triangles(base))
    for (const auto& u : triangles(a)) kept += t == u;
  EXPECT_GE(kept, 2u);
  Mesh b = base;
  InsertSegmentsStats st;
  insert_segments(b, s, {}, &st);
  expect_valid(b, true, s);
  EXPECT_GT(st.flips, 0u);
  // make_constrained_delaunay alone: the Delaunay triangulation (no segments).
  Mesh c = base;
  EXPECT_GT(make_constrained_delaunay(c), 0u);
  expect_valid(c, true);
  EXPECT_EQ(make_constrained_delaunay(c), 0u);
}

// Random segments between vertices of a ring: inside the domain unless they
// pass through the open hole (a test independent of the code's walk); the
// ones inside go in, crossing each other and the ring's segments; the result
// is a CDT holding all of them, and refinement keeps them.
TEST(InsertSegments, RandomSegmentsThenRefinement) {
  std::mt19937 rng(12345);
  std::size_t inserted = 0, rejected = 0, added = 0;
  for (int round = 0; round < 6; ++round) {
    Ring r = ring(10, 4, 7);
    const int k = r.k;
    std::uniform_int_distribution<int> coord(0, k);
    std::vector<Segment> given, all = r.g.segments;
    std::size_t errors = 0;
    for (int i = 0; i < 20; ++i) {
      const int x0 = coord(rng), y0 = coord(rng), x1 = coord(rng), y1 = coord(rng);
      if (x0 == x1 && y0 == y1) continue;
      // Does the open segment meet the open square (4,7)^2? Clip to the
      // closed square; outside iff the clipped piece's midpoint is inside.
      double t0 = 0, t1 = 1;
      const double dx = x1 - x0, dy = y1 - y0;
      auto clip = [&](double p, double q) {  // p t <= q
        if (p == 0) return q >= 0;
        const double t = q / p;
        if (p < 0) t0 = std::max(t0, t);
        else t1 = std::min(t1, t);
        return true;
      };
      const bool meets = clip(-dx, x0 - 4.0) && clip(dx, 7.0 - x0) && clip(-dy, y0 - 4.0) && clip(dy, 7.0 - y0) && t0 < t1;
      const double mx = x0 + dx * (t0 + t1) / 2, my = y0 + dy * (t0 + t1) / 2;
      const bool outside = meets && mx > 4 && mx < 7 && my > 4 && my < 7;
      // Ends strictly inside the hole are in no triangle: also errors.
      const bool end_in_hole = (x0 > 4 && x0 < 7 && y0 > 4 && y0 < 7) || (x1 > 4 && x1 < 7 && y1 > 4 && y1 < 7);
      const Segment s{r.at(x0, y0), r.at(x1, y1), 10 + i};
      try {
        insert_segments(r.mesh, std::vector<Segment>{s});
        EXPECT_FALSE(outside || end_in_hole) << x0 << "," << y0 << " - " << x1 << "," << y1;
        given.push_back(s);
        all.push_back(s);
      } catch (const SegmentError&) {
        EXPECT_TRUE(outside || end_in_hole) << x0 << "," << y0 << " - " << x1 << "," << y1;
        ++errors;
      }
    }
    expect_valid(r.mesh, true, all);
    EXPECT_DOUBLE_EQ(area(r.mesh), 100.0 - 9.0);
    inserted += given.size();
    rejected += errors;
    added += r.mesh.num_vertices() - r.g.points.size();
    RefineOptions ro;
    ro.min_angle_deg = 30;
    const RefineStats rs = refine(r.mesh, ro);
    EXPECT_TRUE(rs.complete);
    expect_valid(r.mesh, true, all);
  }
  // The test means something: both kinds occurred, and crossings added vertices.
  std::printf("inserted %zu, rejected %zu, crossing vertices %zu\n", inserted, rejected, added);
  EXPECT_GE(inserted, 20u);
  EXPECT_GE(rejected, 3u);
  EXPECT_GE(added, 10u);
}

// ---------------------------------------------------------------------------
// Holes and regions on a finished mesh

TEST(CarveMesh, NewLoopWithAHolePointAndARegion) {
  // The 8x8 grid without a hole, then a loop of new segments around
  // [2,4]^2 and a hole point in it; a region seed outside it.
  Ring r = ring(8, 3, 5);
  Pslg g;
  g.points = r.g.points;
  for (const Segment& s : r.g.segments)
    if (s.marker == 1) g.segments.push_back(s);
  Mesh m = triangulate(g);
  const std::vector<Segment> loop = {{r.at(2, 2), r.at(4, 2), 7}, {r.at(4, 2), r.at(4, 4), 7},
                                     {r.at(4, 4), r.at(2, 4), 7}, {r.at(2, 4), r.at(2, 2), 7}};
  insert_segments(m, loop);
  Pslg seeds;
  seeds.holes = {{3.5, 3.25}, {3, 2}, {-5, -5}};  // inside the loop; on a segment; outside the mesh
  seeds.regions = {{{0.5, 0.5}, 9.0, -1}};
  DomainOptions d;
  d.regional_attributes = true;
  DomainStats st;
  carve_mesh(m, seeds, d, &st);
  expect_valid(m, true, loop);
  EXPECT_EQ(st.holes_used, 1u);
  EXPECT_EQ(st.holes_ignored, 1u);
  EXPECT_EQ(st.holes_outside, 1u);
  EXPECT_EQ(st.regions_used, 1u);
  EXPECT_DOUBLE_EQ(area(m), 64.0 - 4.0);
  ASSERT_EQ(m.num_triangle_attributes(), 1u);
  for (TriId t = 0; t < m.num_triangle_slots(); ++t) EXPECT_EQ(m.triangle_attributes()[t], 9.0);
  // Again: the hole point is now in no triangle; nothing changes.
  const auto tris = triangles(m);
  carve_mesh(m, seeds, d, &st);
  EXPECT_EQ(st.holes_used, 0u);
  EXPECT_EQ(st.holes_outside, 2u);
  EXPECT_EQ(triangles(m), tris);
}

}  // namespace
