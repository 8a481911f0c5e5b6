// Any finite coordinates, any scale (issue 20), and the one exit-code rule
// for unmet bounds (issue 19, item 5). docs/robustness.md, "Any finite
// coordinates" and "Exit codes", cites these tests.
//
// run() meshes in a power-of-two frame (src/algo/normalize.hpp): scaling the
// input by 2^k must give the same mesh scaled by 2^k, bit for bit; scaling
// by 10^k (inexact) nearly the same mesh. Every mesh goes through check().
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "deltamesh/deltamesh.hpp"
#include "scale_inputs.hpp"
#include "mesh/editor.hpp"

using namespace deltamesh;
namespace fs = std::filesystem;

namespace {

void expect_valid(const Mesh& m) {
  CheckOptions co;
  co.convex_hull = false;
  const CheckReport r = check(m, co);
  EXPECT_TRUE(r.ok()) << r.summary();
}

// A validator run on a mesh in the user's frame needs coordinates the
// predicates take: check it scaled back to 1 by the same power of two.
void expect_valid_scaled(const Mesh& m, int k) {
  Mesh copy = m;
  for (Point& p : deltamesh::detail::MeshEditor(copy).points()) p = {std::ldexp(p.x, -k), std::ldexp(p.y, -k)};
  expect_valid(copy);
}

bool normal_or_zero(double v) { return v == 0.0 || std::isnormal(v); }

// The switches' run on `in`, with a global area bound when area > 0 (set
// in the plan: switch numbers have no exponents).
RunResult mesh(const std::string& switches, const Pslg& in, double area = 0) {
  RunInput ri;
  ri.pslg = in;
  Plan plan = parse_arguments({switches, "x"}).plan;
  if (area > 0) plan.refine.max_area = area;
  return run(plan, std::move(ri));
}

double min_angle(const Mesh& m) { return quality_report(m).min_angle_deg; }

bool quick() {  // DELTAMESH_TEST_QUICK: fewer scales
  const char* q = std::getenv("DELTAMESH_TEST_QUICK");
  return q != nullptr && *q != '\0' && *q != '0';
}

}  // namespace

// 2^k: bit-for-bit the same mesh up to the scale, for k where the input and
// the result stay finite and normal (both checked here).
TEST(Scale, PowersOfTwoGiveTheSameMeshBitForBit) {
  const int ks[] = {-1000, -200, -60, 0, 60, 200, 1000};
  for (const test::ScaleInput& input : test::scale_inputs(false)) {
    for (const bool sized : {false, true}) {
      SCOPED_TRACE(input.name + (sized ? " -pq30a" : " -pq30"));
      const RunResult base = mesh("-pq30", input.pslg, sized ? input.area : 0);
      expect_valid(base.mesh);
      ASSERT_GT(base.mesh.num_triangles(), 0u);
      for (int k : ks) {
        SCOPED_TRACE("2^" + std::to_string(k));
        bool fits = true;
        for (const Point& p : base.mesh.points())
          fits = fits && normal_or_zero(std::ldexp(p.x, k)) && normal_or_zero(std::ldexp(p.y, k));
        // The area bound maps with the square of the scale.
        const double area = std::ldexp(input.area, 2 * k);
        if (sized) fits = fits && std::isnormal(area);
        for (const RegionSeed& r : input.pslg.regions)
          fits = fits && (r.max_area <= 0 || std::isnormal(std::ldexp(r.max_area, 2 * k)));
        if (!fits) continue;  // outside "finite and normal"
        const Pslg scaled = test::scaled_pslg(input.pslg, std::ldexp(1.0, k));
        const RunResult r = mesh("-pq30", scaled, sized ? area : 0);
        expect_valid_scaled(r.mesh, k);
        ASSERT_EQ(r.mesh.num_vertices(), base.mesh.num_vertices());
        ASSERT_EQ(r.mesh.num_triangle_slots(), base.mesh.num_triangle_slots());
        for (VertexId v = 0; v < base.mesh.num_vertices(); ++v) {
          const Point& p = base.mesh.point(v);
          ASSERT_EQ(r.mesh.point(v), (Point{std::ldexp(p.x, k), std::ldexp(p.y, k)})) << "vertex " << v;
        }
        for (VertexId v = 0; v < scaled.points.size(); ++v) ASSERT_EQ(r.mesh.point(v), scaled.points[v]);
        for (TriId t = 0; t < base.mesh.num_triangle_slots(); ++t) ASSERT_EQ(r.mesh.triangle(t), base.mesh.triangle(t));
        EXPECT_EQ(r.complete(), base.complete());
        // Statistics in the user's frame agree with the unscaled ones.
        const QualityReport q0 = quality_report(base.mesh, {.min_angle_deg = 30});
        const QualityReport q = quality_report(r.mesh, {.min_angle_deg = 30});
        EXPECT_EQ(q.min_angle_deg, q0.min_angle_deg);
        EXPECT_EQ(q.below_angle, q0.below_angle);
        EXPECT_EQ(q.below_angle, r.stats.refine.below_bound);
        EXPECT_EQ(q.min_radius_edge, q0.min_radius_edge);
      }
    }
  }
}

// 10^k (rounded, so not the same input): the same mesh but for rounding.
// Refinement is laid out in the input's own unit (its box), its candidate
// points shun degenerate places rounding would decide, and it starts from a
// canonical numbering (src/mesh/canonical.hpp), so the meshes agree: the
// triangle count within 1% and the smallest angle within 0.01 degrees (the
// issue's bounds; measured: identical counts and angles on these inputs).
void expect_powers_of_ten_agree(const test::ScaleInput& input) {
  SCOPED_TRACE(input.name);
  const RunResult base = mesh("-pq30", input.pslg);
  expect_valid(base.mesh);
  const double n0 = double(base.mesh.num_triangles()), a0 = min_angle(base.mesh);
  ASSERT_GT(n0, 0);
  const std::vector<int> ks = quick() ? std::vector<int>{-60, -3, 12, 200}
                                                  : std::vector<int>{-200, -60, -12, -3, 3, 12, 60, 200};
  for (int k : ks) {
    SCOPED_TRACE("10^" + std::to_string(k));
    const RunResult r = mesh("-pq30", test::scaled_pslg(input.pslg, std::pow(10.0, k)));
    expect_valid_scaled(r.mesh, int(std::lround(k * std::log2(10.0))));
    EXPECT_LE(std::fabs(double(r.mesh.num_triangles()) - n0), 0.01 * n0) << r.mesh.num_triangles() << " vs " << n0;
    EXPECT_NEAR(min_angle(r.mesh), a0, 0.01);
    EXPECT_EQ(r.complete(), base.complete()) << r.stats.refine.summary();
  }
}

TEST(Scale, PowersOfTenGiveTheSameMeshButForRounding) {
  for (const test::ScaleInput& input : test::scale_inputs(false))
    if (input.name == "plate" || input.name == "holed square") expect_powers_of_ten_agree(input);
}

TEST(Scale, PowersOfTenGiveTheSameMeshButForRoundingOnTheCorpus) {
  std::error_code ec;
  if (!fs::exists(test::corpus_dir(), ec)) GTEST_SKIP() << "no corpus at " << test::corpus_dir() << ": examples only";
  for (const test::ScaleInput& input : test::scale_inputs(false))
    if (input.name != "plate" && input.name != "holed square") expect_powers_of_ten_agree(input);
}

// With an area bound (1/1000 of the box, times 10^2k where that stays a
// normal double) the meshes are larger and the same but for rounding: the
// triangle count within 1% and the smallest angle within 0.01 degrees, and
// the bound is met. Needs each fan written from the cavity's lowest vertex
// (insert.cpp) and bucket keys nudged off their bounds (queue.hpp).
TEST(Scale, PowersOfTenWithAnAreaBoundGiveNearlyTheSameMesh) {
  for (const test::ScaleInput& input : test::scale_inputs(false)) {
    SCOPED_TRACE(input.name);
    const double area = input.area / 5;
    const RunResult base = mesh("-pq30", input.pslg, area);
    const double n0 = double(base.mesh.num_triangles()), a0 = min_angle(base.mesh);
    for (int k : {-150, -60, -12, 12, 60, 150}) {
      SCOPED_TRACE("10^" + std::to_string(k));
      const double s = std::pow(10.0, k);
      const RunResult r = mesh("-pq30", test::scaled_pslg(input.pslg, s), area * s * s);
      expect_valid_scaled(r.mesh, int(std::lround(k * std::log2(10.0))));
      EXPECT_LE(std::fabs(double(r.mesh.num_triangles()) - n0), 0.01 * n0) << r.mesh.num_triangles() << " vs " << n0;
      EXPECT_NEAR(min_angle(r.mesh), a0, 0.01);
      EXPECT_TRUE(r.complete()) << r.stats.refine.summary();
      EXPECT_GE(r.stats.refine.reached_angle_deg, 30.0);
      if (a0 >= 30.0 && r.stats.refine.below_small_input_angle == 0) {
        EXPECT_GE(min_angle(r.mesh), 30.0);
      }
    }
  }
}

// The lower-level library calls mesh in a power-of-two frame only when
// their input is beyond the predicates' range (2^+-200), so an input scaled
// by 2^k out of that range gives the in-range mesh times 2^k, bit for bit;
// in-range calls do not pass through the frame.
TEST(Scale, LibraryCallsBeyondThePredicatesRangeMeshInAFrame) {
  // Largest magnitude in [1/2, 1): the frame of its scaled copies is itself.
  Pslg p = test::holed_square();
  for (Point& q : p.points) q = {q.x * 0.75, q.y * 0.75};
  for (Point& q : p.holes) q = {q.x * 0.75, q.y * 0.75};
  const auto same_scaled = [](const Mesh& a, const Mesh& b, int k) {
    ASSERT_EQ(a.num_vertices(), b.num_vertices());
    ASSERT_EQ(a.num_triangle_slots(), b.num_triangle_slots());
    for (VertexId v = 0; v < a.num_vertices(); ++v) {
      const Point& q = a.point(v);
      ASSERT_EQ(b.point(v), (Point{std::ldexp(q.x, k), std::ldexp(q.y, k)})) << "vertex " << v;
    }
    for (TriId t = 0; t < a.num_triangle_slots(); ++t) ASSERT_EQ(a.triangle(t), b.triangle(t));
  };
  TriangulateOptions topt;
  topt.refine = RefineOptions{};
  topt.refine->min_angle_deg = 30;
  topt.refine->max_area = 0.002;
  const Mesh base = triangulate(p, topt);
  expect_valid(base);
  ASSERT_GT(base.num_triangles(), 100u);
  const Mesh points_base = delaunay(p.points);
  for (int k : {-450, -300, 300, 450}) {  // the area bound times 2^2k stays normal
    SCOPED_TRACE("2^" + std::to_string(k));
    const Pslg scaled = test::scaled_pslg(p, std::ldexp(1.0, k));
    TriangulateOptions o = topt;
    o.refine->max_area = std::ldexp(topt.refine->max_area, 2 * k);
    const Mesh m = triangulate(scaled, o);
    expect_valid_scaled(m, k);
    same_scaled(base, m, k);
    same_scaled(points_base, delaunay(scaled.points), k);
    // refine() on a mesh beyond the range: the mesh comes back in the
    // user's coordinates, refined as in range.
    TriangulateOptions plain;
    Mesh coarse = triangulate(scaled, plain);
    RefineOptions ro = *o.refine;
    const RefineStats st = refine(coarse, ro);
    EXPECT_TRUE(st.complete) << st.summary();
    expect_valid_scaled(coarse, k);
    Mesh coarse0 = triangulate(p, plain);
    refine(coarse0, *topt.refine);
    same_scaled(coarse0, coarse, k);
  }
}

// Every finite double is taken: coordinates beyond the predicates' own range
// (2^+-200), subnormal ones, and DBL_MAX, with the input vertices bit for
// bit in the output. NaN and infinity are refused by name.
TEST(Scale, EveryFiniteMagnitudeIsAccepted) {
  for (double s : {1e-300, 1e-310, 5e-324 * 1024, 1e-60, 1e60, 1e300, 1.5e308 / 10}) {
    SCOPED_TRACE(s);
    Pslg p;
    p.points = {{0, 0}, {10 * s, 0}, {10 * s, 10 * s}, {0, 10 * s}, {3 * s, 4 * s}};
    for (VertexId i = 0; i < 4; ++i) p.segments.push_back({i, (i + 1) % 4, 1});
    const RunResult r = mesh("-pq30", p);
    for (VertexId v = 0; v < p.points.size(); ++v) EXPECT_EQ(r.mesh.point(v), p.points[v]);
    EXPECT_GT(r.mesh.num_triangles(), 4u);
    EXPECT_GE(min_angle(r.mesh), 30.0);
    EXPECT_TRUE(r.complete()) << r.stats.refine.summary();
  }
  Pslg bad;
  bad.points = {{0, 0}, {1, 0}, {0, NAN}};
  try {
    mesh("-p", bad);
    ADD_FAILURE() << "NaN accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.index(), 2u);
    EXPECT_NE(std::string(e.what()).find("NaN"), std::string::npos) << e.what();
  }
  bad.points[2] = {INFINITY, 0};
  EXPECT_THROW(mesh("-p", bad), InputError);
  // A coordinate about 2^400 below the largest cannot be told apart from 0
  // by the exact predicates next to it: refused, naming the point.
  bad.points = {{0, 0}, {1, 0}, {0, 1}, {1e-300, 0.5}};
  try {
    mesh("-p", bad);
    ADD_FAILURE() << "a 2^-997 coordinate beside 1 accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.index(), 3u);
    EXPECT_NE(std::string(e.what()).find("2^400"), std::string::npos) << e.what();
  }
  // Up to that ratio the frame is raised so both ends fit (2^-200 and 2^200
  // in one input, as the predicates' own range always allowed).
  Pslg wide;
  wide.points = {{0, 0}, {0x1p200, 0}, {0, 0x1p200}, {0x1p-200, 0x1p-200}, {-0x1p200, -0x1p-200}};
  const RunResult w = mesh("", wide);
  expect_valid(w.mesh);  // in the predicates' own range: checked as is
  EXPECT_GE(w.mesh.num_triangles(), 3u);
  for (VertexId v = 0; v < wide.points.size(); ++v) EXPECT_EQ(w.mesh.point(v), wide.points[v]);
}

// The cases: a 1e-12 square in [-1, 1]^2 at -q20 (Triangle: 362
// triangles, all >= 20.1°), features at 1e-12 and 1e12 at once.
TEST(Scale, SmallFeaturesFarBelowTheDomainReachTheBound) {
  const RunResult r = mesh("-pq20", test::tiny_square_in_box());
  expect_valid(r.mesh);
  EXPECT_TRUE(r.complete()) << r.stats.refine.summary();
  EXPECT_GE(min_angle(r.mesh), 20.0);
  EXPECT_LE(r.mesh.num_triangles(), 362u);

  Pslg mixed = test::tiny_square_in_box();
  for (std::size_t i = 0; i < 4; ++i) mixed.points[i] = {mixed.points[i].x * 1e12, mixed.points[i].y * 1e12};
  const RunResult m = mesh("-pq20", mixed);
  EXPECT_TRUE(m.complete()) << m.stats.refine.summary();
  EXPECT_GE(min_angle(m.mesh), 20.0);
}

// Points 1e15 from the origin on the lattice of doubles there (spacing
// 1/8), at random: edges of a few ulps, where off-centres and split points
// round onto vertices.
Pslg lattice_points_at_offset() {
  Pslg p;
  std::mt19937 rng(3);
  std::set<std::pair<int, int>> seen;
  while (seen.size() < 40) seen.insert({int(rng() % 32), int(rng() % 32)});
  for (const auto& [i, j] : seen) p.points.push_back({1e15 + 0.125 * i, 1e15 + 0.125 * j});
  return p;
}

// Precision is measured where the work is, by what rounding does. Unit
// features 1e15 from the origin (an edge of 1 is 8 ulps there) still mesh:
// their split points and off-centres land on distinct lattice points.
TEST(Scale, UnitFeaturesAtAHugeOffsetMeshWhereTheLatticeAllows) {
  Pslg p;
  const double o = 1e15;
  p.points = {{o, o}, {o + 8, o}, {o + 8, o + 1}, {o + 1, o + 1}, {o + 0.5, o + 4}};
  for (VertexId i = 0; i < 5; ++i) p.segments.push_back({i, (i + 1) % 5, 1});
  const RunResult r = mesh("-pq30", p);
  expect_valid_scaled(r.mesh, -50);
  EXPECT_TRUE(r.complete()) << r.stats.refine.summary();
  EXPECT_EQ(r.stats.refine.below_precision, 0u);
  // The one triangle left below 30 degrees is in the input's 7-degree corner.
  EXPECT_EQ(r.stats.refine.below_bound, r.stats.refine.below_small_input_angle);
}

// Where every new vertex tried rounds onto a vertex or out of its cavity,
// the run is incomplete, with the count and the place: the worst triangle's
// shortest edge is a few ulps of its coordinates.
TEST(Scale, UlpSizedFeaturesAtAHugeOffsetAreReportedAtThePrecisionOfDoubles) {
  const RunResult r = mesh("-q30", lattice_points_at_offset());
  expect_valid_scaled(r.mesh, -50);
  EXPECT_FALSE(r.complete());
  const RefineStats& st = r.stats.refine;
  EXPECT_GT(st.below_precision, 0u) << st.summary();
  EXPECT_EQ(st.below_bound, st.below_precision) << st.summary();
  EXPECT_GT(st.precision_magnitude, 1e15);
  EXPECT_LT(st.precision_edge, 8 * 0.125);
  EXPECT_NEAR(st.precision_x, 1e15, 4);
  EXPECT_NE(st.unmet().find("at the precision of doubles"), std::string::npos) << st.unmet();
}

// ---------------------------------------------------------------------------
// One exit-code rule: an unmet angle or size bound is exit 3, with or
// without -Y, except triangles in small input angles (counted, explained).

namespace {

struct Cli {
  int code = -1;
  std::string out, err;
};

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

// Runs the CLI in a fresh temporary directory holding `files` (name, text).
Cli run_cli(const std::string& args, const std::vector<std::pair<std::string, std::string>>& files) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::temp_directory_path() / ("deltamesh_scale_" + std::to_string(::getpid()) + "_" + info->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const auto& [name, text] : files) std::ofstream(dir / name, std::ios::binary) << text;
  const fs::path out = dir / "stdout", err = dir / "stderr";
  const std::string cmd = "cd '" + dir.string() + "' && '" + std::string(DELTAMESH_CLI) + "' " + args + " > '" +
                          out.string() + "' 2> '" + err.string() + "'";
  const int status = std::system(cmd.c_str());
  Cli r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  fs::remove_all(dir);
  return r;
}

std::pair<std::string, std::string> plate() {
  return {"plate.poly", slurp(std::string(DELTAMESH_SOURCE_DIR) + "/examples/plate.poly")};
}

}  // namespace

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE((haystack).find(needle), std::string::npos) << "expected '" << (needle) << "' in:\n" << (haystack)

TEST(ExitCodes, AnUnmetAngleBoundUnderYIsExitThree) {
  // -Y forbids the boundary splits some triangles below 30° need.
  const Cli y = run_cli("-pq30Y plate.poly", {plate()});
  EXPECT_EQ(y.code, 3) << y.err;
  EXPECT_CONTAINS(y.err, "bounds not met");
  EXPECT_CONTAINS(y.err, "need a segment split -Y/-YY forbids");
  // The same with an area bound: exit 3 as before, both reasons named.
  const Cli ya = run_cli("-pq30a0.2Y plate.poly", {plate()});
  EXPECT_EQ(ya.code, 3) << ya.err;
  EXPECT_CONTAINS(ya.err, "above their size bound");
  // Without -Y every bound is met: exit 0.
  const Cli ok = run_cli("-pq30a0.2 plate.poly", {plate()});
  EXPECT_EQ(ok.code, 0) << ok.err;
  EXPECT_EQ(ok.err.find("bounds not met"), std::string::npos) << ok.err;
}

TEST(ExitCodes, SmallInputAnglesAloneAreNotAnUnmetBound) {
  // A 5° wedge: the triangles in it stay below 20° (expected, counted).
  const Cli r = run_cli("-pq20V wedge.poly",
                        {{"wedge.poly", "3 2 0 0\n1 0 0\n2 10 0\n3 10 0.8748866352592401\n3 0\n1 1 2\n2 2 3\n3 3 1\n0\n"}});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_CONTAINS(r.out, "at input angles < 60°");
}

TEST(ExitCodes, UnreachablePrecisionIsExitThreeNamingThePlace) {
  std::ostringstream f;
  f.precision(17);
  const Pslg p = lattice_points_at_offset();
  f << p.points.size() << " 2 0 0\n";
  for (std::size_t i = 0; i < p.points.size(); ++i) f << i + 1 << " " << p.points[i].x << " " << p.points[i].y << "\n";
  const Cli r = run_cli("-q30 off.node", {{"off.node", f.str()}});
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_CONTAINS(r.err, "at the precision of doubles");
  EXPECT_CONTAINS(r.err, "the worst near (1e+15, 1e+15)");
  EXPECT_CONTAINS(r.err, "would round onto its neighbours or out of its cavity");
}
