// Constrained triangulations: the four methods of the seed (§1-§2) against
// each other, against Delaunay, on degenerate PSLGs and on small inputs
// whose result we derived by hand. Every mesh goes through the validator,
// with the PSLG so that every segment must be present as a constrained chain.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "algo/cdt_lifting.hpp"
#include "deltamesh-gen/generators.hpp"
#include "deltamesh/cdt.hpp"
#include "deltamesh/delaunay.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/predicates.hpp"
#include "deltamesh/validate.hpp"

using namespace deltamesh;

namespace {

// A method, and for Fast whether it tries the chain order first (forced
// here, to test it on every input; statistics then count differently, the
// CDT is the same).
struct Variant {
  constexpr Variant(CdtMethod m, bool c = false) : method(m), chain(c) {}  // NOLINT: implicit on purpose
  CdtMethod method;
  bool chain;
  bool operator!=(CdtMethod m) const { return method != m; }
  bool operator==(CdtMethod m) const { return method == m; }
};
constexpr Variant kFastChain{CdtMethod::Fast, true};
constexpr Variant kMethods[] = {{CdtMethod::Fast}, kFastChain, {CdtMethod::Ct}, {CdtMethod::Lawson},
                                {CdtMethod::Lifting}};
constexpr Variant kCdtMethods[] = {{CdtMethod::Fast}, kFastChain, {CdtMethod::Lawson}, {CdtMethod::Lifting}};

using TriSet = std::set<std::array<VertexId, 3>>;

TriSet triangle_set(const Mesh& m) {
  TriSet s;
  for (TriId t = 0; t < m.num_triangle_slots(); ++t) {
    if (!m.is_real(t)) continue;
    auto v = m.triangle(t);
    std::sort(v.begin(), v.end());
    s.insert(v);
  }
  return s;
}

std::string name(CdtMethod m) { return std::string(to_string(m)); }
std::string name(Variant v) { return name(v.method) + (v.chain ? "-chain" : ""); }

// Valid mesh, every segment a constrained chain, constrained Delaunay
// unless the method is Ct; returns the report.
CheckReport expect_valid(const Mesh& m, const Pslg& g, Variant method, const std::string& what) {
  CheckOptions o;
  o.pslg = &g;
  o.delaunay = method != CdtMethod::Ct;
  const CheckReport r = check(m, o);
  EXPECT_TRUE(r.ok()) << what << " [" << name(method) << "]: " << r.summary();
  return r;
}

Mesh cdt(const Pslg& g, Variant method, CdtStats* st = nullptr, bool strict = false) {
  CdtOptions o;
  o.method = method.method;
  o.chain_order = method.chain ? ChainOrder::Always : ChainOrder::Never;
  o.strict = strict;
  return constrained_triangulation(g, o, st);
}
Mesh cdt(const Pslg& g, CdtMethod method, CdtStats* st = nullptr, bool strict = false) {
  return cdt(g, Variant{method}, st, strict);
}

// Proper crossing or touching of two segments (exact), sharing endpoints allowed.
bool segments_meet(const Point& a, const Point& b, const Point& c, const Point& d) {
  const double o1 = orient2d(a, b, c), o2 = orient2d(a, b, d);
  const double o3 = orient2d(c, d, a), o4 = orient2d(c, d, b);
  auto sgn = [](double v) { return (v > 0) - (v < 0); };
  if (sgn(o1) * sgn(o2) < 0 && sgn(o3) * sgn(o4) < 0) return true;
  auto on = [&](const Point& p, const Point& q, const Point& r) {  // r on closed pq, given collinear
    return std::min(p.x, q.x) <= r.x && r.x <= std::max(p.x, q.x) && std::min(p.y, q.y) <= r.y &&
           r.y <= std::max(p.y, q.y);
  };
  if (o1 == 0 && on(a, b, c) && !(c == a || c == b)) return true;
  if (o2 == 0 && on(a, b, d) && !(d == a || d == b)) return true;
  if (o3 == 0 && on(c, d, a) && !(a == c || a == d)) return true;
  if (o4 == 0 && on(c, d, b) && !(b == c || b == d)) return true;
  return false;
}

// Random points and random segments between them that do not meet except at
// shared endpoints (greedy), in general position: the CDT is unique.
Pslg random_pslg(std::size_t n, std::size_t segments, std::uint64_t seed, bool short_segments = false) {
  gen::Rng rng(seed * 7919 + 17);
  Pslg g;
  g.points = gen::uniform_points(n, seed);
  std::vector<VertexId> by_x(n);
  for (VertexId i = 0; i < n; ++i) by_x[i] = i;
  std::sort(by_x.begin(), by_x.end(), [&](VertexId p, VertexId q) { return g.points[p].x < g.points[q].x; });
  for (std::size_t attempt = 0; attempt < 30 * segments && g.segments.size() < segments; ++attempt) {
    VertexId a, b;
    if (short_segments) {
      const std::size_t i = rng.below(n);
      const std::size_t j = std::min(n - 1, i + 1 + rng.below(12));
      a = by_x[i];
      b = by_x[j];
    } else {
      a = static_cast<VertexId>(rng.below(n));
      b = static_cast<VertexId>(rng.below(n));
    }
    if (a == b) continue;
    bool ok = true;
    for (const Segment& s : g.segments) {
      if ((s.a == a && s.b == b) || (s.a == b && s.b == a) ||
          segments_meet(g.points[a], g.points[b], g.points[s.a], g.points[s.b])) {
        ok = false;
        break;
      }
    }
    if (ok) g.segments.push_back({a, b, static_cast<int>(g.segments.size() % 3)});
  }
  return g;
}

// Segments between random points with no care for crossings.
Pslg random_crossing_pslg(std::size_t n, std::size_t segments, std::uint64_t seed) {
  gen::Rng rng(seed * 31 + 5);
  Pslg g;
  g.points = gen::uniform_points(n, seed);
  while (g.segments.size() < segments) {
    const auto a = static_cast<VertexId>(rng.below(n)), b = static_cast<VertexId>(rng.below(n));
    if (a != b) g.segments.push_back({a, b, 1 + static_cast<int>(g.segments.size() % 2)});
  }
  return g;
}

Pslg scaled(Pslg g, double s) {
  for (Point& p : g.points) p = {p.x * s, p.y * s};
  return g;
}

// All methods valid; Fast, Lawson and Lifting identical. Fast in chain order
// too, unless segments cross (the crossings are then found in another order
// and rounded differently).
void expect_methods_agree(const Pslg& g, const std::string& what, CdtStats* fast_stats = nullptr) {
  TriSet reference;
  std::size_t crossings = 0;
  for (Variant method : kMethods) {
    CdtStats st;
    const Mesh m = cdt(g, method, &st);
    expect_valid(m, g, method, what);
    if (method == CdtMethod::Fast && !method.chain) {
      reference = triangle_set(m);
      crossings = st.intersections;
      if (fast_stats) *fast_stats = st;
    } else if (method.chain) {
      if (crossings == 0) {
        EXPECT_TRUE(triangle_set(m) == reference) << what << ": fast-chain differs from fast";
      }
    } else if (method != CdtMethod::Ct) {
      EXPECT_TRUE(triangle_set(m) == reference) << what << ": " << name(method) << " differs from fast";
      // (Lawson's Ct phase may stall and finish a piece with Fast: see CtRuleTwoCanStall.)
      if (method == CdtMethod::Lifting) {
        EXPECT_EQ(st.method_fallbacks, 0u) << what << " " << name(method);
      }
    }
  }
}

bool has_edge(const Mesh& m, VertexId a, VertexId b, bool constrained) {
  const HalfEdgeId e = m.find_edge(a, b);
  return e != kNone && (!constrained || m.is_constrained(e));
}

}  // namespace

// ---------------------------------------------------------------------------
// Differential tests.

TEST(CdtDifferential, NoSegmentsEqualsDelaunay) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    Pslg g;
    g.points = gen::uniform_points(3000, seed);
    const Mesh d = delaunay(g.points);
    for (Variant method : kMethods) {
      const Mesh m = cdt(g, method);
      expect_valid(m, g, method, "no segments");
      EXPECT_TRUE(triangle_set(m) == triangle_set(d)) << name(method);
    }
  }
}

TEST(CdtDifferential, SegmentsThatAreDelaunayEdgesChangeNothing) {
  Pslg g;
  g.points = gen::uniform_points(2000, 9);
  const Mesh d = delaunay(g.points);
  for (TriId t = 0; t < d.num_triangle_slots() && g.segments.size() < 300; t += 7) {
    const auto v = d.triangle(t);
    g.segments.push_back({v[0], v[1], 0});
  }
  for (Variant method : kMethods) {
    CdtStats st;
    const Mesh m = cdt(g, method, &st);
    expect_valid(m, g, method, "Delaunay edges as segments");
    EXPECT_TRUE(triangle_set(m) == triangle_set(d)) << name(method);
    EXPECT_EQ(st.flips, 0u);
    EXPECT_EQ(st.segments_already_present + st.overlaps_merged, st.segments_inserted);
  }
}

TEST(CdtDifferential, RandomLongSegments) {
  for (std::uint64_t seed = 1; seed <= 25; ++seed) {
    const Pslg g = random_pslg(150 + 10 * seed, 60, seed);
    CdtStats st;
    expect_methods_agree(g, "random long segments seed " + std::to_string(seed), &st);
    EXPECT_EQ(st.intersections, 0u);
    EXPECT_GT(st.edges_crossed, 0u);
  }
}

TEST(CdtDifferential, RandomShortSegments) {
  for (std::uint64_t seed = 1; seed <= 10; ++seed)
    expect_methods_agree(random_pslg(2000, 800, seed, true), "random short segments seed " + std::to_string(seed));
}

TEST(CdtDifferential, StarPolygons) {
  for (std::size_t n : {3u, 4u, 10u, 100u, 1000u, 5000u})
    for (std::uint64_t seed = 1; seed <= 3; ++seed)
      expect_methods_agree(gen::star_polygon(n, seed), "star " + std::to_string(n) + " seed " + std::to_string(seed));
}

TEST(CdtDifferential, ManyScales) {
  for (double s : {1e-40, 1e-9, 1e-3, 1e3, 1e9, 1e40}) {
    expect_methods_agree(scaled(random_pslg(300, 100, 42), s), "random scaled " + std::to_string(s));
    expect_methods_agree(scaled(gen::star_polygon(500, 3), s), "star scaled " + std::to_string(s));
  }
}

TEST(CdtDifferential, CrossingSegmentsAgree) {
  // Crossings are resolved in the same order by every method, so the
  // vertices added are the same and, the CDT being unique, the triangles too.
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const Pslg g = random_crossing_pslg(120, 40, seed);
    CdtStats st;
    expect_methods_agree(g, "random crossing seed " + std::to_string(seed), &st);
    EXPECT_GT(st.intersections, 0u);
  }
}

// ---------------------------------------------------------------------------
// Small inputs derived by hand.

TEST(CdtGolden, KiteWithItsNonDelaunayDiagonal) {
  // a(0,0) b(4,0) c(2,1) d(2,-1): d lies in the circle of abc, so the
  // Delaunay diagonal is cd; the segment ab forces the other one.
  Pslg g;
  g.points = {{0, 0}, {4, 0}, {2, 1}, {2, -1}};
  EXPECT_TRUE(triangle_set(delaunay(g.points)) == (TriSet{{0, 2, 3}, {1, 2, 3}}));
  g.segments = {{0, 1, 5}};
  for (Variant method : kMethods) {
    CdtStats st;
    const Mesh m = cdt(g, method, &st);
    expect_valid(m, g, method, "kite");
    EXPECT_TRUE(triangle_set(m) == (TriSet{{0, 1, 2}, {0, 1, 3}})) << name(method);
    if (!method.chain) {
      EXPECT_EQ(st.edges_crossed, 1u);
    }
    const HalfEdgeId e = m.find_edge(0, 1);
    ASSERT_NE(e, kNone);
    EXPECT_TRUE(m.is_constrained(e));
    EXPECT_EQ(m.edge_marker(e), 5);
    EXPECT_EQ(m.edge_marker(m.twin(e)), 5);
  }
}

TEST(CdtGolden, PseudoPolygonPicksTheEmptyCircle) {
  // a(0,0) b(10,0) above: p1(2,3) p2(7,2); below: q(5,-3). All five are hull
  // vertices. Above ab the quadrilateral a b p2 p1: p2 lies inside the circle
  // of a b p1 (centre (5,-7/6)), p1 outside that of a b p2 (centre (5,-17/4)),
  // so the triangles are a b p2 and a p2 p1. q lies in the circle of a b p2,
  // so ab is not a Delaunay edge.
  Pslg g;
  g.points = {{0, 0}, {10, 0}, {2, 3}, {7, 2}, {5, -3}};
  EXPECT_FALSE(has_edge(delaunay(g.points), 0, 1, false));
  g.segments = {{0, 1, 0}};
  for (Variant method : kCdtMethods) {
    const Mesh m = cdt(g, method);
    expect_valid(m, g, method, "pseudo-polygon");
    EXPECT_TRUE(triangle_set(m) == (TriSet{{0, 1, 3}, {0, 2, 3}, {0, 1, 4}})) << name(method);
  }
}

TEST(CdtGolden, SquareWithCrossedDiagonals) {
  // The unit square's two diagonals cross at (0.5, 0.5), exactly representable:
  // one vertex is added and the result is the four triangles around it.
  Pslg g;
  g.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  g.segments = {{0, 2, 1}, {1, 3, 2}};
  for (Variant method : kMethods) {
    CdtStats st;
    const Mesh m = cdt(g, method, &st);
    expect_valid(m, g, method, "crossed diagonals");
    ASSERT_EQ(m.num_vertices(), 5u);
    EXPECT_EQ(m.point(4), (Point{0.5, 0.5}));
    EXPECT_EQ(st.intersections, 1u);
    EXPECT_TRUE(triangle_set(m) == (TriSet{{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {0, 3, 4}})) << name(method);
    EXPECT_EQ(m.edge_marker(m.find_edge(0, 4)), 1);
    EXPECT_EQ(m.edge_marker(m.find_edge(4, 2)), 1);
    EXPECT_EQ(m.edge_marker(m.find_edge(1, 4)), 2);
    EXPECT_EQ(m.edge_marker(m.find_edge(4, 3)), 2);
  }
}

// ---------------------------------------------------------------------------
// Degenerate PSLGs.

TEST(CdtDegenerate, VertexOnSegmentSplitsIt) {
  Pslg g;
  g.points = {{0, 0}, {1, 0}, {2, 0}, {3, 0}, {1.5, 1}, {1.5, -1}, {0.7, 0.2}};
  g.segments = {{0, 3, 7}};
  for (Variant method : kMethods) {
    CdtStats st;
    const Mesh m = cdt(g, method, &st);
    expect_valid(m, g, method, "vertex on segment");
    EXPECT_EQ(st.vertices_on_segments, 2u);
    for (auto [a, b] : {std::pair{0u, 1u}, {1u, 2u}, {2u, 3u}}) {
      ASSERT_TRUE(has_edge(m, a, b, true)) << a << "-" << b;
      EXPECT_EQ(m.edge_marker(m.find_edge(a, b)), 7);
    }
  }
}

TEST(CdtDegenerate, VerticesOnALongDiagonal) {
  // Grid points on the diagonal of a grid: cocircular everywhere, and the
  // segment passes through k - 2 vertices.
  const std::size_t k = 20;
  Pslg g;
  g.points = gen::grid_points(k * k);
  g.segments = {{0, static_cast<VertexId>(k * k - 1), 3}, {static_cast<VertexId>(k - 1),
                                                           static_cast<VertexId>(k * (k - 1)), 4}};
  for (Variant method : kMethods) {
    CdtStats st;
    const Mesh m = cdt(g, method, &st);
    expect_valid(m, g, method, "grid diagonals");
    // Both diagonals pass through k - 2 grid vertices; for even k they cross
    // between grid points, at the centre (k-1)/2, a multiple of 1/2.
    EXPECT_EQ(st.intersections, 1u);
    EXPECT_EQ(st.vertices_on_segments, 2 * (k - 2));
  }
}

TEST(CdtDegenerate, CollinearOverlappingSegmentsMerge) {
  Pslg g;
  g.points = {{0, 0}, {1, 0}, {2, 0}, {3, 0}, {1.5, 2}, {1.5, -2}};
  g.segments = {{0, 2, 0}, {1, 3, 9}, {0, 3, 4}, {2, 1, 0}};
  for (Variant method : kMethods) {
    CdtStats st;
    const Mesh m = cdt(g, method, &st);
    expect_valid(m, g, method, "overlaps");
    EXPECT_TRUE(has_edge(m, 0, 1, true));
    EXPECT_TRUE(has_edge(m, 1, 2, true));
    EXPECT_TRUE(has_edge(m, 2, 3, true));
    // (0,1): first segment has marker 0, the third has 4; (1,2): 0 then 9; (2,3): 9.
    EXPECT_EQ(m.edge_marker(m.find_edge(0, 1)), 4);
    EXPECT_EQ(m.edge_marker(m.find_edge(1, 2)), 9);
    EXPECT_EQ(m.edge_marker(m.find_edge(2, 3)), 9);
    // Pieces met constrained already: seg 1 on (1,2); seg 2 on (0,1),(1,2),(2,3); seg 3 whole.
    if (!method.chain) {
      EXPECT_EQ(st.overlaps_merged, 5u);
    }  // (counted in insertion order)
  }
}

TEST(CdtDegenerate, TwoCrossingSegments) {
  Pslg g;
  g.points = {{0, 0}, {3, 1}, {1, 2}, {2, -1}, {5, 5}, {-2, 4}};
  g.segments = {{0, 1, 1}, {2, 3, 2}};
  for (Variant method : kMethods) {
    CdtStats st;
    const Mesh m = cdt(g, method, &st);
    expect_valid(m, g, method, "two crossing");
    EXPECT_EQ(st.intersections, 1u);
    ASSERT_EQ(m.num_vertices(), 7u);
    const Point p = m.point(6);  // the intersection (1.5, 0.5), up to rounding
    EXPECT_NEAR(p.x, 1.5, 1e-15);
    EXPECT_NEAR(p.y, 0.5, 1e-15);
    EXPECT_TRUE(has_edge(m, 0, 6, true));
    EXPECT_TRUE(has_edge(m, 6, 1, true));
    EXPECT_TRUE(has_edge(m, 2, 6, true));
    EXPECT_TRUE(has_edge(m, 6, 3, true));
    EXPECT_EQ(m.edge_marker(m.find_edge(0, 6)), 1);
    EXPECT_EQ(m.edge_marker(m.find_edge(6, 3)), 2);
  }
}

TEST(CdtDegenerate, StrictModeNamesBothSegments) {
  Pslg g;
  g.points = {{0, 0}, {3, 1}, {1, 2}, {2, -1}, {5, 5}, {-2, 4}, {4, 4}};
  g.segments = {{4, 6, 0}, {0, 1, 0}, {2, 3, 0}};
  for (Variant method : kMethods) {
    try {
      cdt(g, method, nullptr, true);
      ADD_FAILURE() << "no exception " << name(method);
    } catch (const IntersectingSegments& e) {
      EXPECT_EQ(e.first(), 1u);
      EXPECT_EQ(e.second(), 2u);
      EXPECT_NE(std::string(e.what()).find("segments 1 and 2"), std::string::npos) << e.what();
    }
  }
  // Touching at a vertex, overlapping and vertices on segments are not errors.
  Pslg ok;
  ok.points = {{0, 0}, {1, 0}, {2, 0}, {1, 1}, {1, -1}};
  ok.segments = {{0, 2, 0}, {0, 1, 0}, {3, 1, 0}, {1, 4, 0}};
  for (Variant method : kMethods) EXPECT_NO_THROW(cdt(ok, method, nullptr, true));
}

TEST(CdtDegenerate, StarThroughOneExactPoint) {
  // Segments through the origin, endpoints symmetric: the first crossing
  // computes (0,0) exactly; every later segment passes through it.
  Pslg g;
  const int dirs[][2] = {{1, 0}, {0, 1}, {1, 1}, {1, -1}, {2, 1}, {1, 2}, {-1, 2}, {2, -1}, {3, 1}, {1, 3}};
  for (const auto& d : dirs) {
    const auto i = static_cast<VertexId>(g.points.size());
    g.points.push_back({static_cast<double>(d[0]), static_cast<double>(d[1])});
    g.points.push_back({-static_cast<double>(d[0]), -static_cast<double>(d[1])});
    g.segments.push_back({i, i + 1, static_cast<int>(i / 2 + 1)});
  }
  for (Variant method : kMethods) {
    CdtStats st;
    const Mesh m = cdt(g, method, &st);
    expect_valid(m, g, method, "exact star");
    EXPECT_EQ(st.intersections, 1u);
    EXPECT_EQ(st.vertices_on_segments, std::size(dirs) - 2);
    ASSERT_EQ(m.num_vertices(), g.points.size() + 1);
    EXPECT_EQ(m.point(static_cast<VertexId>(g.points.size())), (Point{0, 0}));
  }
}

TEST(CdtDegenerate, StarThroughAnInexactPoint) {
  // Many segments through (1/3, 1/7), which no double represents: the
  // crossings are rounded and lie near, not on, the later segments.
  Pslg g;
  const Point c{1.0 / 3.0, 1.0 / 7.0};
  const int k = 24;
  for (int i = 0; i < k; ++i) {
    const double a = std::numbers::pi * (i + 0.37) / k;
    const auto v = static_cast<VertexId>(g.points.size());
    g.points.push_back({c.x + std::cos(a), c.y + std::sin(a)});
    g.points.push_back({c.x - 1.3 * std::cos(a), c.y - 1.3 * std::sin(a)});
    g.segments.push_back({v, v + 1, i});
  }
  CdtStats fast_st;
  expect_methods_agree(g, "inexact star", &fast_st);
  EXPECT_GE(fast_st.intersections, 1u);
  EXPECT_LE(fast_st.intersections, static_cast<std::size_t>(k * (k - 1) / 2));
}

TEST(CdtDegenerate, DuplicateVerticesAreMerged) {
  Pslg g;
  g.points = {{0, 0}, {2, 0}, {1, 1}, {1, -1}, {0, 0}, {2, 0}, {1, 1}};
  g.segments = {{4, 5, 1}, {6, 3, 2}, {0, 6, 3}};
  for (Variant method : kMethods) {
    CdtStats st;
    const Mesh m = cdt(g, method, &st);
    expect_valid(m, g, method, "duplicates");
    EXPECT_EQ(st.duplicate_vertices, 3u);
    // The first copy of each point is the one used.
    for (VertexId v : {0u, 1u, 2u, 3u}) EXPECT_NE(m.out_edge(v), kNone);
    for (VertexId v : {4u, 5u, 6u}) EXPECT_EQ(m.out_edge(v), kNone);
    EXPECT_EQ(st.intersections, 1u);  // 0-1 and 2-3 cross at (1, 0)
    ASSERT_EQ(m.num_vertices(), 8u);
    EXPECT_EQ(m.point(7), (Point{1, 0}));
    for (auto [a, b] : {std::pair{0u, 7u}, {7u, 1u}, {2u, 7u}, {7u, 3u}, {0u, 2u}})
      EXPECT_TRUE(has_edge(m, a, b, true)) << a << "-" << b;
  }
}

TEST(CdtDegenerate, ZeroLengthSegmentsAreIgnored) {
  Pslg g;
  g.points = {{0, 0}, {1, 0}, {0, 1}, {1, 1}, {1, 1}};
  g.segments = {{0, 0, 0}, {3, 4, 0}, {0, 3, 1}};
  for (Variant method : kMethods) {
    CdtStats st;
    const Mesh m = cdt(g, method, &st);
    expect_valid(m, g, method, "zero length");
    EXPECT_EQ(st.zero_length_segments, 2u);
    EXPECT_EQ(st.segments_inserted, 1u);
  }
}

TEST(CdtDegenerate, SegmentsOnTheConvexHull) {
  // Square with points on its sides; segments along whole sides, a segment
  // along part of a side, and one joining two hull vertices through the inside.
  Pslg g;
  g.points = {{0, 0}, {4, 0}, {4, 4}, {0, 4}, {1, 0}, {2, 0}, {3, 0}, {4, 2}, {2, 2}, {1, 3}};
  g.segments = {{0, 1, 1}, {1, 2, 2}, {2, 3, 3}, {3, 0, 4}, {4, 6, 5}, {0, 2, 6}};
  for (Variant method : kMethods) {
    CdtStats st;
    const Mesh m = cdt(g, method, &st);
    expect_valid(m, g, method, "hull segments");
    // 0-1: 4,5,6; 1-2: 7; 4-6: 5; 0-2: 8 (in chain order 5 is met once, on 0-1 and 4-6 at once)
    EXPECT_EQ(st.vertices_on_segments, method.chain ? 5u : 6u);
    EXPECT_EQ(m.edge_marker(m.find_edge(4, 5)), 1);
  }
}

TEST(CdtDegenerate, CocircularGridWithSegments) {
  const std::size_t k = 30;
  Pslg g;
  g.points = gen::grid_points(k * k);
  gen::Rng rng(5);
  for (int s = 0; s < 60; ++s) {
    const auto a = static_cast<VertexId>(rng.below(k * k)), b = static_cast<VertexId>(rng.below(k * k));
    if (a != b) g.segments.push_back({a, b, s});
  }
  for (Variant method : kMethods) {
    CdtStats st;
    const Mesh m = cdt(g, method, &st);
    expect_valid(m, g, method, "grid with segments");
  }
}

TEST(CdtDegenerate, ManyRandomCrossings) {
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const Pslg g = random_crossing_pslg(300, 150, seed);
    for (Variant method : kMethods) {
      CdtStats st;
      const Mesh m = cdt(g, method, &st);
      expect_valid(m, g, method, "many crossings seed " + std::to_string(seed));
      EXPECT_GT(st.intersections, 100u);
    }
  }
}

TEST(CdtDegenerate, NearlyParallelSegments) {
  // Long segments at tiny angles to each other, crossing near their middles:
  // the rounded crossings sit within rounding distance of other segments.
  Pslg g;
  const int k = 12;
  for (int i = 0; i < k; ++i) {
    const double e = 1e-13 * (i - k / 2);
    const auto v = static_cast<VertexId>(g.points.size());
    g.points.push_back({0.1 * i / k, 1.0 + e});
    g.points.push_back({1.0 + 0.1 * i / k, 1.0 - e + 3e-14 * i});
    g.segments.push_back({v, v + 1, i});
  }
  g.points.push_back({0.5, 0.0});
  g.points.push_back({0.5, 2.0});
  for (Variant method : kMethods) {
    CdtStats st;
    const Mesh m = cdt(g, method, &st);
    expect_valid(m, g, method, "nearly parallel");
  }
}

TEST(CdtDegenerate, SegmentEndpointOutOfRange) {
  Pslg g;
  g.points = {{0, 0}, {1, 0}, {0, 1}};
  g.segments = {{0, 1, 0}, {1, 3, 0}};
  try {
    cdt(g, CdtMethod::Fast);
    ADD_FAILURE() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.index(), 1u);
  }
}

TEST(CdtGolden, CtRuleTwoCanStall) {
  // §1.2.2's rule (2), never re-create an edge flipped before, can leave no
  // flippable crossing edge (against Lemma 1.1). Segment 0-1 crosses 5-3,
  // 6-3, 2-3, 2-4. The queue flips 6-3 -> 5-2 and 2-3 -> 5-4; then 2-4 and
  // 5-3 have non-convex quadrilaterals and 5-4 could only flip back to 2-3.
  // Ct counts the stall and finishes the piece by cavity retriangulation.
  Pslg g;
  g.points = {{0.94070313461681032, 0.53922335309401248}, {0.25932844341119832, 0.65380630433091891},
              {0.39292474564523305, 0.63291791754424209}, {0.76124479191970984, 0.4453086748443088},
              {0.57027720766124346, 0.15779353162799037}, {0.74542173535171141, 0.62387346740194782},
              {0.6434784246042905, 0.68285977806548737}};
  g.segments = {{0, 1, 0}};
  CdtStats st;
  const Mesh m = cdt(g, CdtMethod::Ct, &st);
  expect_valid(m, g, CdtMethod::Ct, "rule (2) stall");
  EXPECT_EQ(st.edges_crossed, 4u);
  EXPECT_EQ(st.flips, 2u);
  EXPECT_EQ(st.method_fallbacks, 1u);
}

// ---------------------------------------------------------------------------
// The lifting map's event time (§2.3, equation (1)).

TEST(CdtLifting, SeedEventTimeIsTheVerticalGap) {
  // Equation (1): t(c,d) is the gap, above the point where cd crosses ab,
  // between the lifted segment a'b' and the lifted edge c'd'.
  gen::Rng rng(3);
  int tested = 0;
  for (int i = 0; i < 200; ++i) {
    const Point a{rng.uniform(-1, 0), rng.uniform(-1, 1)}, b{rng.uniform(1, 2), rng.uniform(-1, 1)};
    const Point c{rng.uniform(0, 1), rng.uniform(1, 2)}, d{rng.uniform(0, 1), rng.uniform(-2, -1)};
    if (!(orient2d(a, b, c) > 0 && orient2d(a, b, d) < 0 && orient2d(c, d, a) * orient2d(c, d, b) < 0)) continue;
    ++tested;
    const double s = orient2d(c, d, a) / (orient2d(c, d, a) - orient2d(c, d, b));  // along ab
    const double r = orient2d(a, b, c) / (orient2d(a, b, c) - orient2d(a, b, d));  // along cd
    auto lift = [](const Point& p) { return p.x * p.x + p.y * p.y; };
    const double gap = (1 - s) * lift(a) + s * lift(b) - ((1 - r) * lift(c) + r * lift(d));
    const detail::EventTime t = detail::seed_event_time(a, b, c, d);
    EXPECT_NEAR(t.t, gap, 1e-12 * (1 + std::fabs(gap)));
    EXPECT_LE(t.lo, t.t);
    EXPECT_GE(t.hi, t.t);
  }
  EXPECT_GT(tested, 50);
}

TEST(CdtLifting, SeedEventTimesCompareExactly) {
  // Symmetric edges crossing a horizontal segment have equal event times.
  const Point a{0, 0}, b{4, 0};
  const Point c1{1, 1}, d1{1, -1}, c2{3, 1}, d2{3, -1};
  EXPECT_EQ(detail::compare_seed_event_times(a, b, c1, d1, c2, d2), 0);
  EXPECT_EQ(detail::compare_times(detail::seed_event_time(a, b, c1, d1), detail::seed_event_time(a, b, c2, d2)), 0);
  // c3 higher: its lifted edge is higher, the gap smaller: earlier.
  const Point c3{3, 1.5};
  EXPECT_EQ(detail::compare_seed_event_times(a, b, c3, d2, c2, d2), -1);
  EXPECT_EQ(detail::compare_seed_event_times(a, b, c2, d2, c3, d2), 1);
}

TEST(CdtLifting, SeedOrderDoesNotGiveTheCdt) {
  // Why the Lifting method moves the lifted points differently from §2.3's
  // equation (1). Segment a-b crosses 3-2 then 3-4 (3 left of ab, 2 and 4
  // right). The CDT's right side is the quadrilateral a 2 4 b split by 2-b
  // (4 is outside the circle of a 2 b). Equation (1) orders 3-2 first, and
  // flipping it (apexes a and 4) creates a-4, the other diagonal.
  Pslg g;
  g.points = {{0.782714, 0.098533}, {0.498231, 0.750122}, {0.799279, 0.134122}, {0.668237, 0.127841},
              {0.828161, 0.500339}, {0.790370, 0.832473}};
  const Point &a = g.points[0], &b = g.points[1];
  ASSERT_LT(orient2d(a, b, g.points[2]), 0);
  ASSERT_GT(orient2d(a, b, g.points[3]), 0);
  ASSERT_LT(orient2d(a, b, g.points[4]), 0);
  EXPECT_LT(incircle(a, g.points[2], b, g.points[4]), 0);
  EXPECT_EQ(detail::compare_seed_event_times(a, b, g.points[3], g.points[2], g.points[3], g.points[4]), -1);
  g.segments = {{0, 1, 0}};
  for (Variant method : kCdtMethods) {
    CdtStats st;
    const Mesh m = cdt(g, method, &st);
    expect_valid(m, g, method, "seed counterexample");
    if (!method.chain) {
      EXPECT_EQ(st.edges_crossed, 2u);
    }
    EXPECT_TRUE(has_edge(m, 2, 1, false)) << name(method);
    EXPECT_FALSE(has_edge(m, 0, 4, false)) << name(method);
  }
}

TEST(CdtLifting, KineticEvents) {
  const Point a{0, 0}, b{4, 0};
  // A quad wholly on one side never changes (R1 = 0 exactly).
  const detail::Quad left{{1, 1}, {3, 1}, {2, 3}, {2, 0.5}, false, false, false, false};
  EXPECT_FALSE(detail::kinetic_event(a, b, left).happens);
  const detail::Quad right{{1, -1}, {3, -1}, {2, -0.5}, {2, -3}, true, true, true, true};
  EXPECT_FALSE(detail::kinetic_event(a, b, right).happens);
  // The edge (1,1)-(1,-1) between apexes a and (3,0.1) is locally Delaunay and
  // crosses ab: it flips at a positive time, and ties compare equal.
  const detail::Quad cross{{1, 1}, {1, -1}, {3, 0.1}, {0, 0}, false, true, false, false};
  const detail::KineticEvent k = detail::kinetic_event(a, b, cross);
  ASSERT_TRUE(k.happens);
  EXPECT_LT(incircle(cross.x, cross.y, cross.p, cross.q), 0);
  EXPECT_GT(k.time.t, 0.0);
  EXPECT_EQ(detail::compare_kinetic_times(a, b, cross, cross), 0);
  // Further from the segment's line, the right vertex rises faster: earlier.
  const detail::Quad deeper{{1, 1}, {1, -2}, {3, 0.1}, {0, 0}, false, true, false, false};
  const detail::KineticEvent k2 = detail::kinetic_event(a, b, deeper);
  ASSERT_TRUE(k2.happens);
  const int s = detail::compare_kinetic_times(a, b, deeper, cross);
  EXPECT_EQ(s, k2.time.t < k.time.t ? -1 : 1);
  EXPECT_EQ(detail::compare_kinetic_times(a, b, cross, deeper), -s);
  // The exact comparison (degree 8) holds at the ends of the coordinate range.
  for (double scale : {0x1p-150, 0x1p150}) {
    auto sp = [&](const Point& q) { return Point{q.x * scale, q.y * scale}; };
    auto sq = [&](const detail::Quad& k) {
      return detail::Quad{sp(k.x), sp(k.y), sp(k.p), sp(k.q), k.rx, k.ry, k.rp, k.rq};
    };
    EXPECT_EQ(detail::compare_kinetic_times(sp(a), sp(b), sq(deeper), sq(cross)), s) << scale;
    EXPECT_EQ(detail::compare_kinetic_times(sp(a), sp(b), sq(cross), sq(cross)), 0) << scale;
  }
}

// ---------------------------------------------------------------------------
// Statistics and method names.

TEST(CdtApi, MethodNamesRoundTrip) {
  for (Variant m : kMethods) EXPECT_EQ(parse_cdt_method(to_string(m.method)), m.method);
  EXPECT_FALSE(parse_cdt_method("delaunay").has_value());
}

TEST(CdtApi, FlipCountsFollowTheSeed) {
  // Fast (in the classic order) flips nothing.
  const Pslg g = random_pslg(400, 120, 77);
  CdtStats fast, ct, lawson, lifting;
  cdt(g, CdtMethod::Fast, &fast);
  EXPECT_FALSE(fast.chain_order);
  cdt(g, CdtMethod::Ct, &ct);
  cdt(g, CdtMethod::Lawson, &lawson);
  cdt(g, CdtMethod::Lifting, &lifting);
  EXPECT_EQ(fast.flips, 0u);
  EXPECT_EQ(fast.cavity_triangles, fast.edges_crossed + fast.segments_inserted - fast.segments_already_present);
  // Fast and Lifting see the same CDT before every segment, so the same crossings.
  EXPECT_EQ(lifting.edges_crossed, fast.edges_crossed);
  // Every crossed edge is flipped at least once.
  EXPECT_GE(lifting.flips, lifting.edges_crossed);
  EXPECT_GE(ct.flips, ct.edges_crossed);
  EXPECT_GE(lawson.flips, lawson.edges_crossed);
  EXPECT_EQ(lifting.method_fallbacks, 0u);
}

// ---------------------------------------------------------------------------
// Fast's chain order.

TEST(CdtChainOrder, UsedOnPolygonsAndSameCdt) {
  for (std::size_t n : {10u, 1000u, 20000u}) {
    const Pslg g = gen::star_polygon(n, 7);
    CdtStats chain, classic;
    const Mesh a = cdt(g, kFastChain, &chain);
    const Mesh b = cdt(g, CdtMethod::Fast, &classic);
    EXPECT_TRUE(chain.chain_order) << n;
    EXPECT_FALSE(classic.chain_order);
    expect_valid(a, g, kFastChain, "star chain order");
    EXPECT_TRUE(triangle_set(a) == triangle_set(b)) << n;
    // Segments meet far fewer edges when inserted as their vertices arrive.
    if (n >= 1000) {
      EXPECT_LT(chain.edges_crossed * 4, classic.edges_crossed) << n;
    }
    // The default options use it on these long segments.
    CdtStats def;
    constrained_triangulation(g, {}, &def);
    if (n >= 1000) {
      EXPECT_TRUE(def.chain_order);
    }
  }
}

TEST(CdtChainOrder, GivesUpOnConvexCurves) {
  // Points along an ellipse inserted in order make every insertion flip
  // across the whole triangulation; the attempt stops and the classic order
  // gives the same CDT.
  Pslg g;
  const std::size_t n = 20000;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = 2 * std::numbers::pi * static_cast<double>(i) / n;
    g.points.push_back({std::cos(t), 0.5 * std::sin(t)});
    g.segments.push_back({static_cast<VertexId>(i), static_cast<VertexId>((i + 1) % n), 1});
  }
  CdtStats st;
  const Mesh m = cdt(g, kFastChain, &st);
  EXPECT_TRUE(st.chain_order_abandoned);
  EXPECT_FALSE(st.chain_order);
  expect_valid(m, g, kFastChain, "ellipse");
  EXPECT_EQ(st.segments_inserted, n);
}

TEST(CdtChainOrder, LoosePointsAndManyChains) {
  // Random short segments (many small chains) plus points on no segment.
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    Pslg g = random_pslg(3000, 600, seed, true);
    CdtStats chain, classic;
    const Mesh a = cdt(g, kFastChain, &chain);
    const Mesh b = cdt(g, CdtMethod::Fast, &classic);
    expect_valid(a, g, kFastChain, "chains and loose points");
    EXPECT_TRUE(triangle_set(a) == triangle_set(b)) << seed;
  }
}

TEST(CdtChainOrder, NotTriedOnShortSegments) {
  // Coastline-like input: segments as short as the vertex spacing along
  // them, far below the spacing of the vertices over the bounding box.
  Pslg g;
  const std::size_t n = 5000;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = 2 * std::numbers::pi * static_cast<double>(i) / n;
    const double r = 1 + 0.1 * std::sin(37 * t);
    g.points.push_back({r * std::cos(t), r * std::sin(t)});
    g.segments.push_back({static_cast<VertexId>(i), static_cast<VertexId>((i + 1) % n), 0});
  }
  CdtStats st;
  const Mesh m = constrained_triangulation(g, {}, &st);
  EXPECT_FALSE(st.chain_order);
  EXPECT_FALSE(st.chain_order_abandoned);
  expect_valid(m, g, CdtMethod::Fast, "short segments");
}

TEST(CdtChainOrder, InputVertexAtACrossing) {
  // The diagonals cross at (1,1), which is also an input vertex on no segment:
  // in the chain order it arrives after the crossing was added, and takes
  // that vertex's place (no extra vertex is left over).
  Pslg g;
  g.points = {{0, 0}, {2, 2}, {0, 2}, {2, 0}, {1, 1}, {3, 1}, {1, 3}};
  g.segments = {{0, 1, 1}, {2, 3, 2}, {5, 6, 3}};
  for (Variant method : kMethods) {
    CdtStats st;
    const Mesh m = cdt(g, method, &st);
    expect_valid(m, g, method, "input vertex at a crossing");
    EXPECT_EQ(m.num_vertices(), g.points.size()) << name(method);
    EXPECT_EQ(st.intersections, method.chain ? 1u : 0u) << name(method);
    for (auto [a, b] : {std::pair{0u, 4u}, {4u, 1u}, {2u, 4u}, {4u, 3u}})
      EXPECT_TRUE(has_edge(m, a, b, true)) << name(method) << " " << a << "-" << b;
  }
}

TEST(CdtDegenerate, NearlyConcurrentSegmentsTerminate) {
  // Short random segments between points close in x: many cross, some
  // nearly at a shared endpoint, where rounded crossings used to keep
  // creating new crossings an ulp apart. Crossings within rounding distance
  // of an endpoint are resolved at it.
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    Pslg g;
    g.points = gen::uniform_points(1000, seed);
    gen::Rng rng(seed + 1000);
    std::vector<VertexId> order(1000);
    for (VertexId i = 0; i < 1000; ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](VertexId a, VertexId b) { return g.points[a].x < g.points[b].x; });
    for (int s = 0; s < 500; ++s) {
      const std::size_t i = rng.below(1000), j = std::min<std::size_t>(999, i + 1 + rng.below(31));
      if (i != j) g.segments.push_back({order[i], order[j], 1});
    }
    for (Variant method : kMethods) {
      CdtStats st;
      const Mesh m = cdt(g, method, &st);
      expect_valid(m, g, method, "nearly concurrent seed " + std::to_string(seed));
      EXPECT_LT(st.intersections, 2000u) << name(method);
    }
  }
}
