// OFF (Geomview's Object File Format), as Triangle's -g writes it: a header
// line "OFF", then "<#vertices> <#faces> <#edges>", the vertices as x y z,
// and the faces as "3 a b c" with 0-based vertex indices.
#include "deltamesh/formats.hpp"
#include "io/export_util.hpp"

namespace deltamesh {

void write_off(const Mesh& mesh, const std::string& path) {
  const io::TriangleOrder order = io::live_triangles(mesh);
  // The edge count is informational in OFF; write the real one.
  std::size_t edges = 0;
  for (const TriId t : order.slots)
    for (HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e) {
      const HalfEdgeId tw = io::real_twin(mesh, e);
      edges += tw == kNone || e < tw;
    }
  io::AtomicFile file(path);
  io::OutBuffer out(file);
  out.put("OFF\n");
  out.put_uint(mesh.num_vertices());
  out.put(' ');
  out.put_uint(order.size());
  out.put(' ');
  out.put_uint(edges);
  out.put('\n');
  for (const Point& p : mesh.points()) {
    out.put_double(p.x);
    out.field_double(p.y);
    out.put(" 0\n");
  }
  for (const TriId t : order.slots) {
    out.put('3');
    for (const VertexId v : mesh.triangle(t)) out.field_int(v);
    out.put('\n');
  }
  out.commit();
}

}  // namespace deltamesh
