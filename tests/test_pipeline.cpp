// The library's pipeline: the switch parser's Plan, and run() on in-memory
// input for each input kind. Every mesh goes through the validator.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "deltamesh/deltamesh.hpp"

using namespace deltamesh;

namespace {

Plan plan_of(const std::vector<std::string>& args) { return parse_arguments(args).plan; }

// A unit square with a square hole, markers 5 (outside) and 7 (hole).
Pslg square_with_hole() {
  Pslg p;
  p.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.4, 0.4}, {0.6, 0.4}, {0.6, 0.6}, {0.4, 0.6}};
  for (VertexId i = 0; i < 4; ++i) p.segments.push_back({i, (i + 1) % 4, 5});
  for (VertexId i = 0; i < 4; ++i) p.segments.push_back({4 + i, 4 + (i + 1) % 4, 7});
  p.holes = {{0.5, 0.5}};
  return p;
}

void expect_valid(const Mesh& m, bool delaunay = true) {
  CheckOptions co;
  co.convex_hull = false;
  co.delaunay = delaunay;
  const CheckReport r = check(m, co);
  EXPECT_TRUE(r.ok()) << r.summary();
}

TEST(PipelinePlan, SwitchesDescribeTheRun) {
  Plan p = plan_of({"-pq30a0.5zCj", "x"});
  EXPECT_EQ(p.input, InputKind::Pslg);
  EXPECT_TRUE(p.refine.quality);
  EXPECT_EQ(p.refine.min_angle, 30.0);
  EXPECT_EQ(p.refine.max_area, 0.5);
  EXPECT_TRUE(p.zero_based && p.check && p.jettison);
  EXPECT_TRUE(p.refine.requested());
  EXPECT_EQ(p.refine.options().min_angle_deg, 30.0);

  p = plan_of({"-c", "x"});
  EXPECT_EQ(p.input, InputKind::Points);
  EXPECT_TRUE(p.domain.convex_hull);
  EXPECT_FALSE(p.refine.requested());

  // -r and -p in either order; --adapt implies -r.
  p = plan_of({"-pr", "x"});
  EXPECT_EQ(p.input, InputKind::Mesh);
  EXPECT_TRUE(p.mesh_segments);
  p = plan_of({"--adapt", "-q", "x"});
  EXPECT_EQ(p.input, InputKind::Adapt);
  EXPECT_FALSE(p.mesh_segments);

  // -a alone: the input's own bounds, which ask for refinement.
  p = plan_of({"-pa", "x"});
  EXPECT_TRUE(p.refine.input_area_bounds);
  EXPECT_TRUE(p.refine.requested());
  EXPECT_FALSE(p.refine.max_area);

  p = plan_of({"-pYYo2", "--cdt=lawson", "--steiner=offcenter", "--order=worst", "--fill=evenodd", "x"});
  EXPECT_EQ(p.refine.options().segment_splitting, SegmentSplitting::None);
  EXPECT_EQ(p.order, 2);
  EXPECT_EQ(p.method, CdtMethod::Lawson);
  EXPECT_EQ(p.refine.steiner, SteinerRule::Offcenter);
  EXPECT_EQ(p.refine.order, RefineOrder::WorstFirst);
  EXPECT_EQ(p.domain.fill, FillRule::EvenOdd);

  EXPECT_EQ(plan_of({"-pq", "x"}).refine.steiner, SteinerRule::Best);
  EXPECT_EQ(plan_of({"-pq", "--steiner=grid", "x"}).refine.steiner, SteinerRule::Grid);
}

TEST(PipelinePlan, UsageErrorsNameTheSwitch) {
  auto message = [](const std::vector<std::string>& args) -> std::string {
    try {
      parse_arguments(args);
    } catch (const UsageError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(message({"-pk"}), "unknown switch -k in '-pk' (see deltamesh --help)");
  EXPECT_EQ(message({"-pa-1"}), "unknown switch -- in '-pa-1' (see deltamesh --help)");
  EXPECT_EQ(message({"--cdt=x"}), "--cdt=x: the method must be fast, ct, lawson or lifting");
  EXPECT_EQ(message({"--cdt"}), "option --cdt needs a value");
  EXPECT_EQ(message({"--smooth", "-D"}), "--smooth cannot be combined with -D: moved vertices may encroach segments");
  // A misspelled long option is unknown, with or without a value, and the
  // nearest known name is suggested (it used to say "takes no value").
  EXPECT_EQ(message({"--time-limt=5"}), "unknown option --time-limt (did you mean --time-limit?)");
  EXPECT_EQ(message({"--cdtt=ct"}), "unknown option --cdtt (did you mean --cdt?)");
  EXPECT_EQ(message({"--outptu=x.msh"}), "unknown option --outptu (did you mean --output?)");
  EXPECT_EQ(message({"--quite"}), "unknown option --quite (did you mean --quiet?)");
  EXPECT_EQ(message({"--frobnicate=3"}), "unknown option --frobnicate (see deltamesh --help)");
  EXPECT_EQ(message({"--quiet=3"}), "option --quiet takes no value");
  CommandLine cl;
  EXPECT_THROW(apply_long_option(cl, "--max-area", "0"), UsageError);
  apply_long_option(cl, "--min-angle", "28.5");
  EXPECT_TRUE(cl.plan.refine.quality);
  EXPECT_EQ(cl.plan.refine.min_angle, 28.5);
}

TEST(PipelineRun, QualityMeshOfAPslg) {
  Plan plan = plan_of({"-pq30a0.01C", "x"});
  RunInput in;
  in.pslg = square_with_hole();
  const RunResult r = run(plan, in);
  expect_valid(r.mesh);
  EXPECT_TRUE(r.refined);
  EXPECT_TRUE(r.complete());
  ASSERT_TRUE(r.check.has_value());
  EXPECT_TRUE(r.check->ok()) << r.check->summary();
  EXPECT_EQ(r.stats.domain.holes_used, 1u);
  const QualityReport q = quality_report(r.mesh, {});
  EXPECT_GE(q.min_angle_deg, 30.0 - 1e-9);
  EXPECT_LE(q.max_area, 0.01);
  // Vertex markers were finished after refinement: Steiner points on the
  // outer boundary carry its segments' marker.
  std::size_t on_outer = 0;
  for (VertexId v = 8; v < r.mesh.num_vertices(); ++v) {
    const Point& p = r.mesh.point(v);
    if (p.x == 0 || p.y == 0 || p.x == 1 || p.y == 1) {
      ++on_outer;
      EXPECT_EQ(r.mesh.vertex_markers()[v], 5);
    }
  }
  EXPECT_GT(on_outer, 0u);
  // The phases -V lists, in order.
  ASSERT_GE(r.phases.size(), 4u);
  EXPECT_EQ(r.phases[0].name, "constrained triangulation (fast)");
}

TEST(PipelineRun, DomainWarningsAreData) {
  Plan plan = plan_of({"-p", "x"});
  RunInput in;
  in.pslg = square_with_hole();
  in.pslg.holes.push_back({5, 5});  // outside the hull: ignored, with a warning
  const RunResult r = run(plan, in);
  expect_valid(r.mesh);
  EXPECT_EQ(r.stats.domain.holes_ignored, 1u);
  EXPECT_FALSE(r.warnings().empty());
}

// -r: a mesh from another tool (not Delaunay) is flipped to a CDT before
// refinement; -o2 adds midpoint nodes after -C.
TEST(PipelineRun, RefiningAMeshFlipsItFirst) {
  RunInput in;
  // A thin rhombus split along its long diagonal: not Delaunay.
  in.pslg.points = {{0, 0}, {2, -0.2}, {4, 0}, {2, 0.2}};
  in.triangles = {0, 1, 2, 0, 2, 3};
  const RunResult r = run(plan_of({"-rq20Co2", "x"}), in);
  EXPECT_GT(r.delaunay_flips, 0u);
  ASSERT_TRUE(r.check.has_value());
  EXPECT_TRUE(r.check->ok()) << r.check->summary();
  EXPECT_EQ(r.midside.size(), 3 * r.mesh.num_triangle_slots());
  EXPECT_EQ(r.read_triangles, 2u);
}

// --adapt with per-vertex sizes on a mesh whose new segments cross: the
// vertex added at the crossing takes its neighbours' mean size, so constant
// sizes give what a constant size function gives.
TEST(PipelineRun, AdaptSizesForVerticesSegmentInsertionAdds) {
  RunInput in;
  in.pslg.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  in.triangles = {0, 1, 2, 0, 2, 3};
  in.pslg.segments = {{0, 2, 3}, {1, 3, 4}};  // both diagonals: they cross at the centre
  Plan plan = plan_of({"-rpq30", "--adapt", "x"});
  RunInput by_sizes = in;
  by_sizes.vertex_sizes = {0.1, 0.1, 0.1, 0.1};
  const RunResult a = run(plan, by_sizes);
  EXPECT_EQ(a.inserted.vertices_added, 1u);
  EXPECT_TRUE(a.adapted);
  expect_valid(a.mesh);
  RunInput by_function = in;
  by_function.size = [](double, double) { return 0.1; };
  const RunResult b = run(plan, by_function);
  ASSERT_EQ(a.mesh.num_vertices(), b.mesh.num_vertices());
  ASSERT_EQ(a.mesh.num_triangles(), b.mesh.num_triangles());
  for (VertexId v = 0; v < a.mesh.num_vertices(); ++v) {
    EXPECT_EQ(a.mesh.point(v).x, b.mesh.point(v).x);
    EXPECT_EQ(a.mesh.point(v).y, b.mesh.point(v).y);
  }
  EXPECT_GT(a.mesh.num_triangles(), 50u);  // refined towards edges of 0.1

  // Sizes that do not match the vertices are an input error.
  RunInput wrong = in;
  wrong.vertex_sizes = {0.1, 0.1};
  EXPECT_THROW(run(plan, wrong), InputError);
}

TEST(PipelineRun, SmoothingAfterRefinementKeepsTheBounds) {
  Plan plan = plan_of({"-pq30a0.01", "--smooth=2", "x"});
  RunInput in;
  in.pslg = square_with_hole();
  const RunResult r = run(plan, in);
  EXPECT_TRUE(r.smoothed);
  EXPECT_GT(r.smooth.passes, 0u);
  expect_valid(r.mesh);
  EXPECT_TRUE(r.complete());
}

}  // namespace
