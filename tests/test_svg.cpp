// SVG output: well-formed XML, one closed subpath per triangle, y axis up,
// quality shading, constrained edges, vertices, legend, size.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "deltamesh/errors.hpp"
#include "deltamesh/mesh.hpp"
#include "support/grid_mesh.hpp"
#include "deltamesh/svg.hpp"

using namespace deltamesh;
namespace fs = std::filesystem;
using deltamesh::test::grid_mesh;

namespace {

class Svg : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("deltamesh_svg_" + std::to_string(::getpid()) + "_" + info->test_suite_name() + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  static std::string slurp(const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
  fs::path dir_;
};

// A small well-formedness checker: one root element, balanced and properly
// nested tags, quoted attributes, entities only where '&' appears. Returns
// an empty string or the first problem.
std::string xml_problem(const std::string& s) {
  std::vector<std::string> stack;
  int roots = 0;
  std::size_t i = 0;
  const auto entity_ok = [&](std::size_t at) {
    static const std::regex ent("^&(amp|lt|gt|quot|apos|#[0-9]+|#x[0-9a-fA-F]+);");
    return std::regex_search(s.begin() + static_cast<long>(at),
                             s.begin() + static_cast<long>(std::min(s.size(), at + 12)), ent);
  };
  while (i < s.size()) {
    if (s[i] != '<') {
      if (s[i] == '&' && !entity_ok(i)) return "bad entity at " + std::to_string(i);
      if (stack.empty() && !std::isspace(static_cast<unsigned char>(s[i]))) return "text outside the root";
      ++i;
      continue;
    }
    if (s.compare(i, 5, "<?xml") == 0) {
      if (i != 0) return "XML declaration not at the start";
      const std::size_t e = s.find("?>", i);
      if (e == std::string::npos) return "unterminated declaration";
      i = e + 2;
      continue;
    }
    if (s.compare(i, 4, "<!--") == 0) {
      const std::size_t e = s.find("-->", i);
      if (e == std::string::npos) return "unterminated comment";
      i = e + 3;
      continue;
    }
    const bool closing = i + 1 < s.size() && s[i + 1] == '/';
    std::size_t j = i + (closing ? 2 : 1);
    const std::size_t name_start = j;
    while (j < s.size() && (std::isalnum(static_cast<unsigned char>(s[j])) || s[j] == '-' || s[j] == ':')) ++j;
    const std::string name = s.substr(name_start, j - name_start);
    if (name.empty()) return "bad tag at " + std::to_string(i);
    // Attributes.
    for (;;) {
      while (j < s.size() && std::isspace(static_cast<unsigned char>(s[j]))) ++j;
      if (j >= s.size()) return "unterminated tag " + name;
      if (s[j] == '>' || (s[j] == '/' && j + 1 < s.size() && s[j + 1] == '>')) break;
      if (closing) return "attributes in a closing tag";
      const std::size_t a = j;
      while (j < s.size() && (std::isalnum(static_cast<unsigned char>(s[j])) || s[j] == '-' || s[j] == ':')) ++j;
      if (j == a || j >= s.size() || s[j] != '=') return "bad attribute in " + name;
      ++j;
      if (j >= s.size() || (s[j] != '"' && s[j] != '\'')) return "unquoted attribute in " + name;
      const char q = s[j++];
      while (j < s.size() && s[j] != q) {
        if (s[j] == '<') return "'<' in an attribute of " + name;
        if (s[j] == '&' && !entity_ok(j)) return "bad entity in an attribute of " + name;
        ++j;
      }
      if (j >= s.size()) return "unterminated attribute in " + name;
      ++j;
    }
    const bool self_closing = s[j] == '/';
    i = j + (self_closing ? 2 : 1);
    if (closing) {
      if (stack.empty() || stack.back() != name) return "mismatched </" + name + ">";
      stack.pop_back();
    } else {
      if (stack.empty() && ++roots > 1) return "more than one root element";
      if (!self_closing) stack.push_back(name);
    }
  }
  if (!stack.empty()) return "unclosed <" + stack.back() + ">";
  if (roots != 1) return "no root element";
  return "";
}

// The d attributes of <path> elements whose class is `cls` (plain string
// search: std::regex overflows its stack on megabyte-long attributes).
std::vector<std::string> path_data(const std::string& svg, const std::string& cls) {
  std::vector<std::string> out;
  const std::string open = "<path class=\"" + cls + "\"";
  for (std::size_t p = svg.find(open); p != std::string::npos; p = svg.find(open, p + 1)) {
    const std::size_t end = svg.find('>', p);
    const std::size_t d = svg.find(" d=\"", p);
    if (end == std::string::npos || d == std::string::npos || d > end) continue;
    const std::size_t q = svg.find('"', d + 4);
    out.push_back(svg.substr(d + 4, q - (d + 4)));
  }
  return out;
}

// Longest run of digits after a '.' anywhere in s.
std::size_t max_decimals(const std::string& s) {
  std::size_t best = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '.') continue;
    std::size_t j = i + 1;
    while (j < s.size() && std::isdigit(static_cast<unsigned char>(s[j]))) ++j;
    best = std::max(best, j - i - 1);
  }
  return best;
}

std::size_t count_char(const std::string& s, char c) { return static_cast<std::size_t>(std::count(s.begin(), s.end(), c)); }

std::size_t count_substr(const std::string& s, const std::string& sub) {
  std::size_t n = 0;
  for (std::size_t p = s.find(sub); p != std::string::npos; p = s.find(sub, p + sub.size())) ++n;
  return n;
}

bool have_xmllint() { return std::system("command -v xmllint >/dev/null 2>&1") == 0; }

}  // namespace

TEST_F(Svg, WellFormedWithOneSubpathPerTriangle) {
  Mesh m = grid_mesh(10, 6);
  // Constrain the bottom row of edges and one interior diagonal.
  for (HalfEdgeId e = 0; e < 3 * m.num_triangle_slots(); ++e) {
    const Point a = m.point(m.origin(e)), b = m.point(m.dest(e));
    if ((a.y == 0 && b.y == 0) || (a.x == 2 && a.y == 2 && b.x == 3 && b.y == 3) ||
        (b.x == 2 && b.y == 2 && a.x == 3 && a.y == 3))
      m.set_edge_flags(e, kConstrained);
  }
  const std::string p = path("m.svg");
  SvgOptions opt;
  opt.title = "grid";
  write_svg(m, p, opt);
  const std::string svg = slurp(p);
  EXPECT_EQ(xml_problem(svg), "");
  EXPECT_NE(svg.find("<title>grid</title>"), std::string::npos);
  EXPECT_NE(svg.find("xmlns=\"http://www.w3.org/2000/svg\""), std::string::npos);
  std::size_t subpaths = 0;
  for (const std::string& d : path_data(svg, "tri")) subpaths += count_char(d, 'z');
  EXPECT_EQ(subpaths, m.num_triangles());
  const auto seg = path_data(svg, "segments");
  ASSERT_EQ(seg.size(), 1u);
  EXPECT_EQ(count_char(seg[0], 'l'), 11u);  // 10 bottom edges + 1 diagonal
  EXPECT_NE(svg.find("77 vertices, 120 triangles, 11 segment edges, min angle 45.00&#176;"), std::string::npos);
  // Limited precision: no coordinate with more than 3 decimals.
  EXPECT_LE(max_decimals(svg), 3u);
  EXPECT_EQ(fs::directory_iterator(dir_)->path().filename(), "m.svg");  // no temporary left
}

TEST_F(Svg, XmllintAcceptsIt) {
  if (!have_xmllint()) GTEST_SKIP() << "xmllint not installed (Debian: libxml2-utils)";
  Mesh m = grid_mesh(5, 5);
  const std::string p = path("m.svg");
  SvgOptions opt;
  opt.title = "quotes \" & <angles> 'too'";
  opt.draw_vertices = true;
  write_svg(m, p, opt);
  EXPECT_EQ(std::system(("xmllint --noout '" + p + "'").c_str()), 0);
  write_svg(Mesh(), p);
  EXPECT_EQ(std::system(("xmllint --noout '" + p + "'").c_str()), 0);
}

TEST_F(Svg, YAxisPointsUp) {
  Mesh m;
  m.add_vertex({0, 0});
  m.add_vertex({1, 0});
  m.add_vertex({0, 1});
  m.add_triangle(0, 1, 2);
  m.compact();
  const std::string p = path("t.svg");
  SvgOptions opt;
  opt.shade_by_quality = false;
  write_svg(m, p, opt);
  const auto d = path_data(slurp(p), "tri");
  ASSERT_EQ(d.size(), 1u);
  // "M ax ay l dx1 dy1 dx2 dy2 z": vertex 1 is level with vertex 0, vertex 2 above it.
  const std::regex num("-?[0-9]*\\.?[0-9]+");
  std::vector<double> v;
  for (auto it = std::sregex_iterator(d[0].begin(), d[0].end(), num); it != std::sregex_iterator(); ++it)
    v.push_back(std::stod(it->str()));
  ASSERT_EQ(v.size(), 6u) << d[0];
  EXPECT_GT(v[2], 0.0);       // to the right
  EXPECT_EQ(v[3], 0.0);       // same height
  EXPECT_LT(v[5], 0.0);       // up the page: smaller SVG y
  EXPECT_NEAR(v[2], -v[5], 0.02);  // aspect ratio kept
}

TEST_F(Svg, ShadesByQuality) {
  Mesh m;
  m.add_vertex({0, 0});
  m.add_vertex({10, 0});
  m.add_vertex({5, 0.1});  // a sliver: smallest angle about 1.1 degrees
  m.add_vertex({0, 2});
  m.add_vertex({2, 2});
  m.add_vertex({1, 2 + std::sqrt(3.0)});  // equilateral
  m.add_triangle(0, 1, 2);
  m.add_triangle(3, 4, 5);
  m.compact();
  const std::string p = path("q.svg");
  write_svg(m, p);
  std::string svg = slurp(p);
  EXPECT_EQ(xml_problem(svg), "");
  EXPECT_EQ(path_data(svg, "tri").size(), 2u);
  EXPECT_NE(svg.find("min angle 1.15&#176;"), std::string::npos) << svg;
  EXPECT_NE(svg.find("&lt;10&#176;: 1<"), std::string::npos);
  EXPECT_NE(svg.find("&#8805;50&#176;: 1<"), std::string::npos);

  SvgOptions plain;
  plain.shade_by_quality = false;
  write_svg(m, p, plain);
  svg = slurp(p);
  EXPECT_EQ(xml_problem(svg), "");
  const auto d = path_data(svg, "tri");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(count_char(d[0], 'z'), 2u);
}

TEST_F(Svg, DrawsVerticesAndEscapesTitle) {
  Mesh m = grid_mesh(3, 2);
  m.add_vertex({100, 100});  // in no triangle: not drawn
  const std::string p = path("v.svg");
  SvgOptions opt;
  opt.draw_vertices = true;
  opt.title = "a<b & \"c\"";
  write_svg(m, p, opt);
  const std::string svg = slurp(p);
  EXPECT_EQ(xml_problem(svg), "");
  EXPECT_EQ(count_substr(svg, "<circle "), 12u);
  EXPECT_NE(svg.find("<title>a&lt;b &amp; &quot;c&quot;</title>"), std::string::npos);
}

TEST_F(Svg, HundredThousandTrianglesStaySmall) {
  const Mesh m = grid_mesh(224, 224, 0.01);  // 100352 triangles
  const std::string p = path("big.svg");
  write_svg(m, p);
  const std::string svg = slurp(p);
  EXPECT_EQ(xml_problem(svg), "");
  std::size_t subpaths = 0;
  const auto d = path_data(svg, "tri");
  EXPECT_LE(d.size(), 8u);
  for (const std::string& s : d) subpaths += count_char(s, 'z');
  EXPECT_EQ(subpaths, 100352u);
  EXPECT_LT(svg.size(), 4u << 20) << "bytes: " << svg.size();
  EXPECT_LE(max_decimals(svg), 3u);
}

TEST_F(Svg, EmptyMeshAndMissingDirectory) {
  const std::string p = path("e.svg");
  write_svg(Mesh(), p);
  const std::string svg = slurp(p);
  EXPECT_EQ(xml_problem(svg), "");
  EXPECT_NE(svg.find("0 vertices, 0 triangles"), std::string::npos);
  EXPECT_THROW(write_svg(grid_mesh(2, 2), path("missing/dir/x.svg")), IoError);
  EXPECT_FALSE(fs::exists(path("missing")));
}

TEST(SvgChecker, RejectsMalformedXml) {
  EXPECT_EQ(xml_problem("<svg><g></g></svg>"), "");
  EXPECT_NE(xml_problem("<svg><g></svg>"), "");
  EXPECT_NE(xml_problem("<svg a=b></svg>"), "");
  EXPECT_NE(xml_problem("<svg>a & b</svg>"), "");
  EXPECT_NE(xml_problem("<svg/><svg/>"), "");
}
