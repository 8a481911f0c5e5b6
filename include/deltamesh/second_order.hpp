// Second-order (six-node, subparametric quadratic) triangles: Triangle's -o2.
// One extra node at the midpoint of every edge, shared by the two triangles
// of an interior edge; the edges stay straight.
//
// Node order is Triangle's 6-node .ele order: corners 1, 2, 3 (counter-
// clockwise), then the midpoints of the edges opposite corners 1, 2 and 3.
// Gmsh (type 9) and VTK (type 22) list the midpoints of edges 12, 23, 31
// instead; formats.hpp's writers reorder.
//
//   std::vector<VertexId> mid = deltamesh::add_midpoint_nodes(mesh);
//   deltamesh::TriangleWriteOptions w;
//   w.midside = mid;
//   deltamesh::write_node(mesh, "out.1.node", w);  // corners, then midpoints
//   deltamesh::write_ele(mesh, "out.1.ele", w);    // 6 nodes per triangle
#pragma once
#include <cstddef>
#include <span>
#include <vector>

#include "deltamesh/mesh.hpp"
#include "deltamesh/pslg.hpp"

namespace deltamesh {

struct MidpointNodes {
  // New node i has id mesh.num_vertices() + i.
  std::vector<Point> points;
  // Boundary marker per node: the segment's marker when the edge is a
  // segment with a nonzero marker; else 1 on the mesh boundary (Triangle's
  // convention for unmarked boundary nodes); else 0.
  std::vector<int> markers;
  // mesh.num_vertex_attributes() per node: the mean of the edge ends'.
  std::vector<double> attributes;
  // 3 per triangle slot, in .ele order (node k opposite corner k); kNone for
  // dead and ghost slots.
  std::vector<VertexId> tri_nodes;
};

// The midpoint nodes of a mesh, which is left unchanged.
MidpointNodes midpoint_nodes(const Mesh& mesh);

// Appends the midpoint nodes to the mesh as vertices in no triangle, with
// their markers and attributes (when the mesh had no vertex markers, the
// corners get Triangle's default first: 1 on the boundary, 0 elsewhere, so
// that written files keep it). Compacts the mesh first if needed, so triangle
// slots are the output order. Returns the 3 node ids per triangle, the form
// TriangleWriteOptions::midside and SecondOrderNodes::midside take.
std::vector<VertexId> add_midpoint_nodes(Mesh& mesh);

// For reading a 6-node mesh back as a linear one (-r): removes from `nodes`
// the points that are listed in `midside` (3 per triangle, as EleData has
// them) and are neither a triangle corner nor a segment end, renumbers the
// rest in order and rewrites `triangles` (corners) and the segments.
// Returns how many points were removed.
std::size_t drop_midpoint_nodes(Pslg& nodes, std::vector<VertexId>& triangles, std::span<const VertexId> midside);

}  // namespace deltamesh
