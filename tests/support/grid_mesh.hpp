// A structured mesh for tests that need a known triangulation.
#pragma once
#include <map>
#include <utility>

#include "deltamesh/mesh.hpp"

namespace deltamesh::test {

// nx x ny squares of side h, each split into two counter-clockwise
// triangles along its rising diagonal, twins linked, compacted. Vertex
// (i, j) has id j*(nx+1)+i.
inline Mesh grid_mesh(int nx, int ny, double h = 1.0) {
  Mesh m;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) m.add_vertex({i * h, j * h});
  std::map<std::pair<VertexId, VertexId>, HalfEdgeId> half;
  const auto add = [&](VertexId a, VertexId b, VertexId c) {
    const TriId t = m.add_triangle(a, b, c);
    const VertexId v[3] = {a, b, c};
    for (int k = 0; k < 3; ++k) {
      const HalfEdgeId e = 3 * t + k;
      const auto it = half.find({v[(k + 1) % 3], v[k]});
      if (it != half.end()) m.link(e, it->second);
      half[{v[k], v[(k + 1) % 3]}] = e;
      m.set_out_edge(v[k], e);
    }
  };
  const auto id = [&](int i, int j) { return static_cast<VertexId>(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      add(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      add(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  m.compact();
  return m;
}

}  // namespace deltamesh::test
