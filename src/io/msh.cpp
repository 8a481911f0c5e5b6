// Gmsh .msh writer, MSH 4.1 and 2.2 ASCII (Gmsh reference manual, "MSH file
// format" and "Legacy formats").
//
// Layout: triangles (element type 2, or 9 with midside nodes) grouped by
// region, one discrete surface and one 2-D physical group per region; the
// boundary and segment edges (type 1, or 8) grouped by marker, one discrete
// curve and one 1-D physical group per marker. Physical and entity tags
// coincide: a positive region value / marker is its own tag, the others are
// numbered after the largest positive one, in increasing order. Node tags
// are vertex ids + 1; triangle element tags are the .ele output indices + 1,
// line element tags follow the triangles.
#include <algorithm>
#include <array>
#include <map>
#include <string>
#include <vector>

#include "deltamesh/formats.hpp"
#include "io/export_util.hpp"

namespace deltamesh {

namespace {

using io::OutBuffer;

struct Group {
  long long value;  // region value or marker
  int tag;          // physical tag = entity tag
  std::string name;
  std::vector<std::size_t> items;  // output triangle indices / line indices
  std::array<double, 4> box{INFINITY, INFINITY, -INFINITY, -INFINITY};
};

// Tags for a set of values: positive values keep their own; the rest follow
// the largest positive value.
std::vector<Group> make_groups(const std::map<long long, std::vector<std::size_t>>& by_value, const char* prefix) {
  std::vector<Group> groups;
  long long max_positive = 0;
  for (const auto& [v, items] : by_value)
    if (v > 0) max_positive = std::max(max_positive, v);
  long long next = max_positive + 1;
  for (const auto& [v, items] : by_value) {
    Group g;
    g.value = v;
    g.tag = static_cast<int>(v > 0 && v <= 2147483647 ? v : next++);
    g.name = std::string(prefix) + std::to_string(v);
    g.items = items;
    groups.push_back(std::move(g));
  }
  return groups;
}

void grow(std::array<double, 4>& box, const Point& p) {
  box[0] = std::min(box[0], p.x);
  box[1] = std::min(box[1], p.y);
  box[2] = std::max(box[2], p.x);
  box[3] = std::max(box[3], p.y);
}

void put_box(OutBuffer& out, const std::array<double, 4>& b) {
  const bool empty = !(b[0] <= b[2]);
  out.field_double(empty ? 0.0 : b[0]);
  out.field_double(empty ? 0.0 : b[1]);
  out.put(" 0");
  out.field_double(empty ? 0.0 : b[2]);
  out.field_double(empty ? 0.0 : b[3]);
  out.put(" 0");
}

void put_quoted(OutBuffer& out, const std::string& s) {
  out.put('"');
  for (const char c : s) out.put(c == '"' ? '\'' : c);
  out.put('"');
}

}  // namespace

void write_msh(const Mesh& mesh, const std::string& path, const MshOptions& options) {
  const io::TriangleOrder order = io::live_triangles(mesh);
  const std::size_t nt = order.size();
  const std::span<const VertexId> mid = options.second_order.midside;
  const bool quadratic = !mid.empty();
  if (quadratic && mid.size() != 3 * nt)
    throw Error("write_msh: " + std::to_string(mid.size()) + " midside nodes given for " + std::to_string(nt) +
                " triangles (3 per triangle expected)");
  for (const VertexId v : mid)
    if (v >= mesh.num_vertices()) throw Error("write_msh: midside node " + std::to_string(v) + " is not a vertex");

  // Corner i of triangle k, and the midside node of local edge i (corner i
  // to corner i+1), which Triangle's order lists opposite corner i+2.
  const auto corner = [&](std::size_t k, int i) { return mesh.triangle_vertices()[3 * order.slots[k] + i]; };
  const auto midside = [&](std::size_t k, int i) { return mid[3 * k + (i + 2) % 3]; };

  // 2-D groups by region.
  std::map<long long, std::vector<std::size_t>> by_region;
  for (std::size_t k = 0; k < nt; ++k) by_region[io::triangle_region(mesh, order.slots[k])].push_back(k);
  std::vector<Group> regions = make_groups(by_region, "region_");
  if (mesh.num_triangle_attributes() == 0 && regions.size() == 1) regions[0].name = "domain";
  if (regions.empty()) regions.push_back(Group{0, 1, "domain", {}, {INFINITY, INFINITY, -INFINITY, -INFINITY}});

  // 1-D groups by marker.
  std::vector<io::LineEdge> lines;
  std::vector<std::size_t> line_tri;  // output triangle index of each line's half-edge
  std::vector<Group> curves;
  if (options.boundary_lines) {
    lines = io::boundary_and_segment_edges(mesh);
    std::vector<std::size_t> index_of_slot(mesh.num_triangle_slots(), 0);
    for (std::size_t k = 0; k < nt; ++k) index_of_slot[order.slots[k]] = k;
    std::map<long long, std::vector<std::size_t>> by_marker;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      line_tri.push_back(index_of_slot[tri_of(lines[i].e)]);
      by_marker[lines[i].marker].push_back(i);
    }
    curves = make_groups(by_marker, "boundary_");
  }
  const auto line_nodes = [&](std::size_t i, std::array<VertexId, 3>& nodes) {
    const HalfEdgeId e = lines[i].e;
    nodes = {mesh.origin(e), mesh.dest(e), kNone};
    if (quadratic) nodes[2] = midside(line_tri[i], static_cast<int>(e % 3));
  };

  // Bounding boxes, and each node's entity (4.1): the surface of the first
  // triangle using it; unused vertices go to the first surface.
  const std::size_t nv = mesh.num_vertices();
  std::vector<std::uint32_t> node_surface(nv, kNone);
  for (std::size_t g = 0; g < regions.size(); ++g)
    for (const std::size_t k : regions[g].items)
      for (int i = 0; i < 3; ++i) {
        for (const VertexId v : {corner(k, i), quadratic ? midside(k, i) : kNone}) {
          if (v == kNone) continue;
          grow(regions[g].box, mesh.point(v));
          if (node_surface[v] == kNone) node_surface[v] = static_cast<std::uint32_t>(g);
        }
      }
  for (Group& c : curves)
    for (const std::size_t i : c.items) {
      std::array<VertexId, 3> nodes;
      line_nodes(i, nodes);
      for (const VertexId v : nodes)
        if (v != kNone) grow(c.box, mesh.point(v));
    }
  for (auto& s : node_surface)
    if (s == kNone) s = 0;

  const int tri_type = quadratic ? 9 : 2;
  const int line_type = quadratic ? 8 : 1;
  const auto put_triangle_nodes = [&](OutBuffer& out, std::size_t k) {
    for (int i = 0; i < 3; ++i) out.field_int(static_cast<long long>(corner(k, i)) + 1);
    if (quadratic)
      for (int i = 0; i < 3; ++i) out.field_int(static_cast<long long>(midside(k, i)) + 1);
  };
  const auto put_line_nodes = [&](OutBuffer& out, std::size_t i) {
    std::array<VertexId, 3> nodes;
    line_nodes(i, nodes);
    for (int j = 0; j < (quadratic ? 3 : 2); ++j) out.field_int(static_cast<long long>(nodes[j]) + 1);
  };

  io::AtomicFile file(path);
  OutBuffer out(file);
  const bool v41 = options.version == MshVersion::V41;
  out.put(v41 ? "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n" : "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n");

  out.put("$PhysicalNames\n");
  out.put_uint(curves.size() + regions.size());
  out.put('\n');
  for (const Group& c : curves) {
    out.put("1 ");
    out.put_int(c.tag);
    out.put(' ');
    put_quoted(out, c.name);
    out.put('\n');
  }
  for (const Group& r : regions) {
    out.put("2 ");
    out.put_int(r.tag);
    out.put(' ');
    put_quoted(out, r.name);
    out.put('\n');
  }
  out.put("$EndPhysicalNames\n");

  const std::size_t total_elements = nt + lines.size();
  if (v41) {
    out.put("$Entities\n0 ");
    out.put_uint(curves.size());
    out.put(' ');
    out.put_uint(regions.size());
    out.put(" 0\n");
    for (const Group& c : curves) {
      out.put_int(c.tag);
      put_box(out, c.box);
      out.put(" 1");
      out.field_int(c.tag);
      out.put(" 0\n");  // no bounding points
    }
    for (const Group& r : regions) {
      out.put_int(r.tag);
      put_box(out, r.box);
      out.put(" 1");
      out.field_int(r.tag);
      out.put(" 0\n");  // no bounding curves
    }
    out.put("$EndEntities\n");

    // Nodes, one block per surface.
    std::vector<std::vector<VertexId>> block(regions.size());
    for (VertexId v = 0; v < nv; ++v) block[node_surface[v]].push_back(v);
    std::size_t blocks = 0;
    for (const auto& b : block) blocks += !b.empty();
    out.put("$Nodes\n");
    out.put_uint(blocks);
    out.put(' ');
    out.put_uint(nv);
    out.put(nv ? " 1 " : " 0 ");
    out.put_uint(nv);
    out.put('\n');
    for (std::size_t g = 0; g < regions.size(); ++g) {
      if (block[g].empty()) continue;
      out.put("2 ");
      out.put_int(regions[g].tag);
      out.put(" 0 ");
      out.put_uint(block[g].size());
      out.put('\n');
      for (const VertexId v : block[g]) {
        out.put_uint(std::size_t{v} + 1);
        out.put('\n');
      }
      for (const VertexId v : block[g]) {
        const Point& p = mesh.point(v);
        out.put_double(p.x);
        out.field_double(p.y);
        out.put(" 0\n");
      }
    }
    out.put("$EndNodes\n");

    std::size_t el_blocks = 0;
    for (const Group& r : regions) el_blocks += !r.items.empty();
    for (const Group& c : curves) el_blocks += !c.items.empty();
    out.put("$Elements\n");
    out.put_uint(el_blocks);
    out.put(' ');
    out.put_uint(total_elements);
    out.put(total_elements ? " 1 " : " 0 ");
    out.put_uint(total_elements);
    out.put('\n');
    for (const Group& r : regions) {
      if (r.items.empty()) continue;
      out.put("2 ");
      out.put_int(r.tag);
      out.field_int(tri_type);
      out.put(' ');
      out.put_uint(r.items.size());
      out.put('\n');
      for (const std::size_t k : r.items) {
        out.put_uint(k + 1);
        put_triangle_nodes(out, k);
        out.put('\n');
      }
    }
    for (const Group& c : curves) {
      if (c.items.empty()) continue;
      out.put("1 ");
      out.put_int(c.tag);
      out.field_int(line_type);
      out.put(' ');
      out.put_uint(c.items.size());
      out.put('\n');
      for (const std::size_t i : c.items) {
        out.put_uint(nt + i + 1);
        put_line_nodes(out, i);
        out.put('\n');
      }
    }
    out.put("$EndElements\n");
  } else {
    out.put("$Nodes\n");
    out.put_uint(nv);
    out.put('\n');
    for (VertexId v = 0; v < nv; ++v) {
      const Point& p = mesh.point(v);
      out.put_uint(std::size_t{v} + 1);
      out.field_double(p.x);
      out.field_double(p.y);
      out.put(" 0\n");
    }
    out.put("$EndNodes\n$Elements\n");
    out.put_uint(total_elements);
    out.put('\n');
    // Triangles in output order (tags = .ele indices + 1), then lines.
    std::vector<int> tag_of_triangle(nt, 0);
    for (const Group& r : regions)
      for (const std::size_t k : r.items) tag_of_triangle[k] = r.tag;
    for (std::size_t k = 0; k < nt; ++k) {
      out.put_uint(k + 1);
      out.field_int(tri_type);
      out.put(" 2");
      out.field_int(tag_of_triangle[k]);
      out.field_int(tag_of_triangle[k]);
      put_triangle_nodes(out, k);
      out.put('\n');
    }
    std::vector<int> tag_of_line(lines.size(), 0);
    for (const Group& c : curves)
      for (const std::size_t i : c.items) tag_of_line[i] = c.tag;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      out.put_uint(nt + i + 1);
      out.field_int(line_type);
      out.put(" 2");
      out.field_int(tag_of_line[i]);
      out.field_int(tag_of_line[i]);
      put_line_nodes(out, i);
      out.put('\n');
    }
    out.put("$EndElements\n");
  }
  out.commit();
}

}  // namespace deltamesh
