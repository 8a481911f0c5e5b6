// Spatial ordering of points for incremental insertion.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "deltamesh/geometry.hpp"

namespace deltamesh::detail {

// Index of (x, y) on a Hilbert curve of `levels` levels (<= 16) over
// [0, 2^levels)^2.
std::uint32_t hilbert_index(std::uint32_t x, std::uint32_t y, int levels = 16);
// hilbert_index(x, y, 11) for x, y < 2^11, four levels per table lookup.
std::uint32_t hilbert_index_11(std::uint32_t x, std::uint32_t y);

// Insertion order for `points`: a biased randomized insertion order (rounds of
// growing size, chosen by a fixed hash of the index, so deterministic) with
// each round along a Hilbert curve over the bounding box. order[k] is the
// input index of the k-th point to insert. Points in the same round and curve
// cell (2^22 cells) keep input order. When `sorted` is given it receives the
// points in that order.
std::vector<VertexId> hilbert_order(std::span<const Point> points, std::vector<Point>* sorted = nullptr);
// The same for the subset points[subset[0]], points[subset[1]], ..., read in
// place: order[k] is an index into `subset`.
std::vector<VertexId> hilbert_order(std::span<const Point> points, std::span<const VertexId> subset,
                                    std::vector<Point>* sorted = nullptr);

}  // namespace deltamesh::detail
