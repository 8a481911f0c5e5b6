// Constrained Lawson legalization, written once (Lawson 1977; the constrained
// form: Chew 1989, and the seed's §2.2). Two loops share the flip test and
// the flip:
//   legalize_around_vertex - after a vertex is inserted (split of a triangle
//     or an edge): the edges opposite it, Delaunay insertion's flips;
//   constrained_lawson - from any set of edges until each edge looked at is
//     locally Delaunay (after segment recovery, releases, removals).
// Constrained edges are never flipped. Both run over a "topology": MeshTopology
// (the Mesh's own operations, which keep its counts) or RawTopology (the raw
// arrays of a hot loop, compiled with only the arrays it keeps).
#pragma once
#include <cstddef>
#include <vector>

#include "deltamesh/mesh.hpp"
#include "deltamesh/predicates.hpp"
#include "mesh/flip.hpp"
#include "mesh/trace_hooks.hpp"

namespace deltamesh::detail {

// The exact incircle test, the default of RawTopology.
struct ExactIncircle {
  double operator()(const Point& a, const Point& b, const Point& c, const Point& d) const {
    return incircle(a, b, c, d);
  }
};

// A Mesh through its public operations (flip keeps its live-triangle count).
// `carried`, when given, is a per-half-edge array kept beside the mesh's
// (a CDT builder's segment ids): flips carry it as they carry markers.
class MeshTopology {
 public:
  explicit MeshTopology(Mesh& m, int* carried = nullptr) : m_(m), carried_(carried) {}
  VertexId origin(HalfEdgeId e) const { return m_.origin(e); }
  HalfEdgeId twin(HalfEdgeId e) const { return m_.twin(e); }
  const Point& point(VertexId v) const { return m_.point(v); }
  bool constrained(HalfEdgeId e) const { return m_.is_constrained(e); }
  double in_circle(const Point& a, const Point& b, const Point& c, const Point& d) const {
    return incircle(a, b, c, d);
  }
  FlipQuad quad(HalfEdgeId e) const {
    const HalfEdgeId f = m_.twin(e);
    return {e, next_edge(e), prev_edge(e), f, f == kNone ? kNone : next_edge(f), f == kNone ? kNone : prev_edge(f)};
  }
  void flip(const FlipQuad& q, TraceReason why) {
    m_.flip(q.e);
    if (carried_) carry_flip(carried_, q);
    if (TraceObserver* t = m_.trace()) [[unlikely]]
      TraceAccess::flip(*t, why, m_.triangle_vertices().data(), q);
  }

 private:
  Mesh& m_;
  int* carried_;
};

// Raw arrays of a mesh. Carry says which optional arrays flips keep
// (flip.hpp); constrained edges are known only when flags are carried. The
// caller keeps live-triangle counts itself (a flip between two real
// triangles, all constrained_lawson makes, leaves them as they are).
template <unsigned Carry, class InCircle = ExactIncircle>
class RawTopology {
 public:
  explicit RawTopology(const MeshArrays& a, InCircle in_circle = {}) : a_(a), in_circle_(in_circle) {}
  VertexId origin(HalfEdgeId e) const { return a_.tv[e]; }
  HalfEdgeId twin(HalfEdgeId e) const { return a_.tw[e]; }
  const Point& point(VertexId v) const { return a_.pts[v]; }
  bool constrained(HalfEdgeId e) const {
    if constexpr ((Carry & kCarryFlags) != 0) return a_.flags != nullptr && (a_.flags[e] & kConstrained) != 0;
    return false;
  }
  double in_circle(const Point& a, const Point& b, const Point& c, const Point& d) const {
    return in_circle_(a, b, c, d);
  }
  FlipQuad quad(HalfEdgeId e) const { return flip_quad(a_.tw, e); }
  void flip(const FlipQuad& q, TraceReason why) {
    flip_arrays<Carry>(a_, q);
    if (a_.trace) [[unlikely]]
      TraceAccess::flip(*a_.trace, why, a_.tv, q);
  }

 private:
  MeshArrays a_;
  InCircle in_circle_;
};

// Is p strictly inside the circle of the triangle (b, a, d) across edge
// a -> b? Across a hull edge the "circle" of a ghost triangle is the open
// half-plane beyond it (a ghost's own edges are never flipped).
template <class Topo>
inline bool breaks_edge(const Topo& m, VertexId a, VertexId b, VertexId d, const Point& p) {
  if (d == kInfinite) return false;
  if (b == kInfinite) return orient2d(m.point(a), m.point(d), p) > 0;
  if (a == kInfinite) return orient2d(m.point(d), m.point(b), p) > 0;
  return m.in_circle(m.point(a), m.point(b), p, m.point(d)) > 0;
}

struct LegalizeResult {
  std::size_t flips = 0;
  HalfEdgeId last = kNone;  // the half-edge popped last: its triangle touches v
};

// Lawson flips after inserting v: every half-edge on the stack lies opposite
// v in its triangle (a -> b in (a, b, v)). An edge whose neighbour's circle
// holds v is flipped, and the two edges it uncovers (now opposite v) are
// looked at in turn; the stack is empty on return.
template <class Topo>
inline LegalizeResult legalize_around_vertex(Topo& m, VertexId v, std::vector<HalfEdgeId>& stack) {
  LegalizeResult r;
  const Point p = m.point(v);
  while (!stack.empty()) {
    const HalfEdgeId e = stack.back();
    stack.pop_back();
    r.last = e;
    if (m.constrained(e) || m.twin(e) == kNone) continue;
    const FlipQuad q = m.quad(e);
    const VertexId a = m.origin(e), b = m.origin(q.e1), d = m.origin(q.f2);
    if (!breaks_edge(m, a, b, d, p)) continue;
    // (a, b, v) + (b, a, d) become (v, a, d) in e's slot and (d, b, v) in f's.
    m.flip(q, TraceReason::Delaunay);
    ++r.flips;
    stack.push_back(q.e1);  // a -> d
    stack.push_back(q.f);   // d -> b
  }
  return r;
}

// Constrained Lawson flips from the half-edges on `stack` until every edge
// pushed is locally Delaunay. Edges of ghost or dead triangles, hull edges
// and constrained edges are left alone. A flip pushes the four edges around
// it, so an edge that changes neighbours is always looked at again.
// Returns the number of flips.
template <class Topo>
inline std::size_t constrained_lawson(Topo& m, std::vector<HalfEdgeId>& stack) {
  std::size_t flips = 0;
  while (!stack.empty()) {
    const HalfEdgeId e = stack.back();
    stack.pop_back();
    if (m.twin(e) == kNone || m.constrained(e)) continue;
    const FlipQuad q = m.quad(e);
    const VertexId a = m.origin(e), b = m.origin(q.e1), c = m.origin(q.e2), d = m.origin(q.f2);
    // kInfinite (a ghost) and kNone (a dead slot) are the two largest ids.
    if (a >= kInfinite || b >= kInfinite || c >= kInfinite || d >= kInfinite) continue;
    // d strictly inside the circle of abc, across ab: the quadrilateral is
    // strictly convex, so the flip is valid.
    if (!(m.in_circle(m.point(a), m.point(b), m.point(c), m.point(d)) > 0)) continue;
    m.flip(q, TraceReason::Lawson);  // e's slot becomes (c, a, d), f's (d, b, c)
    ++flips;
    stack.push_back(e);
    stack.push_back(q.e1);
    stack.push_back(q.f);
    stack.push_back(q.f1);
  }
  return flips;
}

// The whole mesh for constrained_lawson(): every array carried, open twins.
inline RawTopology<kCarryAll> lawson_topology(Mesh& m) { return RawTopology<kCarryAll>(MeshArrays::of(m)); }

// Constrained Lawson flips over every edge of the mesh's real triangles
// until the whole mesh is constrained Delaunay. Returns the number of flips.
std::size_t constrained_lawson_flips(Mesh& mesh);

}  // namespace deltamesh::detail
