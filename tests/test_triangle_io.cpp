// Triangle's file formats: readers (accepted syntax and every error class),
// writers (round trips, headers, markers, numbering) and the atomic writer.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "deltamesh/errors.hpp"
#include "deltamesh/mesh.hpp"
#include "support/grid_mesh.hpp"
#include "deltamesh/triangle_io.hpp"
#include "io/atomic_file.hpp"
#include "io/text_reader.hpp"
#include "mesh/editor.hpp"

using namespace deltamesh;
namespace fs = std::filesystem;
using deltamesh::test::grid_mesh;

namespace {

class TriangleIo : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("deltamesh_io_" + std::to_string(::getpid()) + "_" + info->test_suite_name() + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    const std::string p = path(name);
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }
  static std::string slurp(const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
  // Names in the directory (to check that no temporary file is left).
  std::vector<std::string> listing() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

  fs::path dir_;
};

// Expects `f` to throw ParseError at `line` of `file` whose problem contains `text`.
template <class F>
void expect_parse_error(F&& f, const std::string& file, std::size_t line, const std::string& text) {
  try {
    f();
    ADD_FAILURE() << "no ParseError; expected '" << text << "'";
  } catch (const ParseError& e) {
    EXPECT_EQ(e.file(), file);
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_NE(e.problem().find(text), std::string::npos) << "problem: " << e.problem() << "\nexpected: " << text;
    EXPECT_NE(std::string(e.what()).find(file + ":" + std::to_string(line) + ": "), std::string::npos) << e.what();
  }
}

// Marks the edge a-b (both halves) as constrained.
void constrain(Mesh& m, VertexId a, VertexId b) {
  for (HalfEdgeId e = 0; e < 3 * m.num_triangle_slots(); ++e)
    if ((m.origin(e) == a && m.dest(e) == b) || (m.origin(e) == b && m.dest(e) == a))
      m.set_edge_flags(e, kConstrained);
}

// Data lines of a written file, tokenised (comments dropped).
std::vector<std::vector<std::string>> data_lines(const std::string& p) {
  io::TextReader r = io::TextReader::open(p);
  std::vector<std::vector<std::string>> out;
  while (r.next_line()) {
    std::vector<std::string> toks;
    for (std::size_t i = 0; i < r.size(); ++i) toks.emplace_back(r.token(i));
    out.push_back(std::move(toks));
  }
  return out;
}

}  // namespace

// ---------------------------------------------------------------------------
// Tokenizer and number parsing

TEST(TextReader, NumbersAndTokens) {
  double d;
  long long i;
  EXPECT_EQ(io::parse_double("1.5", d), io::NumberStatus::Ok);
  EXPECT_EQ(d, 1.5);
  EXPECT_EQ(io::parse_double("+2e3", d), io::NumberStatus::Ok);
  EXPECT_EQ(d, 2000.0);
  EXPECT_EQ(io::parse_double("-.25", d), io::NumberStatus::Ok);
  EXPECT_EQ(d, -0.25);
  EXPECT_EQ(io::parse_double("abc", d), io::NumberStatus::NotANumber);
  EXPECT_EQ(io::parse_double("1.5x", d), io::NumberStatus::NotANumber);
  EXPECT_EQ(io::parse_double("+-1", d), io::NumberStatus::NotANumber);
  EXPECT_EQ(io::parse_double("1e999", d), io::NumberStatus::OutOfRange);
  EXPECT_EQ(io::parse_double("nan", d), io::NumberStatus::Ok);
  EXPECT_TRUE(std::isnan(d));
  EXPECT_EQ(io::parse_integer("42", i), io::NumberStatus::Ok);
  EXPECT_EQ(i, 42);
  EXPECT_EQ(io::parse_integer("+7", i), io::NumberStatus::Ok);
  EXPECT_EQ(i, 7);
  EXPECT_EQ(io::parse_integer("-3", i), io::NumberStatus::Ok);
  EXPECT_EQ(i, -3);
  EXPECT_EQ(io::parse_integer("3.0", i), io::NumberStatus::Ok);
  EXPECT_EQ(i, 3);
  EXPECT_EQ(io::parse_integer("3.5", i), io::NumberStatus::NotAnInteger);
  EXPECT_EQ(io::parse_integer("99999999999999999999", i), io::NumberStatus::OutOfRange);
  EXPECT_EQ(io::parse_integer("x1", i), io::NumberStatus::NotANumber);

  io::TextReader r("mem", "# only a comment\n\n  a  b\t#c d\r\n\r\n\t x#y\nlast");
  ASSERT_TRUE(r.next_line());
  EXPECT_EQ(r.line(), 3u);
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r.token(0), "a");
  EXPECT_EQ(r.token(1), "b");
  ASSERT_TRUE(r.next_line());
  EXPECT_EQ(r.line(), 5u);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r.token(0), "x");
  EXPECT_EQ(r.count_data_lines_left(), 1u);
  ASSERT_TRUE(r.next_line());
  EXPECT_EQ(r.line(), 6u);
  EXPECT_EQ(r.token(0), "last");
  EXPECT_FALSE(r.next_line());
  EXPECT_EQ(r.last_line(), 6u);
}

// ---------------------------------------------------------------------------
// .node

TEST_F(TriangleIo, NodeOneBasedWithAttributesMarkersCommentsCrlfNoFinalNewline) {
  const std::string p = write("a.node",
                              "# leading comment\r\n"
                              "\r\n"
                              "3 2 2 1   # header\r\n"
                              "1 0.0 0.0  10 20  5\r\n"
                              "   # a comment line between vertices\r\n"
                              "2 1.5 -2e-3 11 21 0\r\n"
                              "\t3 +4 1e2 12 22 -1");  // no final newline
  const Pslg g = read_node(p);
  EXPECT_EQ(g.first_index, 1);
  ASSERT_EQ(g.points.size(), 3u);
  EXPECT_EQ(g.points[1], (Point{1.5, -2e-3}));
  EXPECT_EQ(g.points[2], (Point{4.0, 100.0}));
  EXPECT_EQ(g.num_point_attributes, 2u);
  EXPECT_EQ(g.point_attributes, (std::vector<double>{10, 20, 11, 21, 12, 22}));
  EXPECT_EQ(g.point_markers, (std::vector<int>{5, 0, -1}));
  EXPECT_TRUE(g.segments.empty());
}

TEST_F(TriangleIo, NodeZeroBasedAndHeaderDefaults) {
  const std::string p = write("b.node", "3\n0 0 0\n1 1 0\n2 0 1 99 # extra fields are ignored\n");
  const Pslg g = read_node(p);
  EXPECT_EQ(g.first_index, 0);
  ASSERT_EQ(g.points.size(), 3u);
  EXPECT_EQ(g.points[2], (Point{0, 1}));
  EXPECT_TRUE(g.point_markers.empty());
  EXPECT_EQ(g.num_point_attributes, 0u);
}

TEST_F(TriangleIo, NodeWithByteOrderMark) {
  const Pslg g = read_node(write("bom.node", "\xEF\xBB\xBF" "1 2 0 0\n1 0.5 0.25\n"));
  ASSERT_EQ(g.points.size(), 1u);
  EXPECT_EQ(g.points[0], (Point{0.5, 0.25}));
}

TEST_F(TriangleIo, NodeEmptyAndIntegralFloatIds) {
  const Pslg g = read_node(write("e.node", "0 2 0 0\n# nothing\n"));
  EXPECT_TRUE(g.points.empty());
  const Pslg h = read_node(write("f.node", "2 2 0 0\n1.0 0 0\n2e0 1 1\n"));
  EXPECT_EQ(h.first_index, 1);
  EXPECT_EQ(h.points.size(), 2u);
}

// ---------------------------------------------------------------------------
// .poly

TEST_F(TriangleIo, PolyAllSections) {
  const std::string p = write("c.poly",
                              "4 2 0 1\n"
                              "1 0 0 1\n2 4 0 1\n3 4 4 1\n4 0 4 1\n"
                              "\n# segments\n"
                              "4 1\n"
                              "1 1 2 7\n2 2 3 7\n3 3 4 0\n4 4 1 0\n"
                              "1\n"
                              "1 2 2\n"
                              "3\n"
                              "1 1 1 10 0.5\n"
                              "2 3 3 20        # no area: no bound\n"
                              "3 3 1 30 0      # area 0: no bound\n");
  const Pslg g = read_poly(p);
  EXPECT_EQ(g.first_index, 1);
  ASSERT_EQ(g.points.size(), 4u);
  EXPECT_EQ(g.point_markers, (std::vector<int>{1, 1, 1, 1}));
  ASSERT_EQ(g.segments.size(), 4u);
  EXPECT_EQ(g.segments[0].a, 0u);
  EXPECT_EQ(g.segments[0].b, 1u);
  EXPECT_EQ(g.segments[0].marker, 7);
  EXPECT_EQ(g.segments[3].a, 3u);
  EXPECT_EQ(g.segments[3].b, 0u);
  EXPECT_EQ(g.segments[3].marker, 0);
  ASSERT_EQ(g.holes.size(), 1u);
  EXPECT_EQ(g.holes[0], (Point{2, 2}));
  ASSERT_EQ(g.regions.size(), 3u);
  EXPECT_EQ(g.regions[0].p, (Point{1, 1}));
  EXPECT_EQ(g.regions[0].attribute, 10.0);
  EXPECT_EQ(g.regions[0].max_area, 0.5);
  EXPECT_EQ(g.regions[1].attribute, 20.0);
  EXPECT_LT(g.regions[1].max_area, 0.0);
  EXPECT_LT(g.regions[2].max_area, 0.0);
}

TEST_F(TriangleIo, PolyWithoutRegionsSectionAndZeroBased) {
  const Pslg g = read_poly(write("d.poly", "3 2 0 0\n0 0 0\n1 1 0\n2 0 1\n3 0\n0 0 1\n1 1 2\n2 2 0\n0\n"));
  EXPECT_EQ(g.first_index, 0);
  ASSERT_EQ(g.segments.size(), 3u);
  EXPECT_EQ(g.segments[2].a, 2u);
  EXPECT_EQ(g.segments[2].b, 0u);
  EXPECT_TRUE(g.holes.empty());
  EXPECT_TRUE(g.regions.empty());
}

TEST_F(TriangleIo, PolyWithNoVerticesReadsSiblingNode) {
  write("shape.node", "# vertices live here\n3 2 1 1\n1 0 0 0.5 2\n2 1 0 0.25 2\n3 0 1 0.125 3\n");
  const std::string p = write("shape.poly", "0 2 0 0\n2 0\n1 1 2\n2 3 1\n0\n");
  const Pslg g = read_poly(p);
  EXPECT_EQ(g.first_index, 1);
  ASSERT_EQ(g.points.size(), 3u);
  EXPECT_EQ(g.point_attributes, (std::vector<double>{0.5, 0.25, 0.125}));
  EXPECT_EQ(g.point_markers, (std::vector<int>{2, 2, 3}));
  ASSERT_EQ(g.segments.size(), 2u);
  EXPECT_EQ(g.segments[1].a, 2u);
  EXPECT_EQ(g.segments[1].b, 0u);
}

TEST_F(TriangleIo, PolyWithNoVerticesAndNoSiblingNode) {
  const std::string p = write("lonely.poly", "0 2 0 0\n0 0\n0\n");
  expect_parse_error([&] { read_poly(p); }, p, 1, "lonely.node");
}

// ---------------------------------------------------------------------------
// .ele and .area

TEST_F(TriangleIo, EleThreeAndSixNodesWithAttributes) {
  const EleData a = read_ele(write("a.ele", "2 3 1\n1 1 2 3 0.5\n2 3 2 4 -1.5\n"), 1);
  EXPECT_EQ(a.triangles, (std::vector<VertexId>{0, 1, 2, 2, 1, 3}));
  EXPECT_EQ(a.num_attributes, 1u);
  EXPECT_EQ(a.attributes, (std::vector<double>{0.5, -1.5}));
  const EleData b = read_ele(write("b.ele", "# six-node\n1 6 0\n0 0 1 2 3 4 5\n"), 0);
  EXPECT_EQ(b.triangles, (std::vector<VertexId>{0, 1, 2}));
  EXPECT_EQ(b.num_attributes, 0u);
  const EleData c = read_ele(write("c.ele", "1\n1 1 2 3\n"), 1);  // header defaults
  EXPECT_EQ(c.triangles, (std::vector<VertexId>{0, 1, 2}));
}

TEST_F(TriangleIo, AreaFile) {
  const std::vector<double> a = read_area(write("a.area", "4\n1 0.5\n2 -1\n3 0\n4 2.5e-3\n"));
  ASSERT_EQ(a.size(), 4u);
  EXPECT_EQ(a[0], 0.5);
  EXPECT_LT(a[1], 0.0);
  EXPECT_LT(a[2], 0.0);  // 0 means no bound
  EXPECT_EQ(a[3], 2.5e-3);
}

// ---------------------------------------------------------------------------
// Errors: one test per class, each checking file, line and message.

TEST_F(TriangleIo, ErrorNonNumericToken) {
  const std::string p = write("e.node", "2 2 0 0\n1 0 0\n2 abc 1\n");
  expect_parse_error([&] { read_node(p); }, p, 3, "'abc' is not a number (expected the x coordinate of vertex 2)");
  const std::string q = write("f.node", "two 2 0 0\n");
  expect_parse_error([&] { read_node(q); }, q, 1, "'two' is not a number (expected vertex count)");
  const std::string r = write("g.node", "2 2 0 0\n1.5 0 0\n2 1 1\n");
  expect_parse_error([&] { read_node(r); }, r, 2, "'1.5' is not an integer");
  const std::string s = write("h.node", "1 2 0 0\n1 1e999 0\n");
  expect_parse_error([&] { read_node(s); }, s, 2, "'1e999' is out of range");
}

TEST_F(TriangleIo, ErrorTooFewTokens) {
  const std::string p = write("e.node", "5 2 0 0\n1 0 0\n2 1 0\n3 1 1\n4 0 1\n5 0.5\n");
  expect_parse_error([&] { read_node(p); }, p, 6, "expected 2 coordinates for vertex 5, found 1");
  const std::string q = write("f.node", "1 2 2 0\n1 0 0 7\n");
  expect_parse_error([&] { read_node(q); }, q, 2, "expected 2 attributes for vertex 1, found 1");
  const std::string r = write("g.node", "1 2 0 1\n1 0 0\n");
  expect_parse_error([&] { read_node(r); }, r, 2, "expected a boundary marker for vertex 1");
  const std::string s = write("h.poly", "2 2 0 0\n1 0 0\n2 1 0\n1 0\n1 1\n0\n");
  expect_parse_error([&] { read_poly(s); }, s, 5, "expected 2 endpoints for segment 1, found 1");
  const std::string t = write("i.poly", "2 2 0 0\n1 0 0\n2 1 0\n0 0\n0\n1\n1 0.5 0.5\n");
  expect_parse_error([&] { read_poly(t); }, t, 7, "expected a regional attribute for region 1");
  const std::string u = write("j.ele", "1 3 0\n1 1 2\n");
  expect_parse_error([&] { read_ele(u, 1); }, u, 2, "expected 3 vertices for triangle 1, found 2");
  const std::string v = write("k.area", "1\n1\n");
  expect_parse_error([&] { read_area(v); }, v, 2, "expected a maximum area for triangle 1");
}

TEST_F(TriangleIo, ErrorNegativeCount) {
  const std::string p = write("e.node", "# comment first\n-3 2 0 0\n");
  expect_parse_error([&] { read_node(p); }, p, 2, "vertex count -3 is negative");
  const std::string q = write("f.poly", "1 2 0 0\n1 0 0\n-1 0\n");
  expect_parse_error([&] { read_poly(q); }, q, 3, "segment count -1 is negative");
  const std::string r = write("g.node", "1 2 -2 0\n1 0 0\n");
  expect_parse_error([&] { read_node(r); }, r, 1, "attribute count -2 is negative");
}

TEST_F(TriangleIo, ErrorAbsurdCountThrowsQuicklyWithoutAllocating) {
  const std::string p = write("e.node", "1000000000000 2 0 0\n1 0 0\n2 1 1\n");
  const auto start = std::chrono::steady_clock::now();
  expect_parse_error([&] { read_node(p); }, p, 1,
                     "header announces 1000000000000 vertices but the file has only 2 lines left");
  const std::string q = write("f.ele", "1000000000000 3 0\n1 1 2 3\n");
  expect_parse_error([&] { read_ele(q, 1); }, q, 1,
                     "header announces 1000000000000 triangles but the file has only 1 line left");
  const std::string r = write("g.node", "2 2 1000000000000 0\n1 0 0 0\n2 1 1 1\n");
  expect_parse_error([&] { read_node(r); }, r, 1, "attribute count 1000000000000 is larger than the file");
  const std::string s = write("h.poly", "1 2 0 0\n1 0 0\n9223372036854775807 0\n");
  expect_parse_error([&] { read_poly(s); }, s, 3, "header announces 9223372036854775807 segments");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 1.0);
}

TEST_F(TriangleIo, ErrorCountLargerThanFile) {
  // Passes the cheap size bound, then the file ends.
  const std::string p = write("e.node", "5 2 0 0\n1 0 0\n2 1 0\n3 1 1\n#\n#\n#\n#\n#\n#\n#\n#\n#\n#\n#\n");
  expect_parse_error([&] { read_node(p); }, p, 1, "header announces 5 vertices but the file ends after 3");
  const std::string q = write("f.poly", "2 2 0 0\n1 0 0\n2 1 0\n1 0\n1 1 2\n");
  expect_parse_error([&] { read_poly(q); }, q, 5, "the file ends before the hole count line");
  const std::string r = write("g.poly", "2 2 0 0\n1 0 0\n2 1 0\n");
  expect_parse_error([&] { read_poly(r); }, r, 3, "the file ends before the segment count line");
  const std::string s = write("h.node", "# nothing but a comment\n");
  expect_parse_error([&] { read_node(s); }, s, 1, "the file holds no data");
}

TEST_F(TriangleIo, ErrorIndexOutOfRange) {
  std::string text = "50 2 0 0\n";
  for (int i = 1; i <= 50; ++i) text += std::to_string(i) + " " + std::to_string(i) + " " + std::to_string(i * i) + "\n";
  text += "4 0\n1 1 2\n2 2 3\n3 3 4\n4 4 99\n0\n";
  const std::string p = write("e.poly", text);
  expect_parse_error([&] { read_poly(p); }, p, 56, "segment 4 refers to vertex 99, but vertices are numbered 1..50");
  const std::string q = write("f.poly", "2 2 0 0\n0 0 0\n1 1 0\n1 0\n0 0 2\n0\n");
  expect_parse_error([&] { read_poly(q); }, q, 5, "segment 0 refers to vertex 2, but vertices are numbered 0..1");
  // A segment with one vertex at both ends is read (meshing ignores and
  // counts zero-length segments, which real files contain).
  const std::string r = write("g.poly", "2 2 0 0\n1 0 0\n2 1 0\n1 0\n1 2 2\n0\n");
  ASSERT_EQ(read_poly(r).segments.size(), 1u);
  EXPECT_EQ(read_poly(r).segments[0].a, read_poly(r).segments[0].b);
  const std::string s = write("h.ele", "1 3 0\n1 0 1 2\n");
  expect_parse_error([&] { read_ele(s, 1); }, s, 2, "triangle 1 refers to vertex 0, but vertices are numbered from 1");
  const std::string t = write("i.ele", "1 3 0\n1 4 5 4\n");
  expect_parse_error([&] { read_ele(t, 1); }, t, 2, "triangle 1 uses vertex 4 twice");
}

TEST_F(TriangleIo, ErrorNonFiniteCoordinates) {
  const std::string p = write("e.node", "2 2 0 0\n1 0 0\n2 nan 1\n");
  expect_parse_error([&] { read_node(p); }, p, 3, "the x coordinate of vertex 2 is not finite ('nan')");
  const std::string q = write("f.node", "2 2 0 0\n1 0 0\n\n2 1 -inf\n");
  expect_parse_error([&] { read_node(q); }, q, 4, "the y coordinate of vertex 2 is not finite ('-inf')");
  const std::string r = write("g.poly", "1 2 0 0\n1 0 0\n0 0\n1\n1 inf 0\n");
  expect_parse_error([&] { read_poly(r); }, r, 5, "the x coordinate of hole 1 is not finite");
  const std::string s = write("h.node", "1 2 1 0\n1 0 0 NaN\n");
  expect_parse_error([&] { read_node(s); }, s, 2, "attribute 1 of vertex 1 is not finite");
}

TEST_F(TriangleIo, ErrorDuplicateOrNonConsecutiveIds) {
  const std::string p = write("e.node", "3 2 0 0\n1 0 0\n2 1 0\n2 1 1\n");
  expect_parse_error([&] { read_node(p); }, p, 4,
                     "duplicate vertex number 2: vertices must be numbered consecutively, expected 3");
  const std::string q = write("f.node", "3 2 0 0\n1 0 0\n2 1 0\n4 1 1\n");
  expect_parse_error([&] { read_node(q); }, q, 4,
                     "vertex number 4 is out of order: vertices must be numbered consecutively, expected 3");
  const std::string r = write("g.node", "2 2 0 0\n5 0 0\n6 1 0\n");
  expect_parse_error([&] { read_node(r); }, r, 2, "the first vertex is numbered 5, but vertices must be numbered from 0 or 1");
  const std::string s = write("h.poly", "2 2 0 0\n1 0 0\n2 1 0\n2 0\n1 1 2\n1 2 1\n0\n");
  expect_parse_error([&] { read_poly(s); }, s, 6, "duplicate segment number 1");
}

TEST_F(TriangleIo, ErrorHeaderValues) {
  const std::string p = write("e.node", "1 3 0 0\n1 0 0 0\n");
  expect_parse_error([&] { read_node(p); }, p, 1, "dimension is 3, but only 2 is supported");
  const std::string q = write("f.node", "1 2 0 2\n1 0 0 0\n");
  expect_parse_error([&] { read_node(q); }, q, 1, "boundary marker count 2 must be 0 or 1");
  const std::string r = write("g.ele", "1 4 0\n1 1 2 3 4\n");
  expect_parse_error([&] { read_ele(r, 1); }, r, 1, "nodes per triangle is 4, but only 3 or 6 are supported");
}

TEST_F(TriangleIo, ErrorTrailingData) {
  const std::string p = write("e.node", "2 2 0 0\n1 0 0\n2 1 0\n3 1 1\n");
  expect_parse_error([&] { read_node(p); }, p, 4, "unexpected data after the 2 vertices announced on line 1");
  const std::string q = write("f.poly", "1 2 0 0\n1 0 0\n0 0\n0\n0\nextra\n");
  expect_parse_error([&] { read_poly(q); }, q, 6, "unexpected data after the 0 regions announced on line 5");
}

TEST_F(TriangleIo, MissingInputFileIsIoError) {
  EXPECT_THROW(read_node(path("nope.node")), IoError);
  EXPECT_THROW(read_ele(path("nope.ele"), 1), IoError);
  EXPECT_THROW(read_node(dir_.string()), IoError);  // a directory
}

// ---------------------------------------------------------------------------
// Writers

TEST_F(TriangleIo, NodeRoundTripWithAttributesAndMarkers) {
  Mesh m = grid_mesh(3, 2);
  deltamesh::detail::MeshEditor(m).points()[4] = {0.1, 1.0 / 3.0};  // shortest round-trip formatting must be exact
  deltamesh::detail::MeshEditor(m).points()[5] = {-1e-300, 12345678.90123};
  m.set_num_vertex_attributes(2);
  for (std::size_t v = 0; v < m.num_vertices(); ++v) {
    m.vertex_attributes().push_back(static_cast<double>(v) / 7.0);
    m.vertex_attributes().push_back(-static_cast<double>(v));
    m.vertex_markers().push_back(static_cast<int>(v % 3) - 1);
  }
  for (const int first : {0, 1}) {
    TriangleWriteOptions opt;
    opt.first_index = first;
    const std::string p = path("out" + std::to_string(first) + ".node");
    write_node(m, p, opt);
    const Pslg g = read_node(p);
    EXPECT_EQ(g.first_index, first);
    ASSERT_EQ(g.points.size(), m.num_vertices());
    for (VertexId v = 0; v < m.num_vertices(); ++v) EXPECT_EQ(g.points[v], m.point(v)) << v;
    EXPECT_EQ(g.num_point_attributes, 2u);
    EXPECT_EQ(g.point_attributes, m.vertex_attributes());
    EXPECT_EQ(g.point_markers, m.vertex_markers());
  }
  const std::vector<std::string> expected_files{"out0.node", "out1.node"};
  EXPECT_EQ(listing(), expected_files);  // no temporary files left
}

TEST_F(TriangleIo, NodeDefaultMarkersAndOptions) {
  const Mesh m = grid_mesh(2, 2);  // vertex 4 (the centre) is the only interior one
  const std::string p = path("m.node");
  write_node(m, p);
  const std::vector<std::string> lines = [&] {
    std::vector<std::string> v;
    std::istringstream in(slurp(p));
    for (std::string l; std::getline(in, l);) v.push_back(l);
    return v;
  }();
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(lines[0], "9 2 0 1");  // header first, no comment before it
  const Pslg g = read_node(p);
  ASSERT_EQ(g.point_markers.size(), 9u);
  for (VertexId v = 0; v < 9; ++v) EXPECT_EQ(g.point_markers[v], v == 4 ? 0 : 1) << v;

  TriangleWriteOptions opt;
  opt.write_markers = false;
  write_node(m, p, opt);
  EXPECT_EQ(slurp(p).substr(0, 8), "9 2 0 0\n");
  EXPECT_TRUE(read_node(p).point_markers.empty());
}

TEST_F(TriangleIo, EleRoundTripWithTriangleAttributes) {
  Mesh m = grid_mesh(3, 3);
  m.set_num_triangle_attributes(1);
  for (TriId t = 0; t < m.num_triangle_slots(); ++t) m.triangle_attributes().push_back(t * 0.5);
  for (const int first : {0, 1}) {
    TriangleWriteOptions opt;
    opt.first_index = first;
    const std::string p = path("m.ele");
    write_ele(m, p, opt);
    const EleData d = read_ele(p, first);
    ASSERT_EQ(d.triangles.size(), 3 * m.num_triangles());
    for (TriId t = 0; t < m.num_triangles(); ++t) {
      const auto tri = m.triangle(t);
      for (int k = 0; k < 3; ++k) EXPECT_EQ(d.triangles[3 * t + k], tri[k]);
    }
    EXPECT_EQ(d.num_attributes, 1u);
    EXPECT_EQ(d.attributes, m.triangle_attributes());
  }
}

TEST_F(TriangleIo, WritersSkipDeadTriangleSlots) {
  Mesh m = grid_mesh(2, 1);  // 4 triangles
  m.remove_triangle(1);      // leaves a dead slot (mesh no longer compact)
  const std::string e = path("m.ele"), n = path("m.neigh");
  write_ele(m, e);
  write_neigh(m, n);
  const EleData d = read_ele(e, 0);
  ASSERT_EQ(d.triangles.size(), 9u);
  const auto lines = data_lines(n);
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0], (std::vector<std::string>{"3", "3"}));
  // Ids are consecutive and no neighbour refers to the dead slot.
  for (std::size_t i = 1; i < lines.size(); ++i) {
    EXPECT_EQ(lines[i][0], std::to_string(i - 1));
    for (int k = 1; k <= 3; ++k) EXPECT_LT(std::stoi(lines[i][k]), 3);
  }
}

TEST_F(TriangleIo, EdgeFileEveryEdgeOnceWithMarkers) {
  Mesh m = grid_mesh(3, 2);
  constrain(m, 1, 5);  // an interior edge made a segment
  const std::string p = path("m.edge");
  TriangleWriteOptions opt;
  opt.first_index = 1;
  write_edge(m, p, opt);
  const auto lines = data_lines(p);
  const std::size_t v = m.num_vertices(), t = m.num_triangles();
  const std::size_t e = v + t - 1;  // Euler: V - E + F = 1 for a disc
  ASSERT_EQ(lines.size(), e + 1);
  EXPECT_EQ(lines[0], (std::vector<std::string>{std::to_string(e), "1"}));
  std::set<std::pair<int, int>> seen;
  int boundary = 0;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    ASSERT_EQ(lines[i].size(), 4u);
    EXPECT_EQ(lines[i][0], std::to_string(i));
    int a = std::stoi(lines[i][1]) - 1, b = std::stoi(lines[i][2]) - 1;
    if (a > b) std::swap(a, b);
    EXPECT_TRUE(seen.insert({a, b}).second) << "edge " << a << "-" << b << " written twice";
    const Point pa = m.point(a), pb = m.point(b);
    const bool on_hull = (pa.x == pb.x && (pa.x == 0 || pa.x == 3)) || (pa.y == pb.y && (pa.y == 0 || pa.y == 2));
    const bool is_seg = a == 1 && b == 5;
    // Triangle's rule: an interior segment with marker 0 is written as 0.
    EXPECT_EQ(lines[i][3], on_hull ? "1" : "0") << a << "-" << b << (is_seg ? " (segment)" : "");
    boundary += on_hull;
  }
  EXPECT_EQ(boundary, 10);
}

TEST_F(TriangleIo, EdgeAndPolyWriteSegmentMarkers) {
  Mesh m = grid_mesh(2, 2);  // vertex (i, j) is 3j + i
  const auto edge = [&](VertexId a, VertexId b) {
    const HalfEdgeId e = m.find_edge(a, b);
    return e != kNone ? e : m.find_edge(b, a);
  };
  m.constrain_edge(edge(0, 4), 7);  // interior segment with a marker
  m.constrain_edge(edge(4, 8), 0);  // interior segment without one
  m.constrain_edge(edge(0, 1), 5);  // boundary segment with a marker
  const std::string p = path("m.edge");
  write_edge(m, p);
  std::map<std::pair<int, int>, std::string> marker;
  const auto lines = data_lines(p);
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const int a = std::stoi(lines[i][1]), b = std::stoi(lines[i][2]);
    marker[{std::min(a, b), std::max(a, b)}] = lines[i][3];
  }
  EXPECT_EQ(marker.size(), 16u);
  EXPECT_EQ((marker[{0, 4}]), "7");
  EXPECT_EQ((marker[{4, 8}]), "0");  // interior segment with marker 0 (Triangle's rule)
  EXPECT_EQ((marker[{0, 1}]), "5");
  EXPECT_EQ((marker[{1, 2}]), "1");  // boundary, not a segment
  EXPECT_EQ((marker[{1, 4}]), "0");  // interior, not a segment

  write_node(m, path("m.node"));
  write_poly(m, path("m.poly"));
  const Pslg g = read_poly(path("m.poly"));
  std::map<std::pair<VertexId, VertexId>, int> seg;
  for (const Segment& s : g.segments) seg[{std::min(s.a, s.b), std::max(s.a, s.b)}] = s.marker;
  const std::map<std::pair<VertexId, VertexId>, int> expected{{{0, 4}, 7}, {{4, 8}, 0}, {{0, 1}, 5}};
  EXPECT_EQ(seg, expected);
}

// The writers format integers themselves (not with std::to_chars): the
// extremes of a marker, negative ones and every digit count read back as
// std::to_string spells them, in .poly (unchecked per-field path) and .edge.
TEST_F(TriangleIo, IntegerFieldsAreWrittenAsToStringSpellsThem) {
  Mesh m = grid_mesh(2, 2);  // vertex (i, j) is 3j + i
  const auto edge = [&](VertexId a, VertexId b) {
    const HalfEdgeId e = m.find_edge(a, b);
    return e != kNone ? e : m.find_edge(b, a);
  };
  const std::map<std::pair<int, int>, int> markers{{{0, 4}, std::numeric_limits<int>::min()},
                                                   {{4, 8}, std::numeric_limits<int>::max()},
                                                   {{0, 1}, -42},
                                                   {{1, 2}, 9},
                                                   {{3, 4}, 10},
                                                   {{4, 5}, 99},
                                                   {{6, 7}, 100},
                                                   {{7, 8}, -1000000007}};
  for (const auto& [ab, marker] : markers) m.constrain_edge(edge(ab.first, ab.second), marker);
  TriangleWriteOptions opt;
  opt.first_index = 1;
  for (const char* name : {"m.poly", "m.edge"}) {
    const std::string p = path(name);
    if (name[2] == 'p') write_poly(m, p, opt);
    else write_edge(m, p, opt);
    auto lines = data_lines(p);
    if (name[2] == 'p') lines.erase(lines.begin());  // the empty vertex section's header
    std::size_t found = 0;
    for (std::size_t i = 1; i < lines.size() && lines[i].size() == 4; ++i) {
      EXPECT_EQ(lines[i][0], std::to_string(i)) << name;
      const int a = std::stoi(lines[i][1]) - 1, b = std::stoi(lines[i][2]) - 1;
      const auto it = markers.find({std::min(a, b), std::max(a, b)});
      if (it == markers.end()) continue;
      EXPECT_EQ(lines[i][3], std::to_string(it->second)) << name << " " << a << "-" << b;
      ++found;
    }
    EXPECT_EQ(found, markers.size()) << name;
  }
}

TEST_F(TriangleIo, NeighFileOppositeVertices) {
  const Mesh m = grid_mesh(3, 3);
  const std::string p = path("m.neigh");
  write_neigh(m, p);
  const auto lines = data_lines(p);
  ASSERT_EQ(lines.size(), m.num_triangles() + 1);
  EXPECT_EQ(lines[0], (std::vector<std::string>{std::to_string(m.num_triangles()), "3"}));
  int none = 0;
  for (TriId t = 0; t < m.num_triangles(); ++t) {
    const auto& l = lines[t + 1];
    ASSERT_EQ(l.size(), 4u);
    const auto tri = m.triangle(t);
    for (int i = 0; i < 3; ++i) {
      const int n = std::stoi(l[1 + i]);
      if (n == -1) {
        ++none;
        continue;
      }
      // Neighbour i shares the edge opposite vertex i and not vertex i.
      const auto nt = m.triangle(static_cast<TriId>(n));
      const auto has = [&](VertexId v) { return nt[0] == v || nt[1] == v || nt[2] == v; };
      EXPECT_FALSE(has(tri[i]));
      EXPECT_TRUE(has(tri[(i + 1) % 3]) && has(tri[(i + 2) % 3]));
    }
  }
  EXPECT_EQ(none, 12);  // boundary edges of a 3x3 grid
}

TEST_F(TriangleIo, PolyWriterRoundTripThroughSiblingNode) {
  Mesh m = grid_mesh(2, 2);
  const std::string node = path("m.node"), poly = path("m.poly");
  write_node(m, node);
  write_poly(m, poly);  // no constrained edges: the boundary
  Pslg g = read_poly(poly);
  EXPECT_EQ(g.points.size(), 9u);
  EXPECT_EQ(g.segments.size(), 8u);
  for (const Segment& s : g.segments) {
    EXPECT_EQ(s.marker, 1);
    const Point a = g.points[s.a], b = g.points[s.b];
    EXPECT_TRUE((a.x == b.x && (a.x == 0 || a.x == 2)) || (a.y == b.y && (a.y == 0 || a.y == 2)));
  }
  constrain(m, 0, 4);
  constrain(m, 4, 8);
  write_poly(m, poly);
  g = read_poly(poly);
  ASSERT_EQ(g.segments.size(), 2u);
  std::set<std::pair<VertexId, VertexId>> segs;
  for (const Segment& s : g.segments) segs.insert({std::min(s.a, s.b), std::max(s.a, s.b)});
  EXPECT_EQ(segs, (std::set<std::pair<VertexId, VertexId>>{{0, 4}, {4, 8}}));
}

TEST_F(TriangleIo, EmptyMeshWritesReadableFiles) {
  const Mesh m;
  write_node(m, path("z.node"));
  write_ele(m, path("z.ele"));
  write_poly(m, path("z.poly"));
  EXPECT_TRUE(read_node(path("z.node")).points.empty());
  EXPECT_TRUE(read_ele(path("z.ele"), 0).triangles.empty());
  EXPECT_TRUE(read_poly(path("z.poly")).segments.empty());
}

// ---------------------------------------------------------------------------
// Atomic writing

TEST_F(TriangleIo, AtomicFileCommitsCompleteFile) {
  const std::string p = path("big.txt");
  std::string expected;
  {
    io::AtomicFile f(p);
    for (int i = 0; i < 1000; ++i) {
      const std::string chunk = std::string(997, static_cast<char>('a' + i % 26)) + "\n";
      f.write(chunk);
      expected += chunk;
    }
    EXPECT_FALSE(fs::exists(p));  // nothing at the target until commit
    EXPECT_TRUE(fs::exists(f.temp_path()));
    f.commit();
  }
  EXPECT_EQ(slurp(p), expected);
  EXPECT_EQ(listing(), std::vector<std::string>{"big.txt"});
  // Replacing an existing file.
  {
    io::AtomicFile f(p);
    f.write("new\n");
    f.commit();
  }
  EXPECT_EQ(slurp(p), "new\n");
}

TEST_F(TriangleIo, AtomicFileWithoutCommitLeavesNothing) {
  const std::string p = path("x.txt");
  {
    io::AtomicFile f(p);
    f.write("partial");
  }
  EXPECT_TRUE(listing().empty());
  // An existing file survives an aborted rewrite untouched.
  write("y.txt", "old");
  {
    io::AtomicFile f(path("y.txt"));
    f.write("partial");
  }
  EXPECT_EQ(slurp(path("y.txt")), "old");
  EXPECT_EQ(listing(), std::vector<std::string>{"y.txt"});
}

TEST_F(TriangleIo, AtomicFileMissingDirectoryIsIoError) {
  const std::string p = path("no/such/dir/m.node");
  try {
    io::AtomicFile f(p);
    ADD_FAILURE() << "no IoError";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("No such file or directory"), std::string::npos) << e.what();
  }
  EXPECT_THROW(write_node(grid_mesh(1, 1), p), IoError);
  EXPECT_THROW(write_ele(grid_mesh(1, 1), p), IoError);
  EXPECT_FALSE(fs::exists(path("no")));
  EXPECT_TRUE(listing().empty());
}

TEST_F(TriangleIo, AtomicFileWriteErrorIsIoErrorAndLeavesNothing) {
  // A file size limit makes the writes fail (EFBIG) part way through, as a
  // full disk would; the signal it raises is ignored for the test.
  const std::string p = path("full.node");
  rlimit old{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
  const rlimit small{4096, old.rlim_max};
  auto* old_handler = std::signal(SIGXFSZ, SIG_IGN);
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  std::string message;
  try {
    write_node(grid_mesh(40, 40), p);
  } catch (const IoError& e) {
    message = e.what();
  }
  ::setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, old_handler);
  EXPECT_NE(message.find(p), std::string::npos) << message;
  EXPECT_NE(message.find("File too large"), std::string::npos) << message;
  EXPECT_TRUE(listing().empty());  // neither the target nor the temporary name
}

TEST_F(TriangleIo, AtomicFileNeverWritesThroughAnExistingTemporaryName) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  // Someone else's file (here a link to /dev/full) at the first temporary
  // name is left alone: the writer takes the next name and succeeds.
  const std::string p = path("taken.node");
  const std::string first = p + ".tmp." + std::to_string(::getpid()) + ".0";
  fs::create_symlink("/dev/full", first);
  write_node(grid_mesh(40, 40), p);
  EXPECT_EQ(read_node(p).points.size(), 41u * 41u);
  EXPECT_TRUE(fs::is_symlink(first));
  EXPECT_EQ(listing(), (std::vector<std::string>{"taken.node", fs::path(first).filename().string()}));
}

// ---------------------------------------------------------------------------
// Robustness: corrupted files give a ParseError (or parse), never a crash.

TEST_F(TriangleIo, CorruptedFilesOnlyThrowParseError) {
  const std::string good =
      "# square with a hole\n4 2 1 1\n1 0 0 0.5 1\n2 4 0 0.5 1\n3 4 4 0.5 1\n4 0 4 0.5 1\n"
      "4 1\n1 1 2 1\n2 2 3 1\n3 3 4 1\n4 4 1 1\n1\n1 2 2\n2\n1 1 1 3 0.5\n2 3 3 4\n";
  const std::string alphabet = "0123456789-+.e# \n\r\tx,naif";
  std::mt19937 rng(12345);
  const std::string p = path("fuzz.poly");
  int parsed = 0, rejected = 0;
  for (int round = 0; round < 3000; ++round) {
    std::string text = good;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int k = 0; k < edits; ++k) {
      const std::size_t at = rng() % text.size();
      switch (rng() % 3) {
        case 0: text[at] = alphabet[rng() % alphabet.size()]; break;
        case 1: text.erase(at, 1 + rng() % 3); break;
        default: text.insert(at, 1, alphabet[rng() % alphabet.size()]); break;
      }
      if (text.empty()) text = "x";
    }
    write("fuzz.poly", text);
    try {
      const Pslg g = read_poly(p);
      for (const Segment& s : g.segments) {
        ASSERT_LT(s.a, g.points.size());
        ASSERT_LT(s.b, g.points.size());
      }
      for (const Point& q : g.points) ASSERT_TRUE(std::isfinite(q.x) && std::isfinite(q.y));
      ++parsed;
    } catch (const ParseError& e) {
      ASSERT_EQ(e.file(), p);
      ASSERT_GE(e.line(), 1u);
      ASSERT_FALSE(e.problem().empty());
      ++rejected;
    }
  }
  EXPECT_GT(parsed, 0);
  EXPECT_GT(rejected, 0);
}
