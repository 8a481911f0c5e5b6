// The one-call pipeline: a PSLG in, a finished mesh out.
//
//   Pslg  --(Delaunay of the vertices | constrained triangulation)-->
//         --(carve_domain: exterior, holes, regions)-->
//         --(refinement: a later issue)-->
//         --(vertex markers and attributes per Triangle's rules)--> Mesh
#pragma once
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "deltamesh/cdt.hpp"
#include "deltamesh/delaunay.hpp"
#include "deltamesh/domain.hpp"
#include "deltamesh/insert_segments.hpp"
#include "deltamesh/mesh.hpp"
#include "deltamesh/progress.hpp"
#include "deltamesh/pslg.hpp"
#include "deltamesh/refine.hpp"
#include "deltamesh/validate.hpp"

namespace deltamesh {

struct TriangulateOptions {
  // true: segments, holes and regions are used (Triangle's -p): the result
  // is the constrained Delaunay triangulation carved to the domain.
  // false: the Delaunay triangulation of the vertices only (segments, holes
  // and regions are ignored; -c still turns the hull edges into segments).
  bool use_segments = true;
  CdtMethod method = CdtMethod::Fast;  // --cdt=
  bool strict = false;                 // --strict: crossing segments are an error
  DomainOptions domain;                // -c -O -A, --fill=
  // Validate the constrained triangulation before carving (every segment a
  // chain of constrained edges, constrained Delaunay unless method is Ct):
  // after carving, segments whose both sides were removed are gone, so this
  // is where their presence is checked (-C). Result in stats.segment_check.
  bool check_segments = false;
  // Quality refinement of the carved mesh (-q -a -u -S -Y -D, see
  // refine.hpp); none when empty. Triangles carry the regional area bounds
  // of -a without a number (domain.regional_area_bounds), which refinement
  // honours unless refine->use_triangle_area_bounds is false.
  std::optional<RefineOptions> refine;
  // Progress per phase ("insert points", "recover segments", "carve domain",
  // then refinement's "refine" in Steiner points unless refine->progress is
  // set); see progress.hpp. Empty: no reports.
  ProgressCallback progress;
  // Every step of every phase reported to this observer (trace.hpp); it
  // stays attached to the result (Mesh::trace). Null: none.
  TraceObserver* trace = nullptr;
  // Threads for the Delaunay triangulation of a point set (see
  // DelaunayOptions::threads): 0 = every hardware thread, 1 = sequential.
  unsigned threads = 0;
};

struct TriangulateStats {
  std::size_t input_vertices = 0;
  std::size_t input_segments = 0;
  std::size_t input_holes = 0;
  std::size_t input_regions = 0;
  std::size_t duplicate_vertices = 0;  // merged with an earlier vertex (left in no triangle)
  std::size_t steiner_vertices = 0;    // vertices added where segments cross
  CdtStats cdt;                        // segment insertion (with -p)
  DomainStats domain;                  // carving (with -p)
  std::size_t vertices = 0;            // in the result (input + added)
  std::size_t triangles = 0;
  std::size_t triangulated = 0;        // triangles before refinement (after carving)
  std::size_t segments = 0;            // constrained edges in the result
  CheckReport segment_check;           // with options.check_segments
  double check_seconds = 0.0;          // ... its time
  double triangulate_seconds = 0.0;    // Delaunay or constrained triangulation
  double domain_seconds = 0.0;
  RefineStats refine;                  // with options.refine
  double refine_seconds = 0.0;
  double finish_seconds = 0.0;         // markers and attributes
  double total_seconds = 0.0;
  std::vector<std::string> warnings;   // ignored hole points, zero-length segments, empty domain, ...
};

// Meshes `pslg`. Vertex ids 0..n-1 of the result are the input's (duplicates
// stay as vertices in no triangle, like Triangle, until -j); vertices added
// where segments cross follow.
//
// Vertex markers follow Triangle's documented rule: a nonzero input marker is
// kept; otherwise a vertex on a segment with a nonzero marker takes it (the
// first such segment in input order, then any); otherwise a vertex on the mesh
// boundary gets 1; otherwise 0. Vertex attributes are copied; a vertex added
// where segments cross gets them interpolated linearly along a segment
// through it. Coordinates beyond the exact predicates' range (2^+-200) are
// meshed in an exact power-of-two frame (area and length bounds scaled with
// it) and mapped back. Throws InputError (and IntersectingSegments under
// strict).
Mesh triangulate(const Pslg& pslg, const TriangulateOptions& options = {}, TriangulateStats* stats = nullptr);

// The end of Triangle's vertex-marker rule on a finished (compacted) mesh,
// for vertices whose marker is still 0 (or that have none yet: the marker
// and attribute arrays are extended with zeros to every vertex): a vertex on
// a constrained edge with a nonzero marker takes it, else a vertex on the
// boundary gets 1. triangulate() ends with it; code that adds vertices
// afterwards (refinement) calls it again.
void finish_vertex_markers(Mesh& mesh);

struct RebuildOptions {
  // Per-triangle maximum areas (an .area file read with -ra): one per
  // triangle of the list, <= 0 for none. Set before segments are inserted,
  // so they follow their triangles. Empty: none.
  std::span<const double> area_bounds;
  // How segments that are not edges of the mesh are inserted (see
  // insert_segments; no Delaunay flips here: the mesh is rebuilt as is,
  // call make_constrained_delaunay before refine() if it may not be a CDT).
  CdtMethod method = CdtMethod::Fast;
  bool strict = false;
  // Refuse triangles that overlap or meet other than edge to edge, wherever
  // they are (OverlappingTriangles, naming both). Off only to build broken
  // meshes on purpose (the validator's tests).
  bool refuse_overlaps = true;
};

// Rebuilds a mesh from a triangle list, as Triangle's -r reads FILE.node and
// FILE.ele: points, markers and attributes from `nodes`, triangles as 0-based
// vertex triples (either orientation), `num_attributes` attributes per
// triangle. Segments of `nodes` (from a .poly) become constrained edges with
// their markers: a segment that is an edge, or a chain of collinear edges,
// of the mesh is constrained as it is; others are inserted into the mesh by
// insert_segments() (new constraints on an old mesh: the triangles they
// cross are replaced, crossings with other segments add vertices). Holes
// and regions of `nodes` are not used (carve_mesh does that). Vertex
// markers and attributes then follow triangulate()'s rules. The result is
// compacted (no ghost triangles); without inserted segments its triangles
// are the list's, in order. Throws InputError for a vertex id out of range,
// a degenerate triangle, an edge shared by more than two triangles or
// triangles that overlap across an edge, SegmentError for a segment that
// cannot be inserted (insert_segments), and InputError when the triangles'
// boundary crosses or touches itself and a segment needs inserting.
Mesh mesh_from_triangles(const Pslg& nodes, std::span<const VertexId> triangles, std::size_t num_attributes = 0,
                         std::span<const double> attributes = {}, const RebuildOptions& options = {},
                         InsertSegmentsStats* stats = nullptr);

}  // namespace deltamesh
