// Refinement over the shared corpus (../shared/corpus): every file of the
// reference table (Triangle 1.6's counts at -q30 / -q33) is triangulated,
// refined and checked. Skipped when the corpus is absent.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "deltamesh/quality.hpp"
#include "deltamesh/refine.hpp"
#include "deltamesh/triangle_io.hpp"
#include "deltamesh/triangulate.hpp"
#include "deltamesh/validate.hpp"
#include "test_refine_util.hpp"

namespace dm = deltamesh;

namespace {

const std::string kCorpus = DELTAMESH_SOURCE_DIR "/../shared/corpus/";
const std::string kReference = DELTAMESH_SOURCE_DIR "/../shared/reference/triangle-quality-counts.tsv";

struct Row {
  std::string file;
  double q;
  long triangles;
  long below;
};

std::vector<Row> reference() {
  std::vector<Row> rows;
  std::ifstream in(kReference);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("file", 0) == 0) continue;
    std::istringstream s(line);
    Row r;
    double min_angle;
    if (s >> r.file >> r.q >> r.triangles >> r.below >> min_angle) rows.push_back(r);
  }
  return rows;
}

// strict: every triangle left below the bound is at a small input angle (the
// default configuration); otherwise only validity, conformity and totals.
void run_corpus(dm::EncroachmentRule rule, double max_total_ratio, bool strict) {
  if (!std::filesystem::exists(kReference) || !std::filesystem::exists(kCorpus)) GTEST_SKIP() << "no corpus";
  const std::vector<Row> rows = reference();
  ASSERT_GT(rows.size(), 50u);
  std::map<double, long> ours, theirs, below_ours, below_theirs;
  for (const Row& r : rows) {
    SCOPED_TRACE(r.file + " q" + std::to_string(r.q));
    const dm::Pslg pslg = dm::read_poly(kCorpus + r.file);
    dm::Mesh mesh = dm::triangulate(pslg);
    const bool cdt_valid = dm::check(mesh, {.convex_hull = false}).ok();
    const auto segs = dm::test::boundary_segments(mesh);
    dm::RefineOptions opt;
    opt.min_angle_deg = r.q;
    opt.encroachment = rule;
    const dm::RefineStats st = dm::refine(mesh, opt);
    // Complete, or (non-strict configurations) left only triangles at the
    // precision of doubles, an unmet bound under the one exit-code rule.
    EXPECT_TRUE(st.complete || (!strict && !st.budget_exhausted && !st.time_exhausted && st.too_large == 0 &&
                                st.below_bound == st.below_small_input_angle + st.below_precision))
        << st.summary();
    const dm::CheckReport rep = dm::check(mesh, {.convex_hull = false});
    // (A vertex where two holes touch fails the validator's one-fan rule
    // already in the CDT; refinement must not add problems elsewhere.)
    if (cdt_valid) {
      EXPECT_TRUE(rep.ok()) << rep.summary();
    }
    EXPECT_TRUE(dm::test::segments_conform(mesh, segs));
    // Every triangle left below the bound sits in an input angle under 60°.
    if (strict) {
      EXPECT_EQ(st.below_bound, st.below_small_input_angle) << st.summary();
    }
    const auto qr = dm::quality_report(mesh, {.min_angle_deg = r.q});
    EXPECT_EQ(qr.below_angle, st.below_bound);
    // Per file: within a broad band of Triangle's count. The lower end only
    // where we leave more triangles below the bound than Triangle does: the
    // earcut_touching_holes fans of narrow wedges end with one triangle per
    // wedge (the small-angle rules leave it; Triangle refines each wedge down
    // to its apex), about a third of Triangle's count and fewer below.
    if (strict && r.triangles > 100) {
      EXPECT_LT(static_cast<double>(mesh.num_triangles()), 1.6 * r.triangles);
      if (static_cast<long>(st.below_bound) > r.below) {
        EXPECT_GT(static_cast<double>(mesh.num_triangles()), 0.4 * r.triangles);
      }
    }
    ours[r.q] += static_cast<long>(mesh.num_triangles());
    theirs[r.q] += r.triangles;
    below_ours[r.q] += static_cast<long>(st.below_bound);
    below_theirs[r.q] += r.below;
  }
  for (const auto& [q, n] : ours) {
    const double ratio = static_cast<double>(n) / static_cast<double>(theirs[q]);
    std::printf("q%g: %ld triangles (Triangle %ld, ratio %.4f); below the bound %ld (Triangle %ld)\n", q, n,
                theirs[q], ratio, below_ours[q], below_theirs[q]);
    EXPECT_LT(ratio, max_total_ratio);
    // The default leaves no more triangles below the bound than Triangle.
    if (strict) {
      EXPECT_LE(below_ours[q], below_theirs[q]);
    }
  }
}

}  // namespace

// The default (lenses): totals measured 0.985 (q30) and 0.990 (q33) of Triangle's;
// below the bound 1026 (Triangle 1330) and 1660 (Triangle 1688).
TEST(RefineCorpus, DiametralLenses) { run_corpus(dm::EncroachmentRule::DiametralLens, 1.02, true); }
// The seed's circles: 1.02 (q30), 1.15 (q33).
TEST(RefineCorpus, DiametralCircles) { run_corpus(dm::EncroachmentRule::DiametralCircle, 1.25, false); }
