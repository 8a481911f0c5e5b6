// GeoJSON input: polygons with holes, MultiPolygon, wrappers, merging of
// duplicate positions and shared borders, region seeds from properties, and
// malformed JSON / GeoJSON reported with file, line and column.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <string>

#include "deltamesh/errors.hpp"
#include "deltamesh/formats.hpp"
#include "deltamesh/predicates.hpp"

using namespace deltamesh;
namespace fs = std::filesystem;

namespace {

// Segments as unordered vertex-coordinate pairs, for order-free comparison.
std::set<std::pair<std::pair<double, double>, std::pair<double, double>>> segment_set(const Pslg& g) {
  std::set<std::pair<std::pair<double, double>, std::pair<double, double>>> out;
  for (const Segment& s : g.segments) {
    auto a = std::make_pair(g.points[s.a].x, g.points[s.a].y);
    auto b = std::make_pair(g.points[s.b].x, g.points[s.b].y);
    if (b < a) std::swap(a, b);
    out.insert({a, b});
  }
  return out;
}

// Every vertex has even degree (rings are closed chains).
bool closed_chains(const Pslg& g) {
  std::vector<int> degree(g.points.size(), 0);
  for (const Segment& s : g.segments) ++degree[s.a], ++degree[s.b];
  return std::all_of(degree.begin(), degree.end(), [](int d) { return d % 2 == 0; });
}

// Even-odd point-in-polygon test over the PSLG's segments.
bool inside_even_odd(const Pslg& g, const Point& p) {
  bool in = false;
  for (const Segment& s : g.segments) {
    const Point& a = g.points[s.a];
    const Point& b = g.points[s.b];
    if ((a.y > p.y) != (b.y > p.y)) {
      const double x = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
      if (x > p.x) in = !in;
    }
  }
  return in;
}

JsonParseError parse_error(const std::string& text) {
  try {
    parse_geojson(text, "t.geojson");
  } catch (const JsonParseError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for: " << text;
  return JsonParseError("", 0, 0, "");
}

const char* kSquareWithHole = R"({
  "type": "Polygon",
  "coordinates": [
    [[0, 0], [10, 0], [10, 10], [0, 10], [0, 0]],
    [[3, 3], [3, 7], [7, 7], [7, 3], [3, 3]]
  ]
})";

TEST(GeoJson, PolygonWithHole) {
  GeoJsonInfo info;
  const Pslg g = parse_geojson(kSquareWithHole, "sq", {}, &info);
  EXPECT_EQ(g.points.size(), 8u);  // closing positions dropped
  EXPECT_EQ(g.segments.size(), 8u);
  EXPECT_TRUE(g.holes.empty());    // even-odd needs no hole points
  EXPECT_TRUE(g.regions.empty());
  EXPECT_TRUE(closed_chains(g));
  EXPECT_EQ(info.polygons, 1u);
  EXPECT_EQ(info.rings, 2u);
  EXPECT_EQ(info.holes, 1u);
  EXPECT_EQ(info.duplicate_points, 0u);
  for (const Segment& s : g.segments) EXPECT_EQ(s.marker, 1);
  EXPECT_TRUE(inside_even_odd(g, {1, 1}));
  EXPECT_FALSE(inside_even_odd(g, {5, 5}));
  EXPECT_FALSE(inside_even_odd(g, {11, 5}));
}

TEST(GeoJson, MarkersForOuterRingsAndHoles) {
  GeoJsonReadOptions opt;
  opt.outer_marker = 2;
  opt.hole_marker = 3;
  const Pslg g = parse_geojson(kSquareWithHole, "sq", opt);
  int outer = 0, hole = 0;
  for (const Segment& s : g.segments) {
    const Point& a = g.points[s.a];
    const bool on_hole = a.x >= 3 && a.x <= 7 && a.y >= 3 && a.y <= 7;
    if (on_hole) {
      EXPECT_EQ(s.marker, 3);
      ++hole;
    } else {
      EXPECT_EQ(s.marker, 2);
      ++outer;
    }
  }
  EXPECT_EQ(outer, 4);
  EXPECT_EQ(hole, 4);
}

TEST(GeoJson, MultiPolygonInFeatureCollectionWithAttributes) {
  const char* text = R"({"type": "FeatureCollection", "features": [
    {"type": "Feature", "properties": {"zone": 4, "max_area": 0.5},
     "geometry": {"type": "MultiPolygon", "coordinates": [
        [[[0, 0], [4, 0], [4, 4], [0, 4], [0, 0]], [[1, 1], [1, 3], [3, 3], [3, 1], [1, 1]]],
        [[[10, 0], [12, 0], [11, 2], [10, 0]]]
     ]}},
    {"type": "Feature", "properties": {"zone": "forest"},
     "geometry": {"type": "Polygon", "coordinates": [[[20, 0], [24, 0], [24, 1], [20, 1], [20, 0]]]}},
    {"type": "Feature", "properties": {"zone": "lake"},
     "geometry": {"type": "Polygon", "coordinates": [[[30, 0], [34, 0], [34, 1], [30, 1], [30, 0]]]}},
    {"type": "Feature", "properties": {"zone": "forest"},
     "geometry": {"type": "Polygon", "coordinates": [[[40, 0], [44, 0], [44, 1], [40, 1], [40, 0]]]}},
    {"type": "Feature", "properties": {"name": "no zone"},
     "geometry": {"type": "Polygon", "coordinates": [[[50, 0], [54, 0], [54, 1], [50, 1], [50, 0]]]}},
    {"type": "Feature", "properties": null, "geometry": {"type": "Point", "coordinates": [1, 2]}},
    {"type": "Feature", "properties": {}, "geometry": null}
  ]})";
  GeoJsonReadOptions opt;
  opt.attribute_property = "zone";
  opt.area_property = "max_area";
  GeoJsonInfo info;
  const Pslg g = parse_geojson(text, "fc", opt, &info);
  EXPECT_EQ(info.features, 7u);
  EXPECT_EQ(info.polygons, 6u);
  EXPECT_EQ(info.rings, 7u);
  EXPECT_EQ(info.holes, 1u);
  EXPECT_EQ(info.skipped_geometries, 2u);
  EXPECT_EQ(g.segments.size(), 4u + 4u + 3u + 4u * 4u);
  EXPECT_TRUE(closed_chains(g));
  ASSERT_EQ(info.categories, (std::vector<std::string>{"forest", "lake"}));
  // One seed per polygon that has the property: 2 (multipolygon) + 3.
  ASSERT_EQ(g.regions.size(), 5u);
  EXPECT_EQ(info.seeds, 5u);
  const std::vector<double> attrs{4, 4, 1, 2, 1};
  for (std::size_t i = 0; i < g.regions.size(); ++i) {
    EXPECT_EQ(g.regions[i].attribute, attrs[i]) << i;
    // Every seed is strictly inside the domain (and so outside the hole).
    EXPECT_TRUE(inside_even_odd(g, g.regions[i].p)) << i << ": " << g.regions[i].p.x << " " << g.regions[i].p.y;
  }
  EXPECT_EQ(g.regions[0].max_area, 0.5);
  EXPECT_EQ(g.regions[2].max_area, -1.0);
  // The first seed avoids the hole [1,3]^2.
  const Point s0 = g.regions[0].p;
  EXPECT_FALSE(s0.x >= 1 && s0.x <= 3 && s0.y >= 1 && s0.y <= 3);
}

TEST(GeoJson, SeedsInsideAwkwardPolygons) {
  // A comb (many teeth) with a hole in its spine, and a thin sliver.
  std::string ring = "[[0,0],[20,0],[20,2]";
  for (int k = 9; k >= 0; --k) {
    ring += ",[" + std::to_string(2 * k + 2) + ",2],[" + std::to_string(2 * k + 2) + ",8],[" +
            std::to_string(2 * k + 1) + ",8],[" + std::to_string(2 * k + 1) + ",2]";
  }
  ring += ",[0,2],[0,0]]";
  const std::string text = R"({"type":"GeometryCollection","geometries":[
     {"type":"Polygon","coordinates":[)" + ring + R"(,[[1,0.5],[19,0.5],[19,1.5],[1,1.5],[1,0.5]]]},
     {"type":"Polygon","coordinates":[[[100,0],[200,0],[100,1e-6],[100,0]]]}]})";
  // A GeometryCollection has no properties: seeds need a feature.
  const std::string feature = R"({"type":"Feature","properties":{"r":7},"geometry":)" + text + "}";
  GeoJsonReadOptions opt;
  opt.attribute_property = "r";
  GeoJsonInfo info;
  const Pslg g = parse_geojson(feature, "comb", opt, &info);
  ASSERT_EQ(g.regions.size(), 2u);
  EXPECT_EQ(info.seeds_failed, 0u);
  for (const RegionSeed& s : g.regions) {
    EXPECT_TRUE(inside_even_odd(g, s.p)) << s.p.x << " " << s.p.y;
    EXPECT_EQ(s.attribute, 7.0);
  }
}

TEST(GeoJson, DuplicatePointsAndSharedBordersMerged) {
  // Two squares sharing the edge x = 1; the second ring is clockwise and
  // repeats a point; positions carry a z coordinate.
  const char* text = R"({"type":"FeatureCollection","features":[
    {"type":"Feature","properties":{},"geometry":{"type":"Polygon","coordinates":[
      [[0,0,5],[1,0,5],[1,1,5],[0,1,5],[0,0,5]]]}},
    {"type":"Feature","properties":{},"geometry":{"type":"Polygon","coordinates":[
      [[1,0],[1,1],[2,1],[2,1],[2,0],[1,0]]]}}]})";
  GeoJsonInfo info;
  const Pslg g = parse_geojson(text, "two", {}, &info);
  EXPECT_EQ(g.points.size(), 6u);
  EXPECT_EQ(g.segments.size(), 7u);  // 4 + 4 - the shared one
  EXPECT_EQ(info.duplicate_segments, 1u);
  EXPECT_GE(info.duplicate_points, 3u);
  EXPECT_EQ(segment_set(g).size(), 7u);
}

TEST(GeoJson, NegativeZeroIsZeroAndUnclosedRingsAreClosed) {
  const char* text = R"({"type":"Polygon","coordinates":[[[0,0],[1,0],[1,1],[-0.0,1]]]})";
  GeoJsonInfo info;
  const Pslg g = parse_geojson(text, "u", {}, &info);
  EXPECT_EQ(info.unclosed_rings, 1u);
  EXPECT_EQ(g.points.size(), 4u);
  EXPECT_EQ(g.segments.size(), 4u);
  EXPECT_FALSE(std::signbit(g.points[3].x));
}

TEST(GeoJson, DegenerateRingsIgnored) {
  const char* text = R"({"type":"MultiPolygon","coordinates":[
    [[[0,0],[1,0],[0,0]]],
    [[[5,5],[5,5],[5,5],[5,5]]],
    [[[0,0],[3,0],[0,3],[0,0]]]]})";
  GeoJsonInfo info;
  const Pslg g = parse_geojson(text, "d", {}, &info);
  EXPECT_EQ(info.degenerate_rings, 2u);
  EXPECT_EQ(info.rings, 1u);
  EXPECT_EQ(g.segments.size(), 3u);
}

TEST(GeoJson, JsonDetails) {
  // Escapes, unicode, exponents, nesting, whitespace, BOM, duplicate keys
  // (the last wins, as in JavaScript).
  const std::string text =
      "\xEF\xBB\xBF{\"type\":\"Feature\",\"properties\":{\"n\\u00e9\":\"\\ud83d\\ude00\\n\\\"\",\"z\":1E0},"
      "\"geometry\":{\"type\":\"Point\",\"coordinates\":[0,0]},"
      "\"geometry\":{\"type\":\"Polygon\",\"coordinates\":[[[0,0],[1e1,0],[10,-1.5e+1],[0,0]]]}}";
  GeoJsonReadOptions opt;
  opt.attribute_property = "z";
  const Pslg g = parse_geojson(text, "j", opt);
  ASSERT_EQ(g.points.size(), 3u);
  EXPECT_EQ(g.points[2].y, -15.0);
  ASSERT_EQ(g.regions.size(), 1u);
  EXPECT_EQ(g.regions[0].attribute, 1.0);
}

TEST(GeoJson, MalformedJsonNamesLineAndColumn) {
  {
    const JsonParseError e = parse_error("{\"type\": \"Polygon\",\n  \"coordinates\": [[[0, 0], [1, 0] [1, 1]]]\n}");
    EXPECT_EQ(e.file(), "t.geojson");
    EXPECT_EQ(e.line(), 2u);
    EXPECT_EQ(e.column(), 35u);
    EXPECT_NE(std::string(e.what()).find("t.geojson:2:35: expected ',' or ']'"), std::string::npos) << e.what();
  }
  {
    const JsonParseError e = parse_error("{\"type\": \"Polygon\",}");
    EXPECT_EQ(e.line(), 1u);
    EXPECT_EQ(e.column(), 20u);
    EXPECT_NE(e.problem().find("trailing ','"), std::string::npos);
  }
  {
    const JsonParseError e = parse_error("{\"type\": \"Poly");
    EXPECT_EQ(e.column(), 10u);
    EXPECT_NE(e.problem().find("unterminated string"), std::string::npos);
  }
  {
    // Columns count characters, not bytes.
    const JsonParseError e = parse_error("{\"n\u00e9\u00e9\": tru}");
    EXPECT_EQ(e.column(), 9u);
  }
  {
    const JsonParseError e = parse_error("{\"a\": [1, 2]}\n\n  x");
    EXPECT_EQ(e.line(), 3u);
    EXPECT_EQ(e.column(), 3u);
  }
  EXPECT_NE(parse_error("").problem().find("empty"), std::string::npos);
  EXPECT_NE(parse_error("{\"x\": NaN}").problem().find("NaN"), std::string::npos);
  EXPECT_NE(parse_error("{\"x\": 01}").problem().find("expected"), std::string::npos);
  EXPECT_NE(parse_error("{\"x\": 1.}").problem().find("digit"), std::string::npos);
  EXPECT_NE(parse_error("{\"x\": 1e999}").problem().find("out of range"), std::string::npos);
  EXPECT_NE(parse_error("{\"x\": \"a\\qb\"}").problem().find("invalid escape"), std::string::npos);
  EXPECT_NE(parse_error("{\"x\": \"a\tb\"}").problem().find("control character"), std::string::npos);
  EXPECT_NE(parse_error("{x: 1}").problem().find("member name"), std::string::npos);
  EXPECT_NE(parse_error(std::string(300, '[') + std::string(300, ']')).problem().find("nested"), std::string::npos);
  // It is a ParseError too, so callers catching ParseError see it.
  EXPECT_THROW(parse_geojson("[", "x"), ParseError);
}

TEST(GeoJson, GeoJsonStructureErrorsPointAtTheValue) {
  {
    const JsonParseError e = parse_error("{\"type\": \"Polygon\",\n \"coordinates\": [[[0, 0], [1], [1, 1], [0, 0]]]}");
    EXPECT_EQ(e.line(), 2u);
    EXPECT_EQ(e.column(), 27u);
    EXPECT_NE(e.problem().find("position"), std::string::npos);
  }
  EXPECT_NE(parse_error("{\"type\": \"Polygn\", \"coordinates\": []}").problem().find("unknown GeoJSON type"),
            std::string::npos);
  EXPECT_NE(parse_error("{\"coordinates\": []}").problem().find("\"type\""), std::string::npos);
  EXPECT_NE(parse_error("{\"type\": \"Polygon\"}").problem().find("coordinates"), std::string::npos);
  EXPECT_NE(parse_error("[1, 2]").problem().find("GeoJSON object"), std::string::npos);
  EXPECT_NE(parse_error("{\"type\": \"FeatureCollection\", \"features\": [{\"type\": \"Polygon\"}]}")
                .problem()
                .find("Feature"),
            std::string::npos);
  EXPECT_NE(parse_error("{\"type\": \"Polygon\", \"coordinates\": [[0, 0], [1, 0]]}").problem().find("ring"),
            std::string::npos);
  {
    GeoJsonReadOptions opt;
    opt.marker_property = "m";
    EXPECT_THROW(parse_geojson(R"({"type":"Feature","properties":{"m":1.5},
      "geometry":{"type":"Polygon","coordinates":[[[0,0],[1,0],[0,1],[0,0]]]}})",
                               "m", opt),
                 JsonParseError);
  }
}

// Mutated inputs either parse or throw JsonParseError: never anything else
// (no crash, no other exception type, no hang).
TEST(GeoJson, MutatedInputsFailCleanly) {
  const std::string base = R"({"type":"FeatureCollection","features":[
    {"type":"Feature","properties":{"zone":"a\u00e9","m":2},"geometry":{"type":"MultiPolygon","coordinates":[
      [[[0,0],[4,0],[4,4],[0,4],[0,0]],[[1,1],[1,3],[3,3],[3,1],[1,1]]],[[[10,0],[12,0],[11,2.5e0],[10,0]]]]}},
    {"type":"Feature","properties":null,"geometry":{"type":"GeometryCollection","geometries":[
      {"type":"Polygon","coordinates":[[[20,0],[24,0],[24,1],[20,1],[20,0]]]},{"type":"Point","coordinates":[1,2]}]}}]})";
  GeoJsonReadOptions opt;
  opt.attribute_property = "zone";
  opt.marker_property = "m";
  std::mt19937 rng(12345);
  const std::string alphabet = "{}[],:\"0123456789.-+eE \n\\tfnaul";
  std::size_t parsed = 0, failed = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    std::string s = base;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int k = 0; k < edits; ++k) {
      const std::size_t at = rng() % s.size();
      switch (rng() % 4) {
        case 0: s.erase(at, 1 + rng() % 8); break;
        case 1: s.insert(at, 1, alphabet[rng() % alphabet.size()]); break;
        case 2: s[at] = alphabet[rng() % alphabet.size()]; break;
        default: s = s.substr(0, at); break;  // truncation
      }
      if (s.empty()) s = "{";
    }
    try {
      const Pslg g = parse_geojson(s, "fuzz", opt);
      for (const Segment& seg : g.segments) {
        ASSERT_LT(seg.a, g.points.size());
        ASSERT_LT(seg.b, g.points.size());
        ASSERT_NE(seg.a, seg.b);
      }
      ++parsed;
    } catch (const JsonParseError& e) {
      EXPECT_GE(e.line(), 1u);
      EXPECT_GE(e.column(), 1u);
      ++failed;
    }
  }
  EXPECT_GT(parsed, 0u);
  EXPECT_GT(failed, 0u);
}

TEST(GeoJson, ReadFromFileNamesTheFile) {
  const fs::path dir = fs::temp_directory_path() / ("deltamesh_geojson_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string good = (dir / "a.geojson").string();
  const std::string bad = (dir / "b.geojson").string();
  std::ofstream(good) << kSquareWithHole;
  std::ofstream(bad) << "{\n\"type\": \"Polygon\",\n\"coordinates\": [[[0, 0], [1, 0], [1, 1], [0, 0]]],\n}\n";
  EXPECT_EQ(read_geojson(good).segments.size(), 8u);
  try {
    read_geojson(bad);
    ADD_FAILURE() << "no error";
  } catch (const JsonParseError& e) {
    EXPECT_EQ(e.file(), bad);
    EXPECT_EQ(e.line(), 4u);
    EXPECT_EQ(e.column(), 1u);
  }
  EXPECT_THROW(read_geojson((dir / "missing.geojson").string()), IoError);
  fs::remove_all(dir);
}

}  // namespace
