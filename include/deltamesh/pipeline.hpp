// A whole run as data: what is meshed, how, and what is done to the result,
// then one call that does it on in-memory input. The command line and the
// Python bindings both build a Plan (from Triangle's switch string, see
// switches.hpp, or from keywords) and call run(); so a switch means the same
// thing in every front end.
//
//   deltamesh::Plan plan = deltamesh::parse_arguments({"-pq30a0.01"}).plan;
//   deltamesh::RunInput in;
//   in.pslg = deltamesh::read_poly("plate.poly");
//   deltamesh::RunResult r = deltamesh::run(plan, std::move(in));
//   // r.mesh, r.complete(), r.warnings(), r.stats, r.check (with -C) ...
#pragma once
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "deltamesh/adapt.hpp"
#include "deltamesh/metric.hpp"
#include "deltamesh/cdt.hpp"
#include "deltamesh/domain.hpp"
#include "deltamesh/insert_segments.hpp"
#include "deltamesh/mesh.hpp"
#include "deltamesh/progress.hpp"
#include "deltamesh/pslg.hpp"
#include "deltamesh/refine.hpp"
#include "deltamesh/triangulate.hpp"
#include "deltamesh/validate.hpp"

namespace deltamesh {

enum class InputKind {
  Points,  // the Delaunay triangulation of the vertices (no -p)
  Pslg,    // -p: the constrained triangulation of the segments, carved to the domain
  Mesh,    // -r: an existing mesh (triangles given), rebuilt and refined
  Adapt,   // --adapt: an existing mesh coarsened and refined to a size field
};

// Which triangles are kept and what they carry (-c -A -O, --fill).
struct DomainRules {
  bool convex_hull = false;          // -c: keep the hull, its edges become segments
  bool regional_attributes = false;  // -A: an attribute per triangle from the region seeds
  bool ignore_holes = false;         // -O
  FillRule fill = FillRule::Holes;   // --fill=
};

// Quality refinement: -q -a -S -Y -D and the long options that tune it.
struct RefinementPlan {
  bool quality = false;                              // -q
  std::optional<double> min_angle;                   // -qANGLE (20 when -q gives none)
  std::optional<double> max_area;                    // -aAREA
  bool input_area_bounds = false;                    // -a alone: the regions' bounds (-p) or the triangles' (-r)
  std::optional<unsigned long long> steiner_budget;  // -S[N]
  int no_boundary_steiner = 0;                       // -Y (1), -YY (2)
  bool conforming_delaunay = false;                  // -D
  SteinerRule steiner = SteinerRule::Best;
  EncroachmentRule encroachment = EncroachmentRule::DiametralLens;
  RefineOrder order = RefineOrder::ShortestEdgeFirst;
  double time_limit = 0.0;  // seconds, <= 0: none
  // Size functions (the API's and Python's; Triangle's -u): see RefineOptions.
  std::function<double(double x, double y)> max_area_at;
  std::function<double(double x, double y)> max_edge_at;

  // Refinement is asked for by -q, -a, -S, -D or a size function.
  bool requested() const;
  // The refine() options these settings make (no progress callback).
  RefineOptions options() const;
};

struct Plan {
  InputKind input = InputKind::Points;
  // Mesh / Adapt: the input's segments are inserted where they are not
  // edges yet and its holes carved (-r -p).
  bool mesh_segments = false;
  CdtMethod method = CdtMethod::Fast;  // --cdt=
  bool strict = false;                 // --strict: crossing segments are an error
  DomainRules domain;
  RefinementPlan refine;
  // --smooth[=N]: N smoothing passes after meshing or refinement; -1: not
  // given (Adapt then smooths 2 passes, the others not at all).
  int smooth = -1;
  bool check = false;     // -C: the validator on the result (RunResult::check)
  bool jettison = false;  // -j: vertices in no triangle dropped
  int order = 1;          // 2 (-o2): a node at the midpoint of every edge (RunResult::midside)
  // -tN / --threads=N: threads for Delaunay and refinement; 0 = every
  // hardware thread, 1 = the sequential code (docs/scaling.md).
  unsigned threads = 0;
  // How a front end writes the result (nothing here changes the mesh).
  bool zero_based = false;  // -z
  bool markers = true;      // -B: false
  bool edges = false;       // -e
  bool neighbors = false;   // -n
  bool quiet = false;       // -Q
  int verbose = 0;          // -V
  // Live progress of the long phases (see progress.hpp); empty: none.
  ProgressCallback progress;
  // Every step of the run reported to this observer (trace.hpp; not owned),
  // ending with an End event. Null: none.
  TraceObserver* trace = nullptr;

  bool mesh_input() const { return input == InputKind::Mesh || input == InputKind::Adapt; }
  // Segments, holes and regions are used (-p, or -r -p).
  bool uses_segments() const { return input == InputKind::Pslg || mesh_segments; }
};

struct RunInput {
  // Vertices (markers, attributes) and, with segments, segments, holes and
  // regions. Mesh / Adapt: the mesh's vertices, in triangle-list numbering.
  Pslg pslg;
  // Mesh / Adapt: 0-based corner triples; `midside` 3 per triangle for
  // 6-node triangles (their midpoint nodes are dropped: drop_midside_nodes).
  std::vector<VertexId> triangles;
  std::vector<VertexId> midside;
  std::size_t num_triangle_attributes = 0;
  std::vector<double> triangle_attributes;
  // Mesh with refinement.input_area_bounds: one bound per triangle (<= 0: none).
  std::vector<double> triangle_area_bounds;
  // Adapt: the size field, either a function or one size per input vertex
  // (interpolated over the mesh; vertices that segment insertion adds take
  // the mean of their neighbours').
  SizeField size;
  std::vector<double> vertex_sizes;
  // Adapt to a metric instead (metric.hpp's adapt_to_metric): a field, or
  // one tensor per input vertex (log-Euclidean interpolation over the mesh;
  // vertices that segment insertion adds take their neighbours' mean).
  // Refinement switches other than -Y do not apply to it.
  MetricField metric;
  std::vector<Metric> vertex_metrics;
};

// Drops the midpoint nodes of a 6-node mesh (its corners renumbered in
// order) and returns how many went; run() does it too, a front end calls it
// first to warn before anything else happens. Throws InputError for per-vertex
// sizes, which would no longer match.
std::size_t drop_midside_nodes(RunInput& input);

struct PhaseTime {
  std::string name;
  double seconds = 0.0;
};

struct RunResult {
  Mesh mesh;
  // Triangulation, domain and refinement counts; `stats.refine` holds the
  // refinement's (after smoothing's second refinement, or adapt's), and
  // `stats.warnings` the domain's warnings (unused holes and regions, an
  // empty domain, zero-length segments).
  TriangulateStats stats;
  bool refined = false;
  // Mesh / Adapt.
  std::size_t read_vertices = 0, read_triangles = 0;  // the mesh as rebuilt (segments inserted, holes carved)
  InsertSegmentsStats inserted;                       // with mesh_segments
  std::size_t delaunay_flips = 0;                     // before refinement, adaptation or smoothing
  bool adapted = false;
  AdaptStats adapt;
  // Adapt to a metric: its stats and how the result fits the metric.
  bool metric_adapted = false;
  MetricAdaptStats metric_adapt;
  std::optional<MetricFit> metric_fit;
  // --smooth (Adapt smooths inside adapt(): see adapt.smooth).
  bool smoothed = false;
  SmoothStats smooth;
  std::size_t resplit = 0;  // points the refinement after smoothing added
  // -C: the validator's report ("before carving: " problems included).
  std::optional<CheckReport> check;
  // -o2: the midpoint node of each triangle edge, 3 per triangle slot.
  std::vector<VertexId> midside;
  std::vector<PhaseTime> phases;
  double seconds = 0.0;

  // Refinement reached its bounds (true when there was none).
  bool complete() const { return !refined || stats.refine.complete; }
  const std::vector<std::string>& warnings() const { return stats.warnings; }
};

// Settings of `plan` that have no effect on the run it describes (-Y or
// --steiner without refinement, -A or --cdt without segments, ...), one
// message each; run() puts them first among its warnings, so the command
// line and Python say them once.
std::vector<std::string> unused_settings(const Plan& plan);

// Runs `plan` on `input`. Throws what the steps throw: InputError (and its
// IntersectingSegments, SegmentError) for input that cannot be meshed,
// InternalError for a bug. A refinement that stops short of its bounds and
// a -C report with problems are results, not exceptions.
RunResult run(const Plan& plan, RunInput input);

}  // namespace deltamesh
