// Long adaptation runs (ctest label `long`, `make check-long`): a fine mesh
// of ~300k triangles adapted to a ramp, and every corpus .poly refined,
// coarsened and adapted to three size fields, each result validated.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "deltamesh/adapt.hpp"
#include "deltamesh/refine.hpp"
#include "deltamesh/triangle_io.hpp"
#include "deltamesh/triangulate.hpp"
#include "deltamesh/validate.hpp"
#include "test_refine_util.hpp"

namespace dm = deltamesh;
namespace fs = std::filesystem;

namespace {

const std::string kCorpus = DELTAMESH_SOURCE_DIR "/../shared/corpus/";

// With g: its segments must be chains of constrained edges between its
// vertices (ids unchanged: they are protected and not renumbered).
void expect_valid(const dm::Mesh& m, const dm::Pslg* g, bool cdt_valid) {
  dm::CheckOptions co;
  co.convex_hull = false;
  co.pslg = g;
  const dm::CheckReport rep = dm::check(m, co);
  // (A vertex where two holes touch fails the validator's one-fan rule in
  // the CDT already; adaptation must not add problems elsewhere.)
  if (cdt_valid) {
    EXPECT_TRUE(rep.ok()) << rep.summary();
  }
}


}  // namespace

TEST(AdaptLong, FineBoxToARamp) {
  dm::Pslg g;
  g.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.4, 0.4}, {0.6, 0.4}, {0.6, 0.6}, {0.4, 0.6}};
  for (dm::VertexId i = 0; i < 4; ++i) g.segments.push_back({i, (i + 1) % 4, 1});
  for (dm::VertexId i = 0; i < 4; ++i) g.segments.push_back({4 + i, 4 + (i + 1) % 4, 2});
  g.holes.push_back({0.5, 0.5});
  dm::TriangulateOptions o;
  o.refine = dm::RefineOptions{};
  o.refine->min_angle_deg = 30;
  o.refine->max_area = 5e-6;
  dm::Mesh m = dm::triangulate(g, o);
  const std::size_t before = m.num_triangles();
  ASSERT_GT(before, 250'000u);
  dm::AdaptOptions a;
  a.refine.min_angle_deg = 30;
  const dm::AdaptStats st = dm::adapt(m, [](double x, double) { return 0.005 + 0.095 * x; }, a);
  std::printf("box: %zu -> %zu triangles; %s\n", before, m.num_triangles(), st.summary().c_str());
  EXPECT_TRUE(st.complete) << st.summary();
  expect_valid(m, &g, true);
  // Measured: 306,421 -> about 10,300 triangles.
  EXPECT_LT(m.num_triangles(), before / 15);
  EXPECT_GT(m.num_triangles(), 3'000u);
  EXPECT_GE(dm::test::min_angle_deg(m), 30.0 - 1e-9);
  EXPECT_NEAR(dm::test::covered_area(m), 0.96, 1e-12);
}

TEST(AdaptLong, CorpusFilesCoarsenAndAdapt) {
  if (!fs::exists(kCorpus)) GTEST_SKIP() << "no corpus at " << kCorpus << " (it is not part of the repository)";
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(kCorpus))
    if (e.path().extension() == ".poly") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  ASSERT_GT(files.size(), 50u);
  std::size_t runs = 0, removed = 0, refused = 0;
  for (const fs::path& file : files) {
    const dm::Pslg g = dm::read_poly(file.string());
    dm::Mesh cdt;
    try {
      cdt = dm::triangulate(g);
    } catch (const dm::InputError&) {
      continue;  // the corpus tests cover what is refused and why
    }
    if (cdt.num_triangles() == 0) continue;
    const bool cdt_valid = dm::check(cdt, {.convex_hull = false}).ok();
    double lox = INFINITY, hix = -INFINITY, loy = INFINITY, hiy = -INFINITY;
    for (const dm::Point& p : cdt.points()) {
      lox = std::min(lox, p.x), hix = std::max(hix, p.x), loy = std::min(loy, p.y), hiy = std::max(hiy, p.y);
    }
    // Areas are compared at the scale of the domain: removing a split point
    // that was rounded off its segment's line changes the area by ulps of
    // size², which is no small part of a sliver's own area.
    const double size = std::max(hix - lox, hiy - loy);
    const std::vector<std::pair<const char*, dm::SizeField>> fields = {
        {"huge", [size](double, double) { return 10 * size; }},
        {"ramp", [=](double x, double) { return size * (0.005 + 0.05 * (x - lox) / size); }},
        {"wavy", [=](double x, double y) {
           return size * (0.02 + 0.015 * std::sin(20 * (x - lox) / size) * std::cos(20 * (y - loy) / size));
         }},
    };
    for (const auto& [name, h] : fields) {
      // Protected: the input vertices stay (with their ids) and the check
      // includes the PSLG; unprotected: straight runs of input vertices may
      // go too, and the check is of the mesh and its constrained edges.
      for (const bool protect : {true, false}) {
        SCOPED_TRACE(file.filename().string() + " " + name + (protect ? " protected" : " unprotected"));
        dm::Mesh m = cdt;
        dm::RefineOptions r;
        r.min_angle_deg = 25;
        r.max_steiner = 200'000;
        dm::refine(m, r);
        const double area = dm::test::covered_area(m);
        // Crossing or overlapping input segments are split and merged, so
        // some files' refined meshes do not show every PSLG segment as given;
        // the protected check then compares with the refined mesh's state.
        dm::CheckOptions with_pslg;
        with_pslg.convex_hull = false;
        with_pslg.pslg = &g;
        const bool valid = cdt_valid && (!protect || dm::check(m, with_pslg).ok());
        dm::CoarsenOptions co;
        if (protect) {
          co.protect_first = g.points.size();
          co.renumber = false;
        }
        const dm::CoarsenStats cs = dm::coarsen(m, h, co);
        expect_valid(m, protect ? &g : nullptr, valid);
        EXPECT_NEAR(dm::test::covered_area(m), area, 1e-9 * size * size);
        EXPECT_EQ(cs.vertices_before - cs.removed, cs.vertices_after);
        dm::AdaptOptions a;
        a.coarsen = co;
        a.refine.min_angle_deg = 25;
        a.refine.max_steiner = 200'000;
        a.refine.time_limit_seconds = 20;
        const dm::AdaptStats as = dm::adapt(m, h, a);
        expect_valid(m, protect ? &g : nullptr, valid);
        EXPECT_NEAR(dm::test::covered_area(m), area, 1e-9 * size * size);
        ++runs;
        removed += cs.removed + as.removed;
        refused += cs.refused + as.coarsen.refused;
      }
    }
  }
  std::printf("%zu corpus runs: %zu vertices removed, %zu refused\n", runs, removed, refused);
  EXPECT_GT(runs, 200u);
}
