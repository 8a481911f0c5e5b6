// The Bowyer-Watson cavity of a point inside the mesh, the part on R2's hot
// path (inline: decide() builds one per Steiner point); growth, location and
// segment-split cavities are in cavity.cpp.
#pragma once
#include "algo/refine/refiner.hpp"
#include "deltamesh/predicates.hpp"

namespace deltamesh::refinement {

// Cavity of point c (inside seed or on one of its unconstrained edges).
bool Refiner::cavity(const Point& c, TriId seed) {
  begin_cavity();
  add_to_cavity(seed);
  stack_.push_back(3 * seed + 2);
  stack_.push_back(3 * seed + 1);
  stack_.push_back(3 * seed);
  if (!grow(c)) return false;
  // A cavity grown through unconstrained (locally Delaunay) edges around a
  // point inside it is star-shaped (exact incircle); only segments on its
  // boundary can break that, so only then is every edge checked.
  for (const BoundaryEdge& b : bnd_)
    if (b.flags & kConstrained) return boundary_visible(c, 0, bnd_.size());
  return true;
}

}  // namespace deltamesh::refinement
