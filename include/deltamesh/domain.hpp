// The meshing domain: which triangles of a constrained triangulation are
// kept (holes, exterior, nesting depth) and what each carries (regional
// attributes, area bounds).
#pragma once
#include <cstddef>

#include "deltamesh/mesh.hpp"
#include "deltamesh/pslg.hpp"

namespace deltamesh {

enum class FillRule {
  Holes,    // Triangle's rule: remove what hole points (and the exterior) reach, stopping at segments
  EvenOdd,  // keep triangles whose nesting depth (segments crossed from outside) is odd
};

struct DomainOptions {
  FillRule fill = FillRule::Holes;
  bool keep_convex_hull = false;      // -c: keep the exterior (the convex hull), closed by segments
  bool ignore_holes = false;          // -O
  bool regional_attributes = false;   // -A: one attribute per triangle from the region seeds
  bool regional_area_bounds = false;  // -a without a number: area bounds from the region seeds
};

struct DomainStats {
  std::size_t triangles_removed = 0;
  std::size_t holes_ignored = 0;  // hole points outside the domain or on a segment
};

// Removes the triangles outside the domain and compacts the mesh. Regional
// attributes go to the triangle attributes (one per triangle when asked);
// area bounds to per-triangle bounds (see Mesh triangle attributes docs).
void carve_domain(Mesh& mesh, const Pslg& pslg, const DomainOptions& options = {}, DomainStats* stats = nullptr);

}  // namespace deltamesh
