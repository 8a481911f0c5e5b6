// An SVG picture of a mesh.
#pragma once
#include <string>

#include "deltamesh/mesh.hpp"

namespace deltamesh {

struct BoundedVoronoi;  // voronoi.hpp

struct SvgOptions {
  double width_px = 800.0;      // picture width; height follows the aspect ratio
  bool shade_by_quality = true; // fill each triangle by its smallest angle
  bool draw_vertices = false;
  std::string title;
  // Overlay: the bounded Voronoi cells (bounded_voronoi(mesh)) drawn as thin
  // blue lines over the triangles. nullptr: none.
  const BoundedVoronoi* voronoi = nullptr;
};

void write_svg(const Mesh& mesh, const std::string& path, const SvgOptions& opt = {});

}  // namespace deltamesh
