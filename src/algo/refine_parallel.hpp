// Delaunay refinement on several threads by domain decomposition, with the
// sequential refine() as the unit of work (docs/scaling.md).
#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "deltamesh/mesh.hpp"
#include "deltamesh/refine.hpp"

namespace deltamesh::detail {

// Fewer triangles than this per thread (as the area bound predicts) are not
// worth a part: refine() stays sequential.
inline constexpr std::size_t kMinTrianglesPerPart = 150000;

// The coarse stage refines to this many times the area bound before the
// mesh is cut into parts.
inline constexpr double kCoarseAreaFactor = 32.0;

// Edge flag of the cuts between parts (with kConstrained): a temporary
// segment that refinement never splits, so both sides keep its vertices.
inline constexpr std::uint8_t kFrozenEdge = 2;

// refine() in parts when options.threads allows it and the options are ones
// the decomposition keeps (a uniform area bound, no size callbacks, budget,
// time limit or -D, bounds up to kAutomaticBudgetAngle); nullopt otherwise,
// and the caller refines sequentially. `parts` 0: one per thread.
//   1. coarse: refine() to kCoarseAreaFactor x the area bound, with no angle
//      bound (the parts do the grading along fine boundaries);
//   2. cut: the triangles into `parts` vertical slabs by centroid; the edges
//      between slabs become temporary segments;
//   3. refine() every slab concurrently; the cuts are frozen (kFrozenEdge:
//      never split), so both sides of a cut keep the same vertices;
//   4. stitch the slabs back together, drop the temporary segments, flip to
//      the constrained Delaunay triangulation, and refine() the whole once
//      more: it finishes what the frozen cuts left (triangles near them), so
//      the result meets the same bounds as the sequential refinement.
// Refinement of the mesh as its slots stand, on one thread, with
// `scan_threads` for the passes over every triangle (Refiner::
// set_scan_threads): refine()'s sequential path (1, after putting the slots
// in canonical order) and the stages of refine_in_parts (all threads).
// `stage`, when given, says how a stage of refine_in_parts differs from a
// whole refinement (nullptr: refine()'s).
struct RefineStage {
  // In: the first look's verdict per triangle slot, as the parts' last
  // statistics found it: 0 good, 1 bad, kLookAgain rewritten since (the
  // stitch's flips); empty: every slot is evaluated.
  std::vector<std::uint8_t> first_look;
  // Out, when keep_final_bad: per slot, 1 when the triangle is bad at the
  // end (finish()'s statistics evaluate every slot anyway).
  std::vector<std::uint8_t> final_bad;
  bool keep_final_bad = false;
  // Reserve the arrays for the area bound's estimate of the final size
  // (false: the caller has; the last pass adds a few percent to a mesh
  // already at size, and the estimate counts every triangle again).
  bool reserve = true;
};
inline constexpr std::uint8_t kLookAgain = 2;

RefineStats refine_scanning(Mesh& mesh, const RefineOptions& options, unsigned scan_threads,
                            RefineStage* stage = nullptr);

// The last pass of refine_in_parts, for tests. In: whether to try the
// strip (src/algo/refine/strip.hpp) first; Refuse writes it back, then
// leaves the mesh to the whole-mesh pass as a failed check would. Out: the
// strip was kept (the mesh finished on it); its triangles before
// refinement (0: not refined).
struct LastPassReport {
  enum class Strip { Try, Never, Refuse } strip = Strip::Try;
  bool strip_kept = false;
  std::size_t strip_triangles = 0;
};

std::optional<RefineStats> refine_in_parts(Mesh& mesh, const RefineOptions& options, unsigned parts = 0,
                                           LastPassReport* report = nullptr);

}  // namespace deltamesh::detail
