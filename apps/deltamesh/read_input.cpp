// Reading the command line's input files into the pipeline's RunInput.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "cli.hpp"

namespace deltamesh::cli {

namespace {

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

void require_file(const std::string& path) {
  if (!std::filesystem::exists(path)) throw MissingInput(path);
}

void add_phase(Session& s, const char* name, Clock::time_point t0) {
  s.phases.push_back({name, std::chrono::duration<double>(Clock::now() - t0).count()});
}

// -r: FILE.node + FILE.ele (+ FILE.poly with -p: its segments, holes and
// regions), -ra: FILE.area, --adapt: FILE.mtr.
RunInput read_mesh(Session& s, const std::string& in) {
  const bool poly = s.plan.mesh_segments;
  const bool area = s.plan.refine.input_area_bounds;
  const bool adapt = s.plan.input == InputKind::Adapt;
  const std::string node_path = in + ".node", ele_path = in + ".ele", poly_path = in + ".poly";
  const std::string area_path = in + ".area";
  require_file(node_path);
  require_file(ele_path);
  if (poly) require_file(poly_path);
  if (area) require_file(area_path);
  s.reading(node_path);
  const auto t = Clock::now();
  RunInput r;
  r.pslg = read_node(node_path, s.plan.threads);
  s.first_index = r.pslg.first_index;
  if (poly) {
    s.reading(poly_path);
    Pslg p = read_poly(poly_path, s.plan.threads);
    if (p.points.size() != r.pslg.points.size())
      throw InputError(poly_path + " lists " + std::to_string(p.points.size()) + " vertices but " + node_path +
                       " has " + std::to_string(r.pslg.points.size()));
    r.pslg.segments = std::move(p.segments);
    r.pslg.holes = s.holes = std::move(p.holes);
    r.pslg.regions = s.regions = std::move(p.regions);
  }
  s.reading(ele_path);
  s.ele_path = ele_path;
  EleData ele = read_ele(ele_path, r.pslg.first_index);
  if (adapt) {
    const std::string mtr_path = in + ".mtr";
    require_file(mtr_path);
    s.reading(mtr_path);
    MtrData mtr = read_mtr_data(mtr_path);
    const std::size_t count = mtr.values.size() / static_cast<std::size_t>(mtr.per_node);
    if (count != r.pslg.points.size())
      throw InputError("has " + std::to_string(count) + (mtr.per_node == 1 ? " sizes" : " metrics") + " but " +
                       node_path + " has " + std::to_string(r.pslg.points.size()) + " nodes");
    if (mtr.per_node == 1) {
      r.vertex_sizes = std::move(mtr.values);
    } else {
      for (std::size_t i = 0; i < count; ++i)
        r.vertex_metrics.push_back({mtr.values[3 * i], mtr.values[3 * i + 1], mtr.values[3 * i + 2]});
    }
    if (!ele.midside.empty())
      throw InputError("--adapt needs a 3-node mesh; " + ele_path + " has 6-node triangles");
  }
  // -ra: per-triangle bounds (one per triangle of FILE.ele, <= 0: none).
  if (area) {
    s.reading(area_path);
    r.triangle_area_bounds = read_area(area_path);
    if (r.triangle_area_bounds.size() != ele.triangles.size() / 3)
      throw InputError("has " + std::to_string(r.triangle_area_bounds.size()) + " bounds for " +
                       std::to_string(ele.triangles.size() / 3) + " triangles");
  }
  add_phase(s, "read", t);
  r.triangles = std::move(ele.triangles);
  r.midside = std::move(ele.midside);
  r.num_triangle_attributes = ele.num_attributes;
  r.triangle_attributes = std::move(ele.attributes);
  if (!r.midside.empty()) {
    // A 6-node (-o2) mesh: refined as the corner mesh; its midpoint nodes
    // would be vertices in no triangle, so they go (-o2 writes new ones).
    const std::size_t dropped = drop_midside_nodes(r);
    if (!s.plan.quiet)
      std::fprintf(stderr,
                   "deltamesh: warning: %s has 6-node triangles; %zu midpoint nodes dropped, the other "
                   "vertices renumbered in order%s\n",
                   ele_path.c_str(), dropped, s.plan.order == 2 ? " (-o2 writes new ones)" : " (add -o2 for new ones)");
  }
  s.reading(node_path);
  return r;
}

}  // namespace

InputName split_input_name(std::string path) {
  for (const char* ext : {".node", ".poly", ".ele", ".area", ".geojson", ".json"})
    if (ends_with(path, ext)) {
      path.resize(path.size() - std::string(ext).size());
      break;
    }
  InputName name{path, 0};
  const auto dot = path.rfind('.');
  if (dot != std::string::npos && dot + 1 < path.size() && path.find('/', dot) == std::string::npos) {
    const std::string digits = path.substr(dot + 1);
    if (digits.find_first_not_of("0123456789") == std::string::npos && digits.size() < 9) {
      name.base = path.substr(0, dot);
      name.iteration = std::stoi(digits);
    }
  }
  return name;
}

bool is_geojson_input(const std::string& path) { return ends_with(path, ".geojson") || ends_with(path, ".json"); }

Session::Session(const CommandLine& c) : cl(c), plan(c.plan), geojson(is_geojson_input(c.input)) {
  name = split_input_name(c.input);
  if (geojson && !plan.mesh_input()) {
    // GeoJSON polygons are meshed like -p, even-odd; --region-property and
    // --area-property are the regions' attributes and area bounds (which
    // refine, like -a).
    plan.input = InputKind::Pslg;
    plan.domain.fill = FillRule::EvenOdd;
    if (!c.region_property.empty()) plan.domain.regional_attributes = true;
    if (!c.area_property.empty()) plan.refine.input_area_bounds = true;
  }
  if (!plan.quiet && progress.enabled()) plan.progress = progress.callback();
}

RunInput read_input(Session& s) {
  const std::string in = s.name.with_iteration();
  if (s.plan.mesh_input()) return read_mesh(s, in);
  const bool poly = s.plan.uses_segments();
  const std::string in_path = s.geojson ? s.cl.input : in + (poly ? ".poly" : ".node");
  require_file(in_path);
  s.reading(in_path);
  const auto t = Clock::now();
  RunInput r;
  if (s.geojson) {
    GeoJsonReadOptions gopt;
    gopt.attribute_property = s.cl.region_property;
    gopt.area_property = s.cl.area_property;
    r.pslg = read_geojson(in_path, gopt, &s.geojson_info);
  } else {
    r.pslg = poly ? read_poly(in_path, s.plan.threads) : read_node(in_path, s.plan.threads);
  }
  add_phase(s, "read", t);
  s.first_index = r.pslg.first_index;
  s.holes = r.pslg.holes;
  s.regions = r.pslg.regions;
  return r;
}

// Data lines are those with something before any '#'.
namespace {

// The 1-based line of a Triangle file's data line number target(header)
// (1-based, comments and blank lines not counted), where target is computed
// from the first data line; 0 when the file is shorter.
template <class Target>
std::size_t data_line(const std::string& path, Target target_of) {
  std::FILE* f = std::fopen(path.c_str(), "r");
  if (!f) return 0;
  std::size_t line = 0, data = 0, target = 0;
  std::string text;
  for (int c = 0; c != EOF;) {
    text.clear();
    while ((c = std::fgetc(f)) != EOF && c != '\n') text.push_back(static_cast<char>(c));
    ++line;
    text = text.substr(0, text.find('#'));
    if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
    if (data++ == 0) target = target_of(std::max(0LL, std::atoll(text.c_str())));
    if (data == target) {
      std::fclose(f);
      return line;
    }
  }
  std::fclose(f);
  return 0;
}

}  // namespace

std::size_t poly_segment_line(const std::string& path, std::size_t index) {
  // header, vertices, segment header, segments
  return data_line(path, [&](long long vertices) { return static_cast<std::size_t>(vertices) + 3 + index; });
}

std::string vertex_place(const Session& s, std::size_t index) {
  const std::string in = s.name.with_iteration();
  const std::size_t none = static_cast<std::size_t>(-1);
  // header, vertices; a .poly that lists none takes them from FILE.node.
  const auto line_in = [&](const std::string& path) {
    return data_line(path, [&](long long vertices) { return vertices > 0 ? index + 2 : none; });
  };
  std::string path = in + ".node";
  std::size_t line = 0;
  if (s.plan.input == InputKind::Pslg) {
    line = line_in(in + ".poly");
    if (line) path = in + ".poly";
  }
  if (!line) line = line_in(path);
  return path + (line ? ":" + std::to_string(line) : "");
}

std::size_t ele_triangle_line(const std::string& path, std::size_t index) {
  return data_line(path, [&](long long) { return index + 2; });  // header, triangles
}

}  // namespace deltamesh::cli
