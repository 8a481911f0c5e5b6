// Triangle and edge splits on a mesh's raw arrays, written once: the Mesh's
// own split_triangle / split_edge and the hot insertion loops (Delaunay's
// bulk builder, the CDT's chain order) call them with the slots they
// allocated. Carry bits as for flip_arrays (mesh/flip.hpp). And the first
// triangle of a closed triangulation, which every builder starts from.
#pragma once
#include "mesh/flip.hpp"

namespace deltamesh::detail {

// Per-half-edge data across the splits below (carry_flip's counterparts in
// mesh/flip.hpp). A triangle split: bc and ca move to slots t1 and t2, the
// new edges get none.
template <class T>
inline void carry_split_triangle(T* data, TriId t, TriId t1, TriId t2) {
  const HalfEdgeId e1 = 3 * t + 1, e2 = 3 * t + 2, g0 = 3 * t1, h0 = 3 * t2;
  data[g0] = data[e1];
  data[h0] = data[e2];
  data[e1] = data[e2] = data[g0 + 1] = data[g0 + 2] = data[h0 + 1] = data[h0 + 2] = 0;
}

// One side of an edge split: e = (a, b) and its next edge e1 in (a, b, c)
// become (a, v, c) and (v, b, c) in slot t3; v -> b and b -> c keep e's and
// e1's data, the edges to c get none.
template <class T>
inline void carry_split_edge_side(T* data, HalfEdgeId e, HalfEdgeId e1, TriId t3) {
  const HalfEdgeId g0 = 3 * t3;
  data[g0] = data[e];
  data[g0 + 1] = data[e1];
  data[e1] = data[g0 + 2] = 0;
}

// Triangle t = (a, b, c) split at v into (a, b, v) in t, (b, c, v) in slot
// t1 and (c, a, v) in slot t2 (both allocated, contents overwritten). The
// outer edges bc and ca keep their twins, flags and markers; the three new
// edges get none. Returns the half-edge v -> a in t.
template <unsigned Carry>
inline HalfEdgeId split_triangle_arrays(const MeshArrays& m, TriId t, VertexId v, TriId t1, TriId t2) {
  VertexId* const tv = m.tv;
  HalfEdgeId* const tw = m.tw;
  const HalfEdgeId e0 = 3 * t, e1 = e0 + 1, e2 = e0 + 2;
  const HalfEdgeId g0 = 3 * t1, h0 = 3 * t2;
  const VertexId a = tv[e0], b = tv[e1], c = tv[e2];
  const HalfEdgeId tw_bc = tw[e1], tw_ca = tw[e2];
  tv[g0] = b;
  tv[g0 + 1] = c;
  tv[g0 + 2] = v;
  tv[h0] = c;
  tv[h0 + 1] = a;
  tv[h0 + 2] = v;
  tv[e2] = v;
  tw[g0] = tw_bc;
  tw[h0] = tw_ca;
  if ((Carry & kOpenTwins) == 0 || tw_bc != kNone) tw[tw_bc] = g0;
  if ((Carry & kOpenTwins) == 0 || tw_ca != kNone) tw[tw_ca] = h0;
  tw[e1] = g0 + 2;
  tw[g0 + 2] = e1;
  tw[g0 + 1] = h0 + 2;
  tw[h0 + 2] = g0 + 1;
  tw[h0 + 1] = e2;
  tw[e2] = h0 + 1;
  if constexpr ((Carry & kCarryFlags) != 0)
    if (m.flags) carry_split_triangle(m.flags, t, t1, t2);
  if constexpr ((Carry & kCarryMarkers) != 0)
    if (m.markers) carry_split_triangle(m.markers, t, t1, t2);
  if constexpr ((Carry & kCarryOutEdges) != 0) {
    HalfEdgeId* const ve = m.out;
    if (b != kInfinite && ve[b] == e1) ve[b] = g0;
    if (c != kInfinite && ve[c] == e2) ve[c] = h0;
    if (v != kInfinite) ve[v] = e2;
  }
  return e2;
}

// The edge of e = (a, b) in (a, b, c) split at v: (a, b, c) becomes (a, v, c)
// in its slot and (v, b, c) in slot t3; when e has a twin f in (b, a, d),
// that becomes (b, v, d) and (v, a, d) in slot t4 (unused without a twin).
// Both halves of the split edge keep its flags and marker, so do the outer
// edges; the new edges to c and d get none. Returns the half-edge v -> b.
template <unsigned Carry>
inline HalfEdgeId split_edge_arrays(const MeshArrays& m, HalfEdgeId e, VertexId v, TriId t3, TriId t4) {
  VertexId* const tv = m.tv;
  HalfEdgeId* const tw = m.tw;
  const unsigned ie = e % 3;
  const HalfEdgeId e1 = e - ie + kNextIndex[ie], e2 = e - ie + kPrevIndex[ie];
  const HalfEdgeId f = tw[e];
  const bool two_sided = (Carry & kOpenTwins) == 0 || f != kNone;
  const VertexId a = tv[e], b = tv[e1], c = tv[e2];
  const HalfEdgeId tw_bc = tw[e1];
  const HalfEdgeId g0 = 3 * t3;
  tv[g0] = v;
  tv[g0 + 1] = b;
  tv[g0 + 2] = c;
  tv[e1] = v;
  tw[g0 + 1] = tw_bc;
  if ((Carry & kOpenTwins) == 0 || tw_bc != kNone) tw[tw_bc] = g0 + 1;
  tw[g0 + 2] = e1;
  tw[e1] = g0 + 2;
  if constexpr ((Carry & kCarryFlags) != 0)
    if (m.flags) carry_split_edge_side(m.flags, e, e1, t3);
  if constexpr ((Carry & kCarryMarkers) != 0)
    if (m.markers) carry_split_edge_side(m.markers, e, e1, t3);
  if constexpr ((Carry & kCarryOutEdges) != 0) {
    if (b != kInfinite && m.out[b] == e1) m.out[b] = g0 + 1;
    if (v != kInfinite) m.out[v] = g0;
  }
  if (!two_sided) {
    tw[e] = kNone;
    tw[g0] = kNone;
    return g0;
  }
  const unsigned jf = f % 3;
  const HalfEdgeId f1 = f - jf + kNextIndex[jf], f2 = f - jf + kPrevIndex[jf];
  const VertexId d = tv[f2];
  const HalfEdgeId tw_ad = tw[f1];
  const HalfEdgeId h0 = 3 * t4;
  tv[h0] = v;
  tv[h0 + 1] = a;
  tv[h0 + 2] = d;
  tv[f1] = v;
  tw[h0 + 1] = tw_ad;
  if ((Carry & kOpenTwins) == 0 || tw_ad != kNone) tw[tw_ad] = h0 + 1;
  tw[h0 + 2] = f1;
  tw[f1] = h0 + 2;
  tw[e] = h0;
  tw[h0] = e;
  tw[g0] = f;
  tw[f] = g0;
  if constexpr ((Carry & kCarryFlags) != 0)
    if (m.flags) carry_split_edge_side(m.flags, f, f1, t4);
  if constexpr ((Carry & kCarryMarkers) != 0)
    if (m.markers) carry_split_edge_side(m.markers, f, f1, t4);
  if constexpr ((Carry & kCarryOutEdges) != 0)
    if (a != kInfinite && m.out[a] == f1) m.out[a] = h0 + 1;
  return g0;
}

// Starts a closed triangulation: real triangle (a, b, c), counter-clockwise,
// plus its three ghost triangles, all linked; out-edges set.
void make_first_triangle(Mesh& mesh, VertexId a, VertexId b, VertexId c);

}  // namespace deltamesh::detail
