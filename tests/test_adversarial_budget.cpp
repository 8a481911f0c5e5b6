// Refinement always ends: a Steiner budget, a wall-clock limit, an angle
// bound no refinement reaches, absurd options and throwing callbacks end
// with a valid mesh and statistics that say why (RefineStats::complete ==
// false), never a hang or a broken mesh. The CLI turns a budget stop into
// exit code 3 with its statistics.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "deltamesh/refine.hpp"
#include "deltamesh/triangle_io.hpp"
#include "deltamesh/validate.hpp"
#include "test_adversarial_util.hpp"
#include "test_refine_util.hpp"

namespace dm = deltamesh;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The unit square with a needle-thin spike: small input angles everywhere.
dm::Mesh square() { return dm::test::convex_domain({{0, 0}, {1, 0}, {1, 1}, {0, 1}}); }

void expect_valid(const dm::Mesh& m, const std::string& what) {
  const dm::CheckReport rep = dm::check(m, {.delaunay = true, .convex_hull = false});
  EXPECT_TRUE(rep.ok()) << what << ": " << rep.summary();
}

}  // namespace

TEST(Budget, SteinerBudgetEndsRefinementWithAValidMesh) {
  for (const std::size_t budget : {std::size_t{0}, std::size_t{1}, std::size_t{37}, std::size_t{500}}) {
    SCOPED_TRACE(budget);
    dm::Mesh m = square();
    const std::size_t before = m.num_vertices();
    dm::RefineOptions ro;
    ro.min_angle_deg = 30;
    ro.max_area = 1e-7;  // ~10^7 triangles wanted
    ro.max_steiner = budget;
    const dm::RefineStats st = dm::refine(m, ro);
    EXPECT_FALSE(st.complete);
    EXPECT_TRUE(st.budget_exhausted);
    EXPECT_FALSE(st.time_exhausted);
    EXPECT_EQ(st.steiner_points, budget);
    EXPECT_EQ(m.num_vertices(), before + budget);
    EXPECT_GT(st.too_large, 0u);
    EXPECT_NE(st.summary().find("Steiner budget reached"), std::string::npos) << st.summary();
    expect_valid(m, "budget " + std::to_string(budget));
  }
}

TEST(Budget, WallClockLimitEndsRefinementWithAValidMesh) {
  dm::Mesh m = square();
  dm::RefineOptions ro;
  ro.min_angle_deg = 33;
  ro.max_area = 1e-12;  // far more than fits in memory
  ro.max_steiner = dm::kUnlimited;
  ro.time_limit_seconds = 0.2;
  const auto t0 = std::chrono::steady_clock::now();
  const dm::RefineStats st = dm::refine(m, ro);
  const double took = seconds_since(t0);
  EXPECT_FALSE(st.complete);
  EXPECT_TRUE(st.time_exhausted);
  EXPECT_FALSE(st.budget_exhausted);
  EXPECT_GT(st.steiner_points, 0u);
  // The limit is checked every few hundred insertions: it ends soon after
  // (generously bounded for sanitizer builds on a busy machine).
  EXPECT_LT(took, 5.0);
  expect_valid(m, "time limit");
}

TEST(Budget, UnreachableAngleBoundEndsByTheBudget) {
  // 60° cannot be reached in general; the automatic budget would stop it
  // after 10^7 points, an explicit one much earlier.
  for (const double angle : {45.0, 60.0, 1e9}) {
    SCOPED_TRACE(angle);
    dm::Mesh m = dm::test::convex_domain({{0, 0}, {3, 0}, {3.5, 1}, {0.2, 2}, {-1, 0.5}});
    dm::RefineOptions ro;
    ro.min_angle_deg = angle;
    ro.max_steiner = 2000;
    ro.time_limit_seconds = 20;
    const dm::RefineStats st = dm::refine(m, ro);
    EXPECT_LE(st.min_angle_deg, 60.0);  // clamped to the documented maximum
    EXPECT_FALSE(st.complete);
    EXPECT_TRUE(st.budget_exhausted || st.time_exhausted);
    expect_valid(m, "angle " + std::to_string(angle));
  }
}

TEST(Budget, WithoutSmallAngleProtectionTheBudgetStillEndsIt) {
  // Figure 18 literally, on an input with a 2° angle: only the budget
  // guarantees the end.
  const double a = 2.0 * std::numbers::pi / 180;
  dm::Mesh m = dm::test::convex_domain({{0, 0}, {1, 0}, {std::cos(a), std::sin(a)}});
  dm::RefineOptions ro;
  ro.min_angle_deg = 30;
  ro.small_angle_protection = false;
  ro.max_steiner = 3000;
  ro.time_limit_seconds = 20;
  const dm::RefineStats st = dm::refine(m, ro);
  EXPECT_TRUE(st.complete || st.budget_exhausted || st.time_exhausted);
  EXPECT_LE(st.steiner_points, 3000u);
  expect_valid(m, "no small-angle protection");
}

TEST(Budget, NonFiniteAndNegativeOptionsDoNotHang) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  struct Case {
    const char* name;
    double angle, area, limit;
  };
  for (const Case c : {Case{"nan angle", nan, -1, 0}, Case{"negative angle", -30, -1, 0},
                       Case{"infinite angle", inf, -1, 0}, Case{"nan area", 20, nan, 0},
                       Case{"infinite area", 20, inf, 0}, Case{"zero area", 20, 0, 0},
                       Case{"denormal area", 20, 4.9e-324, 0}, Case{"nan time", 20, -1, nan},
                       Case{"negative time", 20, -1, -5}}) {
    SCOPED_TRACE(c.name);
    dm::Mesh m = square();
    dm::RefineOptions ro;
    ro.min_angle_deg = c.angle;
    ro.max_area = c.area;
    ro.time_limit_seconds = c.limit;
    ro.max_steiner = 20000;
    const dm::RefineStats st = dm::refine(m, ro);
    EXPECT_LE(st.steiner_points, 20000u);
    expect_valid(m, c.name);
  }
}

TEST(Budget, SizingCallbackReturningGarbageDoesNotHang) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (const double v : {nan, inf, -inf, -1.0, 0.0, 4.9e-324}) {
    SCOPED_TRACE(v);
    dm::Mesh m = square();
    dm::RefineOptions ro;
    ro.max_area_at = [v](double, double) { return v; };
    ro.max_edge_at = [v](double, double) { return v; };
    ro.max_steiner = 5000;
    const dm::RefineStats st = dm::refine(m, ro);
    EXPECT_LE(st.steiner_points, 5000u);
    expect_valid(m, "callback value");
  }
}

TEST(Budget, ThrowingSizingCallbackLeavesAValidMesh) {
  // The exception propagates; the mesh holds the points inserted so far
  // and is still a valid triangulation.
  dm::Mesh m = square();
  dm::RefineOptions ro;
  ro.min_angle_deg = 25;
  int calls = 0;
  ro.max_area_at = [&calls](double, double) -> double {
    if (++calls > 200) throw std::runtime_error("sizing field failed");
    return 1e-4;
  };
  EXPECT_THROW(dm::refine(m, ro), std::runtime_error);
  expect_valid(m, "after a throwing callback");
  EXPECT_EQ(m.num_triangles(), dm::check(m).triangles);
}

// ---------------------------------------------------------------------------
// The command line: exit code 3, statistics, the mesh written and valid.

namespace {

class BudgetCli : public dm::test::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    write("square.poly", "4 2 0 1\n0 0 0 1\n1 1 0 1\n2 1 1 1\n3 0 1 1\n4 1\n0 0 1 1\n1 1 2 1\n2 2 3 1\n3 3 0 1\n0\n");
  }
};

}  // namespace

TEST_F(BudgetCli, SteinerBudgetExitsWith3AndWritesAValidMesh) {
  const dm::test::CliResult r = run("-pCq30 -a0.000001 -S100 square.poly");
  EXPECT_EQ(r.code, 3) << r.out << r.err;
  EXPECT_CONTAINS(r.out, "Quality mesh:");
  EXPECT_CONTAINS(r.out, "Steiner budget reached");
  EXPECT_CONTAINS(r.out, "Check: mesh is valid");
  EXPECT_CONTAINS(r.err, "deltamesh: warning: refinement stopped by its budget");
  ASSERT_TRUE(exists("square.1.node"));
  ASSERT_TRUE(exists("square.1.ele"));
  EXPECT_EQ(dm::read_node(path("square.1.node")).points.size(), 4u + 100u);
}

TEST_F(BudgetCli, TimeLimitExitsWith3AndWritesAValidMesh) {
  const auto t0 = std::chrono::steady_clock::now();
  const dm::test::CliResult r = run("-pCq33 -a0.000000000001 --time-limit=0.2 square.poly");
  EXPECT_EQ(r.code, 3) << r.out << r.err;
  EXPECT_CONTAINS(r.out, "time limit reached");
  EXPECT_CONTAINS(r.out, "Check: mesh is valid");
  EXPECT_TRUE(exists("square.1.ele"));
  // Reading, refining for 0.2 s, checking and writing what was reached.
  EXPECT_LT(seconds_since(t0), 60.0);
}

TEST_F(BudgetCli, BadBudgetArgumentsAreUsageErrors) {
  for (const std::string args : {"-pq30 --time-limit=-1", "-pq30 --time-limit=nan", "-pq30 --steiner-budget=x",
                                 "-pq30 -S99999999999999999999999"}) {
    SCOPED_TRACE(args);
    const dm::test::CliResult r = run(args + " square.poly");
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_EQ(r.err.rfind("deltamesh: ", 0), 0u) << r.err;
    EXPECT_FALSE(exists("square.1.node"));
  }
}
