// Bowyer-Watson cavities on a mesh's raw arrays, written once (A. Bowyer,
// "Computing Dirichlet tessellations", and D. F. Watson, "Computing the
// n-dimensional Delaunay tessellation", Comput. J. 1981). Find: the triangles
// whose circumcircle strictly contains a point (exact incircle), grown from a
// seed without crossing constrained edges, and the cavity's boundary in
// counter-clockwise order; read-only, so a caller can look at the cavity
// (encroachment, visibility) before anything changes. Commit: the point's
// fan written into the cavity's slots (and new ones), one triangle per
// boundary edge, its spokes linked. Inline: refinement builds one cavity per
// candidate point.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "deltamesh/predicates.hpp"
#include "mesh/flip.hpp"

namespace deltamesh::detail {

// The triangle slots of the current cavity, with membership in O(1): a slot
// is in it while its stamp is the current one (a huge cocircular cavity made
// a linear search quadratic).
class CavitySet {
 public:
  // A new, empty cavity.
  void begin() {
    tris_.clear();
    if (++now_ == 0) {
      std::fill(stamp_.begin(), stamp_.end(), 0);
      now_ = 1;
    }
  }
  void add(TriId t) {
    if (t >= stamp_.size()) stamp_.resize(std::max<std::size_t>(t + 1, 2 * stamp_.size()), 0);
    add_reserved(t);
  }
  // Stamps for every slot below `slots` up front, so that add_reserved()
  // needs no check per triangle.
  void reserve_slots(std::size_t slots) {
    if (stamp_.size() < slots) stamp_.resize(slots, 0);
  }
  void add_reserved(TriId t) {
    stamp_[t] = now_;
    tris_.push_back(t);
  }
  bool contains(TriId t) const { return t < stamp_.size() && stamp_[t] == now_; }
  std::size_t size() const { return tris_.size(); }
  TriId operator[](std::size_t i) const { return tris_[i]; }
  const std::vector<TriId>& tris() const { return tris_; }

 private:
  std::vector<TriId> tris_;
  std::vector<std::uint32_t> stamp_;
  std::uint32_t now_ = 0;
};

// Grows the cavity of c depth-first from the half-edges on `stack` (each
// inside the cavity, its twin a candidate) until the stack is empty. A
// neighbour across an unconstrained edge joins when c lies strictly inside
// its circumcircle; every other edge is a boundary edge, passed to
// record(e) in counter-clockwise order around the cavity. False when a
// triangle is met twice: the cavity's dual graph is a tree, so the
// predicates and the mesh disagree (the caller gives up on c).
template <class Record>
inline bool grow_cavity(const MeshArrays& m, const Point& c, CavitySet& cavity, std::vector<HalfEdgeId>& stack,
                        Record&& record) {
  const VertexId* const tv = m.tv;
  const HalfEdgeId* const tw = m.tw;
  const Point* const pts = m.pts;
  while (!stack.empty()) {
    const HalfEdgeId e = stack.back();
    stack.pop_back();
    const HalfEdgeId f = tw[e];
    if (f != kNone && !(m.flags[e] & kConstrained)) {
      const TriId u = tri_of(f);
      const Point& pa = pts[tv[f]];
      const Point& pb = pts[tv[next_edge(f)]];
      const Point& pc = pts[tv[prev_edge(f)]];
      if (incircle(pa, pb, pc, c) > 0) {
        if (cavity.contains(u)) return false;
        cavity.add(u);
        stack.push_back(prev_edge(f));
        stack.push_back(next_edge(f));
        continue;
      }
    }
    record(e);
  }
  return true;
}

// Commit, one fan triangle: slot t becomes (v, a, b) for the boundary edge
// a -> b whose outside half-edge is `outer` (or kNone); that edge keeps its
// flags and marker, the spokes v -> a and b -> v get none (link_spokes()
// joins them). Carry as for flip_arrays: which optional arrays are written.
template <unsigned Carry>
inline void write_fan_triangle(const MeshArrays& m, TriId t, VertexId v, VertexId a, VertexId b, HalfEdgeId outer,
                               std::uint8_t flags, int marker) {
  const HalfEdgeId e = 3 * t;
  m.tv[e] = v;
  m.tv[e + 1] = a;
  m.tv[e + 2] = b;
  m.tw[e + 1] = outer;
  if (outer != kNone) m.tw[outer] = e + 1;
  if constexpr ((Carry & kCarryFlags) != 0) {
    m.flags[e] = 0;
    m.flags[e + 1] = flags;
    m.flags[e + 2] = 0;
  }
  if constexpr ((Carry & kCarryMarkers) != 0) {
    if (m.markers) {
      m.markers[e] = 0;
      m.markers[e + 1] = marker;
      m.markers[e + 2] = 0;
    }
  }
}

// Commit, the spokes: consecutive fan triangles around v, in slots t and
// next, share a spoke (b -> v of t is v -> b of next).
inline void link_spoke(HalfEdgeId* tw, TriId t, TriId next) {
  tw[3 * t + 2] = 3 * next;
  tw[3 * next] = 3 * t + 2;
}

// The spokes of the fan in slots fan[lo..hi); `closed`: the last one's with
// the first one's too (v inside the cavity).
inline void link_spokes(HalfEdgeId* tw, const TriId* fan, std::size_t lo, std::size_t hi, bool closed) {
  for (std::size_t i = lo; i + 1 < hi; ++i) link_spoke(tw, fan[i], fan[i + 1]);
  if (closed && hi > lo) link_spoke(tw, fan[hi - 1], fan[lo]);
}

}  // namespace deltamesh::detail
