// Constrained triangulations of a PSLG (seed §1-§2): segments inserted into a
// Delaunay triangulation of the vertices by one of the seed's methods.
#pragma once
#include <cstddef>
#include <string_view>
#include <optional>

#include "deltamesh/mesh.hpp"
#include "deltamesh/pslg.hpp"

namespace deltamesh {

enum class CdtMethod {
  Fast,     // default: the fastest method giving the CDT
  Ct,       // §1.2: rotary traversal + queue of flips; a constrained triangulation, not always Delaunay
  Lawson,   // §2.2: Ct, then constrained Lawson flips on the new edges: the CDT
  Lifting,  // §2.3: flips ordered through the lifting map (priority queue): the CDT
};

std::string_view to_string(CdtMethod m);
std::optional<CdtMethod> parse_cdt_method(std::string_view name);

struct CdtOptions {
  CdtMethod method = CdtMethod::Fast;
  // Crossing segments are an error (IntersectingSegments) instead of being
  // split at their intersection.
  bool strict = false;
};

struct CdtStats {
  std::size_t segments_inserted = 0;
  std::size_t segments_already_present = 0;
  std::size_t flips = 0;                 // edge flips performed while recovering segments
  std::size_t intersections = 0;         // crossing segment pairs resolved by a new vertex
  std::size_t vertices_on_segments = 0;  // segments split at an input vertex lying on them
  std::size_t overlaps_merged = 0;       // collinear overlapping segments merged
  std::size_t zero_length_segments = 0;  // ignored, with a warning
  std::size_t duplicate_vertices = 0;
  double triangulate_seconds = 0.0;      // Delaunay of the vertices
  double segments_seconds = 0.0;         // segment recovery
};

// Two segments of the input cross and options.strict is set.
class IntersectingSegments;

// The constrained (Delaunay) triangulation of `pslg`: a closed triangulation
// with ghost triangles, input segments present as chains of constrained edges
// carrying their markers. Vertices 0..n-1 are the input's; vertices added at
// segment crossings follow.
Mesh constrained_triangulation(const Pslg& pslg, const CdtOptions& options = {}, CdtStats* stats = nullptr);

}  // namespace deltamesh
