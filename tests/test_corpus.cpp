// Every file of the shared corpus (../shared/corpus, real inputs from other
// projects; see its SOURCES.md), one test per file:
//  - .node: Delaunay triangulation, validated (convex hull, Euler count);
//  - .poly: the pipeline with -p semantics, validated (every segment a chain
//    of constrained edges, constrained Delaunay), and compared with what SOURCES.md records of
//    Triangle's run (-pz): an empty mesh where Triangle's was empty, the same
//    triangle count and the even-odd area where the input has no crossing,
//    overlapping or touching segments; the files whose notes say they need
//    -c are also meshed with -c.
//  - the command line on a copy of each file: -C passes, exit code 0.
// Skipped with a message when the corpus is not there. The files are not
// copied into this repository (their licences vary).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "deltamesh/errors.hpp"
#include "deltamesh/triangle_io.hpp"
#include "deltamesh/triangulate.hpp"
#include "deltamesh/validate.hpp"

using namespace deltamesh;
namespace fs = std::filesystem;

namespace {

fs::path corpus_dir() { return fs::path(DELTAMESH_SOURCE_DIR) / ".." / "shared" / "corpus"; }

// What SOURCES.md says about one file.
struct Expectation {
  bool listed = false;
  bool clean = false;  // "problems" column is "none"
  bool triangle_empty = false;
  long long triangle_count = -1;  // "-pz: N triangles"
  bool evenodd_area = false;      // "-pz area = even-odd area"
};

std::map<std::string, Expectation> read_sources() {
  std::map<std::string, Expectation> out;
  std::ifstream in(corpus_dir() / "SOURCES.md");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("| ", 0) != 0) continue;
    std::vector<std::string> cols;
    std::stringstream ss(line.substr(1));
    for (std::string c; std::getline(ss, c, '|');) {
      const auto a = c.find_first_not_of(' '), b = c.find_last_not_of(' ');
      cols.push_back(a == std::string::npos ? "" : c.substr(a, b - a + 1));
    }
    if (cols.size() < 9 || (cols[0].find(".poly") == std::string::npos && cols[0].find(".node") == std::string::npos))
      continue;
    Expectation e;
    e.listed = true;
    e.clean = cols[7] == "none";
    const std::string& check = cols[8];
    e.triangle_empty = check.find("empty mesh") != std::string::npos;
    e.evenodd_area = check.find("area = even-odd area") != std::string::npos;
    const auto colon = check.find("-pz: ");
    if (colon != std::string::npos && check.find(" triangles", colon) != std::string::npos)
      e.triangle_count = std::stoll(check.substr(colon + 5));
    out[cols[0]] = e;
  }
  return out;
}

// SOURCES.md notes: "triangle_box.poly has no segments around the outer box:
// Triangle needs -c ... The same applies to the CDT files whose constraints
// are open (hanging edges, crossing edges, test_data_small,
// points_on_constraint_edge, corner_cases, problematic_case1): they are meant
// to be meshed over the convex hull (-c)."
const std::set<std::string>& needs_convex_hull() {
  static const std::set<std::string> files = {
      "triangle_box.poly",         "cdt_hanging.poly",          "cdt_double_hanging.poly",
      "cdt_triple_hanging.poly",   "cdt_hanging_intersection.poly", "cdt_crossing_edges.poly",
      "cdt_issue148_crossing_edges.poly", "cdt_test_data_small.poly", "cdt_points_on_constraint_edge.poly",
      "cdt_corner_cases.poly",     "cdt_problematic_case1.poly"};
  return files;
}

std::vector<std::string> corpus_files() {
  std::vector<std::string> files;
  std::error_code ec;
  if (fs::is_directory(corpus_dir(), ec))
    for (const auto& e : fs::directory_iterator(corpus_dir(), ec)) {
      const std::string ext = e.path().extension().string();
      if (ext == ".poly" || ext == ".node") files.push_back(e.path().filename().string());
    }
  std::sort(files.begin(), files.end());
  if (files.empty()) files.push_back("(corpus missing)");
  return files;
}

double area(const Mesh& m) {
  double s = 0;
  for (TriId t = 0; t < m.num_triangle_slots(); ++t) {
    if (!m.is_real(t)) continue;
    const auto v = m.triangle(t);
    const Point &a = m.point(v[0]), &b = m.point(v[1]), &c = m.point(v[2]);
    s += 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
  }
  return s;
}

void expect_boundary_of_segments(const Mesh& m, const std::string& what) {
  const std::vector<std::string> p = check_domain_boundary(m);
  EXPECT_TRUE(p.empty()) << what << ": " << p.front();
}

void expect_valid(const Mesh& m, bool convex, const std::string& what) {
  CheckOptions opt;
  opt.convex_hull = convex;
  const CheckReport r = check(m, opt);
  EXPECT_TRUE(r.ok()) << what << ": " << r.summary();
}

class Corpus : public ::testing::TestWithParam<std::string> {
 public:
  static void SetUpTestSuite() { sources_ = new std::map<std::string, Expectation>(read_sources()); }
  static void TearDownTestSuite() {
    delete sources_;
    sources_ = nullptr;
  }

 protected:
  static std::map<std::string, Expectation>* sources_;
};
std::map<std::string, Expectation>* Corpus::sources_ = nullptr;

TEST_P(Corpus, MeshesAndValidates) {
  const std::string name = GetParam();
  if (name == "(corpus missing)")
    GTEST_SKIP() << "corpus not found at " << corpus_dir().string() << " (it lives beside the repository)";
  const fs::path file = corpus_dir() / name;
  const Expectation exp = sources_->count(name) ? sources_->at(name) : Expectation{};
  const auto t0 = std::chrono::steady_clock::now();

  if (file.extension() == ".node") {
    const Pslg g = read_node(file.string());
    TriangulateOptions opt;
    opt.use_segments = false;
    TriangulateStats st;
    const Mesh m = triangulate(g, opt, &st);
    expect_valid(m, true, name);
    EXPECT_GT(m.num_triangles(), 0u);
    EXPECT_EQ(m.num_vertices(), g.points.size());
  } else {
    const Pslg g = read_poly(file.string());
    TriangulateOptions opt;
    opt.check_segments = true;
    TriangulateStats st;
    const Mesh m = triangulate(g, opt, &st);
    EXPECT_TRUE(st.segment_check.ok()) << name << " constrained triangulation: " << st.segment_check.summary();
    expect_valid(m, false, name + " -p");
    expect_boundary_of_segments(m, name + " -p");
    if (exp.triangle_empty) {
      EXPECT_EQ(m.num_triangles(), 0u) << name << ": Triangle -pz gives an empty mesh";
    } else if (exp.listed) {
      EXPECT_GT(m.num_triangles(), 0u) << name;
    }
    if (exp.clean && exp.triangle_count >= 0) {
      EXPECT_EQ(static_cast<long long>(m.num_triangles()), exp.triangle_count) << name << ": Triangle -pz's count";
    }
    if (exp.clean) {
      // Hole points and the exterior give the even-odd domain on inputs
      // whose rings are simple and disjoint.
      TriangulateOptions eo;
      eo.domain.fill = FillRule::EvenOdd;
      const Mesh e = triangulate(g, eo);
      expect_valid(e, false, name + " --fill=evenodd");
      expect_boundary_of_segments(e, name + " --fill=evenodd");
      if (exp.evenodd_area) {
        const double a = area(m), b = area(e);
        EXPECT_NEAR(a, b, 1e-9 * std::max(1.0, std::abs(b))) << name << ": area differs from the even-odd area";
        EXPECT_EQ(m.num_triangles(), e.num_triangles()) << name;
      }
    }
    if (needs_convex_hull().count(name)) {
      TriangulateOptions c;
      c.domain.keep_convex_hull = true;
      TriangulateStats cs;
      const Mesh mc = triangulate(g, c, &cs);
      expect_valid(mc, false, name + " -pc");
      expect_boundary_of_segments(mc, name + " -pc");
      EXPECT_GT(mc.num_triangles(), 0u) << name << " -pc";
      if (g.holes.empty()) {
        // The whole convex hull: the Delaunay triangulation's area.
        TriangulateOptions d;
        d.use_segments = false;
        EXPECT_NEAR(area(mc), area(triangulate(g, d)), 1e-9 * std::max(1.0, area(mc))) << name << " -pc";
      }
    }
  }
  // The command line on a copy (outputs go beside the input): -C passes,
  // exit code 0, and the .ele says what the library said.
  const fs::path dir = fs::temp_directory_path() / ("deltamesh_corpus_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy_file(file, dir / name);
  const bool poly = file.extension() == ".poly";
  const std::string switches = !poly ? "-CQ" : needs_convex_hull().count(name) ? "-pcCQ" : "-pCQ";
  const std::string cmd = "cd '" + dir.string() + "' && '" + DELTAMESH_CLI + "' " + switches + " '" + name +
                          "' > cli.out 2> cli.err";
  const int status = std::system(cmd.c_str());
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0)
      << name << " " << switches << ": exit " << (WIFEXITED(status) ? WEXITSTATUS(status) : -1) << "\n"
      << std::ifstream(dir / "cli.err").rdbuf();
  const fs::path ele = dir / (file.stem().string() + ".1.ele");
  EXPECT_TRUE(fs::exists(ele)) << name;
  if (poly && exp.triangle_empty && !needs_convex_hull().count(name) && fs::exists(ele)) {
    std::ifstream in(ele);
    long long count = -1;
    in >> count;
    EXPECT_EQ(count, 0) << name << ": expected an empty mesh from the command line";
  }
  if (!HasFailure()) fs::remove_all(dir);

  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_LT(seconds, 30.0) << name << " took " << seconds << " s";
}

std::string test_name(const ::testing::TestParamInfo<std::string>& info) {
  std::string s = info.param;
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return s;
}

INSTANTIATE_TEST_SUITE_P(Files, Corpus, ::testing::ValuesIn(corpus_files()), test_name);

// The SOURCES.md table is read correctly (guards the expectations above).
TEST(CorpusSources, TableIsParsed) {
  if (!fs::exists(corpus_dir() / "SOURCES.md")) GTEST_SKIP() << "corpus not found at " << corpus_dir().string();
  const auto s = read_sources();
  EXPECT_GE(s.size(), 140u);
  ASSERT_TRUE(s.count("triangle_face.poly"));
  EXPECT_EQ(s.at("triangle_face.poly").triangle_count, 36);
  EXPECT_TRUE(s.at("triangle_face.poly").clean);
  ASSERT_TRUE(s.count("earcut_empty_square.poly"));
  EXPECT_TRUE(s.at("earcut_empty_square.poly").triangle_empty);
  ASSERT_TRUE(s.count("ne50m_lake_huron.poly"));
  EXPECT_TRUE(s.at("ne50m_lake_huron.poly").evenodd_area);
  for (const std::string& f : needs_convex_hull()) EXPECT_TRUE(s.count(f)) << f;
}

}  // namespace
