// GeoJSON writer (RFC 7946): a FeatureCollection of Polygon features, one
// per triangle and, when asked, one per bounded Voronoi cell.
#include <array>

#include "deltamesh/formats.hpp"
#include "deltamesh/voronoi.hpp"
#include "io/export_util.hpp"

namespace deltamesh {

namespace {

void put_position(io::OutBuffer& out, const Point& p) {
  out.put('[');
  out.put_number(p.x);
  out.put(',');
  out.put_number(p.y);
  out.put(']');
}

// A one-ring Polygon geometry from an open ring (the first position is
// repeated at the end, as RFC 7946 requires).
template <class Ring>
void put_polygon(io::OutBuffer& out, const Ring& ring) {
  out.put("{\"type\":\"Polygon\",\"coordinates\":[[");
  for (const Point& p : ring) {
    put_position(out, p);
    out.put(',');
  }
  put_position(out, ring[0]);
  out.put("]]}");
}

}  // namespace

void write_geojson(const Mesh& mesh, const std::string& path, const GeoJsonWriteOptions& options) {
  io::AtomicFile file(path);
  io::OutBuffer out(file);
  out.put("{\"type\":\"FeatureCollection\",\"features\":[");
  bool first = true;
  const auto begin_feature = [&] {
    out.put(first ? "\n" : ",\n");
    first = false;
  };
  if (options.triangles) {
    const io::TriangleOrder order = io::live_triangles(mesh);
    for (std::size_t k = 0; k < order.size(); ++k) {
      const TriId t = order.slots[k];
      const auto tri = mesh.triangle(t);
      const std::array<Point, 3> ring{mesh.point(tri[0]), mesh.point(tri[1]), mesh.point(tri[2])};
      begin_feature();
      out.put("{\"type\":\"Feature\",\"geometry\":");
      put_polygon(out, ring);
      out.put(",\"properties\":{\"kind\":\"triangle\",\"id\":");
      out.put_uint(k);
      out.put(",\"region\":");
      out.put_int(io::triangle_region(mesh, t));
      out.put(",\"min_angle\":");
      out.put_number(io::smallest_angle_deg(ring[0], ring[1], ring[2]));
      out.put(",\"area\":");
      out.put_number(io::triangle_area(ring[0], ring[1], ring[2]));
      out.put("}}");
    }
  }
  if (options.segments) {
    const std::vector<io::LineEdge> lines = io::boundary_and_segment_edges(mesh);
    for (std::size_t i = 0; i < lines.size(); ++i) {
      begin_feature();
      out.put("{\"type\":\"Feature\",\"geometry\":{\"type\":\"LineString\",\"coordinates\":[");
      put_position(out, mesh.point(mesh.origin(lines[i].e)));
      out.put(',');
      put_position(out, mesh.point(mesh.dest(lines[i].e)));
      out.put("]},\"properties\":{\"kind\":\"segment\",\"id\":");
      out.put_uint(i);
      out.put(",\"marker\":");
      out.put_int(lines[i].marker);
      out.put("}}");
    }
  }
  if (options.voronoi) {
    for (const VoronoiCell& cell : options.voronoi->cells) {
      if (cell.ring.size() < 3) continue;
      begin_feature();
      out.put("{\"type\":\"Feature\",\"geometry\":");
      put_polygon(out, cell.ring);
      out.put(",\"properties\":{\"kind\":\"voronoi_cell\",\"site\":");
      out.put_uint(cell.site);
      out.put(",\"area\":");
      out.put_number(cell.area);
      out.put("}}");
    }
  }
  out.put("\n]}\n");
  out.commit();
}

}  // namespace deltamesh
