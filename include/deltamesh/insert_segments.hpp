// New constraints on an existing mesh (Triangle's -r with -p): segments
// inserted into a finished triangulation, which may be non-convex, have
// holes and need not be Delaunay.
//
//   deltamesh::Mesh mesh = deltamesh::mesh_from_triangles(nodes, triangles);
//   deltamesh::insert_segments(mesh, new_segments);   // now a CDT with them in
//   deltamesh::refine(mesh, {.min_angle_deg = 30});
#pragma once
#include <cstddef>
#include <span>

#include "deltamesh/cdt.hpp"
#include "deltamesh/mesh.hpp"
#include "deltamesh/pslg.hpp"

namespace deltamesh {

struct InsertSegmentsOptions {
  CdtMethod method = CdtMethod::Fast;  // how a segment that is not a chain of edges is recovered
  // Crossing a segment already in the mesh, or another given segment, is an
  // error (IntersectingSegments between two given segments, SegmentError
  // for one already in the mesh) instead of a new vertex.
  bool strict = false;
  // Afterwards, constrained Lawson flips over the whole mesh
  // (make_constrained_delaunay): the result is the constrained Delaunay
  // triangulation of its vertices, its boundary and its segments, which
  // refine() needs. false: only the triangles the segments cross change, so
  // a mesh that was not Delaunay stays as it was elsewhere (a mesh that was
  // a CDT stays one either way).
  bool delaunay = true;
};

struct InsertSegmentsStats {
  std::size_t segments = 0;              // given, zero-length ones included
  std::size_t zero_length = 0;           // both ends the same vertex: ignored
  std::size_t already_present = 0;       // an edge or a straight chain of edges already
  std::size_t inserted = 0;              // not: triangles were changed to let them in
  std::size_t vertices_added = 0;        // at crossings with segments
  std::size_t flips = 0;                 // by make_constrained_delaunay (with options.delaunay)
  CdtStats cdt;                          // the segment insertion (when some segment was not present)
  double seconds = 0.0;
};

// Inserts `segments` (vertex ids of `mesh`) into a valid compacted mesh, as
// constrained edges carrying their markers. A segment that is already an
// edge, or a straight chain of edges, is just constrained; otherwise the
// triangles it crosses are replaced with the machinery of
// constrained_triangulation(): it is split at every vertex lying exactly on
// it (exact orientation), and where it crosses a segment already in the mesh
// or another given segment both are split at a new vertex (their rounded
// intersection), unless options.strict. To do this the mesh is closed for a
// while: its exterior and its holes are filled with the constrained
// triangulation of its vertices and boundary edges (kept apart and removed
// again), so the mesh's boundary and the triangles off the segments' way
// are left as they were, in their slots (when every segment is a chain
// already, no triangle changes); then options.delaunay may flip any
// unconstrained edge that is not locally Delaunay. Triangles made where a
// segment passes take the data (attributes, area bound) of the triangles
// they replace, slot by slot. An edge of several segments keeps the marker
// of the lowest-numbered given segment with a nonzero marker, else the
// marker it had. Boundary edges stay unconstrained unless a segment runs
// along them.
//
// Throws SegmentError for a segment with an endpoint out of range or in no
// triangle, and for one that passes outside the mesh (through a hole, a
// notch of the boundary, beyond the hull); nothing is changed then.
// Throws InputError when the mesh's boundary touches or crosses itself
// (a vertex on a boundary edge, overlapping triangles), which a valid
// mesh's does not, and when crossings rounded onto each other would add
// more vertices than there are segment pairs (numerically hopeless input);
// IntersectingSegments / SegmentError under strict. Nothing is changed then.
//
// Vertex ids of the mesh do not change; new ones are appended, with
// attributes interpolated along the segment they split. Ends with
// finish_vertex_markers() (vertices whose marker is 0 take a segment's).
void insert_segments(Mesh& mesh, std::span<const Segment> segments, const InsertSegmentsOptions& options = {},
                     InsertSegmentsStats* stats = nullptr);

// Constrained Lawson flips over a compacted mesh until every unconstrained
// interior edge is locally Delaunay: then the mesh is the constrained
// Delaunay triangulation of its vertices, segments and boundary (seed §2.2),
// which refine() assumes. Boundary edges and constrained edges are never
// flipped; a triangle's data stays with its slot. Returns the number of
// flips (0 on a mesh that is a CDT already, whose triangles then stay as
// they are, ties on common circles included).
std::size_t make_constrained_delaunay(Mesh& mesh);

}  // namespace deltamesh
