// The meshing domain: which triangles of a constrained triangulation are
// kept (holes, exterior, nesting depth) and what each carries (regional
// attributes, area bounds).
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "deltamesh/mesh.hpp"
#include "deltamesh/pslg.hpp"

namespace deltamesh {

enum class FillRule {
  // Triangle's rule: remove what the exterior and the hole points reach by
  // flood fill, never crossing a segment.
  Holes,
  // Keep triangles whose nesting depth (the fewest segments crossed on a
  // path from outside the convex hull) is odd: rings need no hole points.
  // Hole points, when given, still remove what they reach.
  EvenOdd,
};

struct DomainOptions {
  FillRule fill = FillRule::Holes;
  // -c: keep the whole convex hull (the exterior is not removed; under
  // EvenOdd, depth-0 triangles are kept) and constrain the hull edges, so
  // they are written as segments.
  bool keep_convex_hull = false;
  bool ignore_holes = false;          // -O: hole points are not used
  bool regional_attributes = false;   // -A: one attribute per triangle from the region seeds
  bool regional_area_bounds = false;  // -a without a number: area bounds from the region seeds
};

struct DomainStats {
  std::size_t triangles_removed = 0;
  std::size_t triangles_kept = 0;
  std::size_t holes_used = 0;        // hole points that located inside the triangulation
  std::size_t holes_ignored = 0;     // hole points outside the hull, on a vertex or on a segment
  std::size_t holes_outside = 0;     // carve_mesh: hole points in no triangle (in a hole the mesh has already)
  std::size_t regions_used = 0;      // region seeds that located in a kept triangle
  std::size_t regions_ignored = 0;   // region seeds outside the domain, on a vertex or on a segment
  std::size_t hull_segments_added = 0;  // -c: hull edges that were not segments yet
  std::vector<std::size_t> ignored_holes;    // the ignored hole points, 0-based in pslg.holes
  std::vector<std::size_t> ignored_regions;  // the ignored region seeds, 0-based in pslg.regions
  double seconds = 0.0;
};

// Removes the triangles outside the domain and compacts the mesh.
//
// `mesh` must be closed (ghost triangles present, as constrained_triangulation
// returns it); segments are its constrained edges. Hole points and region
// seeds are located exactly: a point strictly inside a triangle or on an
// unconstrained edge selects that segment-bounded region; a point on a
// vertex, on a segment or outside the convex hull is ignored and counted.
//
// Regional attributes (when asked) become triangle attribute 0 (one per
// triangle, 0 where no seed reaches); regional area bounds become the
// per-triangle area bounds. When several seeds fall in one region the last
// one wins, as in Triangle. Removing every triangle is not an error: the
// result is an empty mesh that still holds the vertices.
void carve_domain(Mesh& mesh, const Pslg& pslg, const DomainOptions& options = {}, DomainStats* stats = nullptr);

// Holes and regions on a finished (compacted) mesh, as Triangle's -r with -p
// reads them: the mesh's domain is its triangles, so there is no exterior to
// remove (options.fill and keep_convex_hull are not used). A hole point in a
// triangle, or on an unconstrained edge, removes its segment-bounded region;
// one in no triangle (in a hole the mesh has already: what a .poly written
// with the mesh lists) is counted in holes_outside; one on a vertex or a
// segment is ignored (holes_ignored), unless options.ignore_holes. Region
// seeds (with options.regional_attributes / regional_area_bounds) are
// located the same way; the last seed in a region gives it attribute 0
// (added when the triangles have none; triangles no seed reaches keep
// theirs) and its area bound. The mesh is compacted again when triangles
// were removed. Points are located by one pass over the triangles.
void carve_mesh(Mesh& mesh, const Pslg& pslg, const DomainOptions& options = {}, DomainStats* stats = nullptr);

// The warnings a user gets about a carve: hole points and region seeds that
// were ignored, and an empty result. `existing_mesh` words them for
// carve_mesh (a mesh read back, where hole points outside it are expected);
// otherwise for carve_domain. One place, so the CLI and triangulate() agree.
// With the carve's `pslg`, ignored points are named by number (as its file
// numbers them: first_index) and place: "hole point 2 at (0.5, 0.5) ignored".
std::vector<std::string> domain_warnings(const DomainStats& stats, std::size_t triangles_left,
                                         bool existing_mesh = false, const Pslg* pslg = nullptr);

// The invariant carving leaves: every boundary edge of the (compacted) mesh
// is a segment, since removal stops only at segments and -c makes the hull
// edges segments. Returns the problems found (empty: fine), at most
// `max_problems`.
std::vector<std::string> check_domain_boundary(const Mesh& mesh, std::size_t max_problems = 20);

}  // namespace deltamesh
