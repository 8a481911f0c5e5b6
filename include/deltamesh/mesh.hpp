// The triangulation data structure: index-based, implicit half-edges with a
// twin array, ghost triangles on a vertex at infinity, free list, compaction.
// Topology only: no Delaunay knowledge lives here.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <ranges>
#include <span>
#include <string>
#include <vector>

#include "deltamesh/geometry.hpp"

namespace deltamesh {

namespace detail {
class MeshEditor;  // raw array access for the library's own hot loops (not installed)
}

class TraceObserver;  // deltamesh/trace.hpp

// The observer a mesh reports to: moves carry it, copies do not (a copy is
// another mesh, e.g. a background mesh or a kept state, and its changes are
// not the traced run's).
struct TraceLink {
  TraceObserver* ptr = nullptr;
  TraceLink() = default;
  TraceLink(const TraceLink&) {}
  TraceLink(TraceLink&& o) noexcept : ptr(o.ptr) {}
  TraceLink& operator=(const TraceLink&) {
    ptr = nullptr;
    return *this;
  }
  TraceLink& operator=(TraceLink&& o) noexcept {
    ptr = o.ptr;
    return *this;
  }
};

// Where a point lies relative to the triangulation (result of Mesh::locate).
struct Location {
  enum class Kind : std::uint8_t {
    InTriangle,  // strictly inside real triangle `tri`
    OnEdge,      // in the open half-edge `edge` (its twin is the same edge)
    OnVertex,    // coincides with `vertex`
    Outside,     // outside the convex hull; `tri` is a ghost triangle whose
                 // real edge the point sees strictly from outside
  };
  Kind kind = Kind::Outside;
  TriId tri = kNone;
  HalfEdgeId edge = kNone;
  VertexId vertex = kNone;
};

// Per-half-edge flag bits.
enum EdgeFlag : std::uint8_t {
  kConstrained = 1,  // part of an input segment: never flipped
};

// Ids in [0, end) that a filter accepts, as a forward range: what
// Mesh::triangles(), edges() and boundary_edges() return, so that the skipping
// of dead and ghost slots is written once.
template <class M, class Filter>
class FilteredIds {
 public:
  class iterator {
   public:
    using value_type = std::uint32_t;
    using difference_type = std::ptrdiff_t;
    iterator() = default;
    iterator(const M* m, std::uint32_t i, std::uint32_t end) : m_(m), i_(i), end_(end) { skip(); }
    std::uint32_t operator*() const { return i_; }
    iterator& operator++() {
      ++i_;
      skip();
      return *this;
    }
    iterator operator++(int) {
      iterator old = *this;
      ++*this;
      return old;
    }
    bool operator==(const iterator& o) const { return i_ == o.i_; }

   private:
    void skip() {
      while (i_ < end_ && !Filter{}(*m_, i_)) ++i_;
    }
    const M* m_ = nullptr;
    std::uint32_t i_ = 0, end_ = 0;
  };
  FilteredIds(const M& m, std::uint32_t end) : m_(&m), end_(end) {}
  iterator begin() const { return iterator(m_, 0, end_); }
  iterator end() const { return iterator(m_, end_, end_); }

 private:
  const M* m_;
  std::uint32_t end_;
};

namespace mesh_filters {
struct RealTriangle {
  template <class M>
  bool operator()(const M& m, TriId t) const { return m.is_real(t); }
};
// A half-edge of a real triangle whose other side holds no real triangle.
struct BoundaryEdge {
  template <class M>
  bool operator()(const M& m, HalfEdgeId e) const {
    if (!m.is_real(tri_of(e))) return false;
    const HalfEdgeId t = m.twin(e);
    return t == kNone || !m.is_real(tri_of(t));
  }
};
// Each edge of the real triangles once: the boundary half-edge, or the lower
// id of an interior pair.
struct Edge {
  template <class M>
  bool operator()(const M& m, HalfEdgeId e) const {
    if (!m.is_real(tri_of(e))) return false;
    const HalfEdgeId t = m.twin(e);
    return t == kNone || !m.is_real(tri_of(t)) || e < t;
  }
};
// Every id (Mesh::vertices(); std::views::iota would do, but the libc++ of
// Emscripten 3.1.6, the web build's, has no iota_view).
struct AnyId {
  template <class M>
  bool operator()(const M&, std::uint32_t) const { return true; }
};
}  // namespace mesh_filters

class Mesh {
 public:
  Mesh() = default;

  // ---- read-only views -------------------------------------------------
  std::size_t num_vertices() const { return points_.size(); }
  std::span<const Point> points() const { return points_; }
  const Point& point(VertexId v) const { return points_[v]; }

  // Triangle slots, including dead and (before compact()) ghost triangles.
  std::size_t num_triangle_slots() const { return tri_v_.size() / 3; }
  // Live real triangles (neither dead nor ghost).
  std::size_t num_triangles() const { return live_real_; }
  bool is_dead(TriId t) const { return tri_v_[3 * t] == kNone; }
  bool is_ghost(TriId t) const {
    return tri_v_[3 * t] == kInfinite || tri_v_[3 * t + 1] == kInfinite || tri_v_[3 * t + 2] == kInfinite;
  }
  bool is_real(TriId t) const { return !is_dead(t) && !is_ghost(t); }
  std::array<VertexId, 3> triangle(TriId t) const {
    return {tri_v_[3 * t], tri_v_[3 * t + 1], tri_v_[3 * t + 2]};
  }
  // Flat vertex array, 3 per triangle slot (raw: may contain kNone/kInfinite).
  std::span<const VertexId> triangle_vertices() const { return tri_v_; }

  // ---- ranges: for (TriId t : mesh.triangles()) ... -------------------------
  // Live real triangles in slot order (dead and ghost slots skipped).
  FilteredIds<Mesh, mesh_filters::RealTriangle> triangles() const {
    return {*this, static_cast<std::uint32_t>(num_triangle_slots())};
  }
  // One half-edge per edge of the real triangles, in half-edge order.
  FilteredIds<Mesh, mesh_filters::Edge> edges() const {
    return {*this, static_cast<std::uint32_t>(tri_v_.size())};
  }
  // The half-edges of real triangles with no real triangle across (the
  // domain's boundary, holes included), in half-edge order.
  FilteredIds<Mesh, mesh_filters::BoundaryEdge> boundary_edges() const {
    return {*this, static_cast<std::uint32_t>(tri_v_.size())};
  }
  // Every vertex id, used or not.
  FilteredIds<Mesh, mesh_filters::AnyId> vertices() const {
    return {*this, static_cast<std::uint32_t>(points_.size())};
  }

  VertexId origin(HalfEdgeId e) const { return tri_v_[e]; }
  VertexId dest(HalfEdgeId e) const { return tri_v_[next_edge(e)]; }
  // The opposite half-edge, or kNone on the boundary of a compacted mesh.
  HalfEdgeId twin(HalfEdgeId e) const { return twin_[e]; }
  // One outgoing half-edge of v (kNone when v is in no triangle). In a
  // compacted mesh, for a boundary vertex it is the most clockwise one, so a
  // counter-clockwise rotation from it meets every triangle around v.
  HalfEdgeId out_edge(VertexId v) const { return vert_edge_[v]; }
  // Next outgoing half-edge counter-clockwise around origin(e); kNone at a boundary.
  HalfEdgeId rotate_ccw(HalfEdgeId e) const { return twin_[prev_edge(e)]; }
  // Next outgoing half-edge clockwise around origin(e); kNone at a boundary.
  HalfEdgeId rotate_cw(HalfEdgeId e) const {
    const HalfEdgeId t = twin_[e];
    return t == kNone ? kNone : next_edge(t);
  }
  // The neighbour across half-edge e (kNone on the boundary).
  TriId neighbor(HalfEdgeId e) const { return twin_[e] == kNone ? kNone : tri_of(twin_[e]); }

  bool has_edge_flags() const { return !edge_flags_.empty(); }
  std::uint8_t edge_flags(HalfEdgeId e) const { return edge_flags_.empty() ? 0 : edge_flags_[e]; }
  bool is_constrained(HalfEdgeId e) const { return (edge_flags(e) & kConstrained) != 0; }
  // Boundary marker of the segment an edge belongs to (0 when none); kept on
  // both half-edges, moved by flips and copied by splits like the flags.
  bool has_edge_markers() const { return !edge_markers_.empty(); }
  int edge_marker(HalfEdgeId e) const { return edge_markers_.empty() ? 0 : edge_markers_[e]; }

  // Calls f(e) for each outgoing half-edge of v, counter-clockwise (rotary
  // traversal, §1.2.1). Stops early when f returns false.
  template <class F>
  void for_each_out_edge(VertexId v, F&& f) const {
    const HalfEdgeId start = vert_edge_[v];
    if (start == kNone) return;
    HalfEdgeId e = start;
    do {
      if (!f(e)) return;
      e = rotate_ccw(e);
    } while (e != kNone && e != start);
  }
  // The half-edge from a to b, or kNone (rotary traversal around a).
  HalfEdgeId find_edge(VertexId a, VertexId b) const;

  // ---- construction ------------------------------------------------------
  VertexId add_vertex(Point p) {
    points_.push_back(p);
    vert_edge_.push_back(kNone);
    return static_cast<VertexId>(points_.size() - 1);
  }
  void reserve(std::size_t vertices, std::size_t triangles);
  // New triangle (a, b, c), counter-clockwise, twins unset; reuses a dead slot.
  TriId add_triangle(VertexId a, VertexId b, VertexId c);
  void remove_triangle(TriId t);
  void link(HalfEdgeId e, HalfEdgeId f) {
    twin_[e] = f;
    twin_[f] = e;
  }
  void set_out_edge(VertexId v, HalfEdgeId e) { vert_edge_[v] = e; }
  void set_edge_flags(HalfEdgeId e, std::uint8_t flags);
  void set_edge_marker(HalfEdgeId e, int marker);
  // Marks both halves of an edge as a constrained segment with a marker.
  void constrain_edge(HalfEdgeId e, int marker = 0) {
    set_edge_flags(e, edge_flags(e) | kConstrained);
    set_edge_marker(e, marker);
    if (twin_[e] != kNone) {
      set_edge_flags(twin_[e], edge_flags(twin_[e]) | kConstrained);
      set_edge_marker(twin_[e], marker);
    }
  }

  // ---- topological operations ----------------------------------------------
  // Flips the edge of half-edge e = (a,b) between triangles (a,b,c) and (b,a,d)
  // into (c,d). Both triangles keep their slots. Returns the half-edge c->d.
  // The caller guarantees the quadrilateral is strictly convex.
  HalfEdgeId flip(HalfEdgeId e);
  // Splits triangle t at new vertex p into three (t keeps one slot). Returns
  // the half-edge p -> (first vertex of t).
  HalfEdgeId split_triangle(TriId t, VertexId p);
  // Splits the edge of half-edge e at new vertex p (both sides when it has a
  // twin). Returns the half-edge p -> dest(e).
  HalfEdgeId split_edge(HalfEdgeId e, VertexId p);
  // Inverse of split_triangle: removes v, which has exactly three triangles
  // (v,a,b), (v,b,c), (v,c,a) and is in no other; (a,b,c) takes the slot of
  // the triangle of v's out-edge and the outer edges keep their twins,
  // flags and markers. The caller guarantees (a,b,c) is counter-clockwise.
  void remove_degree3_vertex(VertexId v);
  // Inverse of split_edge: g = v->b lies in (v,b,c), and v's only other
  // triangles are (v,c,a) and, when g has a twin, (b,v,d) and (v,d,a).
  // They become (a,b,c) and (b,a,d); edge a-b takes the flags and marker of
  // a->v. The caller guarantees a, v, b are collinear with v between.
  void unsplit_edge(HalfEdgeId g);

  // Exact point location by a visibility walk from triangle `start` (any live
  // triangle when kNone). Needs ghost triangles (a closed triangulation).
  // Terminates on any triangulation (the walk picks its first edge test at
  // random, which rules out cycles with probability 1 and is Delaunay-proof).
  Location locate(const Point& p, TriId start = kNone) const;

  // Drops dead and ghost triangles, renumbers triangles, sets hull twins to
  // kNone and points boundary vertices' out_edge at their most clockwise edge.
  void compact();
  bool compacted() const { return compacted_; }

  // The observer the algorithms report their steps to (trace.hpp); null:
  // none. Not owned; moves carry it, copies do not (TraceLink).
  TraceObserver* trace() const { return trace_.ptr; }
  void set_trace(TraceObserver* t) { trace_.ptr = t; }

  // Bytes held by the mesh's arrays (capacity), for memory reports.
  std::size_t memory_bytes() const;

  // ---- data carried from the input to the output ----------------------------
  // Per-vertex boundary markers (empty, or one per vertex) and attributes
  // (num_vertex_attributes() per vertex), in vertex order.
  std::vector<int>& vertex_markers() { return vertex_markers_; }
  const std::vector<int>& vertex_markers() const { return vertex_markers_; }
  std::size_t num_vertex_attributes() const { return num_vertex_attributes_; }
  void set_num_vertex_attributes(std::size_t n) { num_vertex_attributes_ = n; }
  std::vector<double>& vertex_attributes() { return vertex_attributes_; }
  const std::vector<double>& vertex_attributes() const { return vertex_attributes_; }
  // Per-triangle attributes (num_triangle_attributes() per triangle slot);
  // compact() keeps them with their triangles.
  std::size_t num_triangle_attributes() const { return num_triangle_attributes_; }
  void set_num_triangle_attributes(std::size_t n) { num_triangle_attributes_ = n; }
  std::vector<double>& triangle_attributes() { return triangle_attributes_; }
  const std::vector<double>& triangle_attributes() const { return triangle_attributes_; }

  // Per-triangle maximum area (empty, or one per triangle slot; <= 0 means
  // no bound), carried through splits and compaction like the attributes.
  bool has_triangle_area_bounds() const { return !triangle_area_bounds_.empty(); }
  double triangle_area_bound(TriId t) const { return triangle_area_bounds_.empty() ? -1.0 : triangle_area_bounds_[t]; }
  void set_triangle_area_bound(TriId t, double max_area);

  // Removes vertices in no triangle (duplicates, points in holes) and
  // renumbers the rest in order, as Triangle's -j does. Returns old -> new id
  // (kNone for removed vertices). Requires a compacted mesh.
  std::vector<VertexId> remove_unused_vertices();

 private:
  friend class detail::MeshEditor;
  void recount();
  void copy_triangle_data(TriId from, TriId to);
  void note_added(TriId t) {
    if (!is_ghost(t)) ++live_real_;
  }
  void note_removed(TriId t) {
    if (!is_ghost(t)) --live_real_;
  }

  std::vector<Point> points_;
  std::vector<VertexId> tri_v_;
  std::vector<HalfEdgeId> twin_;
  std::vector<HalfEdgeId> vert_edge_;
  std::vector<std::uint8_t> edge_flags_;  // empty until a flag is set
  std::vector<int> edge_markers_;         // empty until a marker is set
  std::vector<TriId> free_;
  std::vector<int> vertex_markers_;
  std::vector<double> vertex_attributes_;
  std::vector<double> triangle_attributes_;
  std::vector<double> triangle_area_bounds_;
  std::size_t num_vertex_attributes_ = 0;
  std::size_t num_triangle_attributes_ = 0;
  std::size_t live_real_ = 0;
  bool compacted_ = false;
  TraceLink trace_;
};

}  // namespace deltamesh
