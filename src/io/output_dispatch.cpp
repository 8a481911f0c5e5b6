// Writing a mesh in the format named by a file's extension.
#include <algorithm>
#include <cctype>
#include <string>

#include "deltamesh/formats.hpp"
#include "deltamesh/svg.hpp"
#include "deltamesh/triangle_io.hpp"

namespace deltamesh {

namespace {

std::string lower_extension(std::string_view path) {
  const std::size_t slash = path.find_last_of('/');
  const std::size_t dot = path.rfind('.');
  if (dot == std::string_view::npos || (slash != std::string_view::npos && dot < slash)) return {};
  std::string ext(path.substr(dot + 1));
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

}  // namespace

std::optional<OutputFormat> output_format_for(std::string_view path) {
  const std::string ext = lower_extension(path);
  if (ext == "msh") return OutputFormat::Msh;
  if (ext == "vtu") return OutputFormat::Vtu;
  if (ext == "vtk") return OutputFormat::Vtk;
  if (ext == "svg") return OutputFormat::Svg;
  if (ext == "geojson" || ext == "json") return OutputFormat::GeoJson;
  if (ext == "off") return OutputFormat::Off;
  if (ext == "node") return OutputFormat::Node;
  if (ext == "ele") return OutputFormat::Ele;
  if (ext == "edge") return OutputFormat::Edge;
  if (ext == "neigh") return OutputFormat::Neigh;
  if (ext == "poly") return OutputFormat::Poly;
  return std::nullopt;
}

std::string_view to_string(OutputFormat format) {
  switch (format) {
    case OutputFormat::Msh: return "msh";
    case OutputFormat::Vtu: return "vtu";
    case OutputFormat::Vtk: return "vtk";
    case OutputFormat::Svg: return "svg";
    case OutputFormat::GeoJson: return "geojson";
    case OutputFormat::Off: return "off";
    case OutputFormat::Node: return "node";
    case OutputFormat::Ele: return "ele";
    case OutputFormat::Edge: return "edge";
    case OutputFormat::Neigh: return "neigh";
    case OutputFormat::Poly: return "poly";
  }
  return "?";
}

void write_output(const Mesh& mesh, const std::string& path, const OutputOptions& options) {
  const std::optional<OutputFormat> format = output_format_for(path);
  if (!format) throw UnknownOutputFormat(path);
  TriangleWriteOptions tri;
  tri.first_index = options.first_index;
  tri.write_markers = options.write_markers;
  switch (*format) {
    case OutputFormat::Msh: write_msh(mesh, path, options.msh); return;
    case OutputFormat::Vtu: write_vtu(mesh, path, options.vtk); return;
    case OutputFormat::Vtk: write_vtk(mesh, path, options.vtk); return;
    case OutputFormat::Svg: {
      SvgOptions s = options.svg;
      if (options.voronoi) s.voronoi = options.voronoi;
      write_svg(mesh, path, s);
      return;
    }
    case OutputFormat::GeoJson: {
      GeoJsonWriteOptions g = options.geojson;
      if (options.voronoi) g.voronoi = options.voronoi;
      write_geojson(mesh, path, g);
      return;
    }
    case OutputFormat::Off: write_off(mesh, path); return;
    case OutputFormat::Node: write_node(mesh, path, tri); return;
    case OutputFormat::Ele:
      tri.midside = options.msh.second_order.midside;  // six-node triangles when the msh has them (-o2)
      write_ele(mesh, path, tri);
      return;
    case OutputFormat::Edge: write_edge(mesh, path, tri); return;
    case OutputFormat::Neigh: write_neigh(mesh, path, tri); return;
    case OutputFormat::Poly: write_poly(mesh, path, tri); return;
  }
}

}  // namespace deltamesh
