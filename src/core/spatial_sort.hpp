// Spatial ordering of points for incremental insertion.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "deltamesh/geometry.hpp"

namespace deltamesh::detail {

// Index of (x, y) on a Hilbert curve of order 16 over [0, 2^16)^2.
std::uint32_t hilbert_index(std::uint32_t x, std::uint32_t y);

// Permutation of `points` along a Hilbert curve over their bounding box:
// order[k] is the input index of the k-th point to insert. Ties keep input order.
std::vector<VertexId> hilbert_order(std::span<const Point> points);

}  // namespace deltamesh::detail
