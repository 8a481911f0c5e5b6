// Helpers shared by coarsening, smoothing and the adaptation pipelines.
#pragma once
#include <chrono>
#include <cmath>
#include <cstddef>
#include <vector>

#include "deltamesh/geometry.hpp"
#include "deltamesh/mesh.hpp"

namespace deltamesh::adaptation {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

inline double dist(const Point& a, const Point& b) { return std::hypot(a.x - b.x, a.y - b.y); }

// Vertices of higher degree are never removed nor moved (reducing one costs
// O(degree^2)).
constexpr std::size_t kMaxDegree = 4096;

// The out-edges of v counter-clockwise, whatever out_edge(v) points at (it
// need not be the most clockwise one while a mesh is being edited), and
// whether v is on the boundary. Empty when v is in no triangle.
inline bool star_of(const Mesh& m, VertexId v, std::vector<HalfEdgeId>& out, std::size_t max_degree = 4096) {
  out.clear();
  const HalfEdgeId start = m.out_edge(v);
  if (start == kNone) return false;
  HalfEdgeId e = start;
  for (std::size_t k = 0; k <= max_degree; ++k) {  // to the most clockwise
    const HalfEdgeId c = m.rotate_cw(e);
    if (c == kNone || c == start) break;
    e = c;
  }
  const HalfEdgeId first = e;
  do {
    out.push_back(e);
    e = m.rotate_ccw(e);
  } while (e != kNone && e != first && out.size() <= max_degree);
  return e == kNone;
}

// The neighbours of v: the out-edges' ends, and on the boundary the last
// in-edge's origin too.
inline void neighbors_of(const Mesh& m, VertexId v, std::vector<HalfEdgeId>& scratch, std::vector<VertexId>& nbr) {
  nbr.clear();
  const bool boundary = star_of(m, v, scratch);
  for (HalfEdgeId e : scratch) nbr.push_back(m.dest(e));
  if (boundary && !scratch.empty()) nbr.push_back(m.origin(prev_edge(scratch.back())));
}

}  // namespace deltamesh::adaptation
