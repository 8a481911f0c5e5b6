// Delaunay refinement: validity, quality, size bounds, conformity, budgets,
// small input angles. Every refined mesh goes through deltamesh::check.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "deltamesh-gen/generators.hpp"
#include "deltamesh/delaunay.hpp"
#include "deltamesh/predicates.hpp"
#include "deltamesh/quality.hpp"
#include "deltamesh/refine.hpp"
#include "deltamesh/svg.hpp"
#include "deltamesh/triangulate.hpp"
#include "deltamesh/validate.hpp"
#include "test_refine_util.hpp"

namespace dm = deltamesh;
using dm::test::convex_domain;
using dm::test::expect_valid;
using dm::test::min_angle_deg;
using dm::test::segments_conform;
using dm::test::boundary_segments;

namespace {

std::vector<dm::Point> square() { return {{0, 0}, {1, 0}, {1, 1}, {0, 1}}; }

template <class F>
dm::RefineOptions opts(F&& set) {
  dm::RefineOptions o;
  set(o);
  return o;
}

std::vector<dm::Point> random_convex(std::uint64_t seed, int n) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 2 * std::numbers::pi), r(0.6, 1.0);
  std::vector<double> ang(n);
  for (double& a : ang) a = u(rng);
  std::sort(ang.begin(), ang.end());
  std::vector<dm::Point> p;
  for (double a : ang) p.push_back({std::cos(a), std::sin(a)});
  return p;
}

}  // namespace

TEST(Refine, SquareReachesAngleBounds) {
  for (double q : {20.0, 25.0, 30.0, 33.0}) {
    dm::Mesh mesh = convex_domain(square());
    const auto segs = boundary_segments(mesh);
    dm::RefineOptions opt;
    opt.min_angle_deg = q;
    opt.max_area = 0.01;
    const dm::RefineStats st = dm::refine(mesh, opt);
    SCOPED_TRACE("q=" + std::to_string(q) + " " + st.summary());
    expect_valid(mesh, false);
    EXPECT_TRUE(st.complete);
    EXPECT_EQ(st.below_bound, 0u);
    EXPECT_GE(min_angle_deg(mesh), q);
    EXPECT_TRUE(segments_conform(mesh, segs));
    const dm::QualityReport rep = dm::quality_report(mesh, {.min_angle_deg = q, .max_area = 0.01});
    EXPECT_EQ(rep.below_angle, 0u);
    EXPECT_EQ(rep.above_area, 0u);
    EXPECT_GT(mesh.num_triangles(), 100u);
    EXPECT_LT(mesh.num_triangles(), 400u);
  }
}

TEST(Refine, RandomConvexPolygons) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    for (auto rule : {dm::SteinerRule::Best, dm::SteinerRule::Grid, dm::SteinerRule::Offcenter,
                      dm::SteinerRule::Circumcenter}) {
      dm::Mesh mesh = convex_domain(random_convex(seed, 3 + static_cast<int>(seed % 17)));
      const auto segs = boundary_segments(mesh);
      dm::RefineOptions opt;
      opt.min_angle_deg = 30;
      opt.steiner = rule;
      const dm::RefineStats st = dm::refine(mesh, opt);
      SCOPED_TRACE("seed " + std::to_string(seed) + " " + st.summary());
      expect_valid(mesh, false);
      EXPECT_TRUE(st.complete);
      EXPECT_TRUE(segments_conform(mesh, segs));
      EXPECT_EQ(st.below_bound, st.below_small_input_angle);
      if (st.below_bound == 0) {
        EXPECT_GE(min_angle_deg(mesh), 30.0);
      }
    }
  }
}

namespace {

// Square with the square hole [0.4,0.6]^2 (every segment is a Delaunay edge).
dm::Mesh square_with_hole(std::vector<std::pair<dm::VertexId, dm::VertexId>>* segs = nullptr) {
  std::vector<dm::Point> p{{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.4, 0.4}, {0.6, 0.4}, {0.6, 0.6}, {0.4, 0.6}};
  std::vector<std::pair<dm::VertexId, dm::VertexId>> s{{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6}, {6, 7}, {7, 4}};
  dm::Mesh mesh;
  EXPECT_TRUE(dm::test::delaunay_domain(p, s, {{0.5, 0.5}}, mesh));
  if (segs) *segs = s;
  return mesh;
}

// Apex at the origin, n+1 points on the unit arc [0, n*delta] degrees, a
// segment from the apex to each: n wedges of angle delta.
dm::Mesh fan(int n, double delta_deg, std::vector<std::pair<dm::VertexId, dm::VertexId>>* segs = nullptr) {
  std::vector<dm::Point> p{{0, 0}};
  std::vector<std::pair<dm::VertexId, dm::VertexId>> s;
  for (int i = 0; i <= n; ++i) {
    const double a = i * delta_deg * std::numbers::pi / 180;
    p.push_back({std::cos(a), std::sin(a)});
    s.push_back({0, static_cast<dm::VertexId>(i + 1)});
    if (i > 0) s.push_back({static_cast<dm::VertexId>(i), static_cast<dm::VertexId>(i + 1)});
  }
  dm::Mesh mesh;
  EXPECT_TRUE(dm::test::delaunay_domain(p, s, {}, mesh));
  if (segs) *segs = s;
  return mesh;
}

// The same apex and radial segments (no arc chords), dangling inside the
// square [-2, 3]^2 at an angle `rot` degrees: the wedges open into the domain.
dm::Mesh fan_in_box(int n, double delta_deg, double rot, std::vector<std::pair<dm::VertexId, dm::VertexId>>* segs) {
  std::vector<dm::Point> p{{0, 0}, {-2, -2}, {3, -2}, {3, 3}, {-2, 3}};
  std::vector<std::pair<dm::VertexId, dm::VertexId>> s{{1, 2}, {2, 3}, {3, 4}, {4, 1}};
  for (int i = 0; i <= n; ++i) {
    const double a = (rot + i * delta_deg) * std::numbers::pi / 180;
    p.push_back({std::cos(a), std::sin(a)});
    s.push_back({0, static_cast<dm::VertexId>(p.size() - 1)});
  }
  dm::Mesh mesh;
  EXPECT_TRUE(dm::test::delaunay_domain(p, s, {}, mesh));
  if (segs) *segs = s;
  return mesh;
}

}  // namespace

TEST(Refine, SmallAnglesInsideADomainTerminate) {
  for (double delta : {45.0, 25.0, 10.0, 3.0, 0.5, 0.05, 0.001}) {
    for (double q : {20.0, 30.0, 33.0}) {
      std::vector<std::pair<dm::VertexId, dm::VertexId>> segs;
      dm::Mesh mesh = fan_in_box(delta > 20 ? 3 : 5, delta, 17.0, &segs);
      const dm::RefineStats st = dm::refine(mesh, opts([&](dm::RefineOptions& o) {
        o.min_angle_deg = q;
        o.max_steiner = 200000;
      }));
      SCOPED_TRACE("delta " + std::to_string(delta) + " q " + std::to_string(q) + ": " + st.summary());
      expect_valid(mesh, false);
      EXPECT_TRUE(st.complete);
      EXPECT_TRUE(segments_conform(mesh, segs));
      EXPECT_EQ(st.below_bound, st.below_small_input_angle);
      EXPECT_LT(mesh.num_triangles(), 50000u);
      EXPECT_GT(mesh.num_triangles(), 15u);
      if (::testing::Test::HasFailure() || std::getenv("DELTAMESH_VERBOSE")) {
        std::printf("delta %g q %g: %zu triangles; %s\n", delta, q, mesh.num_triangles(), st.summary().c_str());
        if (const char* dir = std::getenv("DELTAMESH_SVG_DIR"))
          dm::write_svg(mesh, std::string(dir) + "/fan_" + std::to_string(delta) + "_" + std::to_string(q) + ".svg", {});
      }
    }
  }
}

// A star polygon (radii uniform in [0.5, 1] at equally spaced angles, as
// deltamesh-gen star): spikes with input angles down to ~0.01° whose sides
// run on as thin channels. Refining those cascades down every spike (before
// the channel rule: ~32,000 triangles here, 300,000 at 10k vertices); the
// small-angle rules leave them. Measured: ~21,000 triangles for each seed.
TEST(Refine, StarPolygonSmallAngles) {
  for (std::uint64_t seed : {1u, 2u}) {
    const dm::Pslg star = dm::gen::star_polygon(3000, seed);
    dm::Mesh mesh = dm::triangulate(star);
    const auto segs = boundary_segments(mesh);
    const dm::RefineStats st = dm::refine(mesh, opts([&](dm::RefineOptions& o) { o.min_angle_deg = 20; }));
    SCOPED_TRACE("seed " + std::to_string(seed) + ": " + std::to_string(mesh.num_triangles()) + " triangles; " +
                 st.summary());
    expect_valid(mesh, false);
    EXPECT_TRUE(st.complete);
    EXPECT_TRUE(segments_conform(mesh, segs));
    // Whatever is left below the bound is at a small input angle or in a
    // spike's channel (counted with them), and the report agrees.
    EXPECT_GT(st.below_bound, 0u);
    EXPECT_EQ(st.below_bound, st.below_small_input_angle);
    EXPECT_EQ(dm::quality_report(mesh, {.min_angle_deg = 20}).below_angle, st.below_bound);
    EXPECT_LT(mesh.num_triangles(), 27000u);
    EXPECT_GT(mesh.num_triangles(), 6000u);
  }
}

TEST(Refine, SquareWithHole) {
  for (double q : {20.0, 30.0, 33.0, 34.0}) {
    std::vector<std::pair<dm::VertexId, dm::VertexId>> segs;
    dm::Mesh mesh = square_with_hole(&segs);
    const dm::RefineStats st = dm::refine(mesh, opts([&](dm::RefineOptions& o) { o.min_angle_deg = q; }));
    SCOPED_TRACE("q=" + std::to_string(q) + " " + st.summary());
    expect_valid(mesh, false);
    EXPECT_TRUE(st.complete);
    EXPECT_EQ(st.below_bound, 0u);
    EXPECT_GE(min_angle_deg(mesh), q);
    EXPECT_TRUE(segments_conform(mesh, segs));
  }
}

TEST(Refine, AreaBoundsGlobalPerTriangleAndCallback) {
  {
    dm::Mesh mesh = square_with_hole();
    dm::refine(mesh, opts([&](dm::RefineOptions& o) { o.min_angle_deg = 25; o.max_area = 1e-3; }));
    expect_valid(mesh, false);
    const auto rep = dm::quality_report(mesh, {.min_angle_deg = 25, .max_area = 1e-3});
    EXPECT_EQ(rep.above_area, 0u);
    EXPECT_LE(rep.max_area, 1e-3);
    EXPECT_GT(mesh.num_triangles(), 960u);   // at least area / bound
    EXPECT_LT(mesh.num_triangles(), 3000u);
  }
  {
    // Per-triangle bounds: left half fine, right half coarse.
    dm::Mesh mesh = square_with_hole();
    for (dm::TriId t = 0; t < mesh.num_triangle_slots(); ++t) mesh.set_triangle_area_bound(t, 0.01);
    dm::Mesh fine = convex_domain(square());
    for (dm::TriId t = 0; t < fine.num_triangle_slots(); ++t) fine.set_triangle_area_bound(t, t == 0 ? 1e-4 : 1e-2);
    dm::refine(fine, opts([&](dm::RefineOptions& o) { o.min_angle_deg = 20; }));
    expect_valid(fine, false);
    std::size_t small = 0;
    for (dm::TriId t = 0; t < fine.num_triangle_slots(); ++t) {
      const auto v = fine.triangle(t);
      const dm::Point &a = fine.point(v[0]), &b = fine.point(v[1]), &c = fine.point(v[2]);
      const double area = 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
      EXPECT_LE(area, fine.triangle_area_bound(t) * (1 + 1e-12));
      if (fine.triangle_area_bound(t) == 1e-4) ++small;
    }
    EXPECT_GT(small, 1000u);
    dm::refine(mesh, opts([&](dm::RefineOptions& o) { o.min_angle_deg = 20; }));
    expect_valid(mesh, false);
    for (dm::TriId t = 0; t < mesh.num_triangle_slots(); ++t) EXPECT_EQ(mesh.triangle_area_bound(t), 0.01);
  }
  {
    // A sizing callback: fine near the origin.
    dm::Mesh mesh = square_with_hole();
    dm::RefineOptions opt;
    opt.min_angle_deg = 28;
    opt.max_area_at = [](double x, double y) { return 1e-5 + 1e-2 * (x * x + y * y); };
    dm::refine(mesh, opt);
    expect_valid(mesh, false);
    for (dm::TriId t = 0; t < mesh.num_triangle_slots(); ++t) {
      const auto v = mesh.triangle(t);
      const dm::Point &a = mesh.point(v[0]), &b = mesh.point(v[1]), &c = mesh.point(v[2]);
      const double area = 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
      const double cx = (a.x + b.x + c.x) / 3, cy = (a.y + b.y + c.y) / 3;
      EXPECT_LE(area, opt.max_area_at(cx, cy));
    }
    EXPECT_GT(mesh.num_triangles(), 500u);
  }
  {
    // Edge-length callback.
    dm::Mesh mesh = square_with_hole();
    dm::RefineOptions opt;
    opt.min_angle_deg = 20;
    opt.max_edge_at = [](double, double) { return 0.05; };
    dm::refine(mesh, opt);
    expect_valid(mesh, false);
    const auto rep = dm::quality_report(mesh);
    EXPECT_LE(rep.longest_edge, 0.05);
  }
}

// Each rule's meshes are valid and within the bound; the best-point search
// gives fewer triangles than off-centres, which give fewer than circumcentres.
// Grid searches a coarse grid of the petal, then refines around its winner;
// Best (without size bounds) starts from points towards the skinny
// triangles' good sides instead, with ~3x fewer candidates: its counts stay
// close to the exhaustive grid's.
TEST(Refine, SteinerRulesRankByTriangleCount) {
  std::size_t total[4] = {0, 0, 0, 0};
  const dm::SteinerRule rules[4] = {dm::SteinerRule::Best, dm::SteinerRule::Offcenter, dm::SteinerRule::Circumcenter,
                                    dm::SteinerRule::Grid};
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    for (int r = 0; r < 4; ++r) {
      std::vector<dm::Point> p = random_convex(seed, 40);
      std::mt19937_64 rng(seed);
      std::uniform_real_distribution<double> u(-0.5, 0.5);
      for (int i = 0; i < 30; ++i) p.push_back({u(rng), u(rng)});
      dm::Mesh mesh = convex_domain(p);
      const auto segs = boundary_segments(mesh);
      dm::RefineOptions opt;
      opt.min_angle_deg = 33;
      opt.steiner = rules[r];
      const auto st = dm::refine(mesh, opt);
      SCOPED_TRACE(std::string(dm::to_string(rules[r])) + " seed " + std::to_string(seed) + ": " + st.summary());
      expect_valid(mesh, false);
      EXPECT_TRUE(st.complete);
      EXPECT_TRUE(segments_conform(mesh, segs));
      EXPECT_EQ(st.below_bound, st.below_small_input_angle);
      if (st.below_bound == 0) {
        EXPECT_GE(min_angle_deg(mesh), 33.0);
      }
      total[r] += mesh.num_triangles();
    }
  }
  EXPECT_LT(total[0], total[1]);
  EXPECT_LT(total[1], total[2]);
  // Measured: best ~0.85x the off-centres' count here; a search that does
  // nothing would give 1x.
  EXPECT_LT(static_cast<double>(total[0]), 0.95 * static_cast<double>(total[1]));
  // Measured: Best 1.3% above Grid here (4,889 vs 4,825; 1.1% below it on
  // the corpus); a Best that skipped the search would be ~15% above.
  EXPECT_NEAR(static_cast<double>(total[0]), static_cast<double>(total[3]), 0.03 * static_cast<double>(total[3]));
}

// With a size bound the search only runs away from too-large triangles; the
// area bound still holds everywhere.
TEST(Refine, BestRuleHonoursAreaBounds) {
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    dm::Mesh mesh = convex_domain(random_convex(seed, 30));
    dm::RefineOptions opt;
    opt.min_angle_deg = 30;
    opt.max_area = 0.002;
    opt.steiner = dm::SteinerRule::Best;
    const auto st = dm::refine(mesh, opt);
    SCOPED_TRACE(st.summary());
    expect_valid(mesh, false);
    EXPECT_TRUE(st.complete);
    const auto rep = dm::quality_report(mesh, {.min_angle_deg = 30, .max_area = 0.002});
    EXPECT_EQ(rep.above_area, 0u);
    EXPECT_LE(rep.max_area, 0.002);
    if (st.below_bound == 0) {
      EXPECT_GE(min_angle_deg(mesh), 30.0);
    }
  }
}

TEST(Refine, SmallAnglesTerminate) {
  for (double delta : {50.0, 20.0, 5.0, 1.0, 0.1, 0.01}) {
    for (double q : {20.0, 30.0, 34.0}) {
      std::vector<std::pair<dm::VertexId, dm::VertexId>> segs;
      const int n = delta >= 20 ? 3 : 6;
      dm::Mesh mesh = fan(n, delta, &segs);
      const dm::RefineStats st = dm::refine(mesh, opts([&](dm::RefineOptions& o) { o.min_angle_deg = q; o.max_steiner = 200000; }));
      SCOPED_TRACE("delta " + std::to_string(delta) + " q " + std::to_string(q) + ": " + st.summary());
      expect_valid(mesh, false);
      EXPECT_TRUE(st.complete);
      EXPECT_TRUE(segments_conform(mesh, segs));
      // Whatever is left is at the small angle.
      EXPECT_EQ(st.below_bound, st.below_small_input_angle);
      EXPECT_LT(mesh.num_triangles(), 20000u);
    }
  }
  // A thin triangle: 0.057° at the origin.
  dm::Mesh mesh = convex_domain({{0, 0}, {1, 0}, {1, 1e-3}});
  const auto st = dm::refine(mesh, opts([&](dm::RefineOptions& o) { o.min_angle_deg = 30; }));
  expect_valid(mesh, false);
  EXPECT_TRUE(st.complete) << st.summary();
  EXPECT_EQ(st.below_bound, st.below_small_input_angle) << st.summary();
}

TEST(Refine, BudgetsStopEarlyWithValidMesh) {
  dm::Mesh mesh = square_with_hole();
  const dm::RefineStats st = dm::refine(mesh, opts([&](dm::RefineOptions& o) { o.min_angle_deg = 30; o.max_area = 1e-4; o.max_steiner = 100; }));
  expect_valid(mesh, false);
  EXPECT_FALSE(st.complete);
  EXPECT_TRUE(st.budget_exhausted);
  EXPECT_EQ(st.steiner_points, 100u);
  EXPECT_EQ(mesh.num_vertices(), 108u);
  EXPECT_GT(st.too_large, 0u);

  dm::Mesh zero = square_with_hole();
  const dm::RefineStats z = dm::refine(zero, opts([&](dm::RefineOptions& o) { o.min_angle_deg = 30; o.max_steiner = 0; }));
  EXPECT_EQ(zero.num_vertices(), 8u);
  EXPECT_FALSE(z.complete);

  dm::Mesh timed = square_with_hole();
  const dm::RefineStats t = dm::refine(timed, opts([&](dm::RefineOptions& o) { o.min_angle_deg = 30; o.max_area = 1e-9; o.time_limit_seconds = 0.05; }));
  expect_valid(timed, false);
  EXPECT_FALSE(t.complete);
  EXPECT_TRUE(t.time_exhausted);

  // Above the practical bound the automatic budget stops refinement.
  dm::Mesh high = square_with_hole();
  const dm::RefineStats h = dm::refine(high, opts([&](dm::RefineOptions& o) { o.min_angle_deg = 45; o.max_steiner = 20000; }));
  expect_valid(high, false);
  EXPECT_LE(h.steiner_points, 20000u);
}

TEST(Refine, NoSteinerPointsOnProtectedSegments) {
  // -Y: boundary segments keep their vertices; -YY: every segment does.
  for (auto mode : {dm::SegmentSplitting::InteriorOnly, dm::SegmentSplitting::None}) {
    std::vector<std::pair<dm::VertexId, dm::VertexId>> segs;
    dm::Mesh mesh = fan(4, 15, &segs);
    const auto st = dm::refine(mesh, opts([&](dm::RefineOptions& o) { o.min_angle_deg = 25; o.max_area = 1e-3; o.segment_splitting = mode; }));
    expect_valid(mesh, false);
    std::size_t on_boundary = 0, on_interior = 0;
    for (dm::HalfEdgeId e = 0; e < mesh.triangle_vertices().size(); ++e) {
      if (!mesh.is_constrained(e)) continue;
      const bool steiner = mesh.origin(e) >= 6 || mesh.dest(e) >= 6;
      if (steiner) {
        (mesh.twin(e) == dm::kNone ? on_boundary : on_interior)++;
      }
    }
    EXPECT_EQ(on_boundary, 0u) << st.summary();
    if (mode == dm::SegmentSplitting::None) {
      EXPECT_EQ(on_interior, 0u);
    } else {
      EXPECT_GT(on_interior, 0u);
    }
  }
}

TEST(Refine, LensAndConformingDelaunay) {
  for (auto enc : {dm::EncroachmentRule::DiametralCircle, dm::EncroachmentRule::DiametralLens}) {
    std::vector<std::pair<dm::VertexId, dm::VertexId>> segs;
    dm::Mesh mesh = fan(3, 40, &segs);
    dm::RefineOptions opt;
    opt.min_angle_deg = 30;
    opt.encroachment = enc;
    const auto st = dm::refine(mesh, opt);
    expect_valid(mesh, false);
    EXPECT_TRUE(segments_conform(mesh, segs));
    EXPECT_EQ(st.below_bound, st.below_small_input_angle) << st.summary();
  }
  // -D: every interior edge, segments included, is locally Delaunay.
  dm::Mesh mesh = fan(5, 12);
  dm::RefineOptions opt;
  opt.min_angle_deg = 0;
  opt.conforming_delaunay = true;
  dm::refine(mesh, opt);
  expect_valid(mesh, false);
  for (dm::HalfEdgeId e = 0; e < mesh.triangle_vertices().size(); ++e) {
    const dm::HalfEdgeId f = mesh.twin(e);
    if (f == dm::kNone) continue;
    const double in = dm::incircle(mesh.point(mesh.origin(e)), mesh.point(mesh.dest(e)),
                                   mesh.point(mesh.origin(dm::prev_edge(e))), mesh.point(mesh.origin(dm::prev_edge(f))));
    EXPECT_LE(in, 0) << "edge " << mesh.origin(e) << "-" << mesh.dest(e);
  }
}

TEST(Refine, MarkersAndAttributesCarried) {
  dm::Mesh mesh = convex_domain(square(), 7);
  mesh.vertex_markers().assign(mesh.num_vertices(), 7);
  mesh.set_num_vertex_attributes(1);
  for (dm::VertexId v = 0; v < mesh.num_vertices(); ++v) mesh.vertex_attributes().push_back(mesh.point(v).x);
  mesh.set_num_triangle_attributes(1);
  mesh.triangle_attributes().assign(mesh.num_triangle_slots(), 3.5);
  dm::refine(mesh, opts([&](dm::RefineOptions& o) { o.min_angle_deg = 30; o.max_area = 0.01; }));
  expect_valid(mesh, false);
  ASSERT_EQ(mesh.vertex_markers().size(), mesh.num_vertices());
  ASSERT_EQ(mesh.vertex_attributes().size(), mesh.num_vertices());
  ASSERT_EQ(mesh.triangle_attributes().size(), mesh.num_triangle_slots());
  for (double a : mesh.triangle_attributes()) EXPECT_EQ(a, 3.5);
  for (dm::VertexId v = 0; v < mesh.num_vertices(); ++v) {
    // x is linear, so interpolation reproduces it.
    EXPECT_NEAR(mesh.vertex_attributes()[v], mesh.point(v).x, 1e-9);
    const dm::Point p = mesh.point(v);
    const bool on_boundary = p.x == 0 || p.x == 1 || p.y == 0 || p.y == 1;
    if (!on_boundary) {
      EXPECT_EQ(mesh.vertex_markers()[v], 0);
    }
  }
  for (dm::HalfEdgeId e = 0; e < mesh.triangle_vertices().size(); ++e) {
    if (mesh.is_constrained(e)) {
      EXPECT_EQ(mesh.edge_marker(e), 7);
    }
  }
}

TEST(Quality, ReportTextAndJson) {
  dm::Mesh mesh = square_with_hole();
  const auto st = dm::refine(mesh, opts([&](dm::RefineOptions& o) { o.min_angle_deg = 30; }));
  const auto rep = dm::quality_report(mesh, {.min_angle_deg = 30, .input_vertices = 8}, &st);
  EXPECT_EQ(rep.triangles, mesh.num_triangles());
  EXPECT_EQ(rep.input_vertices, 8u);
  EXPECT_EQ(rep.steiner_vertices, st.steiner_points);
  EXPECT_GE(rep.min_angle_deg, 30);
  EXPECT_LE(rep.max_angle_deg, 120);
  std::size_t angles = 0;
  for (auto c : rep.angle_histogram) angles += c;
  EXPECT_EQ(angles, 3 * rep.triangles);
  EXPECT_GE(rep.min_aspect_ratio, 2 / std::sqrt(3.0) - 1e-9);
  EXPECT_GE(rep.min_radius_edge, 1 / std::sqrt(3.0) - 1e-9);
  // Radius-edge ratio and the smallest angle: rho = 1 / (2 sin theta) (§3.4).
  EXPECT_LE(rep.max_radius_edge, 1 / (2 * std::sin(30 * std::numbers::pi / 180)) + 1e-9);
  EXPECT_NE(rep.text().find("angle histogram"), std::string::npos);
  const std::string j = rep.json();
  EXPECT_EQ(j.front(), '{');
  EXPECT_EQ(j.back(), '}');
  EXPECT_NE(j.find("\"below_reasons\""), std::string::npos);
  EXPECT_NE(j.find("\"triangles\":" + std::to_string(rep.triangles)), std::string::npos);
}

TEST(Refine, ThroughTheTriangulatePipeline) {
  // The unit square with a square hole, -pq30a0.001 through triangulate().
  dm::Pslg g;
  g.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.4, 0.4}, {0.6, 0.4}, {0.6, 0.6}, {0.4, 0.6}};
  for (dm::VertexId i = 0; i < 4; ++i) {
    g.segments.push_back({i, (i + 1) % 4, 1});
    g.segments.push_back({4 + i, 4 + (i + 1) % 4, 2});
  }
  g.holes.push_back({0.5, 0.5});
  dm::TriangulateOptions topt;
  topt.refine = opts([](dm::RefineOptions& o) {
    o.min_angle_deg = 30;
    o.max_area = 1e-3;
  });
  dm::TriangulateStats tst;
  const dm::Mesh mesh = dm::triangulate(g, topt, &tst);
  expect_valid(mesh, false);
  EXPECT_TRUE(tst.refine.complete);
  EXPECT_GT(tst.refine.steiner_points, 500u);
  EXPECT_EQ(tst.vertices, mesh.num_vertices());
  EXPECT_GE(min_angle_deg(mesh), 30.0);
  ASSERT_EQ(mesh.vertex_markers().size(), mesh.num_vertices());
  // Steiner points on the hole's segments carry its marker 2, inside 0.
  for (dm::VertexId v = 8; v < mesh.num_vertices(); ++v) {
    const dm::Point p = mesh.point(v);
    const bool inner = std::fabs(p.x - 0.4) < 1e-12 || std::fabs(p.x - 0.6) < 1e-12 || std::fabs(p.y - 0.4) < 1e-12 ||
                       std::fabs(p.y - 0.6) < 1e-12;
    const bool outer = p.x == 0 || p.x == 1 || p.y == 0 || p.y == 1;
    if (inner && p.x >= 0.4 - 1e-12 && p.x <= 0.6 + 1e-12 && p.y >= 0.4 - 1e-12 && p.y <= 0.6 + 1e-12) {
      EXPECT_EQ(mesh.vertex_markers()[v], 2);
    } else if (outer) {
      EXPECT_EQ(mesh.vertex_markers()[v], 1);
    } else {
      EXPECT_EQ(mesh.vertex_markers()[v], 0);
    }
  }
}

TEST(Refine, RegionalAttributesStayInTheirRegions) {
  // -pq30a0.002A: the unit square split by an interior segment x = 0.3 into
  // regions with attributes 1 (left) and 2 (right). Splitting the interior
  // segment rebuilds triangles on both sides at once: each must keep its own
  // side's attribute.
  dm::Pslg g;
  g.points = {{0, 0}, {0.3, 0}, {1, 0}, {1, 1}, {0.3, 1}, {0, 1}};
  for (dm::VertexId i = 0; i < 6; ++i) g.segments.push_back({i, (i + 1) % 6, 1});
  g.segments.push_back({1, 4, 2});
  g.regions.push_back({{0.1, 0.5}, 1.0, -1});
  g.regions.push_back({{0.7, 0.5}, 2.0, -1});
  for (const double area : {0.002, 0.0005}) {
    SCOPED_TRACE(area);
    dm::TriangulateOptions topt;
    topt.domain.regional_attributes = true;
    topt.refine = opts([&](dm::RefineOptions& o) {
      o.min_angle_deg = 30;
      o.max_area = area;
    });
    dm::TriangulateStats tst;
    const dm::Mesh mesh = dm::triangulate(g, topt, &tst);
    expect_valid(mesh, false);
    EXPECT_TRUE(tst.refine.complete) << tst.refine.summary();
    EXPECT_GT(tst.refine.segment_splits, 0u);
    ASSERT_EQ(mesh.num_triangle_attributes(), 1u);
    std::size_t wrong = 0, left = 0, right = 0;
    for (dm::TriId t = 0; t < mesh.num_triangle_slots(); ++t) {
      if (!mesh.is_real(t)) continue;
      const auto v = mesh.triangle(t);
      const double cx = (mesh.point(v[0]).x + mesh.point(v[1]).x + mesh.point(v[2]).x) / 3;
      const double want = cx < 0.3 ? 1.0 : 2.0;
      (cx < 0.3 ? left : right) += 1;
      if (mesh.triangle_attributes()[t] != want) ++wrong;
    }
    EXPECT_EQ(wrong, 0u) << "of " << mesh.num_triangles() << " triangles";
    EXPECT_GT(left, 10u);
    EXPECT_GT(right, 10u);
  }
}

TEST(Refine, TrianglesAboveTheirAreaBoundAreSplitAtSmallInputAngles) {
  // A square (area bound 0.5) with a square hole, and a triangle meeting it
  // at a 26.6° angle at (4, 4). Segments next to that small angle were not
  // split on behalf of triangles that were only too large (the rule against
  // cascades, meant for skinny ones): 2 triangles of area 2 were left.
  dm::Pslg g;
  g.points = {{0, 0}, {4, 0}, {4, 4}, {0, 4}, {1, 1}, {3, 1}, {3, 3}, {1, 3}, {6, 0}};
  for (dm::VertexId i = 0; i < 4; ++i) {
    g.segments.push_back({i, (i + 1) % 4, 1});
    g.segments.push_back({4 + i, 4 + (i + 1) % 4, 2});
  }
  g.segments.push_back({1, 8, 3});
  g.segments.push_back({8, 2, 3});
  g.holes.push_back({2, 2});
  g.regions.push_back({{0.5, 2}, 1.0, 0.5});
  g.regions.push_back({{4.5, 1}, 2.0, -1});
  dm::TriangulateOptions topt;
  topt.domain.regional_area_bounds = true;
  topt.refine = opts([](dm::RefineOptions& o) { o.min_angle_deg = 20; });
  dm::TriangulateStats tst;
  const dm::Mesh mesh = dm::triangulate(g, topt, &tst);
  expect_valid(mesh, false);
  EXPECT_TRUE(tst.refine.complete) << tst.refine.summary();
  EXPECT_EQ(tst.refine.too_large, 0u) << tst.refine.summary();
  for (dm::TriId t = 0; t < mesh.num_triangle_slots(); ++t) {
    if (!mesh.is_real(t) || mesh.triangle_area_bound(t) <= 0) continue;
    const auto v = mesh.triangle(t);
    EXPECT_LE(0.5 * dm::orient2d(mesh.point(v[0]), mesh.point(v[1]), mesh.point(v[2])), 0.5);
  }
}
