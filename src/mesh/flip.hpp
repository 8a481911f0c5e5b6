// The edge flip on a mesh's raw per-half-edge arrays, written once: Mesh::flip
// and the hot insertion loops (Delaunay's bulk builder, the CDT's chain
// order) all call flip_arrays, each compiled with only the arrays it keeps.
#pragma once
#include <cstdint>

#include "deltamesh/geometry.hpp"
#include "deltamesh/mesh.hpp"
#include "mesh/editor.hpp"

namespace deltamesh::detail {

// Local index arithmetic without divisions in the hot loops.
inline constexpr std::uint8_t kNextIndex[3] = {1, 2, 0};
inline constexpr std::uint8_t kPrevIndex[3] = {2, 0, 1};

// Raw views of a mesh's arrays. The optional ones may be null.
struct MeshArrays {
  VertexId* tv = nullptr;           // 3 per triangle slot
  HalfEdgeId* tw = nullptr;         // twin per half-edge
  std::uint8_t* flags = nullptr;    // EdgeFlag bits per half-edge
  int* markers = nullptr;           // segment marker (or id) per half-edge
  HalfEdgeId* out = nullptr;        // one outgoing half-edge per vertex
  const Point* pts = nullptr;
  TraceObserver* trace = nullptr;   // the mesh's observer (trace_hooks.hpp), or null

  // The arrays of m (optional ones null while empty); valid until m's
  // arrays reallocate.
  static MeshArrays of(Mesh& m) {
    MeshArrays a;
    a.tv = detail::MeshEditor(m).triangle_vertices().data();
    a.tw = detail::MeshEditor(m).twins().data();
    a.flags = detail::MeshEditor(m).edge_flags().empty() ? nullptr : detail::MeshEditor(m).edge_flags().data();
    a.markers = detail::MeshEditor(m).edge_markers().empty() ? nullptr : detail::MeshEditor(m).edge_markers().data();
    a.out = detail::MeshEditor(m).out_edges().data();
    a.pts = m.points().data();
    a.trace = m.trace();
    return a;
  }
};

// Which arrays a flip keeps up to date. A set bit means "may be present":
// the array is used when its pointer is not null. kOpenTwins: twins may be
// kNone (a compacted mesh); without it every edge around the quadrilateral
// has a twin (a closed triangulation with ghosts).
enum FlipCarry : unsigned {
  kCarryTopologyOnly = 0,
  kCarryFlags = 1,
  kCarryMarkers = 2,
  kCarryOutEdges = 4,
  kOpenTwins = 8,
  kCarryAll = kCarryFlags | kCarryMarkers | kCarryOutEdges | kOpenTwins,
};

// The six half-edges of the quadrilateral around the edge of e: e = a -> b,
// e1 = b -> c, e2 = c -> a in one triangle, f = b -> a, f1 = a -> d,
// f2 = d -> b in the other (local indices by table, no division per edge).
struct FlipQuad {
  HalfEdgeId e, e1, e2, f, f1, f2;
};
inline FlipQuad flip_quad(const HalfEdgeId* tw, HalfEdgeId e) {
  const unsigned ie = e % 3;
  const HalfEdgeId f = tw[e];
  const unsigned jf = f % 3;
  return {e, e - ie + kNextIndex[ie], e - ie + kPrevIndex[ie], f, f - jf + kNextIndex[jf], f - jf + kPrevIndex[jf]};
}

// Per-half-edge data across the flip of q (flip_arrays below): the outer
// edges' data moves with them, the new edge gets none. Any per-half-edge
// array kept beside a mesh's (a CDT builder's segment ids) goes through it.
template <class T>
inline void carry_flip(T* data, const FlipQuad& q) {
  // (Indices copied first: stores through a byte array may alias q.)
  const HalfEdgeId e0 = q.e, e1 = q.e1, e2 = q.e2, f0 = q.f, f1 = q.f1, f2 = q.f2;
  const T bc = data[e1], ca = data[e2], ad = data[f1], db = data[f2];
  data[e0] = ca;
  data[e1] = ad;
  data[e2] = 0;
  data[f0] = db;
  data[f1] = bc;
  data[f2] = 0;
}

// Flips the edge of half-edge e = (a, b) between (a, b, c) and (b, a, d)
// into (c, d): e's slot becomes (c, a, d), its twin's (d, b, c); both keep
// their slots. Flags and markers move with the edges they belong to; the
// new edge gets none. Returns the new half-edge c -> d. The caller
// guarantees the quadrilateral is strictly convex.
template <unsigned Carry>
inline HalfEdgeId flip_arrays(const MeshArrays& m, const FlipQuad& q) {
  const HalfEdgeId e0 = q.e, e1 = q.e1, e2 = q.e2, f0 = q.f, f1 = q.f1, f2 = q.f2;
  VertexId* const tv = m.tv;
  HalfEdgeId* const tw = m.tw;
  const VertexId a = tv[e0], b = tv[e1], c = tv[e2], d = tv[f2];
  const HalfEdgeId tw_bc = tw[e1], tw_ca = tw[e2], tw_ad = tw[f1], tw_db = tw[f2];
  tv[e0] = c;
  tv[e1] = a;
  tv[e2] = d;
  tv[f0] = d;
  tv[f1] = b;
  tv[f2] = c;
  auto relink = [tw](HalfEdgeId x, HalfEdgeId y) {
    tw[x] = y;
    if constexpr ((Carry & kOpenTwins) != 0) {
      if (y != kNone) tw[y] = x;
    } else {
      tw[y] = x;
    }
  };
  relink(e0, tw_ca);
  relink(e1, tw_ad);
  relink(f0, tw_db);
  relink(f1, tw_bc);
  tw[e2] = f2;
  tw[f2] = e2;
  const FlipQuad local{e0, e1, e2, f0, f1, f2};  // (q itself may alias the stores above)
  if constexpr ((Carry & kCarryFlags) != 0)
    if (m.flags) carry_flip(m.flags, local);
  if constexpr ((Carry & kCarryMarkers) != 0)
    if (m.markers) carry_flip(m.markers, local);
  if constexpr ((Carry & kCarryOutEdges) != 0) {
    // Each vertex's out-edge keeps pointing at an edge that plays its role.
    HalfEdgeId* const ve = m.out;
    if (a != kInfinite && (ve[a] == e0 || ve[a] == f1)) ve[a] = e1;
    if (b != kInfinite && (ve[b] == e1 || ve[b] == f0)) ve[b] = f1;
    if (c != kInfinite && ve[c] == e2) ve[c] = e0;
    if (d != kInfinite && ve[d] == f2) ve[d] = f0;
  }
  return f2;
}

template <unsigned Carry>
inline HalfEdgeId flip_arrays(const MeshArrays& m, HalfEdgeId e) {
  return flip_arrays<Carry>(m, flip_quad(m.tw, e));
}

}  // namespace deltamesh::detail
