// Settings and options that change nothing in a run: said once, so that a
// misplaced switch is not a silent no-op (issue "No surprises", item 4).
#include <algorithm>
#include <initializer_list>
#include <tuple>

#include "deltamesh/pipeline.hpp"
#include "deltamesh/switches.hpp"

namespace deltamesh {

std::vector<std::string> unused_settings(const Plan& plan) {
  std::vector<std::string> out;
  auto no_effect = [&](const std::string& what, const std::string& why) {
    out.push_back(what + " has no effect: " + why);
  };
  const RefinementPlan& rp = plan.refine;
  if (!rp.requested() && plan.input != InputKind::Adapt) {
    const std::string why = "nothing is refined (add -q, -a, -S or -D)";
    if (rp.no_boundary_steiner) no_effect(rp.no_boundary_steiner > 1 ? "-YY" : "-Y", why);
    if (rp.steiner != SteinerRule::Best) no_effect("--steiner", why);
    if (rp.encroachment != EncroachmentRule::DiametralLens) no_effect("--encroachment", why);
    if (rp.order != RefineOrder::ShortestEdgeFirst) no_effect("--order", why);
    if (rp.time_limit > 0) no_effect("--time-limit", why);
  }
  if (!plan.uses_segments()) {
    const std::string why = plan.mesh_input() ? "without -p a mesh's segments, holes and regions are not read"
                                              : "a point set has no segments, holes or regions (add -p)";
    if (plan.domain.regional_attributes) no_effect("-A", why);
    if (plan.domain.ignore_holes) no_effect("-O", why);
    if (plan.method != CdtMethod::Fast) no_effect("--cdt", why);
    if (plan.strict) no_effect("--strict", why);
  }
  if (plan.domain.fill != FillRule::Holes && plan.input != InputKind::Pslg)
    no_effect("--fill", "it chooses the domain of a PSLG (-p)");
  if (rp.input_area_bounds && plan.input == InputKind::Points)
    no_effect("-a without a number", "it reads the .poly regions' area bounds (-p) or FILE.area (-r)");
  return out;
}

namespace {

bool has_output(const CommandLine& cl, std::initializer_list<const char*> exts) {
  return std::any_of(cl.outputs.begin(), cl.outputs.end(), [&](const std::string& path) {
    return std::any_of(exts.begin(), exts.end(), [&](const char* ext) {
      const std::string e(ext);
      return path.size() >= e.size() && path.compare(path.size() - e.size(), e.size(), e) == 0;
    });
  });
}

}  // namespace

std::vector<std::string> unused_options(const CommandLine& cl, bool geojson_input, const GeoJsonInfo* geojson) {
  std::vector<std::string> out;
  auto no_effect = [&](const std::string& what, const std::string& why) {
    out.push_back(what + " has no effect: " + why);
  };
  if (cl.msh_version_given && !has_output(cl, {".msh"})) no_effect("--msh-version", "no .msh output (--output FILE.msh)");
  if (cl.vtu_binary && !has_output(cl, {".vtu"})) no_effect("--vtu-binary", "no .vtu output (--output FILE.vtu)");
  if (cl.geojson_segments && !has_output(cl, {".geojson", ".json"}))
    no_effect("--geojson-segments", "no GeoJSON output (--output FILE.geojson)");
  if (cl.voronoi_overlay && !has_output(cl, {".svg", ".geojson", ".json"}))
    no_effect("--voronoi-overlay", "no .svg or .geojson output named by --output");
  if (!cl.outputs.empty()) {
    const std::string why = "with --output only the named files are written";
    if (cl.no_poly) no_effect("-P", why);
    if (cl.no_node) no_effect("-N", why);
    if (cl.no_ele) no_effect("-E", why);
  }
  for (const auto& [name, value, found] :
       {std::tuple{"--region-property", &cl.region_property, geojson ? geojson->polygons_with_attribute : 1},
        std::tuple{"--area-property", &cl.area_property, geojson ? geojson->polygons_with_area : 1}}) {
    if (value->empty()) continue;
    if (!geojson_input)
      no_effect(name, "it reads a property of GeoJSON features, and the input is not GeoJSON");
    else if (found == 0)
      no_effect(std::string(name) + "=" + *value, "no polygon's feature has a property \"" + *value + "\"" +
                                                      (geojson && geojson->polygons ? "" : " (no polygons)"));
  }
  return out;
}

}  // namespace deltamesh
