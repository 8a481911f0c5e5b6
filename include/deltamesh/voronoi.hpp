// The Voronoi diagram of a mesh's vertices, read off the triangulation: its
// dual graph (Triangle's -v output, .v.node and .v.edge) and the bounded
// cells clipped to the meshed domain (for SVG overlays and GeoJSON).
//
// Both are exact duals only where the mesh is Delaunay: for a Delaunay
// triangulation the dual graph *is* the Voronoi diagram. For a constrained
// Delaunay triangulation the dual graph is what Triangle writes too (its -v
// documentation says the same: a Voronoi diagram of a CDT is only the dual).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "deltamesh/geometry.hpp"
#include "deltamesh/mesh.hpp"

namespace deltamesh {

// The dual graph of a mesh.
struct VoronoiDiagram {
  // One Voronoi vertex per live real triangle, in output (.ele) order: the
  // triangle's circumcentre.
  std::vector<Point> vertices;
  // The mesh's vertex attributes at each Voronoi vertex (num_attributes
  // per vertex): the linear interpolation over its triangle, evaluated at
  // the circumcentre (an extrapolation when it lies outside the triangle).
  std::size_t num_attributes = 0;
  std::vector<double> attributes;
  struct Edge {
    std::uint32_t a = 0;       // Voronoi vertex (the triangle on the left of `delaunay_edge`)
    std::uint32_t b = kNone;   // the other Voronoi vertex, kNone for an infinite ray
    Point direction;           // rays: outward normal of the boundary edge, as long as that edge
    HalfEdgeId delaunay_edge = kNone;  // the mesh half-edge this edge is dual to (in triangle a)
    bool is_ray() const { return b == kNone; }
  };
  // One Voronoi edge per mesh edge: interior edges join the circumcentres of
  // their two triangles, boundary edges give rays from the circumcentre of
  // their triangle, pointing out of the mesh, perpendicular to the edge.
  std::vector<Edge> edges;
};

VoronoiDiagram voronoi_diagram(const Mesh& mesh);

// Triangle's .v.node: "<#vertices> 2 <#attributes> 0", then "<id> <x> <y>
// [attributes]" (no markers). first_index 0 or 1 as the other output files.
void write_voronoi_node(const VoronoiDiagram& diagram, const std::string& path, int first_index = 0);
// Triangle's .v.edge: "<#edges> 0", then "<id> <a> <b>" for finite edges
// and "<id> <a> -1 <dx> <dy>" for rays (-1 whatever first_index is).
void write_voronoi_edge(const VoronoiDiagram& diagram, const std::string& path, int first_index = 0);

// A Voronoi cell clipped to the meshed domain.
struct VoronoiCell {
  VertexId site = kNone;
  std::vector<Point> ring;  // counter-clockwise, not closed (first point not repeated)
  double area = 0.0;
};

struct BoundedVoronoi {
  // One per vertex used by a triangle, in vertex order (a cell that vanishes
  // numerically, fewer than 3 distinct corners, is left out).
  std::vector<VoronoiCell> cells;
};

// Bounded Voronoi cells. The cell of vertex v is computed locally: starting
// from the triangles around v, the triangles the cell still overlaps are
// visited (never crossing the mesh boundary); the cell is the intersection
// of the half-planes closer to v than to each vertex of those triangles,
// cut by the boundary edges met. Precisely, the result is the connected
// piece containing v of (the Voronoi cell of v among the vertices reached)
// intersected with the domain. For a Delaunay mesh of a convex domain (any
// Delaunay triangulation of points) that is exactly the Voronoi cell
// clipped to the domain, and the cells tile the domain. For a non-convex
// domain each cell stays on v's side of the boundary: the part of a true
// Voronoi cell that lies beyond a hole or a notch (not connected to v
// inside the domain) is not included, and a cell is not cut by vertices it
// cannot reach without leaving the domain, so cells tile the domain only
// approximately there. A reflex boundary vertex's cell is the non-convex
// polygon left after removing the outside wedge.
// Coordinates are computed in floating point (the cells are for pictures
// and GIS layers, not for exact predicates).
BoundedVoronoi bounded_voronoi(const Mesh& mesh);

}  // namespace deltamesh
