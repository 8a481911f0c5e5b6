// Small input angles at hubs (issue 18): a vertex where many segments meet,
// at equal or random angles (neighbours down to hundredths of a degree
// apart), of equal or random lengths, through the vertex or ending at it,
// two hubs whose spokes cross, at 1e-6 and 1e6 scale. Delaunay refinement
// runs away there unless the small-angle rules keep its work bounded by
// the local feature size. Each input is refined at 20°, 30° and 33°:
// refinement must complete (no budget, no time limit), the mesh must pass
// the validator, every triangle left below the bound must lie inside an
// input angle under 60° (checked here from the geometry, not only from the
// refiner's own report), and the triangle count must stay in a range far
// below what plain Ruppert refinement makes (the counts Triangle 1.6 makes on
// inputs of this construction are 2-100 times larger).
//
// The inputs are built here with their own seeded generator (the same
// construction as the issue's family, not its files).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <numeric>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include "algo/refine/queue.hpp"
#include "deltamesh/pslg.hpp"
#include "deltamesh/refine.hpp"
#include "deltamesh/triangle_io.hpp"
#include "deltamesh/triangulate.hpp"
#include "test_refine_util.hpp"

namespace dm = deltamesh;

namespace {

constexpr double kPi = std::numbers::pi;

// Uniform in [lo, hi) from the top 53 bits (std::mt19937_64 is fully
// specified; the standard distributions are not, across libraries).
double uniform(std::mt19937_64& rng, double lo, double hi) {
  return lo + (hi - lo) * static_cast<double>(rng() >> 11) * 0x1p-53;
}

void add_box(dm::Pslg& g, double half) {
  const auto b0 = static_cast<dm::VertexId>(g.points.size());
  g.points.insert(g.points.end(), {{-half, -half}, {half, -half}, {half, half}, {-half, half}});
  for (dm::VertexId i = 0; i < 4; ++i) g.segments.push_back({b0 + i, b0 + (i + 1) % 4, 0});
}

// k spokes of length `scale` at equal angles from the origin, or (cross)
// k/2 segments through the origin; inside a box of half-width 2 scale.
dm::Pslg hub(int k, double scale, bool cross = false) {
  dm::Pslg g;
  if (cross) {
    for (int i = 0; i < k / 2; ++i) {
      const double a = kPi * i / (k / 2);
      const auto v = static_cast<dm::VertexId>(g.points.size());
      g.points.push_back({-scale * std::cos(a), -scale * std::sin(a)});
      g.points.push_back({scale * std::cos(a), scale * std::sin(a)});
      g.segments.push_back({v, v + 1, 0});
    }
  } else {
    g.points.push_back({0, 0});
    for (int i = 0; i < k; ++i) {
      const double a = 2 * kPi * i / k;
      g.points.push_back({scale * std::cos(a), scale * std::sin(a)});
      g.segments.push_back({0, static_cast<dm::VertexId>(g.points.size() - 1), 0});
    }
  }
  add_box(g, 2 * scale);
  return g;
}

// k spokes at uniformly random angles, lengths uniform in [0.3, 1) scale.
dm::Pslg irregular(int k, std::uint64_t seed, double scale) {
  std::mt19937_64 rng(seed);
  std::vector<double> ang(k);
  for (double& a : ang) a = uniform(rng, 0, 2 * kPi);
  std::sort(ang.begin(), ang.end());
  dm::Pslg g;
  g.points.push_back({0, 0});
  for (const double a : ang) {
    const double r = scale * uniform(rng, 0.3, 1.0);
    g.points.push_back({r * std::cos(a), r * std::sin(a)});
    g.segments.push_back({0, static_cast<dm::VertexId>(g.points.size() - 1), 0});
  }
  add_box(g, 2 * scale);
  return g;
}

// Two 64-spoke hubs 0.01 apart: their spokes cross at 4000-odd points.
dm::Pslg two_hubs() {
  dm::Pslg g = hub(64, 1.0);
  const auto base = static_cast<dm::VertexId>(g.points.size());
  for (int i = 0; i <= 64; ++i) g.points.push_back({g.points[i].x + 0.01, g.points[i].y});
  for (int i = 0; i < 64; ++i) g.segments.push_back({base, base + 1 + static_cast<dm::VertexId>(i), 0});
  return g;
}

// Spokes along primitive lattice directions (p, q), |p|, |q| <= m, to
// lattice points 1-3 times farther out (many segments at one vertex, angles
// from 45° down to under 1°, lengths differing by factors up to 10).
dm::Pslg lattice(int m, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  dm::Pslg g;
  g.points.push_back({0, 0});
  for (int p = -m; p <= m; ++p)
    for (int q = -m; q <= m; ++q) {
      if (std::gcd(p, q) != 1) continue;
      const double f = 1.0 + static_cast<double>(rng() % 3);
      g.points.push_back({f * p, f * q});
      g.segments.push_back({0, static_cast<dm::VertexId>(g.points.size() - 1), 0});
    }
  add_box(g, 4.0 * m);
  return g;
}

struct HubCase {
  std::string name;
  dm::Pslg (*make)();
  // Largest triangle count accepted at 20°, 30° and 33° (about 1.5 times
  // what the rules give today).
  std::size_t most[3];
};

// The triangles below the bound that are not explained by a small input
// angle, decided from the final mesh alone (not from the refiner's report).
// Segments are the straight chains of constrained edges (through Steiner
// vertices and crossings); a triangle below the bound is explained when
//  - it has a corner between two segments at an input vertex, or
//  - its centroid lies in an angle under 60° between two segments at an
//    input vertex, no farther from that vertex than the longer of the two
//    reaches (first looked for at the input vertices on the segments the
//    triangle touches, then at any: Shewchuk's rule, and the guard at an
//    apex, leave triangles whose Steiner point would encroach a subsegment
//    near the apex, and such a triangle need not touch that segment), or
//  - at an input vertex on a segment it touches, its shortest edge joins two
//    different segments there that make an angle under 60°, its centroid in
//    their cone (Miller, Pav and Walkington, IMR 2003: that edge faces the
//    input angle; splitting the triangle only makes shorter edges there).
std::size_t below_outside_small_angles(const dm::Mesh& mesh, std::size_t n_input, double bound_deg) {
  std::vector<std::vector<dm::VertexId>> adj(mesh.num_vertices());
  for (dm::HalfEdgeId e = 0; e < mesh.triangle_vertices().size(); ++e) {
    if (!mesh.is_real(dm::tri_of(e)) || !mesh.is_constrained(e)) continue;
    const dm::HalfEdgeId f = mesh.twin(e);
    if (f != dm::kNone && f < e) continue;
    adj[mesh.origin(e)].push_back(mesh.dest(e));
    adj[mesh.dest(e)].push_back(mesh.origin(e));
  }
  // The end of the straight chain of constrained edges that leaves v
  // towards w: through Steiner vertices (two constrained edges each) and
  // through crossings (input vertices with a constrained edge straight on,
  // within 1e-6 rad), so that a chain is a whole input segment.
  auto end_of = [&](dm::VertexId v, dm::VertexId w, std::vector<dm::VertexId>* passed = nullptr) {
    for (std::size_t guard = 0; guard < mesh.num_vertices(); ++guard) {
      const dm::Point& V = mesh.point(v);
      const dm::Point& W = mesh.point(w);
      const double ix = W.x - V.x, iy = W.y - V.y;
      dm::VertexId next = dm::kNone;
      if (w >= n_input && adj[w].size() == 2) {
        next = adj[w][0] == v ? adj[w][1] : adj[w][0];
      } else {
        for (const dm::VertexId x : adj[w]) {
          const dm::Point& X = mesh.point(x);
          const double ox = X.x - W.x, oy = X.y - W.y;
          const double cr = ix * oy - iy * ox, dot = ix * ox + iy * oy;
          if (dot > 0 && std::fabs(cr) < 1e-6 * dot) next = x;
        }
      }
      if (passed && w < n_input) passed->push_back(w);
      if (next == dm::kNone) return w;
      v = w;
      w = next;
    }
    return w;
  };
  auto P = [&](dm::VertexId v) { return mesh.point(v); };
  auto dist = [](const dm::Point& p, const dm::Point& q) { return std::hypot(p.x - q.x, p.y - q.y); };
  std::vector<std::vector<std::pair<double, double>>> rays(n_input);
  std::vector<std::vector<dm::VertexId>> inputs_near(mesh.num_vertices());
  std::vector<char> inputs_known(mesh.num_vertices(), 0);
  // Is g inside an angle under 60° between two segments at apex, no farther
  // from it than the longer of the two reaches?
  auto in_small_angle = [&](dm::VertexId apex, const dm::Point& g) {
    const dm::Point& A = P(apex);
    std::vector<std::pair<double, double>>& dir = rays[apex];  // (direction, reach) of each segment at apex
    if (dir.empty()) {
      for (const dm::VertexId w : adj[apex]) {
        const dm::Point& E = P(end_of(apex, w));
        dir.push_back({std::atan2(E.y - A.y, E.x - A.x), std::hypot(E.x - A.x, E.y - A.y)});
      }
      std::sort(dir.begin(), dir.end());
    }
    const std::size_t k = dir.size();
    if (k < 2) return false;
    const double r = std::hypot(g.x - A.x, g.y - A.y), th = std::atan2(g.y - A.y, g.x - A.x);
    std::size_t hi = 0;  // first direction counter-clockwise from th
    while (hi < k && dir[hi].first < th) ++hi;
    auto at = [&](std::size_t i) { return dir[i % k]; };
    auto span = [&](std::size_t i, std::size_t j) {  // counter-clockwise from dir i to dir j
      double d = at(j).first - at(i).first;
      while (d < 0) d += 2 * kPi;
      return d;
    };
    const std::size_t lo = hi + k - 1;  // the one clockwise from th
    if (span(lo, hi) >= kPi / 3) return false;
    if (std::max(at(lo).second, at(hi).second) >= r) return true;
    for (std::size_t j = hi + 1; j < hi + k && span(lo, j) < kPi / 3; ++j)
      if (at(j).second >= r) return true;
    for (std::size_t i = lo + k - 1; i > lo && span(i, hi) < kPi / 3; --i)
      if (at(i).second >= r) return true;
    return false;
  };
  // Miller-Pav-Walkington: the shortest edge pq joins two different segments
  // at apex that make an angle under 60° there, and g lies in their cone.
  auto faces_small_angle = [&](dm::VertexId apex, const dm::Point& p, const dm::Point& q, const dm::Point& g) {
    const dm::Point& A = P(apex);
    const double px = p.x - A.x, py = p.y - A.y, qx = q.x - A.x, qy = q.y - A.y;
    auto on_a_segment = [&](double x, double y) {
      if (x == 0 && y == 0) return true;  // the apex itself
      for (const dm::VertexId w : adj[apex]) {
        const double dx = P(w).x - A.x, dy = P(w).y - A.y;
        const double dot = dx * x + dy * y;
        if (dot > 0 && std::fabs(dx * y - dy * x) < 1e-9 * dot) return true;
      }
      return false;
    };
    if (!on_a_segment(px, py) || !on_a_segment(qx, qy)) return false;
    const double side = px * qy - py * qx, dot = px * qx + py * qy;
    if (!(dot > 0) || std::fabs(std::atan2(std::fabs(side), dot)) >= kPi / 3) return false;
    const double gx = g.x - A.x, gy = g.y - A.y;
    const double s1 = px * gy - py * gx, s2 = gx * qy - gy * qx;
    return side > 0 ? (s1 >= 0 && s2 >= 0) : (s1 <= 0 && s2 <= 0);
  };
  const double sin_bound = std::sin(bound_deg * (1 - 1e-9) * kPi / 180);
  std::size_t outside = 0;
  for (dm::TriId t = 0; t < mesh.num_triangle_slots(); ++t) {
    if (!mesh.is_real(t)) continue;
    const auto v = mesh.triangle(t);
    double len[3];
    for (int i = 0; i < 3; ++i) len[i] = dist(P(v[i]), P(v[(i + 1) % 3]));
    const double cross = (P(v[1]).x - P(v[0]).x) * (P(v[2]).y - P(v[0]).y) -
                         (P(v[1]).y - P(v[0]).y) * (P(v[2]).x - P(v[0]).x);
    const int s = len[0] <= len[1] && len[0] <= len[2] ? 0 : (len[1] <= len[2] ? 1 : 2);
    if (!(std::fabs(cross) < sin_bound * len[(s + 1) % 3] * len[(s + 2) % 3])) continue;
    bool explained = false;
    // A corner at an input vertex between two constrained edges.
    for (int i = 0; i < 3 && !explained; ++i) {
      if (v[i] >= n_input) continue;
      const dm::VertexId x = v[(i + 1) % 3], y = v[(i + 2) % 3];
      const auto& n = adj[v[i]];
      explained = std::find(n.begin(), n.end(), x) != n.end() && std::find(n.begin(), n.end(), y) != n.end();
    }
    const dm::Point g{(P(v[0]).x + P(v[1]).x + P(v[2]).x) / 3, (P(v[0]).y + P(v[1]).y + P(v[2]).y) / 3};
    // The input vertices on the segments the triangle touches.
    std::vector<dm::VertexId> apexes;
    for (const dm::VertexId w : v) {
      if (!inputs_known[w]) {
        inputs_known[w] = 1;
        if (w < n_input) inputs_near[w].push_back(w);
        for (const dm::VertexId x : adj[w]) end_of(w, x, &inputs_near[w]);
      }
      apexes.insert(apexes.end(), inputs_near[w].begin(), inputs_near[w].end());
    }
    std::sort(apexes.begin(), apexes.end());
    apexes.erase(std::unique(apexes.begin(), apexes.end()), apexes.end());
    for (const dm::VertexId apex : apexes) {
      if (explained) break;
      explained = in_small_angle(apex, g) || faces_small_angle(apex, P(v[s]), P(v[(s + 1) % 3]), g);
    }
    // Any input vertex (above: a triangle left by Shewchuk's rule or the
    // apex guard need not touch the segment whose split was refused).
    for (dm::VertexId apex = 0; apex < n_input && !explained; ++apex)
      explained = adj[apex].size() >= 2 && in_small_angle(apex, g);
    if (!explained) ++outside;
  }
  return outside;
}

void PrintTo(const HubCase& c, std::ostream* os) { *os << c.name; }

class Hubs : public ::testing::TestWithParam<HubCase> {};

TEST_P(Hubs, RefineWithinBoundedWork) {
  const HubCase& hc = GetParam();
  const dm::Pslg input = hc.make();
  const double bounds[] = {20, 30, 33};
  for (int i = 0; i < 3; ++i) {
    dm::Mesh mesh = dm::triangulate(input);
    const std::size_t n_input = mesh.num_vertices();  // crossings included
    dm::RefineOptions o;
    o.min_angle_deg = bounds[i];
    o.time_limit_seconds = 20;  // a safety net: refinement that needs it has failed
    const dm::RefineStats st = dm::refine(mesh, o);
    SCOPED_TRACE(hc.name + " q" + std::to_string(static_cast<int>(bounds[i])) + ": " +
                 std::to_string(mesh.num_triangles()) + " triangles; " + st.summary());
    EXPECT_TRUE(st.complete);
    EXPECT_FALSE(st.budget_exhausted || st.time_exhausted);
    dm::test::expect_valid(mesh, false);
    EXPECT_EQ(st.below_bound, st.below_small_input_angle);
    EXPECT_EQ(below_outside_small_angles(mesh, n_input, bounds[i]), 0u);
    EXPECT_LE(mesh.num_triangles(), hc.most[i]);
    EXPECT_GT(mesh.num_triangles(), 2 * (input.segments.size() - 4));
  }
}

const HubCase kCases[] = {
    {"hub16", [] { return hub(16, 1.0); }, {120, 140, 150}},
    {"hub64", [] { return hub(64, 1.0); }, {400, 450, 500}},
    {"hub200", [] { return hub(200, 1.0); }, {1100, 1300, 1500}},
    {"hub1000", [] { return hub(1000, 1.0); }, {5000, 7000, 8000}},
    {"cross200", [] { return hub(200, 1.0, true); }, {1100, 1300, 1500}},
    {"hub200_small", [] { return hub(200, 1e-6); }, {1100, 1300, 1600}},
    {"hub200_large", [] { return hub(200, 1e6); }, {1100, 1400, 1400}},
    {"twohubs64", two_hubs, {52000, 100000, 125000}},
    {"irr16", [] { return irregular(16, 16, 1.0); }, {400, 800, 1200}},
    {"irr64", [] { return irregular(64, 64, 1.0); }, {1500, 4000, 5000}},
    {"irr200", [] { return irregular(200, 200, 1.0); }, {6000, 12000, 18000}},
    {"irr1000", [] { return irregular(1000, 1000, 1.0); }, {50000, 75000, 120000}},
    {"irr200_small", [] { return irregular(200, 7, 1e-6); }, {6000, 12000, 18000}},
    {"irr200_large", [] { return irregular(200, 8, 1e6); }, {6000, 12000, 18000}},
    {"lattice9", [] { return lattice(9, 3); }, {6000, 12000, 20000}},
};

INSTANTIATE_TEST_SUITE_P(Issue18, Hubs, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<HubCase>& i) { return i.param.name; });

// The same work in other orders (the test hook of src/algo/refine/queue.hpp):
// bucket bounds moved by a relative 2^-40, or each fan written from its
// lowest slot and vertex. Orders like these made irr16 run down to 2^-169 of
// its size (19,197 triangles at 33°) and irr1000 keep a triangle outside the
// small angles: the rules must not depend on luck of order.
class HubsInOtherOrders : public ::testing::TestWithParam<HubCase> {};

TEST_P(HubsInOtherOrders, RefineWithinBoundedWork) {
  const HubCase& hc = GetParam();
  const dm::Pslg input = hc.make();
  struct Restore {
    ~Restore() { dm::refinement::order_perturbation_for_tests = 0; }
  } restore;
  for (const int order : {1, 2}) {
    dm::refinement::order_perturbation_for_tests = order;
    for (const double bound : {30.0, 33.0}) {
      dm::Mesh mesh = dm::triangulate(input);
      const std::size_t n_input = mesh.num_vertices();
      dm::RefineOptions o;
      o.min_angle_deg = bound;
      o.time_limit_seconds = 20;
      const dm::RefineStats st = dm::refine(mesh, o);
      SCOPED_TRACE(hc.name + " order " + std::to_string(order) + " q" + std::to_string(static_cast<int>(bound)) +
                   ": " + std::to_string(mesh.num_triangles()) + " triangles; " + st.summary());
      EXPECT_TRUE(st.complete);
      dm::test::expect_valid(mesh, false);
      EXPECT_EQ(st.below_bound, st.below_small_input_angle);
      EXPECT_EQ(below_outside_small_angles(mesh, n_input, bound), 0u);
      EXPECT_LE(mesh.num_triangles(), hc.most[bound < 31 ? 1 : 2]);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Issue18, HubsInOtherOrders, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<HubCase>& i) { return i.param.name; });

// Above the bounds refinement reaches in practice it stops when it makes no
// progress, says where, and returns a mesh at least as good as the one
// refined to 34°.
TEST(HubsBeyond, HighBoundsStopWithAMeshAsGoodAs34) {
  for (const auto& make : {+[] { return hub(64, 1.0); }, +[] { return irregular(64, 64, 1.0); }}) {
    const dm::Pslg input = make();
    dm::Mesh at34 = dm::triangulate(input);
    dm::RefineOptions o34;
    o34.min_angle_deg = 34;
    const dm::RefineStats s34 = dm::refine(at34, o34);
    ASSERT_TRUE(s34.complete) << s34.summary();
    for (const double q : {37.0, 45.0, 60.0}) {
      dm::Mesh mesh = dm::triangulate(input);
      dm::RefineOptions o;
      o.min_angle_deg = q;
      const dm::RefineStats st = dm::refine(mesh, o);
      SCOPED_TRACE("q" + std::to_string(q) + ": " + st.summary());
      dm::test::expect_valid(mesh, false);
      EXPECT_GE(dm::test::min_angle_deg(mesh), dm::test::min_angle_deg(at34) - 1e-9);
      if (!st.complete) {
        EXPECT_TRUE(st.stalled);
        EXPECT_GE(st.reached_angle_deg, 34.0 - 1e-9);
        EXPECT_LT(st.reached_angle_deg, q);
        EXPECT_NE(st.summary().find("out of reach"), std::string::npos);
        EXPECT_EQ(st.below_bound, st.below_small_input_angle + st.below_out_of_reach + st.below_precision);
      }
    }
  }
}

// A fuzz_hubs input at the edge of what the rules cover: bunches of spokes
// a few 1e-8 rad wide whose lengths differ by factors up to 2^10. It
// completes at 20° and 30°; at 33° refinement still cascades around the tips
// of the short spokes (docs/robustness.md, known limits), so there only a
// valid mesh within the budget is required.
TEST(HubsLimit, BunchesWithSpreadLengths) {
  const dm::Pslg input = dm::read_poly(DELTAMESH_SOURCE_DIR "/tests/regress/refine_hub_bunches_spread_lengths.poly");
  for (const double q : {20.0, 30.0, 33.0}) {
    dm::Mesh mesh = dm::triangulate(input);
    dm::RefineOptions o;
    o.min_angle_deg = q;
    o.max_steiner = 30000;
    o.time_limit_seconds = 20;
    const dm::RefineStats st = dm::refine(mesh, o);
    SCOPED_TRACE("q" + std::to_string(q) + ": " + st.summary());
    dm::test::expect_valid(mesh, false);
    EXPECT_LE(st.steiner_points, o.max_steiner);
    if (q <= 30) {
      // Complete but for triangles at the precision of doubles (which make a
      // run incomplete since the one exit-code rule): no budget stopped it.
      EXPECT_TRUE(st.complete || (!st.budget_exhausted && !st.time_exhausted && st.below_precision > 0));
      EXPECT_EQ(st.below_bound, st.below_small_input_angle + st.below_precision);
    }
  }
}

// A fuzz_hubs seed (random_9) since precision is measured by rounding alone
// (issue 20): 138 spokes in pairs 2^-50..2^-20 rad wide, lengths spread over
// 2^-10..1 at scale 2^35. Their tips are a few ulps apart, so some triangles
// stay at the precision of doubles: incomplete, but not by a budget.
// A fuzz_hubs input from tests/regress refined to `angle` under the
// fuzzer's budget for work bounded by the feature size; the mesh validated.
dm::RefineStats refine_fuzz_hub(const std::string& name, double angle, double seconds) {
  const dm::Pslg input = dm::read_poly(DELTAMESH_SOURCE_DIR "/tests/regress/" + name);
  dm::Mesh mesh = dm::triangulate(input);
  dm::RefineOptions o;
  o.min_angle_deg = angle;
  o.max_steiner = 200 * mesh.num_vertices() + 20000;
  o.time_limit_seconds = seconds;
  const dm::RefineStats st = dm::refine(mesh, o);
  dm::test::expect_valid(mesh, false);
  return st;
}

TEST(HubsLimit, BunchTipsAtThePrecisionOfDoubles) {
  const dm::RefineStats st = refine_fuzz_hub("refine_hub_bunch_tips_at_precision.poly", 20, 20);
  SCOPED_TRACE(st.summary());
  EXPECT_FALSE(st.budget_exhausted);
  EXPECT_FALSE(st.time_exhausted);
  EXPECT_EQ(st.too_large, 0u);
  EXPECT_EQ(st.below_bound, st.below_small_input_angle + st.below_precision);
  EXPECT_TRUE(st.complete || st.below_precision > 0);
}

// Found by an idle fuzz_hubs run after stop 26's merges: 91 spokes, 30
// bunches of three (1e-15..1e-6 rad apart) and one alone, 2^26 long, q33. Main at
// 0840b5d and ed8ef0e finished with ~12k Steiner points; without the
// precision floor ~22k (off-centres: past 400k); after stop 26's rules
// (the best point's grid rows from 1.15) a cascade down one narrow wedge
// from its tips took 236,712 (past fuzz_hubs' budget of 39,200). Leaving
// the triangles whose points would sit in a cell across a hub's narrow
// wedge (Refiner::leave_for_narrow_wedge) ends it: 18,610.
TEST(HubsLimit, TwoBunchesAtQ33StayWithinBoundedWork) {
  const dm::RefineStats st = refine_fuzz_hub("refine_hub_bunch_cascade_q33.poly", 33, 60);
  SCOPED_TRACE(st.summary());
  EXPECT_FALSE(st.budget_exhausted);
  EXPECT_EQ(st.below_bound, st.below_small_input_angle + st.below_precision);
}

// A fuzz_hubs timeout of stop 27: 152 spokes in bunches of four, 1e-15..1e-6
// rad apart. The same cascade down one narrow wedge ran it to the fuzzer's
// budget (51,400) at 33° and 34°; with leave_for_narrow_wedge 24,260 and
// 31,498 Steiner points.
TEST(HubsLimit, BunchesOfFourStayWithinBoundedWork) {
  for (const double q : {33.0, 34.0}) {
    const dm::RefineStats st = refine_fuzz_hub("refine_hub_bunches_of_four_q34.poly", q, 60);
    SCOPED_TRACE("q" + std::to_string(q) + ": " + st.summary());
    EXPECT_FALSE(st.budget_exhausted);
    EXPECT_FALSE(st.time_exhausted);
    EXPECT_EQ(st.below_bound, st.below_small_input_angle + st.below_precision);
  }
}

// A fuzz_hubs failure of stop 27 (on 783679e too): one hub of 27 equal
// spokes whose narrowest wedges are 0.37° and 0.71°. At 33° refinement
// completes, every triangle left below the bound at an input angle, but
// with 45,892 Steiner points, about 1,400 per input vertex: past the
// fuzzer's bound for a single hub. Disabled until the work near sub-degree
// wedges is bounded (docs/robustness.md, the fuzz_hubs row of stop 27).
TEST(HubsLimit, DISABLED_SubDegreeWedgesAtQ33StayWithinTheFuzzersBudget) {
  const dm::RefineStats st = refine_fuzz_hub("refine_hub27_subdegree_wedges_q33.poly", 33, 60);
  SCOPED_TRACE(st.summary());
  EXPECT_FALSE(st.budget_exhausted);
  EXPECT_EQ(st.below_bound, st.below_small_input_angle + st.below_precision);
}

}  // namespace
