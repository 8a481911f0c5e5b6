// Exchange formats (.msh 4.1/2.2, .vtu, .vtk, .geojson, .off, writing by
// extension), each file opened by a real reader from Debian, not ours:
// gmsh, python3-meshio, python3's json and xml modules, rsvg-convert. A
// real-reader test is skipped (GTEST_SKIP) only when its tool is missing;
// scripts/install-deps.sh installs them.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "deltamesh/delaunay.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/formats.hpp"
#include "deltamesh/mesh.hpp"
#include "deltamesh/svg.hpp"
#include "deltamesh/validate.hpp"
#include "deltamesh/voronoi.hpp"

using namespace deltamesh;
namespace fs = std::filesystem;

namespace {

struct Result {
  int status = -1;
  std::string out;
};

// Runs a shell command, stdout and stderr together.
Result run(const std::string& cmd) {
  Result r;
  FILE* p = ::popen((cmd + " 2>&1").c_str(), "r");
  if (!p) return r;
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
  const int st = ::pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

// Debian's python3 (python3-meshio installs into its dist-packages), not
// whatever `python3` a developer's PATH finds first.
const char* kPython = "/usr/bin/python3";

bool have_gmsh() {
  static const bool yes = run("command -v gmsh").status == 0;
  return yes;
}
bool have_python() {
  static const bool yes = fs::exists(kPython);
  return yes;
}
bool have_meshio() {
  static const bool yes = have_python() && run(std::string(kPython) + " -c 'import meshio'").status == 0;
  return yes;
}
bool have_rsvg() {
  static const bool yes = run("command -v rsvg-convert").status == 0;
  return yes;
}

#define REQUIRE_TOOL(ok, name)                                                                          \
  if (!(ok))                                                                                            \
  GTEST_SKIP() << name << " is not installed (scripts/install-deps.sh core installs it); real-reader " \
                          "check skipped"

std::string quote(const std::string& s) { return "'" + s + "'"; }

// Points on the border of the unit square (so the hull is the square) and
// random points inside; triangle attribute 0 is 1 left of x = 0.5 and 2
// right of it, except a band near y = 0 with -3 (a non-positive region);
// the bottom side is marked 5, the other hull edges keep the default.
Mesh sample_mesh(int interior = 150, unsigned seed = 7) {
  std::vector<Point> pts;
  const int side = 6;
  for (int i = 0; i < side; ++i) {
    const double t = static_cast<double>(i) / side;
    pts.push_back({t, 0.0});
    pts.push_back({1.0, t});
    pts.push_back({1.0 - t, 1.0});
    pts.push_back({0.0, 1.0 - t});
  }
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.02, 0.98);
  for (int i = 0; i < interior; ++i) pts.push_back({u(rng), u(rng)});
  Mesh m = delaunay(pts);
  m.set_num_triangle_attributes(1);
  auto& attr = m.triangle_attributes();
  attr.assign(m.num_triangle_slots(), 0.0);
  for (TriId t = 0; t < m.num_triangle_slots(); ++t) {
    if (!m.is_real(t)) continue;
    const auto v = m.triangle(t);
    const double cx = (m.point(v[0]).x + m.point(v[1]).x + m.point(v[2]).x) / 3.0;
    const double cy = (m.point(v[0]).y + m.point(v[1]).y + m.point(v[2]).y) / 3.0;
    attr[t] = cy < 0.15 ? -3.0 : (cx < 0.5 ? 1.0 : 2.0);
  }
  for (HalfEdgeId e = 0; e < m.triangle_vertices().size(); ++e) {
    if (m.twin(e) != kNone) continue;
    if (m.point(m.origin(e)).y == 0.0 && m.point(m.dest(e)).y == 0.0) m.constrain_edge(e, 5);
  }
  return m;
}

struct Expect {
  std::size_t points, triangles, lines;
  std::map<long long, std::size_t> per_region;  // rounded attribute -> triangles
  std::map<int, std::size_t> per_marker;        // boundary marker -> lines
};

Expect expected(const Mesh& m) {
  Expect x{m.num_vertices(), m.num_triangles(), 0, {}, {}};
  for (TriId t = 0; t < m.num_triangle_slots(); ++t) {
    if (!m.is_real(t)) continue;
    const double a = m.num_triangle_attributes() ? m.triangle_attributes()[t] : 0.0;
    ++x.per_region[std::llround(a)];
    for (HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e)
      if (m.twin(e) == kNone) {
        ++x.lines;
        ++x.per_marker[m.edge_marker(e) != 0 ? m.edge_marker(e) : 1];
      }
  }
  return x;
}

// meshio's view of a file: "points N", "cells TYPE N" (summed over blocks),
// "cell_data NAME", "point_data NAME", "field NAME TAG DIM".
const char* kMeshioScript = R"PY(
import sys, collections, meshio
m = meshio.read(sys.argv[1])
print("points", len(m.points))
counts = collections.OrderedDict()
for c in m.cells:
    counts[c.type] = counts.get(c.type, 0) + len(c.data)
for k, v in counts.items():
    print("cells", k, v)
for k in m.cell_data:
    print("cell_data", k)
for k in m.point_data:
    print("point_data", k)
for k, v in m.field_data.items():
    print("field", k, int(v[0]), int(v[1]))
if "gmsh:physical" in m.cell_data:
    tally = collections.Counter()
    for c, tags in zip(m.cells, m.cell_data["gmsh:physical"]):
        for t in tags:
            tally[(c.type, int(t))] += 1
    for (ty, t), n in sorted(tally.items()):
        print("physical", ty, t, n)
for name in ("region", "min_angle", "area"):
    if name in m.cell_data:
        vals = [float(x) for block in m.cell_data[name] for x in block]
        print("range", name, min(vals), max(vals), sum(vals))
)PY";

class Formats : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("deltamesh_fmt_" + std::to_string(::getpid()) + "_" + info->test_suite_name() + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(path("summary.py")) << kMeshioScript;
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  static std::string slurp(const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
  // meshio's summary as a list of lines.
  std::vector<std::string> meshio(const std::string& file) {
    const Result r = run(std::string(kPython) + " " + quote(path("summary.py")) + " " + quote(file));
    EXPECT_EQ(r.status, 0) << r.out;
    std::vector<std::string> lines;
    std::istringstream in(r.out);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
  }
  // Runs a Python script (written to a file) with Debian's python3.
  Result py(const std::string& code, const std::vector<std::string>& args) {
    std::string name = "check_";
    name += std::to_string(++scripts_);
    name += ".py";
    const std::string script = path(name);
    std::ofstream(script) << code;
    std::string cmd = kPython;
    cmd += ' ';
    cmd += quote(script);
    for (const std::string& a : args) {
      cmd += ' ';
      cmd += quote(a);
    }
    return run(cmd);
  }
  static bool has(const std::vector<std::string>& lines, const std::string& line) {
    for (const std::string& l : lines)
      if (l == line) return true;
    return false;
  }
  static std::string joined(const std::vector<std::string>& lines) {
    std::string s;
    for (const std::string& l : lines) s += l + "\n";
    return s;
  }
  // No temporary files left next to the outputs.
  void expect_no_temporaries() {
    for (const auto& e : fs::directory_iterator(dir_))
      EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << e.path();
  }
  fs::path dir_;
  int scripts_ = 0;
};

// ---------------------------------------------------------------------------
// Gmsh

// Physical tags as docs/formats.md documents them: a positive value is its
// own tag, the others follow the largest positive value in increasing order.
template <class K>
std::map<int, std::size_t> by_tag(const std::map<K, std::size_t>& counts) {
  long long max_positive = 0;
  for (const auto& [v, n] : counts) max_positive = std::max<long long>(max_positive, v);
  long long next = max_positive + 1;
  std::map<int, std::size_t> out;
  for (const auto& [v, n] : counts) out[static_cast<int>(v > 0 ? v : next++)] = n;
  return out;
}

// gmsh itself reads the file and writes back (MSH 2.2) the elements of every
// physical group, each with its physical tag; we count what it wrote.
void check_with_gmsh(const std::string& file, const std::string& out, const Expect& x) {
  const Result r = run("gmsh -nopopup -v 2 " + quote(file) + " -0 -format msh22 -o " + quote(out));
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out.find("Error"), std::string::npos) << r.out;
  std::ifstream in(out);
  std::string line;
  std::size_t nodes = 0;
  std::map<int, std::size_t> tris, lines;  // physical tag -> elements
  while (std::getline(in, line)) {
    if (line == "$Nodes") {
      in >> nodes;
    } else if (line == "$Elements") {
      std::size_t n;
      in >> n;
      std::getline(in, line);
      for (std::size_t i = 0; i < n && std::getline(in, line); ++i) {
        std::istringstream ls(line);
        int id, type, ntags, physical;
        ls >> id >> type >> ntags >> physical;
        if (type == 2) ++tris[physical];
        if (type == 1) ++lines[physical];
      }
    }
  }
  EXPECT_EQ(nodes, x.points);
  EXPECT_EQ(tris, by_tag(x.per_region));
  EXPECT_EQ(lines, by_tag(x.per_marker));
}

TEST_F(Formats, Msh41ReadByGmshAndMeshio) {
  const Mesh m = sample_mesh();
  ASSERT_TRUE(check(m).ok());
  const Expect x = expected(m);
  write_msh(m, path("a.msh"));
  expect_no_temporaries();
  const std::string text = slurp(path("a.msh"));
  EXPECT_EQ(text.rfind("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n", 0), 0u);
  EXPECT_NE(text.find("$Entities"), std::string::npos);
  EXPECT_NE(text.find("2 1 \"region_1\""), std::string::npos);
  EXPECT_NE(text.find("2 2 \"region_2\""), std::string::npos);
  EXPECT_NE(text.find("2 3 \"region_-3\""), std::string::npos);  // after the largest positive region
  EXPECT_NE(text.find("1 5 \"boundary_5\""), std::string::npos);
  EXPECT_NE(text.find("1 1 \"boundary_1\""), std::string::npos);

  if (have_meshio()) {
    const auto s = meshio(path("a.msh"));
    EXPECT_TRUE(has(s, "points " + std::to_string(x.points))) << joined(s);
    EXPECT_TRUE(has(s, "cells triangle " + std::to_string(x.triangles))) << joined(s);
    EXPECT_TRUE(has(s, "cells line " + std::to_string(x.lines))) << joined(s);
    EXPECT_TRUE(has(s, "field region_1 1 2")) << joined(s);
    EXPECT_TRUE(has(s, "field boundary_5 5 1")) << joined(s);
    EXPECT_TRUE(has(s, "physical triangle 1 " + std::to_string(x.per_region.at(1)))) << joined(s);
    EXPECT_TRUE(has(s, "physical triangle 2 " + std::to_string(x.per_region.at(2)))) << joined(s);
    EXPECT_TRUE(has(s, "physical triangle 3 " + std::to_string(x.per_region.at(-3)))) << joined(s);
    EXPECT_TRUE(has(s, "physical line 5 " + std::to_string(x.per_marker.at(5)))) << joined(s);
    EXPECT_TRUE(has(s, "physical line 1 " + std::to_string(x.per_marker.at(1)))) << joined(s);
  }
  REQUIRE_TOOL(have_meshio(), "python3-meshio");
  REQUIRE_TOOL(have_gmsh(), "gmsh");
  check_with_gmsh(path("a.msh"), path("gmsh_out.msh"), x);
}

TEST_F(Formats, Msh22ReadByGmshAndMeshio) {
  const Mesh m = sample_mesh(80, 3);
  const Expect x = expected(m);
  MshOptions opt;
  opt.version = MshVersion::V22;
  write_msh(m, path("b.msh"), opt);
  const std::string text = slurp(path("b.msh"));
  EXPECT_EQ(text.rfind("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n", 0), 0u);
  EXPECT_EQ(text.find("$Entities"), std::string::npos);
  if (have_meshio()) {
    const auto s = meshio(path("b.msh"));
    EXPECT_TRUE(has(s, "points " + std::to_string(x.points))) << joined(s);
    EXPECT_TRUE(has(s, "cells triangle " + std::to_string(x.triangles))) << joined(s);
    EXPECT_TRUE(has(s, "cells line " + std::to_string(x.lines))) << joined(s);
    EXPECT_TRUE(has(s, "physical triangle 2 " + std::to_string(x.per_region.at(2)))) << joined(s);
    EXPECT_TRUE(has(s, "physical line 5 " + std::to_string(x.per_marker.at(5)))) << joined(s);
  }
  REQUIRE_TOOL(have_meshio(), "python3-meshio");
  REQUIRE_TOOL(have_gmsh(), "gmsh");
  check_with_gmsh(path("b.msh"), path("gmsh_out.msh"), x);
}

TEST_F(Formats, MshWithoutAttributesIsOneDomainGroup) {
  std::vector<Point> pts{{0, 0}, {2, 0}, {2, 1}, {0, 1}, {1, 0.5}};
  const Mesh m = delaunay(pts);
  write_msh(m, path("c.msh"));
  const std::string text = slurp(path("c.msh"));
  EXPECT_NE(text.find("2 1 \"domain\""), std::string::npos) << text;
  EXPECT_NE(text.find("1 1 \"boundary_1\""), std::string::npos) << text;
  REQUIRE_TOOL(have_gmsh(), "gmsh");
  check_with_gmsh(path("c.msh"), path("gmsh_out.msh"), expected(m));
}

TEST_F(Formats, MshWithoutBoundaryLines) {
  const Mesh m = sample_mesh(30);
  MshOptions opt;
  opt.boundary_lines = false;
  write_msh(m, path("d.msh"), opt);
  REQUIRE_TOOL(have_meshio(), "python3-meshio");
  const auto s = meshio(path("d.msh"));
  EXPECT_TRUE(has(s, "cells triangle " + std::to_string(m.num_triangles()))) << joined(s);
  for (const auto& l : s) EXPECT_EQ(l.rfind("cells line", 0), std::string::npos) << l;
}

// Six-node triangles through the -o2 hook: midpoints added as vertices.
struct Quadratic {
  Mesh mesh;
  std::vector<VertexId> midside;
};
Quadratic quadratic_mesh() {
  Quadratic q;
  q.mesh = delaunay(std::vector<Point>{{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.4, 0.6}});
  std::map<std::pair<VertexId, VertexId>, VertexId> mids;
  Mesh& m = q.mesh;
  for (TriId t = 0; t < m.num_triangle_slots(); ++t) {
    if (!m.is_real(t)) continue;
    const auto v = m.triangle(t);
    for (int i = 0; i < 3; ++i) {
      // Opposite corner i: the edge (i+1, i+2).
      VertexId a = v[(i + 1) % 3], b = v[(i + 2) % 3];
      if (a > b) std::swap(a, b);
      auto it = mids.find({a, b});
      if (it == mids.end()) {
        const Point pa = m.point(a), pb = m.point(b);
        it = mids.emplace(std::make_pair(a, b), m.add_vertex({(pa.x + pb.x) / 2, (pa.y + pb.y) / 2})).first;
      }
      q.midside.push_back(it->second);
    }
  }
  return q;
}

TEST_F(Formats, SixNodeTrianglesInMshAndVtk) {
  const Quadratic q = quadratic_mesh();
  MshOptions mopt;
  mopt.second_order.midside = q.midside;
  write_msh(q.mesh, path("q.msh"), mopt);
  VtkOptions vopt;
  vopt.second_order.midside = q.midside;
  write_vtu(q.mesh, path("q.vtu"), vopt);
  write_vtk(q.mesh, path("q.vtk"), vopt);
  // Wrong count: an error, and no file.
  MshOptions bad;
  std::vector<VertexId> short_list(q.midside.begin(), q.midside.end() - 1);
  bad.second_order.midside = short_list;
  EXPECT_THROW(write_msh(q.mesh, path("bad.msh"), bad), Error);
  EXPECT_FALSE(fs::exists(path("bad.msh")));
  expect_no_temporaries();
  REQUIRE_TOOL(have_meshio(), "python3-meshio");
  const std::string nt = std::to_string(q.mesh.num_triangles());
  for (const char* f : {"q.msh", "q.vtu", "q.vtk"}) {
    const auto s = meshio(path(f));
    EXPECT_TRUE(has(s, "cells triangle6 " + nt)) << f << "\n" << joined(s);
    EXPECT_TRUE(has(s, "points " + std::to_string(q.mesh.num_vertices()))) << f << "\n" << joined(s);
  }
  // Node order: corners, then midpoints of edges 01, 12, 20 (Gmsh and VTK).
  const Result r = py("import sys\n"
                          "import meshio, numpy as np\n"
                             "m = meshio.read(sys.argv[1])\n"
                             "bad = 0\n"
                             "for c in m.cells:\n"
                             "  for t in c.data:\n"
                             "    p = m.points[t]\n"
                             "    if c.type == 'triangle6':\n"
                             "      for i in range(3):\n"
                             "        bad += int(np.abs(p[3+i] - (p[i] + p[(i+1)%3]) / 2).max() > 1e-12)\n"
                             "    elif c.type == 'line3':\n"
                             "      bad += int(np.abs(p[2] - (p[0] + p[1]) / 2).max() > 1e-12)\n"
                             "    else:\n"
                             "      bad += 1000\n"
                             "print(bad)\n", {path("q.msh")});
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(r.out.ends_with("\n0\n") || r.out == "0\n") << r.out;  // meshio may print a blank line first
}

// ---------------------------------------------------------------------------
// VTK

TEST_F(Formats, VtuAsciiAndBinaryAndLegacyVtkReadByMeshio) {
  const Mesh m = sample_mesh();
  const Expect x = expected(m);
  write_vtu(m, path("a.vtu"));
  VtkOptions bin;
  bin.binary = true;
  write_vtu(m, path("b.vtu"), bin);
  write_vtk(m, path("c.vtk"));
  expect_no_temporaries();
  EXPECT_NE(slurp(path("a.vtu")).find("format=\"ascii\""), std::string::npos);
  EXPECT_NE(slurp(path("b.vtu")).find("format=\"binary\""), std::string::npos);
  EXPECT_EQ(slurp(path("c.vtk")).rfind("# vtk DataFile Version 3.0\n", 0), 0u);
  REQUIRE_TOOL(have_meshio(), "python3-meshio");
  double total_area = 0.0;
  for (TriId t = 0; t < m.num_triangle_slots(); ++t)
    if (m.is_real(t)) {
      const auto v = m.triangle(t);
      const Point a = m.point(v[0]), b = m.point(v[1]), c = m.point(v[2]);
      total_area += 0.5 * std::fabs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
    }
  for (const char* f : {"a.vtu", "b.vtu", "c.vtk"}) {
    const auto s = meshio(path(f));
    EXPECT_TRUE(has(s, "points " + std::to_string(x.points))) << f << "\n" << joined(s);
    EXPECT_TRUE(has(s, "cells triangle " + std::to_string(x.triangles))) << f << "\n" << joined(s);
    for (const char* name : {"region", "min_angle", "area", "attribute_0"})
      EXPECT_TRUE(has(s, std::string("cell_data ") + name)) << f << " " << name << "\n" << joined(s);
    EXPECT_TRUE(has(s, "point_data marker")) << f << "\n" << joined(s);
    // Values: regions -3..2, angles within (0, 60], areas summing to the square.
    bool region_ok = false, angle_ok = false, area_ok = false;
    for (const std::string& l : s) {
      std::istringstream ls(l);
      std::string word, name;
      double lo, hi, sum;
      if (!(ls >> word >> name >> lo >> hi >> sum) || word != "range") continue;
      if (name == "region") region_ok = lo == -3 && hi == 2;
      if (name == "min_angle") angle_ok = lo > 0 && hi <= 60.0 + 1e-9;
      if (name == "area") area_ok = std::fabs(sum - total_area) < 1e-9 && std::fabs(sum - 1.0) < 1e-9;
    }
    EXPECT_TRUE(region_ok && angle_ok && area_ok) << f << "\n" << joined(s);
  }
}

TEST_F(Formats, VtuIsWellFormedXml) {
  const Mesh m = sample_mesh(20);
  write_vtu(m, path("a.vtu"));
  REQUIRE_TOOL(have_python(), "python3");
  const Result r = py("import sys\n"
                          "import xml.etree.ElementTree as ET\n"
                             "r = ET.parse(sys.argv[1]).getroot()\n"
                             "p = r.find('UnstructuredGrid/Piece')\n"
                             "print(r.tag, p.get('NumberOfPoints'), p.get('NumberOfCells'))\n", {path("a.vtu")});
  EXPECT_EQ(r.out, "VTKFile " + std::to_string(m.num_vertices()) + " " + std::to_string(m.num_triangles()) + "\n");
}

// ---------------------------------------------------------------------------
// GeoJSON, OFF, SVG

TEST_F(Formats, GeoJsonWrittenIsValidJsonWithProperties) {
  const Mesh m = sample_mesh(40);
  const BoundedVoronoi cells = bounded_voronoi(m);
  GeoJsonWriteOptions opt;
  opt.voronoi = &cells;
  write_geojson(m, path("a.geojson"), opt);
  REQUIRE_TOOL(have_python(), "python3");
  const Result r = py("import sys\n"
                          "import json, collections\n"
                             "d = json.load(open(sys.argv[1]))\n"
                             "assert d['type'] == 'FeatureCollection'\n"
                             "k = collections.Counter(f['properties']['kind'] for f in d['features'])\n"
                             "bad = 0\n"
                             "area = 0.0\n"
                             "for f in d['features']:\n"
                             "  g = f['geometry']\n"
                             "  assert g['type'] == 'Polygon'\n"
                             "  ring = g['coordinates'][0]\n"
                             "  assert ring[0] == ring[-1] and len(ring) >= 4\n"
                             "  s = sum(ring[i][0]*ring[i+1][1] - ring[i+1][0]*ring[i][1] for i in range(len(ring)-1))\n"
                             "  bad += s <= 0\n"
                             "  if f['properties']['kind'] == 'triangle':\n"
                             "    p = f['properties']\n"
                             "    assert set(p) == {'kind', 'id', 'region', 'min_angle', 'area'}\n"
                             "    area += p['area']\n"
                             "print(k['triangle'], k['voronoi_cell'], bad, round(area, 9))\n", {path("a.geojson")});
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out, std::to_string(m.num_triangles()) + " " + std::to_string(cells.cells.size()) + " 0 1.0\n");
}

TEST_F(Formats, GeoJsonSegmentsLayer) {
  const Mesh m = sample_mesh(40);
  const Expect x = expected(m);
  GeoJsonWriteOptions opt;
  opt.triangles = false;
  opt.segments = true;
  write_geojson(m, path("s.geojson"), opt);
  REQUIRE_TOOL(have_python(), "python3");
  const Result r = py("import sys, json, collections\n"
                      "d = json.load(open(sys.argv[1]))\n"
                      "c = collections.Counter(f['properties']['marker'] for f in d['features']\n"
                      "                        if f['geometry']['type'] == 'LineString')\n"
                      "print(len(d['features']), c[1], c[5])\n",
                      {path("s.geojson")});
  EXPECT_EQ(r.out, std::to_string(x.lines) + " " + std::to_string(x.per_marker.at(1)) + " " +
                       std::to_string(x.per_marker.at(5)) + "\n");
}

TEST_F(Formats, OffReadByMeshio) {
  const Mesh m = sample_mesh(40);
  write_off(m, path("a.off"));
  const std::string text = slurp(path("a.off"));
  EXPECT_EQ(text.rfind("OFF\n", 0), 0u);
  REQUIRE_TOOL(have_meshio(), "python3-meshio");
  const auto s = meshio(path("a.off"));
  EXPECT_TRUE(has(s, "points " + std::to_string(m.num_vertices()))) << joined(s);
  EXPECT_TRUE(has(s, "cells triangle " + std::to_string(m.num_triangles()))) << joined(s);
}

TEST_F(Formats, SvgParsesAsXmlAndRenders) {
  const Mesh m = sample_mesh(60);
  write_output(m, path("a.svg"));
  REQUIRE_TOOL(have_python(), "python3");
  const Result r = py("import sys\n"
                          "import xml.etree.ElementTree as ET\n"
                             "r = ET.parse(sys.argv[1]).getroot()\n"
                             "print(r.tag)\n", {path("a.svg")});
  EXPECT_EQ(r.out, "{http://www.w3.org/2000/svg}svg\n");
  REQUIRE_TOOL(have_rsvg(), "rsvg-convert (librsvg2-bin)");
  const Result png = run("rsvg-convert -o " + quote(path("a.png")) + " " + quote(path("a.svg")));
  EXPECT_EQ(png.status, 0) << png.out;
  EXPECT_GT(fs::file_size(path("a.png")), 1000u);
}

TEST_F(Formats, SvgVoronoiOverlayParsesAndRenders) {
  const Mesh m = sample_mesh(60);
  const BoundedVoronoi cells = bounded_voronoi(m);
  OutputOptions opt;
  opt.voronoi = &cells;
  write_output(m, path("v.svg"), opt);
  const std::string text = slurp(path("v.svg"));
  EXPECT_NE(text.find("class=\"voronoi\""), std::string::npos);
  REQUIRE_TOOL(have_python(), "python3");
  const Result r = py("import sys\n"
                      "import xml.etree.ElementTree as ET\n"
                      "r = ET.parse(sys.argv[1]).getroot()\n"
                      "ns = '{http://www.w3.org/2000/svg}'\n"
                      "v = [p for p in r.iter(ns + 'path') if p.get('class') == 'voronoi']\n"
                      "print(len(v), v[0].get('d').count('z'))\n",
                      {path("v.svg")});
  EXPECT_EQ(r.out, "1 " + std::to_string(cells.cells.size()) + "\n");
  REQUIRE_TOOL(have_rsvg(), "rsvg-convert (librsvg2-bin)");
  const Result png = run("rsvg-convert -o " + quote(path("v.png")) + " " + quote(path("v.svg")));
  EXPECT_EQ(png.status, 0) << png.out;
}

// ---------------------------------------------------------------------------
// Writing by extension

TEST_F(Formats, OutputFormatByExtension) {
  EXPECT_EQ(output_format_for("a/b.msh"), OutputFormat::Msh);
  EXPECT_EQ(output_format_for("B.VTU"), OutputFormat::Vtu);
  EXPECT_EQ(output_format_for("x.vtk"), OutputFormat::Vtk);
  EXPECT_EQ(output_format_for("x.svg"), OutputFormat::Svg);
  EXPECT_EQ(output_format_for("x.geojson"), OutputFormat::GeoJson);
  EXPECT_EQ(output_format_for("x.json"), OutputFormat::GeoJson);
  EXPECT_EQ(output_format_for("x.off"), OutputFormat::Off);
  EXPECT_EQ(output_format_for("x.1.node"), OutputFormat::Node);
  EXPECT_EQ(output_format_for("x.ele"), OutputFormat::Ele);
  EXPECT_EQ(output_format_for("x.edge"), OutputFormat::Edge);
  EXPECT_EQ(output_format_for("x.neigh"), OutputFormat::Neigh);
  EXPECT_EQ(output_format_for("x.poly"), OutputFormat::Poly);
  EXPECT_FALSE(output_format_for("x.stl"));
  EXPECT_FALSE(output_format_for("dir.msh/file"));
  EXPECT_FALSE(output_format_for("noext"));
}

TEST_F(Formats, WriteOutputDispatchesEveryFormat) {
  const Mesh m = sample_mesh(30);
  for (const char* name : {"m.msh", "m.vtu", "m.vtk", "m.svg", "m.geojson", "m.off", "m.node", "m.ele", "m.edge",
                           "m.neigh", "m.poly"}) {
    write_output(m, path(name));
    EXPECT_TRUE(fs::exists(path(name))) << name;
  }
  EXPECT_THROW(write_output(m, path("m.stl")), UnknownOutputFormat);
  EXPECT_FALSE(fs::exists(path("m.stl")));
  OutputOptions opt;
  opt.msh.version = MshVersion::V22;
  write_output(m, path("old.msh"), opt);
  EXPECT_EQ(slurp(path("old.msh")).rfind("$MeshFormat\n2.2", 0), 0u);
  expect_no_temporaries();
}

TEST_F(Formats, FailedWriteLeavesNoFile) {
  const Mesh m = sample_mesh(10);
  const std::string missing = path("no/such/dir/m.msh");
  EXPECT_THROW(write_msh(m, missing), IoError);
  EXPECT_THROW(write_vtu(m, path("no/such/dir/m.vtu")), IoError);
  EXPECT_THROW(write_geojson(m, path("no/such/dir/m.geojson")), IoError);
  EXPECT_THROW(write_off(m, path("no/such/dir/m.off")), IoError);
  expect_no_temporaries();
}

TEST_F(Formats, EmptyMeshStillReadable) {
  Mesh m;
  m.add_vertex({0, 0});
  m.add_vertex({1, 0});
  write_msh(m, path("e.msh"));
  write_vtu(m, path("e.vtu"));
  write_vtk(m, path("e.vtk"));
  write_geojson(m, path("e.geojson"));
  // (meshio 7 cannot read a .vtu without cells, a meshio limitation: ParaView can.)
  REQUIRE_TOOL(have_meshio(), "python3-meshio");
  for (const char* f : {"e.msh", "e.vtk"}) {
    const auto s = meshio(path(f));
    EXPECT_TRUE(has(s, "points 2")) << f << "\n" << joined(s);
  }
}

}  // namespace
