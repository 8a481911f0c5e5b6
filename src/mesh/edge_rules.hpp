// Small rules about a mesh's edges and vertices, one home each, shared by the
// algorithms, the writers (src/io) and the Python module:
//   edge_key            - an undirected edge as one sortable integer;
//   real_twin           - the neighbour half-edge, or kNone on the boundary;
//   is_segment_edge     - constrained on either half;
//   edge_output_marker  - Triangle's boundary-marker rule for edges;
//   boundary_vertices / vertex_output_marker - the rule for vertices;
//   for_each_edge       - each edge of the live real triangles once.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "deltamesh/mesh.hpp"

namespace deltamesh {

// The undirected edge {u, v} as one integer (smaller id in the high half).
inline std::uint64_t edge_key(VertexId u, VertexId v) {
  return (std::uint64_t{std::min(u, v)} << 32) | std::max(u, v);
}

// The twin of e when it lies in a live real triangle, else kNone: the mesh
// boundary, whether hull twins are kNone (compacted) or ghosts (not yet).
inline HalfEdgeId real_twin(const Mesh& m, HalfEdgeId e) {
  const HalfEdgeId f = m.twin(e);
  return f == kNone || !m.is_real(tri_of(f)) ? kNone : f;
}

// Is the edge of e part of a segment (constrained on either half)?
inline bool is_segment_edge(const Mesh& m, HalfEdgeId e) {
  if (m.is_constrained(e)) return true;
  const HalfEdgeId f = real_twin(m, e);
  return f != kNone && m.is_constrained(f);
}

// The boundary marker written for the edge of e (tw = real_twin(m, e)), by
// Triangle's documented rule: the marker of the segment it belongs to when
// that is nonzero; otherwise 1 on the mesh boundary (holes included);
// otherwise 0 (interior edges, and interior segments with marker 0).
inline int edge_output_marker(const Mesh& m, HalfEdgeId e, HalfEdgeId tw) {
  int marker = m.edge_marker(e);
  if (marker == 0 && tw != kNone) marker = m.edge_marker(tw);
  if (marker != 0) return marker;
  return tw == kNone ? 1 : 0;
}

// Calls f(e, boundary) once per edge of the live real triangles: e is the
// half-edge with no real twin (boundary = true), or the lower of the two.
template <class F>
void for_each_edge(const Mesh& m, F&& f) {
  for (TriId t : m.triangles()) {
    for (HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e) {
      const HalfEdgeId tw = real_twin(m, e);
      if (tw == kNone || e < tw) f(e, tw == kNone);
    }
  }
}

// 1 for vertices on an edge of the mesh boundary, 0 otherwise.
inline std::vector<std::uint8_t> boundary_vertices(const Mesh& m) {
  std::vector<std::uint8_t> on(m.num_vertices(), 0);
  for_each_edge(m, [&](HalfEdgeId e, bool boundary) {
    if (boundary) on[m.origin(e)] = on[m.dest(e)] = 1;
  });
  return on;
}

// The boundary marker written for vertex v: its marker from the input when
// the mesh has one for it, otherwise 1 on the boundary and 0 elsewhere
// (on_boundary from boundary_vertices(); needed only when markers run short).
inline int vertex_output_marker(const Mesh& m, VertexId v, const std::vector<std::uint8_t>& on_boundary) {
  const std::vector<int>& given = m.vertex_markers();
  return v < given.size() ? given[v] : on_boundary[v];
}

}  // namespace deltamesh
