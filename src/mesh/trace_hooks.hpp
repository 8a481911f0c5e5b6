// What the algorithms call to report to a TraceObserver (include/deltamesh/
// trace.hpp). Every call site tests the observer pointer first, off the hot
// path, so with no observer nothing here runs. The algorithms report which
// triangle slots an operation wrote; TraceAccess turns slot contents into
// removed/added triangles through the observer's copy of the slots.
#pragma once
#include <initializer_list>
#include <span>

#include "deltamesh/mesh.hpp"
#include "deltamesh/trace.hpp"
#include "mesh/flip.hpp"

namespace deltamesh::detail {

struct TraceAccess {
  // Reports `ev` with the triangles the slots held before (removed) and
  // hold now in tv (added); a slot holding the same triangle counts as
  // neither.
  static void slots(TraceObserver& o, TraceEvent ev, const VertexId* tv, std::span<const TriId> slots);
  static void slots(TraceObserver& o, const TraceEvent& ev, const VertexId* tv, std::initializer_list<TriId> s) {
    slots(o, ev, tv, std::span<const TriId>(s.begin(), s.size()));
  }
  // The algorithms' coordinates are the user's times 2^k (pipeline's frame).
  static void set_frame(TraceObserver& o, int k) { o.frame_exponent_ = k; }
  // An event that changes no triangle.
  static void plain(TraceObserver& o, const TraceEvent& ev);
  // After a flip by flip_arrays of quad q (e's slot holds (c, a, d), f's (d, b, c)).
  static void flip(TraceObserver& o, TraceReason why, const VertexId* tv, const FlipQuad& q);
  // After Mesh::flip(e) where f was e's twin (both keep their slots).
  static void flip_at(TraceObserver& o, TraceReason why, const VertexId* tv, HalfEdgeId e, HalfEdgeId f) {
    flip(o, why, tv, FlipQuad{e, next_edge(e), prev_edge(e), f, next_edge(f), prev_edge(f)});
  }
  // The mesh went back to an earlier copy (tv, `vertices` vertices): every
  // slot that differs is reported in one Undo event, then the vertices
  // added since are dropped (a Renumber).
  static void rewind(TraceObserver& o, std::span<const VertexId> tv, std::size_t vertices, std::size_t before);
  // The slots were renumbered (compaction) or rewritten wholesale: takes tv
  // as the new copy after checking it holds the same triangles. A
  // difference is an operation nobody reported: InternalError.
  static void resync(TraceObserver& o, std::span<const VertexId> tv, const char* where);
  static void phase(TraceObserver& o, std::string_view name) {
    TraceEvent ev;
    ev.kind = TraceKind::Phase;
    ev.phase = name;
    plain(o, ev);
  }
  static void points(TraceObserver& o, VertexId first, std::span<const Point> pts) {
    TraceEvent ev;
    ev.kind = TraceKind::Points;
    ev.vertex = first;
    ev.points = pts;
    plain(o, ev);
  }
  // Vertex i is now map[i] (kNone: gone), `vertices` in all; the copy of
  // the slots is renumbered too.
  static void renumber(TraceObserver& o, std::span<const VertexId> map, std::size_t vertices);
};

// Vertex v at p inserted into the slots listed (the split's).
inline TraceEvent trace_insert(VertexId v, const Point& p, TraceReason why = TraceReason::Delaunay) {
  TraceEvent ev;
  ev.kind = TraceKind::Insert;
  ev.reason = why;
  ev.vertex = v;
  ev.point = p;
  return ev;
}

inline TraceEvent trace_event(TraceKind kind, TraceReason why) {
  TraceEvent ev;
  ev.kind = kind;
  ev.reason = why;
  return ev;
}

// Triangles removed from the slots listed (domain carving).
inline void trace_carved(const Mesh& m, std::span<const TriId> slots) {
  TraceAccess::slots(*m.trace(), trace_event(TraceKind::Carve, TraceReason::None), m.triangle_vertices().data(), slots);
}

// While an algorithm runs in a power-of-two frame (algo/normalize.hpp), the
// observer is told k so it can report the user's coordinates; it is told 0
// again on every way out, a thrown exception included, so an observer that
// outlives a failed run is not left scaled. No observer: nothing happens.
class TraceFrameScope {
 public:
  TraceFrameScope(TraceObserver* o, int k) : o_(o) {
    if (o_) TraceAccess::set_frame(*o_, k);
  }
  ~TraceFrameScope() { end(); }
  TraceFrameScope(const TraceFrameScope&) = delete;
  TraceFrameScope& operator=(const TraceFrameScope&) = delete;
  // Ends the frame early (events after this are in the user's frame).
  void end() {
    if (o_) TraceAccess::set_frame(*o_, 0);
    o_ = nullptr;
  }

 private:
  TraceObserver* o_;
};

}  // namespace deltamesh::detail
