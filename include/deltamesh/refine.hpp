// Delaunay refinement: Ruppert/Chew refinement of a carved constrained
// Delaunay triangulation into a quality mesh, with off-centre Steiner points,
// concentric-shell segment splitting and small-angle rules (after Shewchuk
// 2002 and Miller, Pav & Walkington 2003) so that it terminates on every
// input. docs/internals.md maps each rule to the code (src/algo/refine/).
//
//   deltamesh::Mesh mesh = deltamesh::triangulate(pslg);   // carved CDT
//   deltamesh::RefineStats st = deltamesh::refine(mesh, {.min_angle_deg = 30, .max_area = 0.01});
//   if (!st.complete) ...   // a budget stopped it or triangles are too large; mesh still valid
#pragma once
#include <cstddef>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "deltamesh/mesh.hpp"
#include "deltamesh/progress.hpp"

namespace deltamesh {

// Where a skinny (or too large) triangle is split.
enum class SteinerRule {
  // Üngör's off-centre: on the bisector of the shortest edge, no farther from
  // it than the point that makes a triangle of exactly the angle bound with
  // it; the circumcentre when that is nearer. Fewer triangles than
  // circumcentres, and the quickest rule.
  Offcenter,
  // The circumcentre: with EncroachmentRule::DiametralCircle and
  // RefineOrder::WorstFirst this is exactly the seed's Figure 18 (Ruppert).
  Circumcenter,
  // The off-centre when its insertion leaves no skinny triangle; otherwise
  // the point of the shortest edge's petal (where that edge makes a triangle
  // within the bound) whose insertion leaves the fewest skinny triangles
  // (in the spirit of Erten and Üngör's locally optimal Steiner points),
  // found by a pattern search from seeds towards the good sides of the
  // triangles the off-centre leaves skinny (with size bounds: from a coarse
  // grid), each point scored on the few triangles whose circumcircle meets
  // the petal, gathered once. Next to triangles that break a size bound the
  // off-centre is used as is. Default: on the corpus 18% (q30) to 22% (q33)
  // fewer triangles than Triangle 1.6, for about 1.4-1.9 times the
  // off-centres' instructions (docs/benchmarks.md).
  Best,
  // A coarse grid and a pattern search with every candidate scored by the
  // cavity it would make in the mesh (the default until 2026-12); with size
  // bounds Best's search on the mesh. Kept to compare rules.
  Grid,
};

// When a vertex encroaches upon a subsegment.
enum class EncroachmentRule {
  // Inside the diametral lens (Shewchuk 2002): the segment subtends an angle
  // > max(90°, 180° - 2·min_angle) at the vertex, i.e. the vertex would make
  // a triangle below the bound with it. Steiner points beyond a segment
  // still split it. Default: on the corpus it gives 5% (q30) to 20% (q33)
  // fewer triangles than circles and leaves fewer triangles below the bound.
  DiametralLens,
  // Inside the diametral circle (the seed's R1 exactly): the segment
  // subtends an angle > 90° at the vertex. Decided with an exact sign.
  DiametralCircle,
};

// The order in which bad triangles are split. Both use an O(1) bucketed
// queue whose entries keep their three vertex ids (stale ones are skipped).
enum class RefineOrder {
  // Shortest edge first (buckets by the shortest edge's length, a third of
  // an octave wide): refinement proceeds from small features outwards and
  // grades better; 15-20% fewer triangles than worst-first on the corpus
  // (default).
  ShortestEdgeFirst,
  // Worst quality first (buckets by the sine of the smallest angle).
  WorstFirst,
};

// Which segments may receive Steiner points (Triangle's -Y / -YY).
enum class SegmentSplitting {
  All,           // default
  InteriorOnly,  // -Y: none on boundary segments (edges with one triangle)
  None,          // -YY: none on any segment
};

// No Steiner budget.
inline constexpr std::size_t kUnlimited = std::numeric_limits<std::size_t>::max();
// The default budget (docs/robustness.md, "Budgets"): kAutomaticBudgetBase +
// kAutomaticBudgetPerVertex × (vertices before refinement) Steiner points,
// raised to four times the vertex count an area bound asks for. It bounds
// memory on adversarial inputs without cutting ordinary refinements short.
inline constexpr std::size_t kAutomaticBudget = kUnlimited - 1;
inline constexpr std::size_t kAutomaticBudgetBase = 2'000'000;
inline constexpr std::size_t kAutomaticBudgetPerVertex = 50;
// Bounds above this are refined in two stages: to this angle first (where
// refinement ends in practice), then on towards the bound, worst triangles
// first, while a progress watch sees the number of triangles below it fall
// or their smallest angle rise (checked every max(256, vertices/8) Steiner
// points; at most 4 × vertices + 10^4 of them). When the watch stops it,
// RefineStats::stalled says where, and the first stage's mesh is returned
// if its smallest angle is larger.
inline constexpr double kAutomaticBudgetAngle = 34.0;

struct RefineOptions {
  // Triangles with an angle below this are split (Triangle's -q; 0 turns the
  // angle criterion off). Termination is proven up to ~20.7° for the seed's
  // algorithm; up to ~34° it terminates in practice (off-centres reach higher
  // bounds); beyond, see kAutomaticBudgetAngle. At most 60°.
  double min_angle_deg = 20.0;
  // Global maximum triangle area (-a0.01); <= 0: none.
  double max_area = -1.0;
  // Honour the mesh's per-triangle area bounds (Mesh::triangle_area_bound:
  // regional -a, or an .area file with -r).
  bool use_triangle_area_bounds = true;
  // Sizing callbacks, evaluated at a triangle's centroid; a value <= 0 means
  // no bound there. They are called from the refining thread only, and the
  // library keeps no global state, so concurrent refine() calls with
  // different callbacks are safe (the callback itself must be safe to call
  // from the thread that calls refine()). max_area_at bounds the area,
  // max_edge_at the longest edge.
  std::function<double(double x, double y)> max_area_at;
  std::function<double(double x, double y)> max_edge_at;

  SteinerRule steiner = SteinerRule::Best;
  EncroachmentRule encroachment = EncroachmentRule::DiametralLens;
  RefineOrder order = RefineOrder::ShortestEdgeFirst;
  SegmentSplitting segment_splitting = SegmentSplitting::All;
  // -D: every interior edge, segments included, ends locally Delaunay, so the
  // mesh is Delaunay within each connected region (diametral circles are
  // used whatever `encroachment` says).
  bool conforming_delaunay = false;
  // Split segments on concentric shells around input vertices (at a hub, a
  // vertex of three or more segments with wedges under 10°, every subsegment
  // on a grid of power-of-two radii around it) and leave alone skinny
  // triangles that sit in small input angles (< 60°), which is what makes
  // refinement terminate on every input. Also left: the skinny triangles of
  // thin channels between the sides of a spike (sides of a wedge under 10°,
  // continued through bends under 30°, running within 10°
  // of antiparallel closer than 1/64 of their length), and encroached
  // subsegments whose split would only make such triangles. Turning it off
  // runs Ruppert's algorithm literally (midpoint splits, every skinny
  // triangle split); then only the budgets guarantee termination.
  bool small_angle_protection = true;

  // Maximum number of Steiner points (-S); kUnlimited, or kAutomaticBudget.
  std::size_t max_steiner = kAutomaticBudget;
  // Wall-clock limit in seconds (<= 0: none).
  double time_limit_seconds = 0.0;
  // Threads: 0 = every hardware thread, 1 = the sequential refinement. With
  // a uniform area bound (max_area) that asks for at least 150000
  // triangles per thread, and no size callback, budget, time limit or -D,
  // the mesh is refined in parts (docs/scaling.md): the same bounds are
  // met; the mesh depends on the thread count, not on the run.
  unsigned threads = 0;
  // Progress: phase "refine", counting Steiner points (total unknown);
  // see progress.hpp. Empty: no reports.
  ProgressCallback progress;
};

struct RefineStats {
  // False when a bound is not met (one rule, docs/robustness.md): a budget
  // or the time limit stopped refinement, triangles are left above their
  // size bound (too_large), or below the angle bound other than in small
  // input angles (below_segment_protected, below_precision). The mesh is
  // valid either way; unmet() says why in words.
  bool complete = true;
  bool budget_exhausted = false;
  bool time_exhausted = false;

  std::size_t input_vertices = 0;    // vertices before refinement
  std::size_t steiner_points = 0;    // vertices added
  std::size_t segment_splits = 0;    // ... on segments (R1)
  std::size_t interior_points = 0;   // ... inside the domain (R2 and area)
  std::size_t offcenters = 0;        // interior points at an off-centre rather than a circumcentre
  std::size_t rejected_points = 0;   // R2 points not inserted because they encroached segments
  std::size_t small_angle_skips = 0; // splits refused by the small-angle rules (events, not triangles)
  std::size_t failed_splits = 0;     // segment splits abandoned: the rounded split point did not fit

  // Triangles still below the angle bound when refinement ended, and why.
  std::size_t below_bound = 0;
  std::size_t below_small_input_angle = 0;  // in an input angle < 60° or a spike's channel: expected
  std::size_t below_segment_protected = 0;  // needed a split that -Y/-YY forbids
  std::size_t below_budget = 0;             // left when a budget/time limit stopped refinement
  std::size_t below_out_of_reach = 0;       // left where refinement beyond kAutomaticBudgetAngle stalled
  std::size_t below_precision = 0;          // at the resolution of doubles: no distinct point fits
  // Triangles still above their area / edge-length bound.
  std::size_t too_large = 0;
  std::size_t too_large_precision = 0;  // ... because no split of them fits at the resolution of doubles

  double min_angle_deg = 0.0;  // the bound refined for
  // The smallest angle of the triangles not left at small input angles
  // (min_angle_deg when all of them meet it).
  double reached_angle_deg = 0.0;
  // Above kAutomaticBudgetAngle: refinement towards the bound stopped
  // making progress (budget_exhausted is set too, complete is false). Half of
  // its last Steiner points lie within stall_radius of (stall_x, stall_y).
  // When that left a smaller smallest angle than the mesh refined to
  // kept_angle_deg (= kAutomaticBudgetAngle), that mesh is returned and
  // the discarded_steiner points added after it are dropped.
  bool stalled = false;
  double stall_x = 0.0, stall_y = 0.0, stall_radius = 0.0;
  double kept_angle_deg = 0.0;
  std::size_t discarded_steiner = 0;
  double seconds = 0.0;
  std::size_t peak_queue = 0;  // largest number of queued bad triangles

  // Where the worst triangle left at the precision of doubles is (its
  // centroid), its shortest edge and the largest coordinate magnitude of its
  // corners: there every new vertex tried rounded onto a vertex or out of
  // its cavity (valid when below_precision or too_large_precision is
  // nonzero).
  double precision_x = 0.0, precision_y = 0.0, precision_edge = 0.0, precision_magnitude = 0.0;

  std::string summary() const;
  // Why the run is incomplete, in words with the counts ("13 triangles
  // below 30°: 13 need a split -Y forbids"); empty when complete.
  std::string unmet() const;
};

// Refines a carved, compacted constrained Delaunay triangulation in place:
// constrained edges are the segments, boundary half-edges have twin kNone
// (boundary edges that are not constrained are treated as segments and get
// the kConstrained flag). A mesh with ghost triangles is compacted first.
// Vertices keep their ids; Steiner points are appended. Segment splits keep
// the segment's marker on both halves. Returns what happened; never throws
// for a budget or an unreachable bound.
// A mesh with coordinates beyond the exact predicates' range (2^+-200) is
// refined in an exact power-of-two frame (its bounds scaled with it) and
// mapped back; in range it is refined as is.
RefineStats refine(Mesh& mesh, const RefineOptions& options = {});

std::string_view to_string(SteinerRule r);
std::optional<SteinerRule> parse_steiner_rule(std::string_view name);          // "best", "offcenter", "circumcenter"
std::string_view to_string(EncroachmentRule r);
std::optional<EncroachmentRule> parse_encroachment_rule(std::string_view name);  // "circle", "lens"

}  // namespace deltamesh
