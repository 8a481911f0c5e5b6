// Every file of the shared corpus (../shared/corpus: real inputs from other
// projects, many with crossing or overlapping segments, vertices on
// segments and duplicates) through constrained_triangulation with each of
// the four methods (Fast in both orders); every result through the validator with the PSLG (every
// segment a chain of constrained edges; constrained Delaunay except for Ct).
// Inputs with all points collinear must fail with InputError, and nothing
// else may throw. Skipped with a message when the corpus is not there.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "deltamesh/cdt.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/predicates.hpp"
#include "deltamesh/triangle_io.hpp"
#include "deltamesh/validate.hpp"

using namespace deltamesh;
namespace fs = std::filesystem;

namespace {

fs::path corpus_dir() { return fs::path(DELTAMESH_SOURCE_DIR) / ".." / "shared" / "corpus"; }

std::vector<fs::path> corpus_files() {
  std::vector<fs::path> files;
  std::error_code ec;
  if (!fs::is_directory(corpus_dir(), ec)) return files;
  for (const auto& entry : fs::directory_iterator(corpus_dir(), ec)) {
    const fs::path& p = entry.path();
    if (p.extension() == ".poly") {
      files.push_back(p);
    } else if (p.extension() == ".node") {
      fs::path poly = p;
      poly.replace_extension(".poly");
      if (!fs::exists(poly)) files.push_back(p);  // a .poly may take its vertices from the .node
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

// No triangle exists: fewer than 3 distinct points, or all on one line.
bool degenerate(const std::vector<Point>& p) {
  for (std::size_t i = 1; i < p.size(); ++i) {
    if (p[i] == p[0]) continue;
    for (std::size_t j = i + 1; j < p.size(); ++j)
      if (orient2d(p[0], p[i], p[j]) != 0) return false;
    return true;
  }
  return true;
}

}  // namespace

TEST(CdtCorpus, EveryFileEveryMethod) {
  const std::vector<fs::path> files = corpus_files();
  if (files.empty()) GTEST_SKIP() << "no corpus at " << corpus_dir() << " (it is not part of the repository)";
  std::size_t meshes = 0, segments = 0, intersections = 0, fallbacks = 0, chain_used = 0;
  for (const fs::path& file : files) {
    const std::string name = file.filename().string();
    Pslg g;
    try {
      g = file.extension() == ".poly" ? read_poly(file.string()) : read_node(file.string());
    } catch (const Error& e) {
      ADD_FAILURE() << name << ": cannot be read: " << e.what();
      continue;
    }
    // Fast twice: trying the chain order first (forced, to test it on every
    // file) and the classic order.
    const std::pair<CdtMethod, bool> variants[] = {{CdtMethod::Fast, true},
                                                   {CdtMethod::Fast, false},
                                                   {CdtMethod::Ct, false},
                                                   {CdtMethod::Lawson, false},
                                                   {CdtMethod::Lifting, false}};
    for (const auto& [method, chain] : variants) {
      const std::string what =
          name + " [" + std::string(to_string(method)) + (chain ? "" : method == CdtMethod::Fast ? "-classic" : "") + "]";
      CdtOptions opt;
      opt.method = method;
      opt.chain_order = chain ? ChainOrder::Always : ChainOrder::Never;
      CdtStats st;
      Mesh m;
      try {
        m = constrained_triangulation(g, opt, &st);
      } catch (const InputError& e) {
        EXPECT_TRUE(degenerate(g.points)) << what << ": " << e.what();
        continue;
      }
      CheckOptions co;
      co.pslg = &g;
      co.delaunay = method != CdtMethod::Ct;
      const CheckReport r = check(m, co);
      EXPECT_TRUE(r.ok()) << what << ": " << r.summary();
      EXPECT_EQ(r.segments_checked, st.segments_inserted) << what;
      ++meshes;
      if (method == CdtMethod::Fast && chain) {
        segments += st.segments_inserted;
        intersections += st.intersections;
        chain_used += st.chain_order;
      }
      if (method == CdtMethod::Lifting) fallbacks += st.method_fallbacks;
    }
  }
  RecordProperty("meshes", static_cast<int>(meshes));
  std::printf(
      "[ corpus   ] %zu files, %zu meshes, %zu segments, %zu crossings resolved, %zu lifting fallbacks, chain order "
      "kept on %zu files\n",
      files.size(), meshes, segments, intersections, fallbacks, chain_used);
}
