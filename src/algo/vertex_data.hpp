// Vertex data of vertices added to a mesh (shared by triangulate.cpp and
// insert_segments.cpp).
#pragma once
#include <cstddef>

#include "deltamesh/mesh.hpp"

namespace deltamesh::detail {

// Attributes of added vertex v (ids >= n are added ones): linear
// interpolation between the ends (ids < n) of a straight chain of
// constrained edges through v; left as they are when there is none. The
// attribute array must already hold v.
void interpolate_vertex_attributes(Mesh& mesh, VertexId v, std::size_t n);

// finish_vertex_markers() (deltamesh/triangulate.hpp) with the scan for
// boundary edges of a compacted mesh on up to `threads` threads; the same
// markers for every thread count.
void finish_vertex_markers(Mesh& mesh, unsigned threads);

}  // namespace deltamesh::detail
