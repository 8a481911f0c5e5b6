// The domain (holes, exterior, even-odd nesting, -c, -O, regional attributes
// and area bounds) and the one-call pipeline, on small PSLGs written here.
// Every mesh goes through the validator.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "deltamesh/cdt.hpp"
#include "deltamesh/domain.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/triangulate.hpp"
#include "deltamesh/validate.hpp"

using namespace deltamesh;

namespace {

// ---------------------------------------------------------------------------
// PSLG builders

struct Builder {
  Pslg g;
  VertexId point(double x, double y, int marker = 0) {
    g.points.push_back({x, y});
    g.point_markers.push_back(marker);
    return static_cast<VertexId>(g.points.size() - 1);
  }
  // A closed ring of segments through the given corners.
  std::vector<VertexId> ring(const std::vector<Point>& corners, int marker = 0) {
    std::vector<VertexId> ids;
    for (const Point& p : corners) ids.push_back(point(p.x, p.y));
    for (std::size_t i = 0; i < ids.size(); ++i) g.segments.push_back({ids[i], ids[(i + 1) % ids.size()], marker});
    return ids;
  }
  std::vector<VertexId> square(double x0, double y0, double x1, double y1, int marker = 0) {
    return ring({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, marker);
  }
};

double triangle_area(const Mesh& m, TriId t) {
  const auto v = m.triangle(t);
  const Point &a = m.point(v[0]), &b = m.point(v[1]), &c = m.point(v[2]);
  return 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
}

double mesh_area(const Mesh& m) {
  double s = 0;
  for (TriId t = 0; t < m.num_triangle_slots(); ++t)
    if (m.is_real(t)) s += triangle_area(m, t);
  return s;
}

Point centroid(const Mesh& m, TriId t) {
  const auto v = m.triangle(t);
  return {(m.point(v[0]).x + m.point(v[1]).x + m.point(v[2]).x) / 3,
          (m.point(v[0]).y + m.point(v[1]).y + m.point(v[2]).y) / 3};
}

std::size_t boundary_edges(const Mesh& m) {
  std::size_t n = 0;
  for (HalfEdgeId e = 0; e < m.triangle_vertices().size(); ++e)
    if (m.is_real(tri_of(e)) && m.twin(e) == kNone) ++n;
  return n;
}

void expect_valid(const Mesh& m, bool convex = false) {
  CheckOptions opt;
  opt.convex_hull = convex;
  const CheckReport r = check(m, opt);
  EXPECT_TRUE(r.ok()) << r.summary();
  EXPECT_TRUE(m.compacted());
}

// The pipeline with -p semantics; the constrained triangulation is checked
// for every segment before carving, the carved mesh for its topology and for
// a boundary made of segments.
Mesh mesh(const Pslg& g, DomainOptions d = {}, TriangulateStats* stats = nullptr) {
  TriangulateOptions opt;
  opt.domain = d;
  opt.check_segments = true;
  TriangulateStats local;
  TriangulateStats& st = stats ? *stats : local;
  Mesh m = triangulate(g, opt, &st);
  EXPECT_TRUE(st.segment_check.ok()) << st.segment_check.summary();
  EXPECT_EQ(st.segment_check.segments_checked, g.segments.size());
  expect_valid(m, false);
  const std::vector<std::string> boundary = check_domain_boundary(m);
  EXPECT_TRUE(boundary.empty()) << boundary.front();
  return m;
}

// Outer square [0,10]^2, a square hole [2,8]^2 with a hole point, an island
// [4,6]^2 inside the hole (no point in it).
Builder nested(bool hole_point = true) {
  Builder b;
  b.square(0, 0, 10, 10, 1);
  b.square(2, 2, 8, 8, 2);
  b.square(4, 4, 6, 6, 3);
  if (hole_point) b.g.holes.push_back({3, 5});
  return b;
}

// ---------------------------------------------------------------------------
// Holes and the exterior

TEST(Domain, SquareWithHole) {
  Builder b;
  b.square(0, 0, 4, 4);
  b.square(1, 1, 3, 3);
  b.g.holes.push_back({2, 2});
  TriangulateStats st;
  const Mesh m = mesh(b.g, {}, &st);
  EXPECT_DOUBLE_EQ(mesh_area(m), 16.0 - 4.0);
  EXPECT_EQ(m.num_triangles(), 8u);  // an annulus of 8 vertices: T = V (one hole)
  EXPECT_EQ(st.domain.holes_used, 1u);
  EXPECT_EQ(st.domain.holes_ignored, 0u);
  EXPECT_EQ(st.segments, 8u);
  EXPECT_TRUE(st.warnings.empty());
  // Every boundary edge is a segment here.
  for (HalfEdgeId e = 0; e < m.triangle_vertices().size(); ++e)
    if (m.twin(e) == kNone) {
      EXPECT_TRUE(m.is_constrained(e));
    }
}

TEST(Domain, NestedHoleKeepsIsland) {
  const Mesh m = mesh(nested().g);
  EXPECT_DOUBLE_EQ(mesh_area(m), 100.0 - 36.0 + 4.0);
}

TEST(Domain, ExteriorRemovedOutsideNonConvexPolygon) {
  Builder b;  // an L shape: the notch is outside the domain
  b.ring({{0, 0}, {4, 0}, {4, 2}, {2, 2}, {2, 4}, {0, 4}});
  const Mesh m = mesh(b.g);
  EXPECT_DOUBLE_EQ(mesh_area(m), 12.0);
  EXPECT_EQ(m.num_triangles(), 4u);
}

TEST(Domain, WithoutHolePointsEverythingInsideTheOuterRingStays) {
  const Mesh m = mesh(nested(false).g);
  EXPECT_DOUBLE_EQ(mesh_area(m), 100.0);
}

TEST(Domain, IgnoreHoles) {
  DomainOptions d;
  d.ignore_holes = true;
  TriangulateStats st;
  const Mesh m = mesh(nested().g, d, &st);
  EXPECT_DOUBLE_EQ(mesh_area(m), 100.0);
  EXPECT_EQ(st.domain.holes_used, 0u);
  EXPECT_EQ(st.domain.holes_ignored, 0u);
}

TEST(Domain, TwoHolePointsInOneHole) {
  Builder b = nested();
  b.g.holes.push_back({7, 3});
  TriangulateStats st;
  const Mesh m = mesh(b.g, {}, &st);
  EXPECT_DOUBLE_EQ(mesh_area(m), 68.0);
  EXPECT_EQ(st.domain.holes_used, 2u);
}

TEST(Domain, HolePointOnSegmentOutsideOrOnVertexIsIgnored) {
  Builder b;
  b.square(0, 0, 4, 4);
  b.square(1, 1, 3, 3);
  b.g.holes.push_back({2, 1});    // on a segment of the inner square
  b.g.holes.push_back({9, 9});    // outside the convex hull
  b.g.holes.push_back({-1, 2});   // outside, beside the hull
  b.g.holes.push_back({3, 3});    // on a vertex
  TriangulateStats st;
  const Mesh m = mesh(b.g, {}, &st);
  EXPECT_DOUBLE_EQ(mesh_area(m), 16.0);
  EXPECT_EQ(st.domain.holes_ignored, 4u);
  EXPECT_EQ(st.domain.holes_used, 0u);
  ASSERT_FALSE(st.warnings.empty());
  EXPECT_NE(st.warnings[0].find("hole points 0 at (2, 1), 1 at (9, 9), 2 at (-1, 2), 3 at (3, 3) ignored"),
            std::string::npos)
      << st.warnings[0];
}

TEST(Domain, HolePointOnUnconstrainedEdgeIsUsed) {
  // The inner square's diagonal from (1,1) to (3,3) or (3,1) to (1,3) is an
  // edge; a hole point at the centre lies on it.
  Builder b;
  b.square(0, 0, 4, 4);
  b.square(1, 1, 3, 3);
  b.g.holes.push_back({2, 2});
  TriangulateStats st;
  const Mesh m = mesh(b.g, {}, &st);
  EXPECT_EQ(st.domain.holes_used, 1u);
  EXPECT_DOUBLE_EQ(mesh_area(m), 12.0);
}

TEST(Domain, EmptyDomain) {
  Builder b;
  b.square(0, 0, 4, 4);
  b.g.holes.push_back({2, 2});  // the hole is the whole domain
  TriangulateStats st;
  const Mesh m = mesh(b.g, {}, &st);
  EXPECT_EQ(m.num_triangles(), 0u);
  EXPECT_EQ(m.num_vertices(), 4u);
  EXPECT_EQ(st.domain.triangles_kept, 0u);
  ASSERT_FALSE(st.warnings.empty());
  EXPECT_NE(st.warnings.back().find("empty"), std::string::npos);
}

TEST(Domain, OpenSegmentsAreEatenWithoutConvexHull) {
  Builder b;  // points with one segment: nothing encloses a region
  for (const Point& p : std::vector<Point>{{0, 0}, {5, 0}, {5, 5}, {0, 5}, {2, 2}}) b.point(p.x, p.y);
  b.g.segments.push_back({0, 4, 0});
  const Mesh m = mesh(b.g);
  EXPECT_EQ(m.num_triangles(), 0u);
}

TEST(Domain, ConvexHullKeepsEverythingAndClosesIt) {
  Builder b;
  for (const Point& p : std::vector<Point>{{0, 0}, {5, 0}, {6, 3}, {5, 5}, {0, 5}, {2, 2}}) b.point(p.x, p.y);
  b.g.segments.push_back({0, 5, 7});
  DomainOptions d;
  d.keep_convex_hull = true;
  TriangulateStats st;
  const Mesh m = mesh(b.g, d, &st);
  EXPECT_DOUBLE_EQ(mesh_area(m), 25.0 + 0.5 * 5 * 1);  // square plus the triangle to (6,3)
  expect_valid(m, true);
  EXPECT_EQ(st.domain.hull_segments_added, 5u);
  EXPECT_EQ(st.segments, 6u);
  for (HalfEdgeId e = 0; e < m.triangle_vertices().size(); ++e)
    if (m.twin(e) == kNone) {
      EXPECT_TRUE(m.is_constrained(e));
    }
}

TEST(Domain, ConvexHullStillHonoursHoles) {
  Builder b = nested();
  DomainOptions d;
  d.keep_convex_hull = true;
  const Mesh m = mesh(b.g, d);
  EXPECT_DOUBLE_EQ(mesh_area(m), 68.0);
}

TEST(Domain, ConvexHullKeepsConcavity) {
  Builder b;  // the L shape again: -c fills the notch
  b.ring({{0, 0}, {4, 0}, {4, 2}, {2, 2}, {2, 4}, {0, 4}});
  DomainOptions d;
  d.keep_convex_hull = true;
  const Mesh m = mesh(b.g, d);
  EXPECT_DOUBLE_EQ(mesh_area(m), 14.0);
  expect_valid(m, true);
}

// ---------------------------------------------------------------------------
// Even-odd

TEST(Domain, EvenOddNestedRingsNeedNoHolePoints) {
  DomainOptions d;
  d.fill = FillRule::EvenOdd;
  const Mesh m = mesh(nested(false).g, d);
  EXPECT_DOUBLE_EQ(mesh_area(m), 68.0);
}

TEST(Domain, EvenOddMatchesHolePointsOnNestedRings) {
  // Five nested squares: depths 1..5, odd kept.
  Builder b;
  for (int k = 0; k < 5; ++k) b.square(k, k, 10 - k, 10 - k);
  DomainOptions d;
  d.fill = FillRule::EvenOdd;
  const Mesh even_odd = mesh(b.g, d);
  b.g.holes = {{1.5, 5}, {3.5, 5}};
  const Mesh holes = mesh(b.g);
  const double expected = 100 - 64 + 36 - 16 + 4;
  EXPECT_DOUBLE_EQ(mesh_area(even_odd), expected);
  EXPECT_DOUBLE_EQ(mesh_area(holes), expected);
  EXPECT_EQ(even_odd.num_triangles(), holes.num_triangles());
}

TEST(Domain, EvenOddSideBySideRingsAndHullSegments) {
  // Two disjoint squares, each depth 1; a hull that is itself a segment
  // chain only in part.
  Builder b;
  b.square(0, 0, 2, 2);
  b.square(3, 0, 5, 2);
  DomainOptions d;
  d.fill = FillRule::EvenOdd;
  const Mesh m = mesh(b.g, d);
  EXPECT_DOUBLE_EQ(mesh_area(m), 8.0);
  d.keep_convex_hull = true;  // -c keeps the depth-0 gap between them as well
  const Mesh c = mesh(b.g, d);
  EXPECT_DOUBLE_EQ(mesh_area(c), 10.0);
}

TEST(Domain, EvenOddHolePointStillRemoves) {
  Builder b = nested(false);
  b.g.holes.push_back({5, 5});  // inside the island: removes it
  DomainOptions d;
  d.fill = FillRule::EvenOdd;
  const Mesh m = mesh(b.g, d);
  EXPECT_DOUBLE_EQ(mesh_area(m), 64.0);
}

// ---------------------------------------------------------------------------
// Regional attributes and area bounds

// Rectangle [0,4]x[0,2] split by an interface at x = 2 (segment with marker
// 0), regions seeded on both sides.
Builder two_regions() {
  Builder b;
  const VertexId a = b.point(0, 0), c = b.point(2, 0), d = b.point(4, 0), e = b.point(4, 2), f = b.point(2, 2),
                 g = b.point(0, 2);
  const VertexId chain[] = {a, c, d, e, f, g};
  for (int i = 0; i < 6; ++i) b.g.segments.push_back({chain[i], chain[(i + 1) % 6], 1});
  b.g.segments.push_back({c, f, 0});
  return b;
}

TEST(Domain, RegionalAttributes) {
  Builder b = two_regions();
  b.g.regions.push_back({{1, 1}, 10.0, 0.5});
  b.g.regions.push_back({{3, 1}, 20.0, -1.0});
  DomainOptions d;
  d.regional_attributes = true;
  d.regional_area_bounds = true;
  TriangulateStats st;
  const Mesh m = mesh(b.g, d, &st);
  ASSERT_EQ(m.num_triangle_attributes(), 1u);
  ASSERT_EQ(m.triangle_attributes().size(), m.num_triangles());
  EXPECT_EQ(st.domain.regions_used, 2u);
  for (TriId t = 0; t < m.num_triangles(); ++t) {
    const bool left = centroid(m, t).x < 2;
    EXPECT_EQ(m.triangle_attributes()[t], left ? 10.0 : 20.0) << t;
    EXPECT_EQ(m.triangle_area_bound(t), left ? 0.5 : -1.0) << t;
  }
}

TEST(Domain, LaterRegionSeedOverridesAndUnseededRegionGetsZero) {
  Builder b = two_regions();
  b.g.regions.push_back({{0.5, 0.5}, 1.0, 0.1});
  b.g.regions.push_back({{1.5, 1.5}, 2.0, 0.2});  // same region, later: wins
  DomainOptions d;
  d.regional_attributes = true;
  d.regional_area_bounds = true;
  const Mesh m = mesh(b.g, d);
  for (TriId t = 0; t < m.num_triangles(); ++t) {
    const bool left = centroid(m, t).x < 2;
    EXPECT_EQ(m.triangle_attributes()[t], left ? 2.0 : 0.0) << t;
    EXPECT_EQ(m.triangle_area_bound(t), left ? 0.2 : -1.0) << t;
  }
}

TEST(Domain, RegionsWithoutTheSwitchesChangeNothing) {
  Builder b = two_regions();
  b.g.regions.push_back({{1, 1}, 10.0, 0.5});
  const Mesh m = mesh(b.g);
  EXPECT_EQ(m.num_triangle_attributes(), 0u);
  EXPECT_FALSE(m.has_triangle_area_bounds());
}

TEST(Domain, RegionSeedInHoleOrOnSegmentIsIgnored) {
  Builder b;
  b.square(0, 0, 4, 4);
  b.square(1, 1, 3, 3);
  b.g.holes.push_back({2, 1.5});
  b.g.regions.push_back({{2, 2.5}, 5.0, -1});   // in the hole
  b.g.regions.push_back({{0, 2}, 6.0, -1});     // on the outer segment
  b.g.regions.push_back({{0.5, 0.5}, 7.0, -1});  // in the domain
  DomainOptions d;
  d.regional_attributes = true;
  TriangulateStats st;
  const Mesh m = mesh(b.g, d, &st);
  EXPECT_EQ(st.domain.regions_used, 1u);
  EXPECT_EQ(st.domain.regions_ignored, 2u);
  for (TriId t = 0; t < m.num_triangles(); ++t) EXPECT_EQ(m.triangle_attributes()[t], 7.0);
}

TEST(Domain, CarveDomainDirectlyOnConstrainedTriangulation) {
  Builder b = nested();
  Mesh m = constrained_triangulation(b.g);
  DomainStats st;
  carve_domain(m, b.g, {}, &st);
  expect_valid(m);
  EXPECT_DOUBLE_EQ(mesh_area(m), 68.0);
  EXPECT_EQ(st.triangles_kept, m.num_triangles());
  EXPECT_GT(st.triangles_removed, 0u);
}

// ---------------------------------------------------------------------------
// Vertex markers and attributes through the pipeline

TEST(Pipeline, VertexMarkersFollowTriangleRule) {
  Builder b;
  const VertexId a = b.point(0, 0, 9);  // own marker: kept
  const VertexId c = b.point(4, 0);
  const VertexId d = b.point(4, 4);
  const VertexId e = b.point(0, 4);
  const VertexId inner = b.point(2, 2);  // interior, on no segment
  const VertexId on = b.point(2, 3);     // interior, end of an interior segment with marker 6
  b.g.segments = {{a, c, 5}, {c, d, 0}, {d, e, 0}, {e, a, 0}, {inner, on, 6}};
  const Mesh m = mesh(b.g);
  const std::vector<int>& mk = m.vertex_markers();
  ASSERT_EQ(mk.size(), 6u);
  EXPECT_EQ(mk[a], 9);
  EXPECT_EQ(mk[c], 5);  // on the segment with marker 5
  EXPECT_EQ(mk[d], 1);  // boundary, segments with marker 0
  EXPECT_EQ(mk[e], 1);
  EXPECT_EQ(mk[inner], 6);
  EXPECT_EQ(mk[on], 6);
}

TEST(Pipeline, InteriorVertexOnNoSegmentGetsZero) {
  Builder b;
  b.square(0, 0, 4, 4);
  const VertexId inner = b.point(1, 2);
  const Mesh m = mesh(b.g);
  EXPECT_EQ(m.vertex_markers()[inner], 0);
  for (VertexId v = 0; v < 4; ++v) EXPECT_EQ(m.vertex_markers()[v], 1);
}

TEST(Pipeline, FinishVertexMarkersForVerticesAddedLater) {
  Builder b;
  b.square(0, 0, 4, 4, 5);
  b.point(2, 2);
  Mesh m = mesh(b.g);
  // Split a boundary segment and an interior edge as refinement would.
  HalfEdgeId bottom = kNone, inner = kNone;
  for (HalfEdgeId e = 0; e < m.triangle_vertices().size(); ++e) {
    if (m.twin(e) == kNone && m.point(m.origin(e)).y == 0 && m.point(m.dest(e)).y == 0) bottom = e;
    if (m.twin(e) != kNone && (m.origin(e) == 4 || m.dest(e) == 4)) inner = e;
  }
  ASSERT_NE(bottom, kNone);
  ASSERT_NE(inner, kNone);
  const Point a = m.point(m.origin(bottom)), c = m.point(m.dest(bottom));
  const VertexId on_segment = m.add_vertex({(a.x + c.x) / 2, 0});
  m.split_edge(bottom, on_segment);
  const Point p = m.point(m.origin(inner)), q = m.point(m.dest(inner));
  const VertexId interior = m.add_vertex({(p.x + q.x) / 2, (p.y + q.y) / 2});
  m.split_edge(m.find_edge(m.origin(inner), m.dest(inner)), interior);
  m.compact();
  finish_vertex_markers(m);
  ASSERT_EQ(m.vertex_markers().size(), 7u);
  EXPECT_EQ(m.vertex_markers()[on_segment], 5);
  EXPECT_EQ(m.vertex_markers()[interior], 0);
  EXPECT_EQ(m.vertex_markers()[4], 0);
}

TEST(Pipeline, PointSetWithoutSegments) {
  Builder b;
  b.square(0, 0, 4, 4);  // segments are ignored without use_segments
  b.point(1, 1);
  b.g.holes.push_back({2, 2});
  TriangulateOptions opt;
  opt.use_segments = false;
  TriangulateStats st;
  const Mesh m = triangulate(b.g, opt, &st);
  expect_valid(m, true);
  EXPECT_DOUBLE_EQ(mesh_area(m), 16.0);
  EXPECT_EQ(st.segments, 0u);
  EXPECT_EQ(st.input_segments, 0u);
  opt.domain.keep_convex_hull = true;  // -c on a point set: hull edges become segments
  const Mesh c = triangulate(b.g, opt, &st);
  expect_valid(c, true);
  EXPECT_EQ(st.segments, boundary_edges(c));
}

TEST(Pipeline, DuplicateVerticesStayUnused) {
  Builder b;
  b.square(0, 0, 4, 4);
  b.point(4, 4);  // duplicate of a corner
  TriangulateStats st;
  Mesh m = mesh(b.g, {}, &st);
  EXPECT_EQ(st.duplicate_vertices, 1u);
  EXPECT_EQ(m.num_vertices(), 5u);
  m.remove_unused_vertices();
  EXPECT_EQ(m.num_vertices(), 4u);
}

TEST(Pipeline, AttributesCopiedAndInterpolatedAtCrossings) {
  // Two crossing diagonals of a square: the crossing vertex gets the mean of
  // a diagonal's end attributes.
  Builder b;
  b.square(0, 0, 4, 4);
  b.g.num_point_attributes = 1;
  b.g.point_attributes = {0.0, 10.0, 20.0, 30.0};
  b.g.segments.push_back({0, 2, 0});
  b.g.segments.push_back({1, 3, 0});
  TriangulateStats st;
  const Mesh m = mesh(b.g, {}, &st);
  ASSERT_EQ(m.num_vertices(), 5u);
  EXPECT_EQ(st.steiner_vertices, 1u);
  EXPECT_EQ(st.cdt.intersections, 1u);
  ASSERT_EQ(m.num_vertex_attributes(), 1u);
  EXPECT_EQ(m.point(4), (Point{2, 2}));
  const double got = m.vertex_attributes()[4];
  EXPECT_TRUE(got == 10.0 || got == 20.0) << got;  // (0+20)/2 or (10+30)/2
  for (VertexId v = 0; v < 4; ++v) EXPECT_EQ(m.vertex_attributes()[v], 10.0 * v);
  EXPECT_EQ(m.num_triangles(), 4u);
}

TEST(Pipeline, StrictRejectsCrossingSegments) {
  Builder b;
  b.square(0, 0, 4, 4);
  b.g.segments.push_back({0, 2, 0});
  b.g.segments.push_back({1, 3, 0});
  TriangulateOptions opt;
  opt.strict = true;
  EXPECT_THROW(triangulate(b.g, opt), IntersectingSegments);
}

TEST(Pipeline, EveryCdtMethodGivesTheSameDomain) {
  Builder b = nested();
  b.point(1, 5);
  b.point(9, 3);
  b.point(5, 9);
  for (CdtMethod method : {CdtMethod::Fast, CdtMethod::Ct, CdtMethod::Lawson, CdtMethod::Lifting}) {
    TriangulateOptions opt;
    opt.method = method;
    const Mesh m = triangulate(b.g, opt);
    CheckOptions co;
    co.convex_hull = false;
    co.delaunay = method != CdtMethod::Ct;
    EXPECT_TRUE(check(m, co).ok()) << to_string(method);
    EXPECT_DOUBLE_EQ(mesh_area(m), 68.0) << to_string(method);
  }
}

TEST(Pipeline, CollinearInputIsAnInputError) {
  Builder b;
  b.point(0, 0);
  b.point(1, 1);
  b.point(2, 2);
  b.g.segments.push_back({0, 2, 0});
  EXPECT_THROW(triangulate(b.g), InputError);
}

// ---------------------------------------------------------------------------
// Rebuilding a mesh from its triangles (-r)

std::vector<VertexId> triangle_list(const Mesh& m) {
  std::vector<VertexId> t;
  for (TriId i = 0; i < m.num_triangle_slots(); ++i)
    if (m.is_real(i))
      for (VertexId v : m.triangle(i)) t.push_back(v);
  return t;
}

TEST(Rebuild, RoundTripKeepsTrianglesSegmentsAndAttributes) {
  Builder b = two_regions();
  b.g.regions.push_back({{1, 1}, 10.0, -1});
  b.g.regions.push_back({{3, 1}, 20.0, -1});
  DomainOptions d;
  d.regional_attributes = true;
  const Mesh m = mesh(b.g, d);
  const std::vector<VertexId> tris = triangle_list(m);
  Pslg nodes = b.g;
  nodes.regions.clear();
  const Mesh r = mesh_from_triangles(nodes, tris, 1, m.triangle_attributes());
  expect_valid(r);
  EXPECT_EQ(r.num_triangles(), m.num_triangles());
  EXPECT_EQ(triangle_list(r), tris);
  EXPECT_EQ(r.triangle_attributes(), m.triangle_attributes());
  EXPECT_EQ(r.vertex_markers(), m.vertex_markers());
  std::size_t constrained = 0;
  for (HalfEdgeId e = 0; e < r.triangle_vertices().size(); ++e) constrained += r.is_constrained(e);
  std::size_t expected = 0;
  for (HalfEdgeId e = 0; e < m.triangle_vertices().size(); ++e) expected += m.is_constrained(e);
  EXPECT_EQ(constrained, expected);
}

TEST(Rebuild, ClockwiseTrianglesAreTurnedAndChainsOfEdgesFormASegment) {
  Pslg g;
  g.points = {{0, 0}, {1, 0}, {2, 0}, {1, 1}};
  const std::vector<VertexId> tris = {0, 3, 1, 1, 3, 2};  // clockwise
  g.segments.push_back({0, 2, 4});                        // along two edges
  const Mesh m = mesh_from_triangles(g, tris);
  expect_valid(m);
  EXPECT_DOUBLE_EQ(mesh_area(m), 1.0);
  EXPECT_EQ(m.vertex_markers()[1], 4);  // inside the segment
  EXPECT_EQ(m.vertex_markers()[3], 1);  // boundary
}

TEST(Rebuild, Errors) {
  Pslg g;
  g.points = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  EXPECT_THROW(mesh_from_triangles(g, std::vector<VertexId>{0, 1, 7}), InputError);       // no vertex 7
  EXPECT_THROW(mesh_from_triangles(g, std::vector<VertexId>{0, 1, 1}), InputError);       // degenerate
  EXPECT_THROW(mesh_from_triangles(g, std::vector<VertexId>{0, 1, 2, 0, 1, 3}), InputError);  // overlap
  g.segments.push_back({0, 7, 0});
  EXPECT_THROW(mesh_from_triangles(g, std::vector<VertexId>{0, 1, 2, 1, 3, 2}), SegmentError);  // no vertex 7
  // A segment that is not an edge is inserted (Triangle's -r -p): 0-3
  // crosses the diagonal 1-2, which is flipped.
  g.segments = {{0, 3, 6}};
  InsertSegmentsStats st;
  const Mesh m = mesh_from_triangles(g, std::vector<VertexId>{0, 1, 2, 1, 3, 2}, 0, {}, {}, &st);
  expect_valid(m);
  EXPECT_EQ(st.inserted, 1u);
  EXPECT_NE(m.find_edge(0, 3), kNone);
  EXPECT_EQ(m.find_edge(1, 2), kNone);
  EXPECT_EQ(m.vertex_markers()[0], 6);
  // One leaving the mesh (a triangle only): an error.
  g.segments = {{2, 4, 0}};
  g.points.push_back({2, 2});
  EXPECT_THROW(mesh_from_triangles(g, std::vector<VertexId>{0, 1, 3, 0, 3, 2, 3, 4, 1}), SegmentError);
}

}  // namespace
