// Delaunay vertex insertion on a mesh with ghost triangles: locate
// (Mesh::locate), split the triangle or edge, then Lawson flips around the new
// vertex (mesh/legalize.hpp). Used by the CDT builders and
// insert_delaunay_vertex().
#pragma once
#include <vector>

#include "deltamesh/mesh.hpp"
#include "mesh/legalize.hpp"
#include "mesh/split.hpp"

namespace deltamesh::detail {

class DelaunayInserter {
 public:
  struct Result {
    VertexId vertex;  // the inserted vertex, or the existing one p coincides with
    TriId tri;        // a triangle incident to `vertex` (a good next hint)
  };

  // `carried`, when given, is a per-half-edge array kept beside the mesh's
  // (a CDT builder's segment ids): grown with the triangle slots, and carried
  // through every split and flip as the mesh's markers are.
  explicit DelaunayInserter(Mesh& mesh, std::vector<int>* carried = nullptr) : mesh_(mesh), carried_(carried) {
    stack_.reserve(64);
  }

  // Inserts vertex v, already in mesh.points() but in no triangle.
  Result insert_existing(VertexId v, TriId hint) {
    const Location loc = mesh_.locate(mesh_.point(v), hint);
    if (loc.kind != Location::Kind::OnVertex && loc.tri == kNone) return {kNone, kNone};
    return insert_located(loc, v);
  }

  // Inserts vertex v (in mesh.points() but in no triangle) by splitting the
  // edge of half-edge e at it, then restores the Delaunay property by flips.
  // The caller guarantees that v lies strictly inside the union of the two
  // triangles of e, so the four new triangles are counter-clockwise; v need
  // not lie exactly on the edge (a rounded segment intersection point). Both
  // halves of the split edge keep its flags and marker.
  Result insert_splitting_edge(HalfEdgeId e, VertexId v) {
    insert_on_edge(e, v, TraceReason::Crossing);
    legalize(v);
    return {v, tri_of(mesh_.out_edge(v))};
  }

  // Inserts vertex v (in mesh.points(), in no triangle) at a location the
  // caller found: in triangle loc.tri, on edge loc.edge, or outside the hull
  // beyond ghost triangle loc.tri. Returns v, or loc.vertex when on a vertex.
  Result insert_located(const Location& loc, VertexId v) {
    switch (loc.kind) {
      case Location::Kind::OnVertex:
        return {loc.vertex, loc.tri};
      case Location::Kind::OnEdge:
        insert_on_edge(loc.edge, v);
        break;
      case Location::Kind::InTriangle:
      case Location::Kind::Outside:
        insert_in_triangle(loc.tri, v);
        break;
    }
    legalize(v);
    return {v, tri_of(mesh_.out_edge(v))};
  }

  // Starts (or stops, with null) carrying a per-half-edge array (above).
  void carry(std::vector<int>* carried) { carried_ = carried; }

  // Flips made by the insertions so far.
  std::size_t flips() const { return flips_; }

  // Adds p as a new vertex (unless it coincides with one) and inserts it.
  Result insert_point(const Point& p, TriId hint) {
    const Location loc = mesh_.locate(p, hint);
    if (loc.kind == Location::Kind::OnVertex) return {loc.vertex, loc.tri};
    if (loc.tri == kNone) return {kNone, kNone};
    const VertexId v = mesh_.add_vertex(p);
    if (loc.kind == Location::Kind::OnEdge)
      insert_on_edge(loc.edge, v);
    else
      insert_in_triangle(loc.tri, v);
    legalize(v);
    return {v, tri_of(mesh_.out_edge(v))};
  }

 private:
  void insert_in_triangle(TriId t, VertexId v) {
    const HalfEdgeId r = mesh_.split_triangle(t, v);  // v -> first vertex, in slot t
    if (carried_) {
      carried_->resize(mesh_.triangle_vertices().size(), 0);
      carry_split_triangle(carried_->data(), t, tri_of(mesh_.twin(r - 1)), tri_of(mesh_.twin(r)));
    }
    if (TraceObserver* o = mesh_.trace()) [[unlikely]]
      TraceAccess::slots(*o, trace_insert(v, mesh_.point(v)), mesh_.triangle_vertices().data(),
                         {t, tri_of(mesh_.twin(r - 1)), tri_of(mesh_.twin(r))});
    stack_.push_back(r - 2);
    stack_.push_back(mesh_.twin(r - 1) - 2);
    stack_.push_back(mesh_.twin(r) - 1);
  }

  void insert_on_edge(HalfEdgeId e, VertexId v, TraceReason why = TraceReason::Delaunay) {
    const HalfEdgeId f = mesh_.twin(e);
    const HalfEdgeId g0 = mesh_.split_edge(e, v);
    if (carried_) {
      carried_->resize(mesh_.triangle_vertices().size(), 0);
      carry_split_edge_side(carried_->data(), e, next_edge(e), tri_of(g0));
      if (f != kNone) carry_split_edge_side(carried_->data(), f, next_edge(f), tri_of(mesh_.twin(e)));
    }
    if (TraceObserver* o = mesh_.trace()) [[unlikely]] {
      const TriId t = tri_of(e), t3 = tri_of(g0);
      const VertexId* tv = mesh_.triangle_vertices().data();
      if (f == kNone)
        TraceAccess::slots(*o, trace_insert(v, mesh_.point(v), why), tv, {t, t3});
      else
        TraceAccess::slots(*o, trace_insert(v, mesh_.point(v), why), tv, {t, t3, tri_of(f), tri_of(mesh_.twin(e))});
    }
    stack_.push_back(prev_edge(e));
    stack_.push_back(g0 + 1);
    if (f != kNone) {
      stack_.push_back(prev_edge(f));
      stack_.push_back(next_edge(mesh_.twin(e)));
    }
  }

  void legalize(VertexId v) {
    MeshTopology topo(mesh_, carried_ ? carried_->data() : nullptr);
    flips_ += legalize_around_vertex(topo, v, stack_).flips;
  }

  Mesh& mesh_;
  std::vector<int>* carried_;
  std::vector<HalfEdgeId> stack_;
  std::size_t flips_ = 0;
};

}  // namespace deltamesh::detail
