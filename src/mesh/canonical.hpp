// A triangle numbering fixed by the triangulation alone (internal).
#pragma once
#include "deltamesh/mesh.hpp"

namespace deltamesh::detail {

// Renumbers the triangle slots of a compacted mesh in an order that depends
// only on which triangles it holds (their vertex ids), not on how they were
// built: each triangle starts at its smallest vertex id, and the triangles
// are sorted by that id, then by the next one. Refinement walks, queues and
// fills slots in slot order, so two runs on the same triangulation built in
// different orders (a Hilbert sort of coordinates that differ in the last
// bit, an input scaled by 10^k) refine alike. Per-half-edge and
// per-triangle data move with their triangles. O(n): a counting sort.
void canonical_triangle_order(Mesh& mesh);

}  // namespace deltamesh::detail
