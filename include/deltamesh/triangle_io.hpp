// Triangle's file formats (.node .poly .ele .edge .neigh .area), read and
// written. Readers throw ParseError naming file, line and problem. Writers
// write to a temporary name and rename, so no partial file is ever left.
#pragma once
#include <span>
#include <string>
#include <vector>

#include "deltamesh/mesh.hpp"
#include "deltamesh/metric.hpp"
#include "deltamesh/pslg.hpp"

namespace deltamesh {

// Points (with attributes and markers) of a .node file. `threads`: 0 =
// every hardware thread, 1 = one; large vertex lists of the plain shape
// "<id> <x> <y> [<marker>]" are parsed in pieces concurrently (same result
// and same error messages either way).
Pslg read_node(const std::string& path, unsigned threads = 0);
// A .poly file; when its vertex count is 0 the vertices come from the .node
// file of the same base name.
Pslg read_poly(const std::string& path, unsigned threads = 0);

// Triangles of an .ele file (3 or 6 nodes per triangle, first three kept),
// re-based to 0; attributes kept per triangle.
struct EleData {
  std::vector<VertexId> triangles;  // 3 per triangle: the corners
  // 6-node files (Triangle's -o2): nodes 4-6 of every triangle (3 per
  // triangle; empty for 3-node files). second_order.hpp's
  // drop_midpoint_nodes removes them from a mesh read back.
  std::vector<VertexId> midside;
  std::size_t num_attributes = 0;
  std::vector<double> attributes;   // num_attributes per triangle
};
EleData read_ele(const std::string& path, int first_index);
// Per-triangle area bounds of an .area file (negative: no bound).
std::vector<double> read_area(const std::string& path);
// A TetGen/MMG-style .mtr file: a header '<#nodes> <k>' (k = 1 when left
// out), then per node, in node order, one line of k values: k = 1, a
// positive size; k = 3, a metric tensor m11 m12 m22, which must be positive
// definite and not degenerate (metric.hpp's metric_problem: the error names
// the line). '#' comments allowed.
struct MtrData {
  int per_node = 1;            // 1 or 3
  std::vector<double> values;  // per_node per node
};
MtrData read_mtr_data(const std::string& path);
// The sizes of a 1-value .mtr file (InputError for metric tensors).
std::vector<double> read_mtr(const std::string& path);

struct TriangleWriteOptions {
  int first_index = 0;        // numbering written (Triangle: the input's; -z forces 0)
  bool write_markers = true;  // boundary markers (-B turns them off)
  bool write_attributes = true;
  // Holes and regions write_poly lists after the segments (none by default).
  std::span<const Point> holes;
  std::span<const RegionSeed> regions;
  // Six-node triangles (Triangle's -o2): 3 midpoint node ids per triangle
  // slot (second_order.hpp's add_midpoint_nodes), written by write_ele after
  // the corners, node k on the edge opposite corner k. Empty: three-node
  // triangles.
  std::span<const VertexId> midside;
};

void write_node(const Mesh& mesh, const std::string& path, const TriangleWriteOptions& opt = {});
void write_ele(const Mesh& mesh, const std::string& path, const TriangleWriteOptions& opt = {});
// Every edge once, with a boundary marker: its segment's marker when nonzero,
// else 1 on the mesh boundary, else 0 (Triangle's rule).
void write_edge(const Mesh& mesh, const std::string& path, const TriangleWriteOptions& opt = {});
// Per triangle its three neighbours, neighbour i opposite vertex i, -1 for none.
void write_neigh(const Mesh& mesh, const std::string& path, const TriangleWriteOptions& opt = {});
// Constrained edges (or the boundary when none) as a .poly with no vertices
// (they are in the .node file of the same name), markers as in write_edge,
// then opt.holes and opt.regions.
void write_poly(const Mesh& mesh, const std::string& path, const TriangleWriteOptions& opt = {});

}  // namespace deltamesh
