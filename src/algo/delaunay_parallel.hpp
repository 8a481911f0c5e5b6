// Delaunay triangulation of a point set on several threads (docs/scaling.md).
#pragma once
#include <chrono>
#include <functional>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "deltamesh/delaunay.hpp"

namespace deltamesh::detail {

// delaunay()'s build before renumbering: the closed triangulation (ghosts
// kept, not compacted) whose vertex k is points[order[k]] (the BRIO/Hilbert
// insertion order), and (duplicate, vertex it met) in that numbering.
// Throws InputError when the points make no triangle. `t0` is the start of
// the sort on entry (for stats->sort_seconds) and of the insertion on return.
// The triangle arrays get capacity for `reserve_triangles`, the points for
// `reserve_points` (untouched pages until used). `after_sort`, when given,
// is called once the points are sorted (`points` is not read again: it may
// free them). `finish` false leaves mesh.num_triangles() (a scan of every
// slot) and the vertices' out-edges unset: the slabs read neither. `subset`, when not empty, says the
// points are points[subset[0]], points[subset[1]], ... (read in place, not
// copied); `order` then indexes `subset`.
struct InsertionOrderDelaunay {
  Mesh mesh;
  std::vector<VertexId> order;
  std::vector<std::pair<VertexId, VertexId>> dups;
};
InsertionOrderDelaunay delaunay_in_insertion_order(std::span<const Point> points, TraceObserver* trace,
                                                   DelaunayStats* stats, std::chrono::steady_clock::time_point& t0,
                                                   std::size_t reserve_triangles = 0, std::size_t reserve_points = 0,
                                                   const std::function<void()>& after_sort = {}, bool finish = true,
                                                   std::span<const VertexId> subset = {});

// Points below this per part are not worth a thread: delaunay() stays
// sequential when n / threads is smaller.
inline constexpr std::size_t kMinPointsPerPart = 50000;

// The Delaunay triangulation of `points` (compacted, input numbering, first
// copies of duplicates kept: what delaunay() returns) built from `parts`
// vertical slabs triangulated concurrently on `threads` threads and merged.
// The same triangles as the sequential build whenever the triangulation is
// unique; their numbering follows the slabs, so it depends on `parts`.
// nullopt when the decomposition does not apply (a slab whose points make no
// triangle, or fewer than two slabs): the caller builds sequentially.
std::optional<Mesh> parallel_delaunay(std::span<const Point> points, unsigned parts, unsigned threads,
                                      DelaunayStats* stats);

}  // namespace deltamesh::detail
