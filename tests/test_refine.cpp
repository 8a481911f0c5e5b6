// Delaunay refinement: validity, quality, size bounds, conformity, budgets,
// small input angles. Every refined mesh goes through deltamesh::check.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "deltamesh/delaunay.hpp"
#include "deltamesh/predicates.hpp"
#include "deltamesh/quality.hpp"
#include "deltamesh/refine.hpp"
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
    for (auto rule : {dm::SteinerRule::Offcenter, dm::SteinerRule::Circumcenter}) {
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
