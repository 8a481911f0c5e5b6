// The validator: checks a mesh exactly. Every mesh produced in a test goes
// through it; the CLI runs it with -C.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "deltamesh/mesh.hpp"

namespace deltamesh {

struct CheckOptions {
  // Every unconstrained interior edge is locally Delaunay (exact incircle).
  bool delaunay = true;
  // The union of triangles is convex (hull edges turn left, exactly).
  bool convex_hull = true;
  std::size_t max_problems = 20;  // stop collecting after this many
};

struct CheckReport {
  std::vector<std::string> problems;  // empty: the mesh is valid
  std::size_t triangles = 0;
  std::size_t edges = 0;
  std::size_t vertices_used = 0;
  bool ok() const { return problems.empty(); }
  std::string summary() const;
};

// Twin symmetry, vertex<->edge consistency, exact positive orientation of
// every triangle, Delaunay property of every unconstrained edge, hull
// convexity, Euler characteristic of each connected piece.
CheckReport check(const Mesh& mesh, const CheckOptions& options = {});

}  // namespace deltamesh
