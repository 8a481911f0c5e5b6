// The scale property of test_scale.cpp on every .poly of the shared corpus
// (label long: make check-long): scaling the input by 2^k gives the mesh
// scaled by 2^k, bit for bit, where the result stays finite and normal.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "deltamesh/deltamesh.hpp"
#include "scale_inputs.hpp"
#include "mesh/editor.hpp"

using namespace deltamesh;

TEST(ScaleLong, PowersOfTwoOnTheCorpus) {
  for (const test::ScaleInput& input : test::scale_inputs(true)) {
    SCOPED_TRACE(input.name);
    RunInput ri;
    ri.pslg = input.pslg;
    Plan plan = parse_arguments({"-pq30", "x"}).plan;
    plan.refine.steiner_budget = 200000;
    RunResult base;
    try {
      base = run(plan, std::move(ri));
    } catch (const InputError&) {
      continue;  // refused at scale 1 (e.g. crossing segments with --strict): nothing to compare
    }
    for (int k : {-1000, -200, -60, 60, 200, 1000}) {
      bool fits = true;
      for (const Point& p : base.mesh.points())
        fits = fits && (p.x == 0 || std::isnormal(std::ldexp(p.x, k))) && (p.y == 0 || std::isnormal(std::ldexp(p.y, k)));
      for (const RegionSeed& r : input.pslg.regions)
        fits = fits && (r.max_area <= 0 || std::isnormal(std::ldexp(r.max_area, 2 * k)));
      if (!fits) continue;
      SCOPED_TRACE("2^" + std::to_string(k));
      RunInput s;
      s.pslg = test::scaled_pslg(input.pslg, std::ldexp(1.0, k));
      const RunResult r = run(plan, std::move(s));
      ASSERT_EQ(r.mesh.num_vertices(), base.mesh.num_vertices());
      ASSERT_EQ(r.mesh.num_triangle_slots(), base.mesh.num_triangle_slots());
      for (VertexId v = 0; v < base.mesh.num_vertices(); ++v) {
        const Point& p = base.mesh.point(v);
        ASSERT_EQ(r.mesh.point(v), (Point{std::ldexp(p.x, k), std::ldexp(p.y, k)})) << "vertex " << v;
      }
      for (TriId t = 0; t < base.mesh.num_triangle_slots(); ++t) ASSERT_EQ(r.mesh.triangle(t), base.mesh.triangle(t));
      Mesh back = r.mesh;
      for (Point& p : deltamesh::detail::MeshEditor(back).points()) p = {std::ldexp(p.x, -k), std::ldexp(p.y, -k)};
      CheckOptions co;
      co.convex_hull = false;
      EXPECT_TRUE(check(back, co).ok());
    }
  }
}
