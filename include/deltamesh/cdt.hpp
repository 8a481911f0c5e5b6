// Constrained triangulations of a PSLG (seed §1-§2): segments inserted into a
// Delaunay triangulation of the vertices by one of the seed's methods.
#pragma once
#include <cstddef>
#include <string_view>
#include <optional>

#include "deltamesh/errors.hpp"
#include "deltamesh/mesh.hpp"
#include "deltamesh/pslg.hpp"

namespace deltamesh {

enum class CdtMethod {
  Fast,     // default: the triangles crossed by the segment are removed and the two
            // pseudo-polygons on either side retriangulated (constrained Delaunay, recursive
            // empty-circle choice); vertices inserted along the segment chains when that
            // pays (ChainOrder)
  Ct,       // §1.2: rotary traversal + queue of flips; a constrained triangulation, not always Delaunay
  Lawson,   // §2.2: Ct, then constrained Lawson flips over the changed region: the CDT
  Lifting,  // §2.3: flips ordered by a motion of the lifted points, in a priority queue of
            // exact event times: the CDT. The motion is not equation (1)'s (lowering the
            // segment's endpoints does not give the CDT; see src/algo/cdt_lifting.hpp) but
            // one that raises the vertices on one side of the segment in proportion to their
            // distance from its line.
};

// "fast", "ct", "lawson", "lifting".
std::string_view to_string(CdtMethod m);
std::optional<CdtMethod> parse_cdt_method(std::string_view name);

// Whether Fast first tries inserting the vertices along the segment chains
// (see CdtStats::chain_order).
enum class ChainOrder {
  Auto,    // when the segments are long against the vertex spacing, and chained
  Always,  // whatever the input (it still gives up when over budget)
  Never,   // the classic order only
};

struct CdtOptions {
  CdtMethod method = CdtMethod::Fast;
  // Crossing segments are an error (IntersectingSegments) instead of being
  // split at their intersection.
  bool strict = false;
  // Fast only: try inserting the vertices along the segment chains first,
  // each segment as soon as its endpoints are in (see CdtStats::chain_order).
  // The CDT is the same either way on input in general position.
  ChainOrder chain_order = ChainOrder::Auto;
  // Reports each step (trace.hpp); with one, Fast does not use the chain
  // order (segments are inserted after the vertices).
  TraceObserver* trace = nullptr;
};

struct CdtStats {
  std::size_t segments_inserted = 0;         // input segments of nonzero length
  std::size_t segments_already_present = 0;  // ... that were an edge already when inserted
  std::size_t flips = 0;                 // edge flips performed while recovering segments (Ct, Lawson, Lifting)
  std::size_t edges_crossed = 0;         // edges crossed by the segment pieces that had to be recovered
  std::size_t cavity_triangles = 0;      // Fast: triangles removed and retriangulated
  std::size_t intersections = 0;         // crossing segment pairs resolved by a new vertex
  std::size_t vertices_on_segments = 0;  // segments split at a vertex lying exactly on them
  std::size_t overlaps_merged = 0;       // segment pieces that were constrained already (collinear overlaps)
  std::size_t zero_length_segments = 0;  // ignored, with a warning
  std::size_t duplicate_vertices = 0;
  // Pieces finished by another method: Ct stalled (the seed's rule (2) can
  // leave no flippable edge: frequent), Lifting met an unflippable edge
  // (cannot happen; a guard) and Fast finished the piece; or Fast met a
  // cavity that encloses triangles it does not contain and Lifting did it.
  // intersection_fallbacks: a rounded crossing point did not fall inside the
  // two triangles of the crossed edge and was inserted as a free vertex.
  std::size_t method_fallbacks = 0;
  std::size_t intersection_fallbacks = 0;
  // Crossings within a few rounding errors (64 ulps of the coordinates) of
  // an endpoint of either segment piece, resolved at that endpoint instead
  // of by a new vertex (nearly concurrent segments would otherwise keep
  // crossing each other's rounded pieces).
  std::size_t crossings_snapped = 0;
  // When the segments are long against the spacing of the vertices (mean
  // length over twice sqrt(bounding box area / vertices): a star-shaped
  // polygon, not a coastline) and form chains (most of their vertices are
  // shared by two segments), Fast first inserts the vertices along the
  // segment chains and each segment as soon as its endpoints are in
  // (chain_order: it did; vertices and segments are then timed together in
  // triangulate_seconds). It gives up when that order makes point location
  // or flips too costly (chain_order_abandoned: points along a convex curve),
  // and the classic order follows: the Delaunay triangulation of all
  // vertices, then the segments one by one.
  bool chain_order = false;
  bool chain_order_abandoned = false;
  double triangulate_seconds = 0.0;      // Delaunay of the vertices
  double segments_seconds = 0.0;         // segment recovery
};

// The constrained (Delaunay) triangulation of `pslg`: a closed triangulation
// with ghost triangles, input segments present as chains of constrained edges
// carrying their markers. Vertices 0..n-1 are the input's (a duplicate stays
// a vertex in no triangle and segments use its first copy); vertices added at
// segment crossings follow.
//
// Degenerate input is handled as users expect: a vertex exactly on a segment
// splits it; collinear overlapping segments merge (an edge of several keeps
// the marker of the lowest-numbered one with a nonzero marker); crossing
// segments (topology decided by exact predicates) get their intersection
// inserted as a new vertex, the point rounded to doubles, and both are split
// there (IntersectingSegments instead under options.strict); zero-length
// segments are ignored and counted.
// Throws InputError for a segment endpoint out of range, for input the
// Delaunay step rejects (non-finite, fewer than 3 distinct or all collinear
// points), VertexError for a nonzero coordinate beyond the predicates'
// range 2^+-200 (triangulate() meshes such input in a frame), and if the number of added vertices exceeds the number of segment
// pairs (it cannot on valid input: the guard against endless loops).
Mesh constrained_triangulation(const Pslg& pslg, const CdtOptions& options = {}, CdtStats* stats = nullptr);

}  // namespace deltamesh
