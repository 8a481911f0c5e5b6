// Writing the command line's output files: FILE.1.* in Triangle's formats,
// and the --output / --svg files.
#include <filesystem>
#include <functional>
#include <optional>

#include "cli.hpp"

namespace deltamesh::cli {
namespace {

// Refuses (exit 4, before anything is written) an output path that names a
// file this run read, e.g. `-I` writing FILE.node over its input, unless
// --overwrite was given.
void refuse_to_replace_inputs(const Session& s, const std::vector<std::string>& outputs) {
  namespace fs = std::filesystem;
  for (const std::string& out : outputs)
    for (const std::string& in : s.inputs_read) {
      std::error_code ec;
      if (fs::equivalent(out, in, ec) && !ec)
        throw IoError(out + ": refusing to overwrite the input file " + in +
                      " (choose another name, drop -I, or give --overwrite)");
    }
}

}  // namespace

std::vector<std::string> write_outputs(Session& s, const RunResult& r) {
  const CommandLine& cl = s.cl;
  const Mesh& mesh = r.mesh;
  const std::string out_base = s.name.base + (cl.no_iteration ? "" : "." + std::to_string(s.name.iteration + 1));
  TriangleWriteOptions wopt;
  wopt.first_index = s.plan.zero_based ? 0 : s.first_index;
  wopt.write_markers = s.plan.markers;
  wopt.holes = s.holes;  // the output .poly describes the same domain
  wopt.regions = s.regions;
  wopt.midside = r.midside;  // -o2
  // Every file is planned first, so that a refusal to replace an input
  // (-I writes FILE.node over FILE.node) leaves nothing half written.
  std::vector<std::pair<std::string, std::function<void()>>> planned;
  auto emit = [&](bool enabled, const char* ext, auto writer) {
    if (!enabled) return;
    const std::string path = out_base + ext;
    planned.emplace_back(path, [&mesh, &wopt, writer, path] { writer(mesh, path, wopt); });
  };
  // Triangle writes a .poly when it read one, and for a point set with -c.
  // With --output, only the named files (and those of -e -n -v -g) are written.
  const bool only_named = !cl.outputs.empty();
  const bool poly_file = !only_named && !cl.no_poly && (s.plan.uses_segments() || s.plan.domain.convex_hull);
  emit(!only_named && !cl.no_node, ".node", [](auto& m, auto& p, auto& w) { write_node(m, p, w); });
  emit(!only_named && !cl.no_ele, ".ele", [](auto& m, auto& p, auto& w) { write_ele(m, p, w); });
  emit(poly_file, ".poly", [](auto& m, auto& p, auto& w) { write_poly(m, p, w); });
  emit(s.plan.edges, ".edge", [](auto& m, auto& p, auto& w) { write_edge(m, p, w); });
  emit(s.plan.neighbors, ".neigh", [](auto& m, auto& p, auto& w) { write_neigh(m, p, w); });
  emit(cl.geomview, ".off", [](auto& m, auto& p, auto&) { write_off(m, p); });
  std::optional<VoronoiDiagram> vd;
  if (cl.voronoi) {
    planned.emplace_back(out_base + ".v.node", [&, path = out_base + ".v.node"] {
      vd = voronoi_diagram(mesh);
      write_voronoi_node(*vd, path, wopt.first_index);
    });
    planned.emplace_back(out_base + ".v.edge",
                         [&, path = out_base + ".v.edge"] { write_voronoi_edge(*vd, path, wopt.first_index); });
  }
  std::optional<BoundedVoronoi> cells;
  if (cl.voronoi_overlay && !cl.outputs.empty()) cells = bounded_voronoi(mesh);
  if (!cl.overwrite) {
    std::vector<std::string> paths = cl.outputs;
    for (const auto& p : planned) paths.push_back(p.first);
    if (cl.svg_path) paths.push_back(*cl.svg_path);
    if (cl.trace_path) paths.push_back(*cl.trace_path);
    if (!cl.stats_path.empty()) paths.push_back(cl.stats_path);
    refuse_to_replace_inputs(s, paths);
  }
  std::vector<std::string> written;
  for (auto& [path, write] : planned) {
    write();
    written.push_back(path);
  }
  for (const std::string& path : cl.outputs) {
    OutputOptions oopt;
    oopt.first_index = wopt.first_index;
    oopt.write_markers = wopt.write_markers;
    oopt.svg.title = cl.input;
    oopt.msh.version = cl.msh_v22 ? MshVersion::V22 : MshVersion::V41;
    oopt.vtk.binary = cl.vtu_binary;
    oopt.geojson.segments = cl.geojson_segments;
    oopt.msh.second_order.midside = r.midside;
    oopt.vtk.second_order.midside = r.midside;
    if (cells) oopt.voronoi = &*cells;
    write_output(mesh, path, oopt);
    written.push_back(path);
  }
  if (cl.svg_path) {
    SvgOptions sopt;
    sopt.title = cl.input;
    write_svg(mesh, *cl.svg_path, sopt);
    written.push_back(*cl.svg_path);
  }
  return written;
}

}  // namespace deltamesh::cli
