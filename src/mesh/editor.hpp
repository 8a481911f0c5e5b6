// Raw access to a Mesh's arrays, for the library's hot loops (Delaunay,
// CDT builders, refinement). Not installed: users change a Mesh only through
// its operations, which keep the invariants; code here keeps them by hand and
// the validator checks them in the tests.
#pragma once
#include <cstdint>
#include <vector>

#include "deltamesh/mesh.hpp"

namespace deltamesh::detail {

class MeshEditor {
 public:
  explicit MeshEditor(Mesh& mesh) : m_(mesh) {}

  std::vector<Point>& points() { return m_.points_; }
  // Three vertex ids per triangle slot (kNone: dead, kInfinite: ghost corner).
  std::vector<VertexId>& triangle_vertices() { return m_.tri_v_; }
  std::vector<HalfEdgeId>& twins() { return m_.twin_; }
  std::vector<HalfEdgeId>& out_edges() { return m_.vert_edge_; }
  // Empty until the first flag or marker is set; one entry per half-edge after.
  std::vector<std::uint8_t>& edge_flags() { return m_.edge_flags_; }
  std::vector<int>& edge_markers() { return m_.edge_markers_; }

  // The live real triangle count, after bulk edits of the arrays.
  void recount() { m_.recount(); }
  std::size_t live_real() const { return m_.live_real_; }
  void set_live_real(std::size_t n) { m_.live_real_ = n; }
  // For a mesh built compact (only real triangles, no free slots, every
  // vertex's out-edge set, boundary ones first): what compact() would leave
  // (the parallel Delaunay's result, refine_in_parts' stitch).
  void set_compacted() { m_.compacted_ = true; }

 private:
  Mesh& m_;
};

}  // namespace deltamesh::detail
