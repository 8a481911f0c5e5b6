// The validator's global overlap test: no two triangles' interiors
// intersect and boundary edges meet only at common endpoints, whatever the
// connectivity. Each case is also decided by a brute-force pairwise check
// with GMP-exact orientations, which the validator must agree with.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "deltamesh-gen/generators.hpp"
#include "deltamesh/delaunay.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/triangle_io.hpp"
#include "deltamesh/triangulate.hpp"
#include "deltamesh/validate.hpp"
#include "support/gmp_oracle.hpp"

using namespace deltamesh;
namespace fs = std::filesystem;

namespace {

using Kind = TriangleConflict::Kind;

CheckReport check_geometry(const Mesh& m) {
  CheckOptions o;
  o.delaunay = false;
  o.convex_hull = false;
  return check(m, o);
}

// A mesh as -r reads it: twins linked where two triangles share an edge.
Mesh from_list(const std::vector<Point>& points, const std::vector<VertexId>& tris) {
  Pslg nodes;
  nodes.points = points;
  RebuildOptions keep_overlaps;
  keep_overlaps.refuse_overlaps = false;
  return mesh_from_triangles(nodes, tris, 0, {}, keep_overlaps);
}

// ---- brute force, GMP-exact ----------------------------------------------

int orient(const Point& a, const Point& b, const Point& c) {
  static oracle::GmpOracle gmp;
  return gmp.orient2d(a, b, c);
}

// Closed bounding boxes of the point sets are disjoint (exact comparisons).
template <class A, class B>
bool boxes_apart(const A& p, const B& q) {
  auto lo = [](const auto& s, bool x) {
    double v = x ? s[0].x : s[0].y;
    for (const Point& r : s) v = std::min(v, x ? r.x : r.y);
    return v;
  };
  auto hi = [](const auto& s, bool x) {
    double v = x ? s[0].x : s[0].y;
    for (const Point& r : s) v = std::max(v, x ? r.x : r.y);
    return v;
  };
  return hi(p, true) < lo(q, true) || hi(q, true) < lo(p, true) || hi(p, false) < lo(q, false) ||
         hi(q, false) < lo(p, false);
}

// p on the line of ab: strictly inside the closed segment's bounding box and
// not an endpoint means strictly between a and b.
bool between(const Point& a, const Point& b, const Point& p) {
  if (p == a || p == b) return false;
  return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
         p.y <= std::max(a.y, b.y);
}

// Two closed segments meet somewhere other than at an endpoint they share.
bool bad_contact(const Point& a, const Point& b, const Point& c, const Point& d) {
  if (boxes_apart(std::array<Point, 2>{a, b}, std::array<Point, 2>{c, d})) return false;
  const int o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (o1 == 0 && o2 == 0) {
    // Collinear: overlap of positive length, measured along the longer axis.
    const bool use_x = std::fabs(b.x - a.x) + std::fabs(d.x - c.x) > 0;
    auto key = [&](const Point& p) { return use_x ? p.x : p.y; };
    const double lo = std::max(std::min(key(a), key(b)), std::min(key(c), key(d)));
    const double hi = std::min(std::max(key(a), key(b)), std::max(key(c), key(d)));
    return lo < hi;
  }
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  return (o1 == 0 && between(a, b, c)) || (o2 == 0 && between(a, b, d)) || (o3 == 0 && between(c, d, a)) ||
         (o4 == 0 && between(c, d, b));
}

// Interiors of two counter-clockwise triangles intersect: no edge line
// separates them.
bool brute_overlap(const std::array<Point, 3>& p, const std::array<Point, 3>& q) {
  if (boxes_apart(p, q)) return false;
  auto sep = [](const std::array<Point, 3>& s, const std::array<Point, 3>& t) {
    for (int i = 0; i < 3; ++i) {
      bool all = true;
      for (const Point& v : t) all = all && orient(s[i], s[(i + 1) % 3], v) <= 0;
      if (all) return true;
    }
    return false;
  };
  return !sep(p, q) && !sep(q, p);
}

std::array<Point, 3> corners(const Mesh& m, TriId t) {
  const auto v = m.triangle(t);
  return {m.point(v[0]), m.point(v[1]), m.point(v[2])};
}

struct Brute {
  bool overlap = false;  // some pair of interiors intersects
  bool contact = false;  // some pair of boundary edges meets badly
  bool any() const { return overlap || contact; }
};

Brute brute(const Mesh& m) {
  Brute b;
  std::vector<TriId> tris;
  std::vector<HalfEdgeId> boundary;
  for (TriId t = 0; t < m.num_triangle_slots(); ++t) {
    if (!m.is_real(t)) continue;
    tris.push_back(t);
    for (int i = 0; i < 3; ++i) {
      const HalfEdgeId e = 3 * t + i;
      if (m.twin(e) == kNone || !m.is_real(tri_of(m.twin(e)))) boundary.push_back(e);
    }
  }
  for (std::size_t i = 0; i < tris.size(); ++i)
    for (std::size_t j = i + 1; j < tris.size(); ++j)
      b.overlap = b.overlap || brute_overlap(corners(m, tris[i]), corners(m, tris[j]));
  for (std::size_t i = 0; i < boundary.size(); ++i)
    for (std::size_t j = i + 1; j < boundary.size(); ++j) {
      const HalfEdgeId e = boundary[i], f = boundary[j];
      b.contact = b.contact || bad_contact(m.point(m.origin(e)), m.point(m.dest(e)), m.point(m.origin(f)),
                                           m.point(m.dest(f)));
    }
  return b;
}

// The validator's finding agrees with the brute force, and the named pair is
// what its kind says (the sweep stops at its leftmost finding, so a contact
// may be named while another pair overlaps further right).
void expect_agrees(const Mesh& m, const CheckReport& r) {
  const Brute b = brute(m);
  ASSERT_EQ(!r.conflicts.empty(), b.any()) << r.summary();
  if (r.conflicts.empty()) return;
  const TriangleConflict& c = r.conflicts.front();
  EXPECT_FALSE(r.ok());
  ASSERT_NE(c.second, kNone) << r.summary();
  ASSERT_TRUE(m.is_real(c.first) && m.is_real(c.second));
  const bool pair_overlaps = brute_overlap(corners(m, c.first), corners(m, c.second));
  EXPECT_EQ(c.kind == Kind::Overlap, pair_overlaps) << r.summary();
}

bool mentions(const CheckReport& r, const std::string& text) {
  for (const std::string& p : r.problems)
    if (p.find(text) != std::string::npos) return true;
  return false;
}

void expect_conflict(const Mesh& m, Kind kind, TriId a, TriId b, const std::string& text) {
  const CheckReport r = check_geometry(m);
  ASSERT_EQ(r.conflicts.size(), 1u) << r.summary();
  EXPECT_EQ(r.conflicts[0].kind, kind) << r.summary();
  EXPECT_EQ(r.conflicts[0].first, a) << r.summary();
  EXPECT_EQ(r.conflicts[0].second, b) << r.summary();
  EXPECT_TRUE(mentions(r, text)) << "expected '" << text << "' in " << r.summary();
  expect_agrees(m, r);
}

void expect_valid(const Mesh& m) {
  const CheckReport r = check_geometry(m);
  EXPECT_TRUE(r.ok()) << r.summary();
  EXPECT_TRUE(r.conflicts.empty());
}

const double s3 = std::sqrt(3.0);

}  // namespace

// ---- the cases of the issue ------------------------------------------------

TEST(ValidateOverlap, StarOfDavid) {
  // Triangles (1,2,3) and (4,6,5) of a .node/.ele pair, sharing no vertex.
  const Mesh m = from_list({{0, 2}, {-s3, -1}, {s3, -1}, {0, -2}, {s3, 1}, {-s3, 1}}, {0, 1, 2, 3, 5, 4});
  expect_conflict(m, Kind::Overlap, 0, 1, "triangles 0 (0, 1, 2) and 1 (3, 4, 5) overlap");
  EXPECT_TRUE(mentions(check_geometry(m), "cross"));
}

TEST(ValidateOverlap, CrossingBoundaryLoops) {
  // Two unit squares of two triangles each, the second shifted by (0.5, 0.5).
  const Mesh m = from_list({{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.5}, {1.5, 0.5}, {1.5, 1.5}, {0.5, 1.5}},
                           {0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7});
  const CheckReport r = check_geometry(m);
  ASSERT_EQ(r.conflicts.size(), 1u) << r.summary();
  EXPECT_EQ(r.conflicts[0].kind, Kind::Overlap);
  expect_agrees(m, r);
}

TEST(ValidateOverlap, ConnectedStripWindingOneAndAHalfTimes) {
  // One strip of quads around the origin, 540 degrees: every vertex's fan
  // is fine and the Euler count is a disc's, but it covers half the annulus
  // twice. Angles are never 360 degrees apart, so no vertices coincide.
  std::vector<Point> p;
  std::vector<VertexId> t;
  const int k = 31;
  for (int i = 0; i <= k; ++i) {
    const double a = 3 * M_PI * i / k;
    p.push_back({std::cos(a), std::sin(a)});
    p.push_back({2 * std::cos(a), 2 * std::sin(a)});
  }
  for (VertexId i = 0; i < static_cast<VertexId>(k); ++i) {
    const VertexId in = 2 * i, out = 2 * i + 1;
    t.insert(t.end(), {in, out, out + 2, in, out + 2, in + 2});
  }
  const Mesh m = from_list(p, t);
  const CheckReport r = check_geometry(m);
  ASSERT_EQ(r.conflicts.size(), 1u) << r.summary();
  EXPECT_EQ(r.conflicts[0].kind, Kind::Overlap);
  expect_agrees(m, r);
}

TEST(ValidateOverlap, OpenFanWrappingPastAFullTurn) {
  // Boundary vertex 0 with a fan of 405 degrees: no pinch, a disc by Euler.
  const Mesh m = from_list({{0, 0}, {1, 0}, {0, 1}, {-1, 0}, {0, -1}, {2, 2}}, {0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 5});
  const CheckReport r = check_geometry(m);
  ASSERT_EQ(r.conflicts.size(), 1u) << r.summary();
  EXPECT_EQ(r.conflicts[0].kind, Kind::Overlap);
  expect_agrees(m, r);
}

TEST(ValidateOverlap, TriangleInsideAnother) {
  const Mesh m = from_list({{0, 0}, {10, 0}, {0, 10}, {1, 1}, {2, 1}, {1, 2}}, {0, 1, 2, 3, 4, 5});
  expect_conflict(m, Kind::Overlap, 0, 1, "triangle 1 lies inside triangle 0");
}

TEST(ValidateOverlap, TriangleInsideAnotherTouchingItsEdge) {
  // The inner triangle's edge lies along the outer one's: still overlap.
  const Mesh m = from_list({{0, 0}, {10, 0}, {0, 10}, {2, 0}, {4, 0}, {3, 1}}, {0, 1, 2, 3, 4, 5});
  expect_conflict(m, Kind::Overlap, 0, 1, "lies inside triangle 0");
}

TEST(ValidateOverlap, SmallComponentOverAMeshInterior) {
  // A triangle lying over interior edges of a Delaunay mesh, crossing no
  // boundary edge: found by the winding number, the partner named.
  Mesh m = delaunay(gen::uniform_points(2000, 3));
  m.compact();
  std::vector<Point> p(m.points().begin(), m.points().end());
  std::vector<VertexId> t(m.triangle_vertices().begin(), m.triangle_vertices().end());
  const VertexId v = static_cast<VertexId>(p.size());
  p.insert(p.end(), {{0.4, 0.4}, {0.6, 0.41}, {0.5, 0.6}});
  t.insert(t.end(), {v, v + 1, v + 2});
  const Mesh bad = from_list(p, t);
  const CheckReport r = check_geometry(bad);
  ASSERT_EQ(r.conflicts.size(), 1u) << r.summary();
  EXPECT_EQ(r.conflicts[0].kind, Kind::Overlap);
  EXPECT_EQ(r.conflicts[0].second, bad.num_triangles() - 1) << r.summary();
  EXPECT_TRUE(brute_overlap(corners(bad, r.conflicts[0].first), corners(bad, r.conflicts[0].second)));
}

TEST(ValidateOverlap, DuplicatedTriangleSameVertices) {
  // Built by hand: the .ele reader refuses two triangles on the same side of
  // an edge, but a mesh made in memory can have them.
  Mesh m;
  for (Point q : {Point{0, 0}, Point{1, 0}, Point{0, 1}}) m.add_vertex(q);
  m.add_triangle(0, 1, 2);
  m.add_triangle(0, 1, 2);
  m.compact();
  expect_conflict(m, Kind::Overlap, 0, 1, "the same triangle twice");
}

TEST(ValidateOverlap, DuplicatedTriangleDuplicatedVertices) {
  const Mesh m = from_list({{0, 0}, {1, 0}, {0, 1}, {0, 0}, {1, 0}, {0, 1}}, {0, 1, 2, 3, 4, 5});
  expect_conflict(m, Kind::Overlap, 0, 1, "overlap");
}

TEST(ValidateOverlap, TouchingAtAVertexIsValid) {
  // The same vertex (a pinch vertex) and two vertices at the same point.
  expect_valid(from_list({{0, 0}, {1, -1}, {1, 1}, {-1, 1}, {-1, -1}}, {0, 1, 2, 0, 3, 4}));
  expect_valid(from_list({{0, 0}, {1, -1}, {1, 1}, {0, 0}, {-1, 1}, {-1, -1}}, {0, 1, 2, 3, 4, 5}));
  // Corner to corner along a diagonal, sharing one point.
  expect_valid(from_list({{0, 0}, {1, 0}, {1, 1}, {1, 1}, {2, 1}, {2, 2}}, {0, 1, 2, 3, 4, 5}));
}

TEST(ValidateOverlap, AnEdgeSharedWithoutConnectivityIsReported) {
  // Two triangles on either side of the same segment: the geometry is fine
  // but the edge is in the mesh twice without a twin link, so the boundary
  // edges lie along each other. Decided: a defect (BoundaryContact).
  const Mesh dup = from_list({{0, 0}, {1, 0}, {0, 1}, {1, 0}, {1, 1}, {0, 1}}, {0, 1, 2, 3, 4, 5});
  expect_conflict(dup, Kind::BoundaryContact, 0, 1, "lie along each other");
  Mesh unlinked;
  for (Point q : {Point{0, 0}, Point{1, 0}, Point{0, 1}, Point{1, 1}}) unlinked.add_vertex(q);
  unlinked.add_triangle(0, 1, 2);
  unlinked.add_triangle(1, 3, 2);
  unlinked.compact();  // no twins linked
  expect_conflict(unlinked, Kind::BoundaryContact, 0, 1, "lie along each other");
  // Linked, the same two triangles are a valid mesh.
  expect_valid(from_list({{0, 0}, {1, 0}, {0, 1}, {1, 1}}, {0, 1, 2, 1, 3, 2}));
}

TEST(ValidateOverlap, TJunctionIsAContact) {
  // Vertex 3 (1, 1) lies inside boundary edge 1-2 of triangle 0; the two
  // triangles on its right do not overlap it.
  const Mesh m = from_list({{0, 0}, {1, 0}, {1, 2}, {1, 1}, {2, 1}}, {0, 1, 2, 1, 4, 3, 3, 4, 2});
  const CheckReport r = check_geometry(m);
  ASSERT_EQ(r.conflicts.size(), 1u) << r.summary();
  EXPECT_EQ(r.conflicts[0].kind, Kind::BoundaryContact);
  EXPECT_EQ(r.conflicts[0].first, 0u);
  EXPECT_TRUE(mentions(r, "vertex 3")) << r.summary();
  EXPECT_TRUE(mentions(r, "T-junction")) << r.summary();
  expect_agrees(m, r);
}

TEST(ValidateOverlap, VertexInsideATriangle) {
  const Mesh m = from_list({{0, 0}, {4, 0}, {0, 4}, {1, 1}, {5, 2}, {5, 3}}, {0, 1, 2, 3, 4, 5});
  expect_conflict(m, Kind::Overlap, 0, 1, "vertex 3 lies inside triangle 0");
}

// ---- exactness ------------------------------------------------------------

TEST(ValidateOverlap, OneUlpDecidesOnAnAxisAlignedEdge) {
  // Vertex q of the second triangle on, just inside or just outside the
  // hypotenuse x + y = 1 of the first.
  auto with = [](double qy) {
    return from_list({{0, 0}, {1, 0}, {0, 1}, {0.5, qy}, {1.5, 0.5}, {0.5, 1.5}}, {0, 1, 2, 3, 4, 5});
  };
  expect_valid(with(std::nextafter(0.5, 1.0)));
  expect_conflict(with(0.5), Kind::BoundaryContact, 0, 1, "T-junction");
  expect_conflict(with(std::nextafter(0.5, 0.0)), Kind::Overlap, 0, 1, "vertex 3 lies inside triangle 0");
}

TEST(ValidateOverlap, OneUlpNeighboursOfAPointNearASlantedEdge) {
  // Edge a-b of triangle (a, b, c) has no representable interior points in
  // general; the second triangle has its corner q at every point within
  // 2 ulps of the rounded point 37% along it and opens away from it. The
  // validator must agree with GMP on each, and all three outcomes must occur
  // over a few edges.
  int valid = 0, contact = 0, overlap = 0;
  for (const auto& [a, b] : std::vector<std::pair<Point, Point>>{
           {{0.1, 0.1}, {0.7, 0.3}}, {{0.5, 0.5}, {1.5, 1.0}}, {{1, 3}, {4, 5}}, {{0.25, 0.125}, {0.75, 0.625}}}) {
    const Point c{a.x - (b.y - a.y), a.y + (b.x - a.x)};  // left of a->b
    const Point d{b.x - a.x, b.y - a.y};
    const Point right{d.y, -d.x};
    const Point q0{a.x + 0.37 * d.x, a.y + 0.37 * d.y};
    for (int i = -2; i <= 2; ++i)
      for (int j = -2; j <= 2; ++j) {
        Point q = q0;
        for (int s = 0; s < std::abs(i); ++s) q.x = std::nextafter(q.x, i > 0 ? 10.0 : -10.0);
        for (int s = 0; s < std::abs(j); ++s) q.y = std::nextafter(q.y, j > 0 ? 10.0 : -10.0);
        const Point r1{q.x + right.x - 0.1 * d.x, q.y + right.y - 0.1 * d.y};
        const Point r2{q.x + right.x + 0.5 * d.x, q.y + right.y + 0.5 * d.y};
        const Mesh m = from_list({a, b, c, q, r1, r2}, {0, 1, 2, 3, 4, 5});
        const CheckReport r = check_geometry(m);
        SCOPED_TRACE(r.summary());
        expect_agrees(m, r);
        const int side = orient(a, b, q);
        if (side < 0) {
          ++valid;
          EXPECT_TRUE(r.ok());
        } else if (side == 0) {
          ++contact;
          ASSERT_EQ(r.conflicts.size(), 1u);
          EXPECT_EQ(r.conflicts[0].kind, Kind::BoundaryContact);
        } else {
          ++overlap;
          ASSERT_EQ(r.conflicts.size(), 1u);
          EXPECT_EQ(r.conflicts[0].kind, Kind::Overlap);
        }
      }
  }
  EXPECT_GT(valid, 0);
  EXPECT_GT(contact, 0);
  EXPECT_GT(overlap, 0);
}

TEST(ValidateOverlap, CollinearBoundaryEdgesOneUlpApart) {
  // The second triangle's top edge runs from (x0, y0) right along the line
  // y = 1 of the first one's bottom edge 0-1, its corner moved by ulps
  // around (1, 1) and (0.5, 1): apart, end to end at a point, along each
  // other, or inside.
  const double below = std::nextafter(1.0, 0.0), above = std::nextafter(1.0, 2.0);
  int outcomes[3] = {0, 0, 0};
  for (const double y0 : {below, 1.0, above})
    for (const double x0 : {0.5, below, 1.0, above}) {
      const Mesh m = from_list({{0, 1}, {1, 1}, {0, 2}, {x0, y0}, {2, 1}, {1.5, 0}}, {0, 1, 2, 3, 4, 5});
      const CheckReport r = check_geometry(m);
      SCOPED_TRACE(r.summary());
      expect_agrees(m, r);
      ++outcomes[r.conflicts.empty() ? 0 : r.conflicts[0].kind == Kind::Overlap ? 1 : 2];
    }
  EXPECT_GT(outcomes[0], 0);
  EXPECT_GT(outcomes[1], 0);
  EXPECT_GT(outcomes[2], 0);
}

TEST(ValidateOverlap, VerticalEdgesAndSharedEndPoints) {
  // Vertical boundary edges meeting end to end, side by side and crossing:
  // the sweep's (x, y) order must treat them like any other.
  expect_valid(from_list({{0, 0}, {1, 0}, {0, 1}, {0, 2}, {1, 2}}, {0, 1, 2, 2, 4, 3}));
  // A vertical edge through another triangle's vertical edge (along).
  expect_conflict(from_list({{0, 0}, {1, 0}, {0, 2}, {0, 1}, {0, 3}, {-1, 2}}, {0, 1, 2, 3, 5, 4}),
                  Kind::BoundaryContact, 0, 1, "inside boundary edge 2-0");
  // A horizontal edge ending on a vertical one.
  expect_conflict(from_list({{0, 0}, {1, 0}, {0, 2}, {-1, 1}, {0, 1}, {-1, 2}}, {0, 1, 2, 3, 4, 5}),
                  Kind::BoundaryContact, 0, 1, "T-junction");
}

// ---- random triangle soups against the brute force -------------------------

TEST(ValidateOverlap, RandomSoupsAgreeWithBruteForce) {
  // Few triangles on a coarse grid (plus duplicated points) make every kind
  // of contact: shared and duplicated vertices, collinear edges, T-junctions,
  // nesting. Whatever -r accepts, the validator must judge like the brute
  // force.
  gen::Rng rng(19);
  int meshes = 0, defects = 0, contacts = 0;
  for (int iter = 0; iter < 30000; ++iter) {
    std::vector<Point> p;
    const int np = 5 + static_cast<int>(rng.below(6));
    for (int i = 0; i < np; ++i) {
      if (i > 0 && rng.below(6) == 0) p.push_back(p[rng.below(p.size())]);
      else p.push_back({0.5 * static_cast<double>(rng.below(7)), 0.5 * static_cast<double>(rng.below(7))});
    }
    std::vector<VertexId> t;
    const int nt = 2 + static_cast<int>(rng.below(4));
    for (int i = 0; i < 3 * nt; ++i) t.push_back(static_cast<VertexId>(rng.below(p.size())));
    Mesh m;
    try {
      m = from_list(p, t);
    } catch (const InputError&) {
      continue;  // degenerate triangle, edge in three triangles, ...
    }
    ++meshes;
    const CheckReport r = check_geometry(m);
    SCOPED_TRACE("iteration " + std::to_string(iter) + ": " + r.summary());
    expect_agrees(m, r);
    if (HasFatalFailure()) return;
    defects += !r.conflicts.empty();
    contacts += !r.conflicts.empty() && r.conflicts[0].kind == Kind::BoundaryContact;
  }
  EXPECT_GT(meshes, 1000);
  EXPECT_GT(defects, 200);
  EXPECT_GT(contacts, 50);
  std::printf("%d meshes, %d with a conflict (%d contacts)\n", meshes, defects, contacts);
  EXPECT_LT(defects, meshes);
}

TEST(ValidateOverlap, RandomScatteredTrianglesAgreeWithBruteForce) {
  // Dozens of small triangles spread over a grid: long sweeps with many
  // edges active at once, most meshes valid, a few with one contact.
  gen::Rng rng(41);
  int meshes = 0, defects = 0;
  for (int iter = 0; iter < 600; ++iter) {
    std::vector<Point> p;
    std::vector<VertexId> t;
    const int nt = 10 + static_cast<int>(rng.below(40));
    for (int i = 0; i < nt; ++i) {
      const double x = static_cast<double>(rng.below(40)), y = static_cast<double>(rng.below(40));
      std::array<Point, 3> c;
      do {
        for (Point& q : c)
          q = {x + 0.5 * static_cast<double>(rng.below(5)), y + 0.5 * static_cast<double>(rng.below(5))};
      } while (orient(c[0], c[1], c[2]) == 0);
      for (const Point& q : c) {
        t.push_back(static_cast<VertexId>(p.size()));
        p.push_back(q);
      }
    }
    Mesh m;
    try {
      m = from_list(p, t);
    } catch (const InputError&) {
      continue;
    }
    ++meshes;
    const CheckReport r = check_geometry(m);
    SCOPED_TRACE("iteration " + std::to_string(iter) + ": " + r.summary());
    expect_agrees(m, r);
    if (HasFatalFailure()) return;
    defects += !r.conflicts.empty();
  }
  std::printf("%d scattered, %d with a conflict\n", meshes, defects);
  EXPECT_GT(meshes, 50);
  EXPECT_GT(defects, 10);
  EXPECT_LT(defects, meshes - 10);
}

TEST(ValidateOverlap, RandomPiecesOfValidMeshesAgreeWithBruteForce) {
  // Delaunay triangulations of grid points (collinear and cocircular
  // everywhere) with triangles removed and some corners moved to a copy of
  // their vertex: mostly valid pieces touching at points, with edges present
  // twice where a copy breaks a twin link.
  gen::Rng rng(23);
  int meshes = 0, defects = 0;
  for (int iter = 0; iter < 3000; ++iter) {
    std::vector<Point> p;
    const int np = 6 + static_cast<int>(rng.below(10));
    for (int i = 0; i < np; ++i) p.push_back({static_cast<double>(rng.below(5)), static_cast<double>(rng.below(5))});
    Mesh d;
    try {
      d = delaunay(p);
    } catch (const InputError&) {
      continue;  // collinear
    }
    d.compact();
    std::vector<Point> q(d.points().begin(), d.points().end());
    std::vector<VertexId> copy(q.size(), kNone);
    for (VertexId v = 0; v < copy.size(); ++v)
      if (rng.below(4) == 0) {
        copy[v] = static_cast<VertexId>(q.size());
        q.push_back(q[v]);
      }
    std::vector<VertexId> t;
    for (TriId k = 0; k < d.num_triangle_slots(); ++k) {
      if (rng.below(4) == 0) continue;
      for (VertexId v : d.triangle(k)) t.push_back(copy[v] != kNone && rng.below(2) ? copy[v] : v);
    }
    if (t.empty()) continue;
    const Mesh m = from_list(q, t);
    ++meshes;
    const CheckReport r = check_geometry(m);
    SCOPED_TRACE("iteration " + std::to_string(iter) + ": " + r.summary());
    expect_agrees(m, r);
    if (HasFatalFailure()) return;
    defects += !r.conflicts.empty();
  }
  std::printf("%d pieces, %d with a conflict\n", meshes, defects);
  EXPECT_GT(meshes, 2000);
  EXPECT_GT(defects, 200);
  EXPECT_LT(defects, meshes - 200);
}

TEST(ValidateOverlap, RandomFansAgreeWithBruteForce) {
  // Triangles around a common vertex, twins linked: overlapping fans are
  // connected through the shared vertex and edges.
  gen::Rng rng(7);
  int defects = 0, meshes = 0;
  for (int iter = 0; iter < 2000; ++iter) {
    std::vector<Point> p{{0, 0}};
    const int n = 3 + static_cast<int>(rng.below(5));
    for (int i = 0; i < n; ++i) {
      const double a = rng.uniform(0, 2 * M_PI) * (1 + static_cast<double>(rng.below(2)));
      const double rad = 1 + static_cast<double>(rng.below(3));
      p.push_back({std::round(8 * rad * std::cos(a)) / 8, std::round(8 * rad * std::sin(a)) / 8});
    }
    std::vector<VertexId> t;
    for (VertexId i = 1; i + 1 < p.size(); ++i) t.insert(t.end(), {0, i, i + 1});
    if (rng.below(2)) t.insert(t.end(), {0, static_cast<VertexId>(p.size() - 1), 1});
    Mesh m;
    try {
      m = from_list(p, t);
    } catch (const InputError&) {
      continue;
    }
    ++meshes;
    const CheckReport r = check_geometry(m);
    SCOPED_TRACE("iteration " + std::to_string(iter) + ": " + r.summary());
    expect_agrees(m, r);
    if (HasFatalFailure()) return;
    defects += !r.conflicts.empty();
  }
  EXPECT_GT(meshes, 300);
  EXPECT_GT(defects, 30);
  std::printf("%d fans, %d with a conflict\n", meshes, defects);
  EXPECT_LT(defects, meshes);
}

// ---- no false positives on large valid meshes ----------------------------

TEST(ValidateOverlap, LargeDelaunayMeshesAreValid) {
  for (const auto& pts : {gen::uniform_points(100000, 1), gen::gaussian_points(100000, 2)}) {
    Mesh m = delaunay(pts);
    const CheckReport closed = check(m);  // with ghost triangles
    EXPECT_TRUE(closed.ok()) << closed.summary();
    m.compact();
    const CheckReport r = check(m);
    EXPECT_TRUE(r.ok()) << r.summary();
    EXPECT_TRUE(r.conflicts.empty());
  }
}

TEST(ValidateOverlap, ManyBoundaryLoopsAndPinchVertices) {
  // A Delaunay mesh with a third of its triangles removed at random: some
  // ten thousand boundary edges in loops that touch at vertices. Valid; one
  // triangle more on top of the remaining ones is not.
  Mesh d = delaunay(gen::uniform_points(20000, 5));
  d.compact();
  std::vector<Point> p(d.points().begin(), d.points().end());
  std::vector<VertexId> t;
  gen::Rng rng(5);
  for (TriId k = 0; k < d.num_triangle_slots(); ++k)
    if (rng.below(3) != 0)
      for (VertexId v : d.triangle(k)) t.push_back(v);
  const Mesh m = from_list(p, t);
  const CheckReport r = check_geometry(m);
  EXPECT_TRUE(r.conflicts.empty()) << r.summary();
  // Triangle 0 again, on copies of its vertices (the .ele reader refuses
  // the same edge twice on one side).
  const auto first = m.triangle(0);
  const VertexId v = static_cast<VertexId>(p.size());
  p.insert(p.end(), {m.point(first[0]), m.point(first[1]), m.point(first[2])});
  t.insert(t.end(), {v, v + 1, v + 2});
  const Mesh bad = from_list(p, t);
  const CheckReport rb = check_geometry(bad);
  ASSERT_EQ(rb.conflicts.size(), 1u) << rb.summary();
  EXPECT_EQ(rb.conflicts[0].kind, Kind::Overlap);
  EXPECT_EQ(rb.conflicts[0].first, 0u);
  EXPECT_EQ(rb.conflicts[0].second, bad.num_triangles() - 1);
  EXPECT_TRUE(mentions(rb, "the same triangle twice")) << rb.summary();
}

TEST(ValidateOverlap, RefinedMeshesWithHolesAreValid) {
  // Carved domains (holes, notches, many boundary loops), refined, and the
  // same triangles rebuilt the way -r reads them.
  std::vector<Pslg> inputs{gen::square_with_hole(400), gen::star_polygon(3000, 5)};
  inputs.push_back(read_poly((fs::path(DELTAMESH_SOURCE_DIR) / "examples/plate.poly").string()));
  const fs::path corpus = fs::path(DELTAMESH_SOURCE_DIR) / "../shared/corpus";
  for (const char* name : {"earcut_water_huge.poly", "ne110m_land.poly", "cdt_island.poly"})
    if (fs::exists(corpus / name)) inputs.push_back(read_poly((corpus / name).string()));
  for (const Pslg& g : inputs) {
    TriangulateOptions o;
    o.refine = RefineOptions{};
    o.refine->min_angle_deg = 25;
    const Mesh m = triangulate(g, o);
    ASSERT_GT(m.num_triangles(), 0u);
    const CheckReport r = check(m, {.convex_hull = false});
    EXPECT_TRUE(r.conflicts.empty()) << r.summary();
    EXPECT_TRUE(r.ok()) << r.summary();
    std::vector<VertexId> t(m.triangle_vertices().begin(), m.triangle_vertices().end());
    Pslg nodes;
    nodes.points.assign(m.points().begin(), m.points().end());
    const Mesh rebuilt = mesh_from_triangles(nodes, t);
    const CheckReport rr = check_geometry(rebuilt);
    EXPECT_TRUE(rr.conflicts.empty()) << rr.summary();
  }
}

// ---- the command line -------------------------------------------------------

TEST(ValidateOverlap, RebuildingRefusesOverlapsByDefault) {
  Pslg nodes;
  nodes.points = {{0, 2}, {-1.732, -1}, {1.732, -1}, {0, -2}, {1.732, 1}, {-1.732, 1}};
  try {
    (void)mesh_from_triangles(nodes, std::vector<VertexId>{0, 1, 2, 3, 5, 4});
    ADD_FAILURE() << "the star of David was accepted";
  } catch (const OverlappingTriangles& e) {
    EXPECT_EQ(e.first(), 0u);
    EXPECT_EQ(e.second(), 1u);
    EXPECT_EQ(e.how(), "overlap");
  }
  // Side by side: accepted and valid.
  nodes.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const Mesh m = mesh_from_triangles(nodes, std::vector<VertexId>{0, 1, 2, 0, 2, 3});
  EXPECT_TRUE(check(m).ok());
}

TEST(ValidateOverlap, CliRefineRefusesTheStarOfDavid) {
  // -r refuses an overlapping mesh as bad input (exit 2) before anything
  // else runs, naming both triangles as numbered in the file and their lines.
  const fs::path dir = fs::temp_directory_path() / ("deltamesh_overlap_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "star.node") << "6 2 0 0\n1 0 2\n2 -1.732 -1\n3 1.732 -1\n4 0 -2\n5 1.732 1\n6 -1.732 1\n";
  std::ofstream(dir / "star.ele") << "2 3 0\n1 1 2 3\n2 4 6 5\n";
  std::ofstream(dir / "ok.node") << "4 2 0 0\n1 0 0\n2 1 0\n3 1 1\n4 0 1\n";
  std::ofstream(dir / "ok.ele") << "2 3 0\n1 1 2 3\n2 1 3 4\n";
  auto run = [&](const std::string& args, std::string& err) {
    const std::string cmd = "cd '" + dir.string() + "' && '" + std::string(DELTAMESH_CLI) + "' " + args +
                            " > out.txt 2> err.txt";
    const int status = std::system(cmd.c_str());
    std::stringstream ss;
    ss << std::ifstream(dir / "err.txt").rdbuf();
    err = ss.str();
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  };
  std::string err;
  EXPECT_EQ(run("-rC star", err), 2) << err;
  EXPECT_NE(err.find("star.ele:2: triangles 1 and 2 (line 3) overlap"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir / "star.1.ele"));
  EXPECT_EQ(run("-rC ok", err), 0) << err;
  fs::remove_all(dir);
}
