// The validator: checks a mesh exactly. Every mesh produced in a test goes
// through it; the CLI runs it with -C.
#pragma once
#include <cstddef>
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

struct CheckReport {
  std::vector<std::string> problems;  // empty: the mesh is valid
  std::size_t triangles = 0;
  std::size_t edges = 0;
  std::size_t vertices_used = 0;
  std::size_t segments_checked = 0;  // PSLG segments found as constrained chains or missing (with options.pslg)
  bool ok() const { return problems.empty(); }
  std::string summary() const;
};

// Twin symmetry, vertex<->edge consistency, exact positive orientation of
// every triangle, Delaunay property of every unconstrained edge, hull
// convexity, Euler characteristic of each connected piece, and with a PSLG
// every segment present as a chain of constrained edges.
CheckReport check(const Mesh& mesh, const CheckOptions& options = {});

}  // namespace deltamesh
