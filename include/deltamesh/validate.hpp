// The validator: checks a mesh exactly. Every mesh produced in a test goes
// through it; the CLI runs it with -C.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "deltamesh/mesh.hpp"
#include "deltamesh/pslg.hpp"

namespace deltamesh {

struct CheckOptions {
  // Every unconstrained interior edge is locally Delaunay (exact incircle).
  // Constrained edges are skipped, so on a constrained triangulation this is
  // the constrained Delaunay property (seed §2.1.1: every edge locally
  // Delaunay, a segment or a hull edge).
  bool delaunay = true;
  // The union of triangles is convex (hull edges turn left, exactly).
  bool convex_hull = true;
  std::size_t max_problems = 20;  // stop collecting after this many
  // When set, every segment of this PSLG (vertex ids = mesh vertex ids) must
  // be present as a chain of constrained edges from one endpoint to the
  // other. The chain's inner vertices must lie on the segment (exact
  // orientation test) or within 1e-9 relative distance of it (vertices
  // added at rounded segment crossings bend the chain by a rounding error).
  // A duplicate endpoint (a vertex in no triangle) stands for the
  // used vertex at the same point; zero-length segments are skipped, and so
  // are segments with an endpoint in no triangle (carved away).
  const Pslg* pslg = nullptr;
};

// Two triangles the global overlap test found in conflict, as data (the
// problem text says the same with 0-based ids). Ids are triangle slots and
// vertex ids of the mesh: in a compacted mesh (one from triangulate(), or
// mesh_from_triangles() without inserted segments) slot t is the t-th
// triangle write_ele() writes and the t-th triangle of the .ele it was read
// from, 0-based; add the file's first index to print its own numbering.
struct TriangleConflict {
  enum class Kind : std::uint8_t {
    // Their interiors intersect with positive area (crossing, nested,
    // duplicated, or a vertex of one strictly inside the other).
    Overlap,
    // Interiors disjoint, but boundary edges of the two meet where they do
    // not share an endpoint: a vertex inside the other's boundary edge
    // (T-junction), or boundary edges lying along each other (an edge
    // present twice without a twin link).
    BoundaryContact,
  };
  Kind kind = Kind::Overlap;
  TriId first = kNone;   // the smaller slot id
  TriId second = kNone;  // kNone only if no second triangle could be named
};

struct CheckReport {
  std::vector<std::string> problems;  // empty: the mesh is valid
  // The global overlap test stops at its first finding (the leftmost in
  // (x, y) order), so this holds at most one entry; its text is in problems.
  std::vector<TriangleConflict> conflicts;
  std::size_t triangles = 0;
  std::size_t edges = 0;
  std::size_t vertices_used = 0;
  std::size_t segments_checked = 0;  // PSLG segments found as constrained chains or missing (with options.pslg)
  bool delaunay_checked = true;      // options.delaunay (the summary says when it was not)
  bool ok() const { return problems.empty(); }
  std::string summary() const;
};

// Twin symmetry, vertex<->edge consistency, exact positive orientation of
// every triangle, no overlap anywhere (below), Delaunay property of every
// unconstrained edge, hull convexity, Euler characteristic of each connected
// piece, and with a PSLG every segment present as a chain of constrained
// edges.
//
// Overlap, always checked once twins and orientations are right, whatever
// the connectivity (separate components, pinch vertices, duplicated
// vertices): no two triangles' interiors intersect, and two boundary edges
// (edges with one triangle) meet only at a common endpoint (the same point,
// even as two vertex ids). Touching at a vertex is fine; a triangle inside
// another, a duplicated triangle, crossing boundary loops, a used vertex
// strictly inside another triangle or inside another boundary edge
// (T-junction), and an edge whose two triangles are not linked as twins
// are all reported, naming both triangles (CheckReport::conflicts). Vertices
// in no triangle are not looked at. A plane sweep over the boundary edges
// with exact orientation tests, O(B log B) for B boundary edges plus one
// pass over the triangles.
CheckReport check(const Mesh& mesh, const CheckOptions& options = {});

}  // namespace deltamesh
