// What a new user trips over (issue "No surprises"): messages in the user's
// numbering, options with no effect said once, --stats=json machine-readable
// and documented, exponents in switch numbers, summary wording. Each test
// runs the command line as a process in a temporary directory; meshes it
// writes are checked with -C and read back through deltamesh::check().
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "deltamesh/quality.hpp"
#include "deltamesh/triangle_io.hpp"
#include "deltamesh/triangulate.hpp"
#include "deltamesh/validate.hpp"
#include "support/cli_fixture.hpp"

namespace fs = std::filesystem;

namespace {

using deltamesh::test::slurp;
using Result = deltamesh::test::CliResult;

std::size_t occurrences(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (std::size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++n;
  return n;
}

class Surprises : public deltamesh::test::CliDirTest {
 protected:
  Surprises() : CliDirTest("deltamesh_surprises") {}

  void example(const std::string& name) const {
    fs::copy_file(fs::path(DELTAMESH_SOURCE_DIR) / "examples" / name, dir_ / name,
                  fs::copy_options::overwrite_existing);
  }
  Result run(const std::string& args) const { return run_program(DELTAMESH_CLI, args); }

  // BASE.node + BASE.ele read back and validated; returns the mesh.
  deltamesh::Mesh read_back(const std::string& base) const {
    const deltamesh::Pslg nodes = deltamesh::read_node(path(base + ".node").string());
    const deltamesh::EleData ele = deltamesh::read_ele(path(base + ".ele").string(), nodes.first_index);
    deltamesh::Mesh m = deltamesh::mesh_from_triangles(nodes, ele.triangles, ele.num_attributes, ele.attributes);
    const deltamesh::CheckReport rep = deltamesh::check(m, {.delaunay = false, .convex_hull = false});
    EXPECT_TRUE(rep.ok()) << base << ": " << rep.summary();
    return m;
  }
};

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE((haystack).find(needle), std::string::npos) << "expected '" << (needle) << "' in:\n" << (haystack)
#define EXPECT_LACKS(haystack, needle) \
  EXPECT_EQ((haystack).find(needle), std::string::npos) << "did not expect '" << (needle) << "' in:\n" << (haystack)

// The unit square, 1-based; kSquareHoles adds the hole count line.
const std::string kSquare = "4 2 0 0\n1 0 0\n2 1 0\n3 1 1\n4 0 1\n4 0\n1 1 2\n2 2 3\n3 3 4\n4 4 1\n";
const std::string kSquareHoles = kSquare + "0\n";

// ---------------------------------------------------------------------------
// Why 2: a misspelled long option is named as unknown, with a suggestion
// (the Python switch-string case is in python/tests).

TEST_F(Surprises, MisspelledLongOptionsWithAValueAreUnknown) {
  write("sq.poly", kSquareHoles);
  for (const auto& [given, suggested] : {std::pair{"--time-limt=5", "--time-limit"}, std::pair{"--cdtt=ct", "--cdt"},
                                         std::pair{"--outptu=x.msh", "--output"}}) {
    const Result r = run(std::string("-p ") + given + " sq");
    EXPECT_EQ(r.code, 1) << given;
    EXPECT_CONTAINS(r.err, std::string("unknown option ") + std::string(given).substr(0, std::string(given).find('=')));
    EXPECT_CONTAINS(r.err, std::string("did you mean ") + suggested + "?");
    EXPECT_LACKS(r.err, "takes no value");
  }
}

// ---------------------------------------------------------------------------
// Why 4: no silent no-ops.

TEST_F(Surprises, OptionsWithoutEffectSaySoOnce) {
  write("sq.poly", kSquareHoles);
  const Result r = run("-pC --msh-version=2.2 --vtu-binary --geojson-segments --voronoi-overlay -Y --steiner=circumcenter "
                       "--region-property=name sq");
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* what : {"--msh-version has no effect: no .msh output", "--vtu-binary has no effect: no .vtu output",
                           "--geojson-segments has no effect: no GeoJSON output", "--voronoi-overlay has no effect",
                           "-Y has no effect: nothing is refined", "--steiner has no effect: nothing is refined",
                           "--region-property has no effect: it reads a property of GeoJSON features"})
    EXPECT_EQ(occurrences(r.err, what), 1u) << what << " in:\n" << r.err;
  EXPECT_CONTAINS(r.out, "Check: mesh is valid");
  read_back("sq.1");
  // With the matching outputs and refinement: not a word.
  const Result used = run("-pqC -Y --msh-version=2.2 --vtu-binary --geojson-segments --voronoi-overlay "
                          "--output sq.msh --output sq.vtu --output sq.geojson sq");
  ASSERT_EQ(used.code, 0) << used.err;
  EXPECT_LACKS(used.err, "has no effect");
  // -Q silences them.
  EXPECT_EQ(run("-pQ -Y sq").err, "");
}

TEST_F(Surprises, GeoJsonPropertiesThatNoFeatureHasAreNamed) {
  write("two.geojson", R"({"type":"FeatureCollection","features":[
    {"type":"Feature","properties":{"name":"a","area":0.05},"geometry":{"type":"Polygon","coordinates":[[[0,0],[1,0],[1,1],[0,1],[0,0]]]}},
    {"type":"Feature","properties":{"name":"b"},"geometry":{"type":"Polygon","coordinates":[[[1,0],[2,0],[2,1],[1,1],[1,0]]]}}]})");
  Result r = run("-C --region-property=nosuch --area-property=nosuch two.geojson");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_CONTAINS(r.err, "--region-property=nosuch has no effect: no polygon's feature has a property \"nosuch\"");
  EXPECT_CONTAINS(r.err, "--area-property=nosuch has no effect: no polygon's feature has a property \"nosuch\"");
  read_back("two.1");
  r = run("-C --region-property=name --area-property=area two.geojson");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_LACKS(r.err, "has no effect");
}

// -r without -p on a mesh with regional attributes: we warn (Triangle's -r
// does the same thing silently); with -p the interface is a segment and
// every triangle keeps its side's attribute.
TEST_F(Surprises, RefiningAnAttributedMeshWithoutItsSegmentsWarns) {
  example("plate.poly");
  ASSERT_EQ(run("-pAQ plate").code, 0);
  Result r = run("-rq30a0.05C plate.1");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(occurrences(r.err, "the triangle attributes differ across"), 1u) << r.err;
  EXPECT_CONTAINS(r.err, "give -p");
  read_back("plate.2");
  r = run("-rpq30a0.05C plate.1");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_LACKS(r.err, "attributes differ");
  // With -p the attribute follows the side of x = 5.5 (region 1 left, 2 right).
  const deltamesh::Mesh m = read_back("plate.2");
  ASSERT_EQ(m.num_triangle_attributes(), 1u);
  std::size_t wrong = 0;
  for (deltamesh::TriId t = 0; t < m.num_triangle_slots(); ++t) {
    if (!m.is_real(t)) continue;
    double cx = 0;
    for (auto v : m.triangle(t)) cx += m.point(v).x / 3;
    if (m.triangle_attributes()[t] != (cx < 5.5 ? 1.0 : 2.0)) ++wrong;
  }
  EXPECT_EQ(wrong, 0u);
  // No attributes to lose, no warning.
  ASSERT_EQ(run("-pQ plate").code, 0);
  EXPECT_LACKS(run("-rq30 plate.1").err, "attributes differ");
}

// ---------------------------------------------------------------------------
// Why 5: the user's numbering, the right file and line; ignored hole and
// region points identified.

TEST_F(Surprises, AVertexErrorNamesTheFileLineAndNumber) {
  // A coordinate the predicates cannot take (nonzero, 2^400 below the
  // largest): the vertex as the file numbers it (3, 1-based; was "point 2"),
  // and its line.
  write("big.node", "# four points\n4 2 0 0\n1 0 0\n2 1e300 0\n3 0 1\n4 1e300 1e300\n");
  Result r = run("big");
  EXPECT_EQ(r.code, 2);
  EXPECT_CONTAINS(r.err, "big.node:5: vertex 3: coordinate y (1)");
  write("big0.node", "4 2 0 0\n0 0 0\n1 1e-300 0\n2 0 1\n3 1 1\n");
  r = run("big0");
  EXPECT_EQ(r.code, 2);
  EXPECT_CONTAINS(r.err, "big0.node:3: vertex 1: coordinate x");
  // In a .poly that lists its vertices, the .poly's line.
  write("badp.poly", "4 2 0 0\n1 0 0\n2 1 0\n3 1 1\n4 0 1e-250\n0 0\n0\n");
  r = run("-p badp");
  EXPECT_EQ(r.code, 2);
  EXPECT_CONTAINS(r.err, "badp.poly:5: vertex 4: coordinate y");
}

TEST_F(Surprises, IgnoredHoleAndRegionPointsAreIdentified) {
  write("sq.poly", kSquare + "1\n1 5 5\n2\n1 0.25 0.5 7 0\n2 9 9 8 0\n");
  const Result r = run("-pAC sq");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_CONTAINS(r.err, "hole point 1 at (5, 5) ignored");
  EXPECT_CONTAINS(r.err, "region point 2 at (9, 9) ignored");
}

// ---------------------------------------------------------------------------
// Why 7: --stats=json is machine-readable, its schema documented.

TEST_F(Surprises, StatsJsonIsAloneOnStdout) {
  example("plate.poly");
  Result r = run("-pq30C --stats=json plate");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);  // throws unless stdout is JSON alone
  EXPECT_EQ(j["schema"], "deltamesh-stats");
  EXPECT_EQ(j["schema_version"], deltamesh::kStatsSchemaVersion);
  EXPECT_GE(j["min_angle_deg"].get<double>(), 30.0);
  EXPECT_CONTAINS(r.err, "Quality mesh:");  // the summary went to stderr
  EXPECT_CONTAINS(r.err, "Check: mesh is valid");
  const deltamesh::Mesh m = read_back("plate.1");
  EXPECT_EQ(j["triangles"].get<std::size_t>(), m.num_triangles());

  // A bare --stats is json and leaves the next argument alone (the input).
  r = run("-pq30 --stats plate");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["triangles"], j["triangles"]);

  // To a file: stdout keeps the summary, the file holds the JSON only.
  r = run("-pq30 --stats=json:plate-stats.json plate");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_CONTAINS(r.out, "Quality mesh:");
  EXPECT_CONTAINS(r.out, "wrote plate-stats.json");
  EXPECT_EQ(nlohmann::json::parse(slurp(path("plate-stats.json")))["triangles"], j["triangles"]);
  EXPECT_EQ(run("-p --stats=yaml plate").code, 1);
  // Not over an input.
  EXPECT_EQ(run("-p --stats=json:plate.poly plate").code, 4);
}

// Every key --stats=json writes is in docs/stats-schema.md's table, and
// every key there is written (nested keys as refine.below_reasons.budget).
TEST_F(Surprises, StatsJsonKeysAreTheDocumentedSchema) {
  example("plate.poly");
  const Result r = run("-pq30Q --stats=json plate");
  ASSERT_EQ(r.code, 0) << r.err;
  std::set<std::string> written;
  const auto walk = [&](auto&& self, const nlohmann::json& o, const std::string& prefix) -> void {
    for (auto it = o.begin(); it != o.end(); ++it) {
      written.insert(prefix + it.key());
      if (it->is_object()) self(self, *it, prefix + it.key() + ".");
    }
  };
  walk(walk, nlohmann::json::parse(r.out), "");
  std::set<std::string> documented;
  const std::string doc = slurp(fs::path(DELTAMESH_SOURCE_DIR) / "docs/stats-schema.md");
  const std::regex row(R"(^\| `([a-z0-9_.]+)` \|)", std::regex::multiline);
  for (auto it = std::sregex_iterator(doc.begin(), doc.end(), row); it != std::sregex_iterator(); ++it)
    documented.insert((*it)[1]);
  // `metric` is written only after adaptation to a metric (--adapt with
  // tensors), not by this run.
  EXPECT_TRUE(documented.count("metric.within_sqrt2"));
  std::erase_if(documented, [](const std::string& k) { return k.rfind("metric", 0) == 0; });
  EXPECT_EQ(written, documented);
  EXPECT_CONTAINS(doc, "schema_version` | " + std::to_string(deltamesh::kStatsSchemaVersion));
}

// ---------------------------------------------------------------------------
// Why 8: exponents in switch numbers are explained, with the number to type.

TEST_F(Surprises, ExponentsInSwitchNumbersAreExplained) {
  write("sq.poly", kSquareHoles);
  Result r = run("-pa1e-3 sq");
  EXPECT_EQ(r.code, 1);
  EXPECT_CONTAINS(r.err, "switch numbers have no exponent");
  EXPECT_CONTAINS(r.err, "type -a0.001");
  r = run("-pq2.5E1 sq");
  EXPECT_EQ(r.code, 1);
  EXPECT_CONTAINS(r.err, "type -q25");
  r = run("-pS1e5 sq");
  EXPECT_CONTAINS(r.err, "type -S100000");
  // An 'e' after a number that is not an exponent is still -e (edges).
  r = run("-pa0.1eC sq");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(path("sq.1.edge")));
  read_back("sq.1");
}

// ---------------------------------------------------------------------------
// Why 9: what each number is, plurals, -V's region note, -C after --cdt=ct.

TEST_F(Surprises, SummaryLinesSayWhatEachCountIs) {
  example("plate.poly");
  const Result cdt = run("-pC plate");
  ASSERT_EQ(cdt.code, 0) << cdt.err;
  const std::size_t cdt_triangles = read_back("plate.1").num_triangles();
  const Result q = run("-pq30C plate");
  ASSERT_EQ(q.code, 0) << q.err;
  const deltamesh::Mesh refined = read_back("plate.1");
  // The first line's count is the triangulation's, the refinement line's the final mesh's.
  EXPECT_CONTAINS(q.out, "2 holes -> " + std::to_string(cdt_triangles) + " triangles\n");
  EXPECT_CONTAINS(q.out, "Quality mesh: " + std::to_string(refined.num_vertices()) + " vertices, " +
                             std::to_string(refined.num_triangles()) + " triangles; refinement complete");
}

TEST_F(Surprises, OneIsSingular) {
  write("tri.node", "3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n");
  Result r = run("-C tri");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_CONTAINS(r.out, "3 input vertices, 1 triangle, 3 hull edges");
  EXPECT_CONTAINS(r.out, "mesh is valid: 1 triangle, 3 edges, 3 vertices");
  read_back("tri.1");
  write("sq.poly", kSquareHoles);
  r = run("-pq30a0.02C --smooth=1 sq");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_CONTAINS(r.out, " in 1 pass ");
  EXPECT_LACKS(r.out, "1 passes");
  read_back("sq.1");
}

TEST_F(Surprises, VerboseRegionNoteKnowsAreaBounds) {
  example("plate.poly");
  Result r = run("-paV plate");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_CONTAINS(r.out, "area bounds used by -a");
  EXPECT_LACKS(r.out, "(not used without -A)");
  r = run("-pV plate");
  EXPECT_CONTAINS(r.out, "not used without -A or -a");
  read_back("plate.1");
}

TEST_F(Surprises, CheckAfterCtSaysDelaunayWasNotChecked) {
  example("plate.poly");
  Result r = run("-pC --cdt=ct plate");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_CONTAINS(r.out, "the Delaunay property was not checked (--cdt=ct need not make it)");
  read_back("plate.1");
  r = run("-pC plate");
  EXPECT_LACKS(r.out, "not checked");
}

}  // namespace
