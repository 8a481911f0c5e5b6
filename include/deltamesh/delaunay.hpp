// Delaunay triangulation of a point set.
#pragma once
#include <cstddef>
#include <span>
#include <vector>

#include "deltamesh/geometry.hpp"
#include "deltamesh/mesh.hpp"

namespace deltamesh {

struct DelaunayOptions {
  // Keep ghost triangles (a closed triangulation on the vertex at infinity),
  // for algorithms that go on inserting; otherwise the result is compacted.
  bool keep_ghosts = false;
  // Reports each insertion and flip (trace.hpp); also set on the result.
  TraceObserver* trace = nullptr;
  // Threads: 0 = every hardware thread, 1 = the sequential build. Without
  // ghosts and with at least 50000 points per thread, the points are cut
  // into that many vertical slabs triangulated concurrently and merged (the
  // same triangles as the sequential build when the triangulation is
  // unique, numbered slab by slab: the same output for the same count).
  unsigned threads = 0;
};

struct DelaunayStats {
  std::size_t duplicates = 0;           // input points equal to an earlier one
  std::vector<VertexId> duplicate_of;   // per input point: the kept twin, or kNone
  double sort_seconds = 0.0;
  double insert_seconds = 0.0;
};

// Delaunay triangulation of `points` by incremental insertion in Hilbert
// order with walking point location and exact predicates. Vertex ids in the
// result are the input indices; duplicates stay as vertices in no triangle
// and are reported in `stats`. Coordinates beyond the exact predicates'
// range (2^+-200) are meshed in an exact power-of-two frame and mapped back
// (docs/robustness.md, "Any finite coordinates"). Throws InputError for
// non-finite coordinates, a nonzero one about 2^400 below the largest, and
// when all points are collinear (or fewer than three distinct points),
// since no triangle exists then.
Mesh delaunay(std::span<const Point> points, const DelaunayOptions& options = {},
              DelaunayStats* stats = nullptr);

// Inserts one more vertex into a triangulation that has ghost triangles and
// is Delaunay, keeping it Delaunay (Lawson flips, constrained edges are not
// flipped). `hint` is a triangle to start the walk from. Returns the new
// vertex id, or the existing one if p coincides with a vertex.
VertexId insert_delaunay_vertex(Mesh& mesh, const Point& p, TriId hint = kNone);

}  // namespace deltamesh
