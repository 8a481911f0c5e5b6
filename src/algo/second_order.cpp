// Six-node triangles (Triangle's -o2). See include/deltamesh/second_order.hpp.
#include "deltamesh/second_order.hpp"

#include <string>

#include "deltamesh/errors.hpp"
#include "mesh/edge_rules.hpp"

namespace deltamesh {

MidpointNodes midpoint_nodes(const Mesh& mesh) {
  MidpointNodes out;
  const std::size_t slots = mesh.num_triangle_slots();
  const std::size_t na = mesh.num_vertex_attributes();
  const std::vector<double>& attr = mesh.vertex_attributes();
  out.tri_nodes.assign(3 * slots, kNone);
  const auto base = static_cast<VertexId>(mesh.num_vertices());
  for (TriId t : mesh.triangles()) {
    for (int i = 0; i < 3; ++i) {
      const HalfEdgeId e = 3 * t + i;
      // Half-edge i runs from corner i to corner i+1: opposite corner i+2.
      const std::size_t slot = 3 * std::size_t{t} + (i + 2) % 3;
      if (out.tri_nodes[slot] != kNone) continue;  // set from the neighbour
      const VertexId a = mesh.origin(e), b = mesh.dest(e);
      const Point& pa = mesh.point(a);
      const Point& pb = mesh.point(b);
      out.points.push_back({0.5 * (pa.x + pb.x), 0.5 * (pa.y + pb.y)});
      for (std::size_t k = 0; k < na; ++k) {
        const std::size_t ia = std::size_t{a} * na + k, ib = std::size_t{b} * na + k;
        const double va = ia < attr.size() ? attr[ia] : 0.0, vb = ib < attr.size() ? attr[ib] : 0.0;
        out.attributes.push_back(0.5 * (va + vb));
      }
      const HalfEdgeId f = real_twin(mesh, e);
      out.markers.push_back(edge_output_marker(mesh, e, f));
      const VertexId id = base + static_cast<VertexId>(out.points.size() - 1);
      out.tri_nodes[slot] = id;
      if (f != kNone) out.tri_nodes[3 * std::size_t{tri_of(f)} + (f % 3 + 2) % 3] = id;
    }
  }
  return out;
}

std::vector<VertexId> add_midpoint_nodes(Mesh& mesh) {
  if (!mesh.compacted()) mesh.compact();
  const std::size_t n0 = mesh.num_vertices();
  std::vector<int>& markers = mesh.vertex_markers();
  if (markers.size() < n0) {
    // Corners without a marker get what write_node would write for them:
    // 1 on the boundary, 0 elsewhere.
    const std::size_t given = markers.size();
    markers.resize(n0, 0);
    for (TriId t : mesh.triangles()) {
      for (HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e) {
        if (real_twin(mesh, e) != kNone) continue;
        for (const VertexId v : {mesh.origin(e), mesh.dest(e)})
          if (v >= given) markers[v] = 1;
      }
    }
  }
  markers.resize(n0);
  MidpointNodes mid = midpoint_nodes(mesh);
  const std::size_t na = mesh.num_vertex_attributes();
  std::vector<double>& attr = mesh.vertex_attributes();
  attr.resize(n0 * na, 0.0);
  for (std::size_t i = 0; i < mid.points.size(); ++i) {
    mesh.add_vertex(mid.points[i]);
    markers.push_back(mid.markers[i]);
  }
  attr.insert(attr.end(), mid.attributes.begin(), mid.attributes.end());
  return std::move(mid.tri_nodes);
}

std::size_t drop_midpoint_nodes(Pslg& nodes, std::vector<VertexId>& triangles, std::span<const VertexId> midside) {
  const std::size_t n = nodes.points.size();
  // keep: 0 unknown, 1 listed only as a midpoint (drop), 2 needed.
  std::vector<char> state(n, 0);
  const auto check = [&](VertexId v, const char* what) {
    if (v >= n)
      throw InputError(std::string(what) + " refers to vertex " + std::to_string(v + static_cast<long long>(nodes.first_index)) +
                       ", but there are " + std::to_string(n) + " vertices");
  };
  const auto need = [&](VertexId v) {
    check(v, "a triangle or segment");
    state[v] = 2;
  };
  for (const VertexId v : triangles) need(v);
  for (const Segment& s : nodes.segments) {
    need(s.a);
    need(s.b);
  }
  for (const VertexId v : midside) {
    check(v, "a midpoint node of a 6-node triangle");
    if (state[v] == 0) state[v] = 1;
  }
  std::vector<VertexId> new_id(n, kNone);
  VertexId next = 0;
  for (std::size_t v = 0; v < n; ++v)
    if (state[v] != 1) new_id[v] = next++;
  const std::size_t dropped = n - next;
  if (dropped == 0) return 0;

  const std::size_t na = nodes.num_point_attributes;
  const bool has_markers = nodes.point_markers.size() == n;
  std::size_t w = 0;
  for (std::size_t v = 0; v < n; ++v) {
    if (new_id[v] == kNone) continue;
    nodes.points[w] = nodes.points[v];
    if (has_markers) nodes.point_markers[w] = nodes.point_markers[v];
    for (std::size_t k = 0; k < na && (v + 1) * na <= nodes.point_attributes.size(); ++k)
      nodes.point_attributes[w * na + k] = nodes.point_attributes[v * na + k];
    ++w;
  }
  nodes.points.resize(w);
  if (has_markers) nodes.point_markers.resize(w);
  if (nodes.point_attributes.size() >= w * na) nodes.point_attributes.resize(w * na);
  for (VertexId& v : triangles) v = new_id[v];
  for (Segment& s : nodes.segments) {
    s.a = new_id[s.a];
    s.b = new_id[s.b];
  }
  return dropped;
}

}  // namespace deltamesh
