// Long refinement runs (ctest label `long`, `make check-long`): the
// 100k-vertex star polygon with tiny input angles at -q20 (Triangle 1.6 ran
// out of memory on it), and seeded random star polygons at several bounds.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cstdio>

#include "deltamesh-gen/generators.hpp"
#include "deltamesh/quality.hpp"
#include "deltamesh/refine.hpp"
#include "deltamesh/triangulate.hpp"
#include "deltamesh/validate.hpp"
#include "test_refine_util.hpp"

namespace dm = deltamesh;

TEST(RefineLong, StarPolygon100kAtQ20) {
  const dm::Pslg star = dm::gen::star_polygon(100000, 1);
  dm::Mesh mesh = dm::triangulate(star);
  const auto segs = dm::test::boundary_segments(mesh);
  dm::RefineOptions opt;
  opt.min_angle_deg = 20;
  const dm::RefineStats st = dm::refine(mesh, opt);
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  std::printf("star 100k q20: %zu triangles, %s; peak RSS %.0f MB\n", mesh.num_triangles(), st.summary().c_str(),
              ru.ru_maxrss / 1024.0);
  // Measured: ~298,000 triangles, 0.7 s, ~40 MB in this process. Before
  // the thin-channel rule it needed ~26·10^6 triangles (2.6 GB) to finish.
  EXPECT_TRUE(st.complete) << st.summary();
  EXPECT_EQ(st.below_bound, st.below_small_input_angle);
  EXPECT_LT(mesh.num_triangles(), 1'000'000u);
  EXPECT_LT(ru.ru_maxrss, 512l * 1024);  // KB: under 512 MB
  const dm::CheckReport rep = dm::check(mesh, {.convex_hull = false});
  EXPECT_TRUE(rep.ok()) << rep.summary();
  EXPECT_TRUE(dm::test::segments_conform(mesh, segs));
}

TEST(RefineLong, RandomStarsAtSeveralBounds) {
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    for (double q : {20.0, 28.0, 33.0}) {
      const dm::Pslg star = dm::gen::star_polygon(2000 * seed, seed);
      dm::Mesh mesh = dm::triangulate(star);
      const auto segs = dm::test::boundary_segments(mesh);
      dm::RefineOptions opt;
      opt.min_angle_deg = q;
      const dm::RefineStats st = dm::refine(mesh, opt);
      SCOPED_TRACE("seed " + std::to_string(seed) + " q" + std::to_string(q) + ": " + st.summary());
      EXPECT_TRUE(st.complete || st.budget_exhausted);
      if (st.complete) {
        EXPECT_EQ(st.below_bound, st.below_small_input_angle);
      }
      const dm::CheckReport rep = dm::check(mesh, {.convex_hull = false});
      EXPECT_TRUE(rep.ok()) << rep.summary();
      EXPECT_TRUE(dm::test::segments_conform(mesh, segs));
    }
  }
}
