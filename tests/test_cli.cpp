// The deltamesh command line, run as a process on inputs in a temporary
// directory: output names, numbering, output switches, exit codes and
// messages, and that a failed run leaves no partial output.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "deltamesh/triangle_io.hpp"
#include "support/cli_fixture.hpp"

namespace fs = std::filesystem;

namespace {

using deltamesh::test::slurp;
using Result = deltamesh::test::CliResult;

// Data lines of a Triangle file (comments and blank lines dropped), split
// into tokens.
std::vector<std::vector<std::string>> table(const fs::path& p) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(slurp(p));
  std::string line;
  while (std::getline(in, line)) {
    line = line.substr(0, line.find('#'));
    std::istringstream ls(line);
    std::vector<std::string> row;
    for (std::string tok; ls >> tok;) row.push_back(tok);
    if (!row.empty()) rows.push_back(row);
  }
  return rows;
}

class Cli : public deltamesh::test::CliDirTest {
 protected:
  Cli() : CliDirTest("deltamesh_cli") {}

  // Copies tests/data/cli/NAME into the temporary directory.
  void data(const std::string& name, const std::string& as = {}) const {
    fs::copy_file(fs::path(DELTAMESH_SOURCE_DIR) / "tests/data/cli" / name, dir_ / (as.empty() ? name : as),
                  fs::copy_options::overwrite_existing);
  }
  // Runs the CLI in the temporary directory with the given arguments.
  Result run(const std::string& args) const { return run_program(DELTAMESH_CLI, args); }

  // Names in the directory, sorted.
  std::vector<std::string> listing() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }
};

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE((haystack).find(needle), std::string::npos) << "expected '" << (needle) << "' in:\n" << (haystack)

// ---------------------------------------------------------------------------
// Output names and numbering

TEST_F(Cli, NodeInputWritesIterationOne) {
  data("points.node");
  const Result r = run("points.node");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(listing(), (std::vector<std::string>{"points.1.ele", "points.1.node", "points.node"}));
  // One-based like the input; attributes and the input's marker 7 carried.
  const auto node = table(path("points.1.node"));
  EXPECT_EQ(node[0], (std::vector<std::string>{"6", "2", "1", "1"}));
  EXPECT_EQ(node[1][0], "1");
  EXPECT_EQ(node[4], (std::vector<std::string>{"4", "0", "3", "3.5", "7"}));
  EXPECT_EQ(node[5].back(), "0");  // interior vertex
  EXPECT_EQ(node[1].back(), "1");  // hull vertex
  const auto ele = table(path("points.1.ele"));
  EXPECT_EQ(ele[0][0], "6");  // 2n - 2 - h = 12 - 2 - 4
  EXPECT_EQ(ele[1][0], "1");
  EXPECT_CONTAINS(r.out, "Delaunay triangulation");
}

// -I names the output like the input: an output that would replace a file
// this run read is refused before anything is written (exit 4), unless
// --overwrite asks for it.
TEST_F(Cli, OutputsNeverReplaceAnInputUnlessAsked) {
  data("square_hole.poly", "dupI.poly");
  const std::string original = slurp(path("dupI.poly"));
  Result r = run("-pI dupI");
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_CONTAINS(r.err, "refusing to overwrite the input file dupI.poly");
  EXPECT_EQ(listing(), (std::vector<std::string>{"dupI.poly"}));  // not even the .node
  EXPECT_EQ(slurp(path("dupI.poly")), original);
  data("points.node", "ptsI.node");
  r = run("-I ptsI");
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_CONTAINS(r.err, "ptsI.node");
  EXPECT_FALSE(exists("ptsI.ele"));
  r = run("-pq30 dupI --output dupI.poly");
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_EQ(slurp(path("dupI.poly")), original);
  r = run("-pI --overwrite dupI");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(exists("dupI.ele"));
  EXPECT_NE(slurp(path("dupI.poly")), original);
}

TEST_F(Cli, BaseNameWithoutExtensionAndIterationCounting) {
  data("points.node", "p.1.node");
  Result r = run("p.1");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(exists("p.2.node"));
  EXPECT_TRUE(exists("p.2.ele"));
  r = run("p.2.node");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(exists("p.3.ele"));
}

TEST_F(Cli, ZeroBasedNumbering) {
  data("points.node");
  const Result r = run("-z points.node");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto node = table(path("points.1.node"));
  EXPECT_EQ(node[1][0], "0");
  const auto ele = table(path("points.1.ele"));
  EXPECT_EQ(ele[1][0], "0");
  for (std::size_t i = 1; i < ele.size(); ++i)
    for (std::size_t k = 1; k <= 3; ++k) EXPECT_LT(std::stoi(ele[i][k]), 6);
}

TEST_F(Cli, OutputSelectionSwitches) {
  data("points.node");
  Result r = run("-enNE points.node");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(listing(), (std::vector<std::string>{"points.1.edge", "points.1.neigh", "points.node"}));
  const auto neigh = table(path("points.1.neigh"));
  EXPECT_EQ(neigh[0], (std::vector<std::string>{"6", "3"}));
  r = run("-IN points.node");  // no iteration number; -N keeps the input intact
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(exists("points.ele"));
  EXPECT_EQ(table(path("points.node"))[0], (std::vector<std::string>{"6", "2", "1", "1"}));
}

TEST_F(Cli, NoMarkers) {
  data("points.node");
  const Result r = run("-Be points.node");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(table(path("points.1.node"))[0], (std::vector<std::string>{"6", "2", "1", "0"}));
  EXPECT_EQ(table(path("points.1.edge"))[0][1], "0");
}

TEST_F(Cli, ConvexHullOnPointSetWritesPoly) {
  data("points.node");
  const Result r = run("-c points.node");
  ASSERT_EQ(r.code, 0) << r.err;
  ASSERT_TRUE(exists("points.1.poly"));
  const auto poly = table(path("points.1.poly"));
  EXPECT_EQ(poly[1][0], "4");  // four hull segments
}

TEST_F(Cli, VoronoiOffAndOutputByExtension) {
  data("points.node");
  Result r = run("-vg --output=points.msh --output points.vtu points.node");
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* f : {"points.1.v.node", "points.1.v.edge", "points.1.off", "points.msh", "points.vtu"})
    EXPECT_TRUE(exists(f)) << f;
  const auto vnode = table(path("points.1.v.node"));
  EXPECT_EQ(vnode[0][0], "6");  // one Voronoi vertex per triangle
  const auto vedge = table(path("points.1.v.edge"));
  EXPECT_EQ(vedge[0][0], "11");  // one Voronoi edge per Delaunay edge: V + T - 1
  EXPECT_EQ(slurp(path("points.1.off")).rfind("OFF", 0), 0u);
  r = run("--output=points.xyz points.node");
  EXPECT_EQ(r.code, 1);
  EXPECT_CONTAINS(r.err, "points.xyz");
}

TEST_F(Cli, OutputWritesOnlyTheNamedFiles) {
  data("square_hole.poly");
  Result r = run("-pq --output=sq.msh --msh-version=2.2 --output sq.vtu --vtu-binary square_hole");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(listing(), (std::vector<std::string>{"sq.msh", "sq.vtu", "square_hole.poly"}));
  EXPECT_EQ(slurp(path("sq.msh")).rfind("$MeshFormat\n2.2 0 8", 0), 0u) << slurp(path("sq.msh")).substr(0, 40);
  EXPECT_CONTAINS(slurp(path("sq.vtu")), "binary");
  r = run("-p --output=sq4.msh square_hole");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(path("sq4.msh")).rfind("$MeshFormat\n4.1 0 8", 0), 0u);
  r = run("-p --msh-version=3 --output=x.msh square_hole");
  EXPECT_EQ(r.code, 1);
  EXPECT_CONTAINS(r.err, "--msh-version");
  // Voronoi overlay and segment lines in the GeoJSON output.
  r = run("-pq --voronoi-overlay --geojson-segments --output=sq.geojson --output=sq.svg square_hole");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string gj = slurp(path("sq.geojson"));
  EXPECT_CONTAINS(gj, "voronoi_cell");
  EXPECT_CONTAINS(gj, "LineString");
  EXPECT_FALSE(exists("square_hole.1.node"));
}

TEST_F(Cli, UnknownOutputExtensionWritesNothing) {
  data("square_hole.poly");
  const Result r = run("-p --output=good.msh --output=bad.xyz square_hole");
  EXPECT_EQ(r.code, 1);
  EXPECT_CONTAINS(r.err, "bad.xyz");
  EXPECT_EQ(listing(), (std::vector<std::string>{"square_hole.poly"}));
}

TEST_F(Cli, GeoJsonInput) {
  // A square with a square hole (named "a") beside a triangle (named "b").
  write("map.geojson", R"({"type": "FeatureCollection", "features": [
    {"type": "Feature", "properties": {"name": "a", "maxa": 0.5},
     "geometry": {"type": "Polygon", "coordinates": [[[0,0],[4,0],[4,4],[0,4],[0,0]],
                                                      [[1,1],[1,3],[3,3],[3,1],[1,1]]]}},
    {"type": "Feature", "properties": {"name": "b"},
     "geometry": {"type": "Polygon", "coordinates": [[[4,0],[6,0],[4,4],[4,0]]]}},
    {"type": "Feature", "properties": {}, "geometry": {"type": "Point", "coordinates": [9,9]}}]})");
  Result r = run("-V map.geojson");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(listing(), (std::vector<std::string>{"map.1.ele", "map.1.node", "map.1.poly", "map.geojson"}));
  EXPECT_CONTAINS(r.out, "GeoJSON: 3 features, 2 polygons, 3 rings (1 hole)");
  EXPECT_CONTAINS(r.out, "1 other geometry skipped");
  // 9 vertices (the shared border's two merged); the hole is removed
  // (even-odd): 8 triangles around it and the adjacent triangle.
  const auto ele = table(path("map.1.ele"));
  const auto node = table(path("map.1.node"));
  EXPECT_EQ(node[0][0], "9");
  EXPECT_EQ(ele[0][0], "9");
  // Regional attributes from a string property: a=1, b=2.
  r = run("-V --region-property=name --area-property maxa -qa map.geojson");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_CONTAINS(r.out, "categories: 1=a 2=b");
  const auto ele2 = table(path("map.1.ele"));
  ASSERT_GE(ele2[0].size(), 3u);
  EXPECT_EQ(ele2[0][2], "1");  // one attribute per triangle
  bool saw1 = false, saw2 = false;
  for (std::size_t i = 1; i < ele2.size(); ++i) {
    saw1 |= ele2[i].back() == "1";
    saw2 |= ele2[i].back() == "2";
  }
  EXPECT_TRUE(saw1);
  EXPECT_TRUE(saw2);
  // The area property alone refines to its bound (0.5 in polygon a).
  r = run("--area-property=maxa -Q map.geojson");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_GT(std::stol(table(path("map.1.ele"))[0][0]), 20);
  r = run("--output=map.vtu map.json");
  EXPECT_EQ(r.code, 2);  // no such file
  r = run("-r map.geojson");
  EXPECT_EQ(r.code, 1);
}

TEST_F(Cli, AlgorithmChoicesAreAcceptedWithANote) {
  data("points.node");
  Result r = run("-iFlXsV points.node");
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* n : {"Note: -i", "Note: -F", "Note: -l", "Note: -X", "Note: -s"}) EXPECT_CONTAINS(r.out, n);
  r = run("-iFlQ points.node");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  r = run("--incremental --sweepline --vertical-cuts --no-exact -Q points.node");
  EXPECT_EQ(r.code, 0) << r.err;
}

TEST_F(Cli, LongOptionsForSwitches) {
  data("square_hole.poly");
  const Result r = run("--poly --min-angle=30.5 --max-area=0.01 --zero-based --quiet square_hole");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(r.out.empty());
  const auto node = table(path("square_hole.1.node"));
  EXPECT_EQ(node[1][0], "0");
  const Result s = run("-pq30.5a0.01zQ square_hole");
  ASSERT_EQ(s.code, 0) << s.err;
  EXPECT_EQ(table(path("square_hole.1.node")), node);  // the same mesh
}

// ---------------------------------------------------------------------------
// -p and the domain switches

TEST_F(Cli, PolyWritesNodeElePoly) {
  data("square_hole.poly");
  const Result r = run("-p square_hole.poly");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(exists("square_hole.1.node"));
  EXPECT_TRUE(exists("square_hole.1.ele"));
  ASSERT_TRUE(exists("square_hole.1.poly"));
  const auto ele = table(path("square_hole.1.ele"));
  EXPECT_EQ(ele[0][2], "0");  // no attributes without -A
  // The ring [0,4]^2 minus [1,3]^2 with all 12 vertices in use on its two
  // boundaries (the cut ends split the hole's sides): T = V + 2h - 2 = 12.
  EXPECT_EQ(ele[0][0], "12");
  const auto poly = table(path("square_hole.1.poly"));
  EXPECT_EQ(poly[0][0], "0");  // vertices are in the .node file
  // 6 outer + 6 hole pieces + 2 cuts.
  EXPECT_EQ(poly[1][0], "14");
  // Segment markers carried: outer 3, hole 2, cuts 0.
  int threes = 0, twos = 0, zeros = 0;
  for (std::size_t i = 2; i < 2 + 14; ++i) {
    threes += poly[i][3] == "3";
    twos += poly[i][3] == "2";
    zeros += poly[i][3] == "0";
  }
  EXPECT_EQ(threes, 6);
  EXPECT_EQ(twos, 6);
  EXPECT_EQ(zeros, 2);
  // Then the input's hole and regions, so the .poly describes the same domain.
  ASSERT_EQ(poly.size(), 2u + 14u + 1u + 1u + 1u + 2u);
  EXPECT_EQ(poly[16], (std::vector<std::string>{"1"}));
  EXPECT_EQ(poly[17], (std::vector<std::string>{"1", "2", "2.5"}));
  EXPECT_EQ(poly[18], (std::vector<std::string>{"2"}));
  EXPECT_EQ(poly[20], (std::vector<std::string>{"2", "0.5", "3.5", "2", "0.5"}));
  // The unused vertex in the hole stays in the .node file (as in Triangle).
  EXPECT_EQ(table(path("square_hole.1.node"))[0][0], "13");
}

TEST_F(Cli, NoPolyJettisonAndRegionalAttributes) {
  data("square_hole.poly");
  const Result r = run("-pPjA square_hole");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_FALSE(exists("square_hole.1.poly"));
  EXPECT_EQ(table(path("square_hole.1.node"))[0][0], "12");  // vertex 9 in the hole dropped
  const auto ele = table(path("square_hole.1.ele"));
  ASSERT_EQ(ele[0][2], "1");
  int ones = 0, twos = 0;
  for (std::size_t i = 1; i < ele.size(); ++i) {
    ones += ele[i][4] == "1";
    twos += ele[i][4] == "2";
  }
  EXPECT_EQ(ones + twos, 12);
  EXPECT_GT(ones, 0);
  EXPECT_GT(twos, 0);
}

TEST_F(Cli, IgnoreHolesAndEvenOdd) {
  data("square_hole.poly");
  Result r = run("-pO square_hole");
  ASSERT_EQ(r.code, 0) << r.err;
  // The hole is meshed too: 13 vertices, 6 on the boundary: 2*13 - 2 - 6.
  EXPECT_EQ(table(path("square_hole.1.ele"))[0][0], "18");
  r = run("-pO --fill=evenodd square_hole");  // even-odd needs no hole point
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(table(path("square_hole.1.ele"))[0][0], "12");
}

TEST_F(Cli, EmptyDomainIsSuccess) {
  data("open.poly");
  Result r = run("-p open");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_CONTAINS(r.err, "empty");
  EXPECT_EQ(table(path("open.1.ele"))[0][0], "0");
  r = run("-pc open");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(table(path("open.1.ele"))[0][0], "4");
}

TEST_F(Cli, CrossingSegmentsAndStrict) {
  data("crossing.poly");
  Result r = run("-pV crossing.poly");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_CONTAINS(r.out, "intersections resolved:    1");
  EXPECT_EQ(table(path("crossing.1.node"))[0][0], "5");
  EXPECT_EQ(table(path("crossing.1.ele"))[0][0], "4");
  fs::remove(path("crossing.1.node"));
  fs::remove(path("crossing.1.ele"));
  fs::remove(path("crossing.1.poly"));
  r = run("-p --strict crossing.poly");
  EXPECT_EQ(r.code, 2);
  EXPECT_CONTAINS(r.err, "segments 5 and 6 cross");  // 1-based like the file
  EXPECT_FALSE(exists("crossing.1.node"));
}

TEST_F(Cli, CdtMethods) {
  data("square_hole.poly");
  for (const char* m : {"fast", "ct", "lawson", "lifting"}) {
    const Result r = run(std::string("-pQ --cdt=") + m + " square_hole");
    ASSERT_EQ(r.code, 0) << m << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;  // -Q
    EXPECT_EQ(table(path("square_hole.1.ele"))[0][0], "12") << m;
  }
  const Result bad = run("-p --cdt=magic square_hole");
  EXPECT_EQ(bad.code, 1);
  EXPECT_CONTAINS(bad.err, "--cdt=magic");
}

TEST_F(Cli, VerboseReportsPhasesAndCounts) {
  data("square_hole.poly");
  const Result r = run("-pV square_hole");
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* s : {"input vertices:", "input segments:", "intersections resolved:", "vertices on segments:",
                        "duplicate vertices merged:", "holes:", "triangles:", "Timings:", "constrained triangulation",
                        "domain", "write"})
    EXPECT_CONTAINS(r.out, s);
  EXPECT_CONTAINS(r.out, "vertices on segments:      2");
}

TEST_F(Cli, CheckSwitch) {
  data("square_hole.poly");
  data("points.node");
  Result r = run("-pC square_hole");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_CONTAINS(r.out, "Check: mesh is valid");
  r = run("-C points");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_CONTAINS(r.out, "mesh is valid");
}

// Two triangles sharing no vertex that overlap like a star of David: -r
// refuses the mesh, naming both in the file's numbering and their .ele lines.
TEST_F(Cli, RefineRefusesOverlappingTriangles) {
  write("star.node", "6 2 0 0\n1 0 0\n2 2 0\n3 1 1.8\n4 0 1.2\n5 2 1.2\n6 1 -0.6\n");
  write("star.ele", "# two triangles\n2 3 0\n1 1 2 3\n\n2 4 6 5\n");
  Result r = run("-rC star");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_CONTAINS(r.err, "star.ele:3: triangles 1 and 2 (line 5) overlap");
  EXPECT_FALSE(exists("star.1.ele"));
  // A triangle inside another, zero-based file.
  write("nest.node", "6 2 0 0\n0 0 0\n1 4 0\n2 0 4\n3 1 1\n4 2 1\n5 1 2\n");
  write("nest.ele", "2 3 0\n0 0 1 2\n1 3 4 5\n");
  r = run("-r nest");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_CONTAINS(r.err, "nest.ele:2: triangles 0 and 1 (line 3) overlap");
  // Side by side they are a valid mesh.
  write("pair.node", "4 2 0 0\n1 0 0\n2 1 0\n3 1 1\n4 0 1\n");
  write("pair.ele", "2 3 0\n1 1 2 3\n2 1 3 4\n");
  r = run("-rC pair");
  EXPECT_EQ(r.code, 0) << r.err;
}

TEST_F(Cli, RefineReadsMeshAndWritesNextIteration) {
  data("square_hole.poly");
  Result r = run("-pA square_hole");
  ASSERT_EQ(r.code, 0) << r.err;
  r = run("-rpCe square_hole.1");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(exists("square_hole.2.node"));
  EXPECT_TRUE(exists("square_hole.2.edge"));
  ASSERT_TRUE(exists("square_hole.2.poly"));
  EXPECT_EQ(table(path("square_hole.2.ele")), table(path("square_hole.1.ele")));  // attributes kept
  EXPECT_EQ(table(path("square_hole.2.poly"))[1][0], "14");
  EXPECT_EQ(table(path("square_hole.2.node")), table(path("square_hole.1.node")));
  // -r without FILE.ele: a clear error.
  fs::remove(path("square_hole.2.ele"));
  r = run("-r square_hole.2");
  EXPECT_EQ(r.code, 2);
  EXPECT_CONTAINS(r.err, "square_hole.2.ele");
}

// -r -p: the .poly's segments that are not edges of the mesh are inserted
// (new constraints on an old mesh), its holes carved.

// square_hole.1.poly (from -p square_hole) with segments appended.
std::string poly_with(const std::vector<std::vector<std::string>>& rows, const std::vector<std::string>& extra) {
  const std::size_t ns = std::stoul(rows[1][0]);
  std::string text;
  auto line = [&](const std::vector<std::string>& row) {
    for (std::size_t i = 0; i < row.size(); ++i) text += (i ? " " : "") + row[i];
    text += "\n";
  };
  line(rows[0]);
  text += std::to_string(ns + extra.size()) + " 1\n";
  for (std::size_t i = 2; i < 2 + ns; ++i) line(rows[i]);
  for (std::size_t i = 0; i < extra.size(); ++i) text += std::to_string(ns + 1 + i) + " " + extra[i] + "\n";
  for (std::size_t i = 2 + ns; i < rows.size(); ++i) line(rows[i]);
  return text;
}

TEST_F(Cli, RefineInsertsNewPolySegments) {
  data("square_hole.poly");
  ASSERT_EQ(run("-pQ square_hole").code, 0);
  const auto rows = table(path("square_hole.1.poly"));
  fs::copy_file(path("square_hole.1.node"), path("inner.node"));
  fs::copy_file(path("square_hole.1.ele"), path("inner.ele"));
  // Vertex 2 (4,0) to vertex 5 (1,1): across the lower part of the ring.
  write("inner.poly", poly_with(rows, {"2 5 7"}));
  Result r = run("-rpC inner");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_CONTAINS(r.out, "1 inserted");
  EXPECT_CONTAINS(r.out, "15 segments present");
  const auto poly = table(path("inner.1.poly"));
  EXPECT_TRUE(std::any_of(poly.begin(), poly.end(), [](const auto& row) {
    return row.size() == 4 && ((row[1] == "2" && row[2] == "5") || (row[1] == "5" && row[2] == "2")) && row[3] == "7";
  }));
  EXPECT_EQ(table(path("inner.1.node")), table(path("inner.node")));  // no vertex added

  // Refinement keeps it: the marker-7 edges form a straight path from 2 to 5.
  r = run("-rpq30C inner");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_CONTAINS(r.out, "mesh is valid");
  const auto node = table(path("inner.1.node"));
  std::map<std::string, std::vector<std::string>> next;
  for (const auto& row : table(path("inner.1.poly")))
    if (row.size() == 4 && row[3] == "7") {
      next[row[1]].push_back(row[2]);
      next[row[2]].push_back(row[1]);
    }
  ASSERT_GE(next.size(), 3u);  // split by refinement
  auto xy = [&](const std::string& id) {
    const auto& row = node[std::stoul(id)];
    return std::pair<double, double>{std::stod(row[1]), std::stod(row[2])};
  };
  std::string prev, cur = "2";
  std::size_t steps = 0;
  while (cur != "5" && steps++ < next.size()) {
    ASSERT_EQ(next[cur].size(), cur == "2" ? 1u : 2u) << cur;
    const std::string nxt = next[cur][0] == prev ? next[cur].back() : next[cur][0];
    const auto [x, y] = xy(nxt);
    EXPECT_NEAR((x - 4) * (1 - 0) - (y - 0) * (1 - 4), 0.0, 1e-9) << nxt;  // on the line (4,0)-(1,1)
    prev = cur;
    cur = nxt;
  }
  EXPECT_EQ(cur, "5");
}

TEST_F(Cli, RefineInsertsSegmentsCrossingOldOnes) {
  data("square_hole.poly");
  ASSERT_EQ(run("-pQ square_hole").code, 0);
  const auto rows = table(path("square_hole.1.poly"));
  fs::copy_file(path("square_hole.1.node"), path("cross.node"));
  fs::copy_file(path("square_hole.1.ele"), path("cross.ele"));
  // Vertex 1 (0,0) to vertex 8 (1,3) crosses the cut from (0,2) to (1,2).
  write("cross.poly", poly_with(rows, {"1 8 9"}));
  Result r = run("-rpC cross");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_CONTAINS(r.out, "1 vertex added");
  EXPECT_CONTAINS(r.out, "mesh is valid");
  const auto node = table(path("cross.1.node"));
  ASSERT_EQ(node[0][0], "14");
  EXPECT_NEAR(std::stod(node[14][1]), 2.0 / 3.0, 1e-12);
  EXPECT_EQ(node[14][2], "2");
  EXPECT_EQ(node[14][3], "9");  // the marker of the segment it lies on (the cut's is 0)
  // --strict: the crossing is an error naming both segments.
  r = run("-rp --strict cross");
  EXPECT_EQ(r.code, 2);
  EXPECT_CONTAINS(r.err, "cross.poly: segments 1 and 15 cross");
}

TEST_F(Cli, RefineRejectsSegmentsLeavingTheMesh) {
  data("square_hole.poly");
  ASSERT_EQ(run("-pQ square_hole").code, 0);
  const auto rows = table(path("square_hole.1.poly"));
  fs::copy_file(path("square_hole.1.node"), path("out.node"));
  fs::copy_file(path("square_hole.1.ele"), path("out.ele"));
  // Vertex 1 (0,0) to vertex 7 (3,3): through the hole.
  write("out.poly", poly_with(rows, {"1 7 0"}));
  Result r = run("-rpq out");
  EXPECT_EQ(r.code, 2);
  // Line 17: header, segment count line, 14 segments, then this one.
  EXPECT_CONTAINS(r.err, "out.poly:17: segment 15 (vertices 1-7) leaves the mesh");
  EXPECT_FALSE(exists("out.1.node"));
  EXPECT_FALSE(exists("out.1.ele"));
  EXPECT_FALSE(exists("out.1.poly"));
  // An endpoint that does not exist is a parse error of the .poly already.
  write("out.poly", poly_with(rows, {"1 99 0"}));
  r = run("-rp out");
  EXPECT_EQ(r.code, 2);
  EXPECT_CONTAINS(r.err, "out.poly:17");
}

TEST_F(Cli, RefineCarvesNewHolesAndAssignsRegions) {
  write("sq.poly",
        "8 2 0 0\n1 0 0\n2 4 0\n3 4 4\n4 0 4\n5 1 1\n6 3 1\n7 3 3\n8 1 3\n"
        "4 1\n1 1 2 1\n2 2 3 1\n3 3 4 1\n4 4 1 1\n0\n");
  ASSERT_EQ(run("-pQ sq").code, 0);
  // The inner square as new segments, a hole point in it, a region seed
  // outside it.
  write("sq.1.poly",
        "0 2 0 1\n8 1\n1 1 2 1\n2 2 3 1\n3 3 4 1\n4 4 1 1\n5 5 6 2\n6 6 7 2\n7 7 8 2\n8 8 5 2\n"
        "1\n1 2 2\n1\n1 0.5 0.5 5 0\n");
  Result r = run("-rpAC sq.1");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_CONTAINS(r.out, "1 hole carved");
  EXPECT_CONTAINS(r.out, "mesh is valid");
  const auto ele = table(path("sq.2.ele"));
  EXPECT_EQ(ele[0], (std::vector<std::string>{"8", "3", "1"}));  // the ring of 8 vertices
  for (std::size_t i = 1; i < ele.size(); ++i) EXPECT_EQ(ele[i][4], "5");
  EXPECT_EQ(table(path("sq.2.poly"))[1][0], "8");
  // The hole is in the output .poly: reading it back carves nothing more.
  r = run("-rpAC sq.2");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(table(path("sq.3.ele")), ele);

  // -rpA on a -pA mesh: the same attributes again, not a second column.
  data("square_hole.poly");
  ASSERT_EQ(run("-pAQ square_hole").code, 0);
  ASSERT_EQ(run("-rpAQ square_hole.1").code, 0);
  EXPECT_EQ(table(path("square_hole.2.ele")), table(path("square_hole.1.ele")));
}

// A mesh from another tool need not be Delaunay: -r writes it as it is, and
// flips it to a constrained Delaunay triangulation before refining it.
TEST_F(Cli, RefiningANonDelaunayMeshFlipsItFirst) {
  // A fan from vertex 1 over 12 points on a slightly squashed circle.
  std::string node = "12 2 0 0\n", ele = "10 3 0\n";
  for (int i = 0; i < 12; ++i) {
    const double a = 2 * 3.141592653589793 * i / 12;
    node += std::to_string(i + 1) + " " + std::to_string(10 * std::cos(a)) + " " + std::to_string(7 * std::sin(a)) + "\n";
  }
  for (int i = 2; i < 12; ++i)
    ele += std::to_string(i - 1) + " 1 " + std::to_string(i) + " " + std::to_string(i + 1) + "\n";
  write("fan.node", node);
  write("fan.ele", ele);
  Result r = run("-rC fan");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(table(path("fan.1.ele")), table(path("fan.ele")));  // as read
  r = run("-rq25CV fan");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_CONTAINS(r.out, "mesh is valid");  // Delaunay checked after refinement
  EXPECT_EQ(r.out.find("Delaunay flips:            0"), std::string::npos) << r.out;
}

// ---------------------------------------------------------------------------
// Switch parsing

TEST_F(Cli, NumbersAttachedToSwitchesParse) {
  data("square_hole.poly");
  // q and a take numbers; z and Q after them are switches again.
  const Result r = run("-pq30.5a0.01zQ square_hole");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(exists("square_hole.1.node"));
  // -u is parsed, then refused (a size function compiled in).
  const Result s = run("-pS100uY square_hole");
  EXPECT_EQ(s.code, 1);
  EXPECT_CONTAINS(s.err, "-u");
  EXPECT_CONTAINS(s.err, "not available");
}

TEST_F(Cli, SecondOrderTriangles) {
  data("square_hole.poly");
  const Result r = run("-pS100o2Ye --output=sq.msh --output=sq.vtu square_hole");
  ASSERT_EQ(r.code, 0) << r.err;
  // --output given: only the named files and -e's.
  EXPECT_EQ(listing(), (std::vector<std::string>{"sq.msh", "sq.vtu", "square_hole.1.edge", "square_hole.poly"}));
  EXPECT_CONTAINS(slurp(path("sq.vtu")), "22");  // VTK_QUADRATIC_TRIANGLE
  const Result t = run("-pqo2 square_hole");
  ASSERT_EQ(t.code, 0) << t.err;
  const auto ele = table(path("square_hole.1.ele"));
  const auto node = table(path("square_hole.1.node"));
  ASSERT_GE(ele.size(), 2u);
  EXPECT_EQ(ele[0][1], "6");
  EXPECT_EQ(ele[1].size(), 7u);  // index, 3 corners, 3 midside nodes
  // Every node index is a vertex of the .node file; the midside nodes come
  // after the corners' vertices.
  const long nv = std::stol(node[0][0]);
  for (std::size_t i = 1; i < ele.size(); ++i)
    for (std::size_t k = 1; k < 7; ++k) EXPECT_LE(std::stol(ele[i][k]), nv);
  EXPECT_GT(std::stol(ele[1][4]), std::stol(ele[1][1]));
}

// -r on a 6-node mesh refines the corner mesh: the old midpoint nodes are
// dropped with a warning (Triangle would keep them as vertices in no
// triangle), and -o2 writes new ones.
TEST_F(Cli, RefiningASixNodeMeshDropsItsMidpoints) {
  data("square_hole.poly");
  ASSERT_EQ(run("-pqQ square_hole").code, 0);
  const long corners = std::stol(table(path("square_hole.1.node"))[0][0]);
  ASSERT_EQ(run("-pqo2Q square_hole").code, 0);
  const long with_mid = std::stol(table(path("square_hole.1.node"))[0][0]);
  ASSERT_GT(with_mid, corners);

  Result r = run("-rpo2 square_hole.1");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_CONTAINS(r.err, "6-node triangles; " + std::to_string(with_mid - corners) + " midpoint nodes dropped");
  // Same mesh again, not midpoints of midpoints.
  EXPECT_EQ(std::stol(table(path("square_hole.2.node"))[0][0]), with_mid);
  EXPECT_EQ(table(path("square_hole.2.ele"))[0][1], "6");
  EXPECT_EQ(slurp(path("square_hole.2.ele")), slurp(path("square_hole.1.ele")));

  r = run("-rqa0.1C square_hole.1");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_CONTAINS(r.err, "midpoint nodes dropped");
  EXPECT_CONTAINS(r.out, "mesh is valid");
  const auto node = table(path("square_hole.2.node"));
  const auto ele = table(path("square_hole.2.ele"));
  EXPECT_EQ(ele[0][1], "3");
  // Every vertex but the input's unused one (in the hole) is a corner.
  std::set<std::string> used;
  for (std::size_t i = 1; i < ele.size(); ++i) used.insert(ele[i].begin() + 1, ele[i].begin() + 4);
  EXPECT_EQ(used.size() + 1, std::stoul(node[0][0]));
  EXPECT_TRUE(run("-rQ square_hole.1").err.empty());  // -Q: no warning
}

TEST_F(Cli, UsageErrors) {
  data("points.node");
  Result r = run("-K points.node");
  EXPECT_EQ(r.code, 1);
  EXPECT_CONTAINS(r.err, "unknown switch -K");
  r = run("-p3 points.node");
  EXPECT_EQ(r.code, 1);
  EXPECT_CONTAINS(r.err, "number '3'");
  r = run("-o3 points.node");
  EXPECT_EQ(r.code, 1);
  EXPECT_CONTAINS(r.err, "-o must be followed by 2");
  r = run("--fill=zigzag points.node");
  EXPECT_EQ(r.code, 1);
  r = run("points.node other.node");
  EXPECT_EQ(r.code, 1);
  r = run("");
  EXPECT_EQ(r.code, 1);
  EXPECT_CONTAINS(r.err, "no input file");
  r = run("--help");
  EXPECT_EQ(r.code, 0);
  EXPECT_CONTAINS(r.out, "Exit codes");
  EXPECT_EQ(listing(), (std::vector<std::string>{"points.node"}));
}

// ---------------------------------------------------------------------------
// Input errors and partial output

TEST_F(Cli, MissingInput) {
  Result r = run("nothing.node");
  EXPECT_EQ(r.code, 2);
  EXPECT_CONTAINS(r.err, "cannot open input file 'nothing.node'");
  r = run("-p nothing");
  EXPECT_EQ(r.code, 2);
  EXPECT_CONTAINS(r.err, "nothing.poly");
  EXPECT_TRUE(listing().empty());
}

TEST_F(Cli, MalformedInputNamesFileAndLine) {
  data("bad.node");
  const Result r = run("bad.node");
  EXPECT_EQ(r.code, 2);
  EXPECT_CONTAINS(r.err, "bad.node:4:");
  EXPECT_CONTAINS(r.err, "coordinate");
  EXPECT_EQ(listing(), (std::vector<std::string>{"bad.node"}));  // nothing written
}

TEST_F(Cli, CollinearInputIsAnInputError) {
  write("line.node", "3 2 0 0\n1 0 0\n2 1 1\n3 2 2\n");
  const Result r = run("line.node");
  EXPECT_EQ(r.code, 2);
  EXPECT_CONTAINS(r.err, "collinear");
  EXPECT_EQ(listing(), (std::vector<std::string>{"line.node"}));
}

TEST_F(Cli, UnwritableOutputLeavesNoPartialFile) {
  data("points.node");
  fs::create_directory(path("points.1.ele"));  // the .ele cannot be written
  const Result r = run("points.node");
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_CONTAINS(r.err, "points.1.ele");
  // The .node written before is complete; no temporary file is left behind.
  for (const std::string& name : listing()) {
    EXPECT_EQ(name.find(".tmp"), std::string::npos) << name;
    EXPECT_NE(name.front(), '.') << name;
  }
  if (exists("points.1.node")) {
    EXPECT_EQ(table(path("points.1.node")).size(), 7u);
  }
}

}  // namespace
