// Six-node triangles (Triangle's -o2, second_order.hpp): node positions and
// sharing, markers and attributes, the 6-node .ele round trip and reading it
// back as the corner mesh, and the .msh/.vtu/.vtk files opened by gmsh and
// meshio (skipped only when the tool is missing; scripts/install-deps.sh
// installs them).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>
#include <utility>
#include <vector>

#include "deltamesh/delaunay.hpp"
#include "deltamesh/formats.hpp"
#include "deltamesh/second_order.hpp"
#include "deltamesh/triangle_io.hpp"
#include "deltamesh/triangulate.hpp"
#include "deltamesh/validate.hpp"

using namespace deltamesh;
namespace fs = std::filesystem;

namespace {

// [0,2]x[0,1]: bottom side marked 5, the other sides unmarked; an interior
// cut x = 1 marked 7 and an interior segment y = 0.5, 0.25 <= x <= 0.75
// unmarked. One vertex attribute, x + 2y at the input vertices.
Pslg plate() {
  Pslg p;
  p.points = {{0, 0}, {1, 0}, {2, 0}, {2, 1}, {1, 1}, {0, 1}, {0.25, 0.5}, {0.75, 0.5}};
  p.segments = {{0, 1, 5}, {1, 2, 5}, {2, 3, 0}, {3, 4, 0}, {4, 5, 0}, {5, 0, 0}, {1, 4, 7}, {6, 7, 0}};
  p.num_point_attributes = 1;
  for (const Point& q : p.points) p.point_attributes.push_back(q.x + 2 * q.y);
  return p;
}

Mesh refined_plate() {
  TriangulateOptions o;
  RefineOptions r;
  r.min_angle_deg = 28;
  r.max_area = 0.02;
  o.refine = r;
  return triangulate(plate(), o);
}

// The marker a midpoint at p should get, from the geometry alone.
int expected_marker(const Point& p) {
  if (p.y == 0) return 5;
  if (p.x == 0 || p.x == 2 || p.y == 1) return 1;  // unmarked boundary
  if (p.x == 1) return 7;
  return 0;  // inside, the unmarked interior segment included
}

std::pair<VertexId, VertexId> key(VertexId a, VertexId b) { return {std::min(a, b), std::max(a, b)}; }

std::string run(const std::string& cmd, int* status = nullptr) {
  std::string out;
  FILE* p = ::popen((cmd + " 2>&1").c_str(), "r");
  if (!p) return out;
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  const int st = ::pclose(p);
  if (status) *status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return out;
}
bool have(const std::string& cmd) {
  int st = -1;
  run(cmd, &st);
  return st == 0;
}
const char* kPython = "/usr/bin/python3";  // Debian's, where python3-meshio lives

class SecondOrder : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("deltamesh_o2_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

TEST(SecondOrderNodes, MidpointsInEleOrderSharedByNeighbours) {
  const Mesh mesh = refined_plate();
  ASSERT_GT(mesh.num_triangles(), 50u);
  const MidpointNodes mid = midpoint_nodes(mesh);
  const VertexId n0 = static_cast<VertexId>(mesh.num_vertices());
  std::map<std::pair<VertexId, VertexId>, VertexId> node_of_edge;
  for (TriId t = 0; t < mesh.num_triangle_slots(); ++t) {
    ASSERT_TRUE(mesh.is_real(t));
    const auto v = mesh.triangle(t);
    for (int k = 0; k < 3; ++k) {
      const VertexId node = mid.tri_nodes[3 * t + k];
      ASSERT_GE(node, n0);
      ASSERT_LT(node - n0, mid.points.size());
      // Node k sits on the edge opposite corner k (Triangle's .ele order).
      const VertexId a = v[(k + 1) % 3], b = v[(k + 2) % 3];
      const Point& p = mid.points[node - n0];
      EXPECT_EQ(p.x, 0.5 * (mesh.point(a).x + mesh.point(b).x));
      EXPECT_EQ(p.y, 0.5 * (mesh.point(a).y + mesh.point(b).y));
      // Both triangles of an edge name the same node; one node per edge.
      const auto [it, fresh] = node_of_edge.emplace(key(a, b), node);
      EXPECT_EQ(it->second, node) << "edge " << a << "-" << b;
    }
  }
  EXPECT_EQ(mid.points.size(), node_of_edge.size());
  EXPECT_EQ(mid.markers.size(), mid.points.size());
  EXPECT_EQ(mid.attributes.size(), mid.points.size());
  // Euler on a disc: E = V + T - 1 over the vertices in triangles.
  std::vector<char> used(mesh.num_vertices(), 0);
  for (const VertexId v : mesh.triangle_vertices()) used[v] = 1;
  const auto nv = static_cast<std::size_t>(std::count(used.begin(), used.end(), 1));
  EXPECT_EQ(mid.points.size(), nv + mesh.num_triangles() - 1);
}

TEST(SecondOrderNodes, MarkersAndAttributes) {
  Mesh mesh = refined_plate();
  const std::size_t n0 = mesh.num_vertices();
  const std::vector<int> corner_markers = mesh.vertex_markers();
  const std::size_t nodes = midpoint_nodes(mesh).points.size();
  const std::vector<VertexId> ids = add_midpoint_nodes(mesh);
  ASSERT_EQ(ids.size(), 3 * mesh.num_triangles());
  ASSERT_EQ(mesh.vertex_markers().size(), mesh.num_vertices());
  ASSERT_EQ(mesh.vertex_attributes().size(), mesh.num_vertices());
  // Corners untouched.
  EXPECT_TRUE(std::equal(corner_markers.begin(), corner_markers.end(), mesh.vertex_markers().begin()));
  std::map<int, int> seen;  // marker -> nodes
  for (TriId t = 0; t < mesh.num_triangle_slots(); ++t) {
    const auto v = mesh.triangle(t);
    for (int k = 0; k < 3; ++k) {
      const VertexId node = ids[3 * t + k];
      const VertexId a = v[(k + 1) % 3], b = v[(k + 2) % 3];
      const int m = mesh.vertex_markers()[node];
      EXPECT_EQ(m, expected_marker(mesh.point(node))) << mesh.point(node).x << "," << mesh.point(node).y;
      ++seen[m];
      const auto& at = mesh.vertex_attributes();
      EXPECT_DOUBLE_EQ(at[node], 0.5 * (at[a] + at[b]));
    }
  }
  // Every kind occurs (the test would be empty otherwise).
  for (const int m : {0, 1, 5, 7}) EXPECT_GT(seen[m], 0) << "marker " << m;
  // The midpoints are vertices in no triangle; the corner mesh stays valid.
  EXPECT_EQ(mesh.num_vertices(), n0 + nodes);
  const CheckReport rep = check(mesh);
  EXPECT_TRUE(rep.ok()) << rep.summary();
}

// A mesh without vertex markers (delaunay() sets none): the corners get
// Triangle's default first, so the written .node keeps 1 on the hull for
// corners and midpoints alike.
TEST(SecondOrderNodes, NoVertexMarkersMeansOneOnTheHull) {
  Mesh mesh = delaunay(std::vector<Point>{{0, 0}, {3, 0}, {3, 2}, {0, 2}, {1, 1}, {2, 1.2}});
  ASSERT_TRUE(mesh.vertex_markers().empty());
  const std::size_t n0 = mesh.num_vertices();
  add_midpoint_nodes(mesh);
  ASSERT_EQ(mesh.vertex_markers().size(), mesh.num_vertices());
  int hull = 0, inside = 0;
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v) {
    const Point& p = mesh.point(static_cast<VertexId>(v));
    const bool on_hull = p.x == 0 || p.x == 3 || p.y == 0 || p.y == 2;
    EXPECT_EQ(mesh.vertex_markers()[v], on_hull ? 1 : 0) << v << " (" << (v < n0 ? "corner" : "midpoint") << ")";
    (on_hull ? hull : inside)++;
  }
  EXPECT_EQ(hull, 8);  // 4 corners, 4 hull edge midpoints
  EXPECT_GT(inside, 2);
}

TEST_F(SecondOrder, SixNodeEleRoundTripAndCornerMeshBack) {
  Mesh mesh = refined_plate();
  const Mesh corners = mesh;
  const std::vector<VertexId> ids = add_midpoint_nodes(mesh);
  TriangleWriteOptions w;
  w.first_index = 1;
  w.midside = ids;
  write_node(mesh, path("m.node"), w);
  write_ele(mesh, path("m.ele"), w);
  write_poly(mesh, path("m.poly"), w);

  Pslg nodes = read_node(path("m.node"));
  nodes.segments = read_poly(path("m.poly")).segments;  // as -rp reads them
  EleData ele = read_ele(path("m.ele"), nodes.first_index);
  ASSERT_EQ(nodes.points.size(), mesh.num_vertices());
  ASSERT_EQ(ele.triangles.size(), 3 * mesh.num_triangles());
  EXPECT_EQ(ele.midside, ids);
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v) {
    EXPECT_EQ(nodes.points[v].x, mesh.point(static_cast<VertexId>(v)).x);
    EXPECT_EQ(nodes.points[v].y, mesh.point(static_cast<VertexId>(v)).y);
    EXPECT_EQ(nodes.point_markers[v], mesh.vertex_markers()[v]);
  }

  // Back to the corner mesh: the midpoint nodes go, the rest keep their ids
  // (the midpoints were appended).
  const std::size_t dropped = drop_midpoint_nodes(nodes, ele.triangles, ele.midside);
  EXPECT_EQ(dropped, mesh.num_vertices() - corners.num_vertices());
  const Mesh back = mesh_from_triangles(nodes, ele.triangles);
  ASSERT_EQ(back.num_vertices(), corners.num_vertices());
  ASSERT_EQ(back.num_triangles(), corners.num_triangles());
  for (TriId t = 0; t < corners.num_triangle_slots(); ++t) EXPECT_EQ(ele.triangles[3 * t], corners.triangle(t)[0]);
  const CheckReport rep = check(back);
  EXPECT_TRUE(rep.ok()) << rep.summary();
  // A 3-node file has no midpoints and nothing to drop.
  write_ele(corners, path("c.ele"), {});
  EleData linear = read_ele(path("c.ele"), 0);
  EXPECT_TRUE(linear.midside.empty());
  Pslg cn = read_node(path("m.node"));
  EXPECT_EQ(drop_midpoint_nodes(cn, linear.triangles, linear.midside), 0u);
  // A midpoint id beyond the nodes is an input error.
  std::vector<VertexId> tris = ele.triangles, bad = ele.midside;
  bad[0] = 1000000;
  Pslg again = read_node(path("m.node"));
  EXPECT_THROW(drop_midpoint_nodes(again, tris, bad), InputError);
}

// gmsh computes the Jacobian determinant of every 6-node element: with
// straight sides and exact midpoints it is constant, minJ/maxJ = 1. A wrong
// node order folds the element (negative); checked on purpose below.
TEST_F(SecondOrder, GmshJacobiansPositive) {
  if (!have("command -v gmsh")) GTEST_SKIP() << "gmsh is not installed (scripts/install-deps.sh core)";
  Mesh mesh = refined_plate();
  const std::vector<VertexId> ids = add_midpoint_nodes(mesh);
  std::vector<VertexId> rotated = ids;  // nodes 4,5,6 -> 5,6,4: a wrong order
  for (std::size_t t = 0; t < rotated.size(); t += 3) std::rotate(rotated.begin() + t, rotated.begin() + t + 1, rotated.begin() + t + 3);
  const auto worst_ratio = [&](const std::string& msh) {
    const std::string geo = msh + ".geo";
    std::ofstream(geo) << "Merge \"" << msh << "\";\n"
                       << "Plugin(AnalyseMeshQuality).JacobianDeterminant = 1;\n"
                       << "Plugin(AnalyseMeshQuality).IGEMeasure = 0;\n"
                       << "Plugin(AnalyseMeshQuality).ICNMeasure = 0;\n"
                       << "Plugin(AnalyseMeshQuality).DimensionOfElements = 2;\n"
                       << "Plugin(AnalyseMeshQuality).CreateView = 0;\n"
                       << "Plugin(AnalyseMeshQuality).Run;\n";
    int st = -1;
    const std::string out = run("gmsh -nopopup '" + geo + "' -parse_and_exit", &st);
    EXPECT_EQ(st, 0) << out;
    EXPECT_EQ(out.find("Error"), std::string::npos) << out;
    std::smatch m;
    const std::regex re(R"(minJ/maxJ\s*=\s*(\S+),)");
    if (!std::regex_search(out, m, re)) {
      ADD_FAILURE() << "no minJ/maxJ in gmsh's output:\n" << out;
      return 0.0;
    }
    return std::stod(m[1]);
  };
  for (const MshVersion v : {MshVersion::V41, MshVersion::V22}) {
    MshOptions o;
    o.version = v;
    o.second_order.midside = ids;
    write_msh(mesh, path("good.msh"), o);
    EXPECT_GT(worst_ratio(path("good.msh")), 0.999);
    o.second_order.midside = rotated;
    write_msh(mesh, path("bad.msh"), o);
    EXPECT_LT(worst_ratio(path("bad.msh")), 0.0);
  }
  // gmsh's own coherence check: no duplicate nodes or elements.
  MshOptions o;
  o.second_order.midside = ids;
  write_msh(mesh, path("m.msh"), o);
  const std::string out = run("gmsh -check '" + path("m.msh") + "'");
  EXPECT_EQ(out.find("Warning"), std::string::npos) << out;
  EXPECT_EQ(out.find("Error"), std::string::npos) << out;
  EXPECT_NE(out.find(std::to_string(mesh.num_vertices()) + " nodes"), std::string::npos) << out;
}

// meshio reads all three quadratic outputs: triangle6 cells whose nodes 3-5
// are the midpoints of edges 01, 12, 20, line3 boundary elements in .msh,
// and the VTK marker point data equal to the mesh's.
TEST_F(SecondOrder, MeshioReadsMshVtuVtk) {
  if (!fs::exists(kPython) || !have(std::string(kPython) + " -c 'import meshio'"))
    GTEST_SKIP() << "python3-meshio is not installed (scripts/install-deps.sh core)";
  Mesh mesh = refined_plate();
  const std::vector<VertexId> ids = add_midpoint_nodes(mesh);
  MshOptions mo;
  mo.second_order.midside = ids;
  write_msh(mesh, path("m.msh"), mo);
  VtkOptions vo;
  vo.second_order.midside = ids;
  write_vtu(mesh, path("m.vtu"), vo);
  vo.binary = true;
  write_vtu(mesh, path("b.vtu"), vo);
  write_vtk(mesh, path("m.vtk"), vo);
  std::ofstream(path("check.py")) << R"PY(
import sys, meshio, numpy as np
m = meshio.read(sys.argv[1])
bad = 0
tri6 = 0
for c in m.cells:
    for t in c.data:
        p = m.points[t][:, :2]
        if c.type == "triangle6":
            tri6 += 1
            for i in range(3):
                bad += int(np.abs(p[3 + i] - (p[i] + p[(i + 1) % 3]) / 2).max() > 0)
            # counter-clockwise corners
            d = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0])
            bad += int(d <= 0)
        elif c.type == "line3":
            bad += int(np.abs(p[2] - (p[0] + p[1]) / 2).max() > 0)
        else:
            bad += 1000
print("points", len(m.points), "triangle6", tri6, "bad", bad)
if "marker" in m.point_data:
    print("markers", " ".join(str(int(x)) for x in m.point_data["marker"]))
)PY";
  std::string markers;
  for (const int m : mesh.vertex_markers()) markers += (markers.empty() ? "" : " ") + std::to_string(m);
  const std::string summary = "points " + std::to_string(mesh.num_vertices()) + " triangle6 " +
                              std::to_string(mesh.num_triangles()) + " bad 0";
  for (const char* f : {"m.msh", "m.vtu", "b.vtu", "m.vtk"}) {
    int st = -1;
    const std::string out = run(std::string(kPython) + " '" + path("check.py") + "' '" + path(f) + "'", &st);
    EXPECT_EQ(st, 0) << f << "\n" << out;
    EXPECT_NE(out.find(summary), std::string::npos) << f << "\n" << out;
    if (std::string(f) != "m.msh") {
      EXPECT_NE(out.find("markers " + markers + "\n"), std::string::npos) << f << "\n" << out;
    }
  }
}

}  // namespace
