// The module's other functions: the validator and quality report on mesh
// dicts, file reading and writing, Delaunay, convex hull and Voronoi of points.
#include <filesystem>

#include "bindings.hpp"

namespace deltamesh::python {


// A mesh rebuilt from arrays (vertices, triangles, optional markers,
// attributes and segments), for check(), quality() and write().
namespace {

struct Rebuilt {
  Pslg nodes;
  Mesh mesh;
  InsertSegmentsStats inserted;
  std::vector<std::string> orientation_problems;
};

Rebuilt rebuild(const py::dict& tri, bool with_segments) {
  InputArrays a = arrays_from_dict(tri);
  if (!given(a.triangles)) throw py::value_error("triangles: required (an (m, 3) array of 0-based vertex indices)");
  if (!with_segments) a.segments = a.segment_markers = py::handle();
  Input in = read_input(a);
  Rebuilt r;
  r.nodes = std::move(in.run.pslg);
  for (std::size_t t = 0; 3 * t < in.run.triangles.size(); ++t) {
    const Point& p = r.nodes.points[in.run.triangles[3 * t]];
    const Point& q = r.nodes.points[in.run.triangles[3 * t + 1]];
    const Point& s = r.nodes.points[in.run.triangles[3 * t + 2]];
    const double o = orient2d(p, q, s);
    if (o <= 0 && r.orientation_problems.size() < 20)
      r.orientation_problems.push_back("triangle " + std::to_string(t) + " (" + std::to_string(in.run.triangles[3 * t]) +
                                       ", " + std::to_string(in.run.triangles[3 * t + 1]) + ", " +
                                       std::to_string(in.run.triangles[3 * t + 2]) +
                                       (o < 0 ? ") is clockwise" : ") is degenerate"));
  }
  if (!in.run.midside.empty()) drop_midpoint_nodes(r.nodes, in.run.triangles, in.run.midside);
  py::gil_scoped_release nogil;
  r.mesh = mesh_from_triangles(r.nodes, in.run.triangles, in.run.num_triangle_attributes, in.run.triangle_attributes, {},
                                   &r.inserted);
  return r;
}

}  // namespace

py::dict check_dict(const py::dict& tri, bool delaunay, bool convex_hull, bool segments) {
  Rebuilt r;
  std::vector<std::string> problems;
  try {
    r = rebuild(tri, segments);
  } catch (const InputError& e) {
    problems.push_back(std::string("not a triangulation: ") + e.what());
  }
  problems.insert(problems.begin(), r.orientation_problems.begin(), r.orientation_problems.end());
  CheckReport rep;
  if (problems.empty()) {
    if (r.inserted.inserted || r.inserted.vertices_added)
      problems.push_back(std::to_string(r.inserted.inserted) +
                         " segment(s) are not edges or chains of edges of the triangles");
    CheckOptions co;
    co.delaunay = delaunay;
    co.convex_hull = convex_hull;
    if (segments && !r.nodes.segments.empty()) co.pslg = &r.nodes;
    {
      py::gil_scoped_release nogil;
      rep = check(r.mesh, co);
    }
    problems.insert(problems.end(), rep.problems.begin(), rep.problems.end());
  }
  py::dict d;
  d["ok"] = problems.empty();
  py::list pl;
  for (const std::string& p : problems) pl.append(p);
  d["problems"] = pl;
  d["triangles"] = rep.triangles;
  d["edges"] = rep.edges;
  d["vertices_used"] = rep.vertices_used;
  d["segments_checked"] = rep.segments_checked;
  d["summary"] =
      problems.empty() ? rep.summary() : std::to_string(problems.size()) + " problem(s): " + problems.front();
  return d;
}

py::dict validate_dict(const py::dict& tri, bool delaunay, bool convex_hull, bool segments) {
  py::dict d = check_dict(tri, delaunay, convex_hull, segments);
  if (!d["ok"].cast<bool>()) {
    raise_with(g_exc.check, "invalid mesh: " + d["summary"].cast<std::string>(), {{"problems", d["problems"]}});
    throw py::error_already_set();
  }
  return d;
}

// The command line's --stats=json object (docs/stats-schema.md) as a dict,
// plus the names quality() used before the schema (min_angle, max_angle,
// angle_histogram), kept as aliases.
py::dict quality_dict(const py::dict& tri, double min_angle, double max_area) {
  Rebuilt r = rebuild(tri, false);
  QualityOptions q;
  q.min_angle_deg = min_angle;
  q.max_area = max_area;
  const QualityReport qr = quality_report(r.mesh, q);
  py::dict d = py::module_::import("json").attr("loads")(qr.json());
  d["min_angle"] = d["min_angle_deg"];
  d["max_angle"] = d["max_angle_deg"];
  d["angle_histogram"] = d["angle_histogram_deg10"];
  return d;
}

py::dict read_file(const std::string& path) {
  namespace fs = std::filesystem;
  std::string base = path;
  for (const char* ext : {".node", ".ele", ".poly"})
    if (ends_with(path, ext)) base = path.substr(0, path.size() - std::string(ext).size());
  if (ends_with(path, ".geojson") || ends_with(path, ".json")) {
    Pslg p;
    {
      py::gil_scoped_release nogil;
      p = read_geojson(path);
    }
    return pslg_dict(p);
  }
  if (ends_with(path, ".poly")) {
    Pslg p;
    {
      py::gil_scoped_release nogil;
      p = read_poly(path);
    }
    return pslg_dict(p);
  }
  // FILE.node (or FILE.ele, or FILE): the vertices, with FILE.ele's
  // triangles and FILE.poly's segments, holes and regions when present.
  const std::string node = base + ".node", ele = base + ".ele", poly = base + ".poly";
  if (!fs::exists(node)) {
    if (base == path && fs::exists(poly)) return read_file(poly);
    throw IoError("cannot open '" + node + "'" +
                      (base == path ? " (read takes FILE.node, FILE.poly, FILE.ele, FILE or FILE.geojson)" : ""));
  }
  Pslg p;
  EleData e;
  bool has_ele = fs::exists(ele), has_poly = fs::exists(poly);
  {
    py::gil_scoped_release nogil;
    p = read_node(node);
    if (has_poly) {
      Pslg q = read_poly(poly);
      if (q.points.size() != p.points.size())
        throw InputError(poly + " lists " + std::to_string(q.points.size()) + " vertices but " + node + " has " +
                             std::to_string(p.points.size()));
      p.segments = std::move(q.segments);
      p.holes = std::move(q.holes);
      p.regions = std::move(q.regions);
    }
    if (has_ele) e = read_ele(ele, p.first_index);
  }
  py::dict d = pslg_dict(p);
  if (has_ele) {
    const std::size_t nt = e.triangles.size() / 3;
    std::vector<std::int32_t> t;
    for (std::size_t i = 0; i < nt; ++i) {
      for (std::size_t k = 0; k < 3; ++k) t.push_back(static_cast<std::int32_t>(e.triangles[3 * i + k]));
      if (!e.midside.empty())
        for (std::size_t k = 0; k < 3; ++k) t.push_back(static_cast<std::int32_t>(e.midside[3 * i + k]));
    }
    d["triangles"] = array_2d(t, e.midside.empty() ? 3 : 6);
    if (e.num_attributes) d["triangle_attributes"] = array_2d(e.attributes, e.num_attributes);
  }
  return d;
}

void write_file(const py::dict& tri, const std::string& path, int first_index, bool markers) {
  if (first_index != 0 && first_index != 1) throw py::value_error("first_index: must be 0 or 1");
  if (!output_format_for(path)) throw py::value_error(UnknownOutputFormat(path).what());
  Rebuilt r = rebuild(tri, true);
  // Inserting a segment changes the triangles: the file would not hold the mesh given.
  if (r.inserted.inserted || r.inserted.vertices_added)
    throw py::value_error("segments: " + std::to_string(r.inserted.inserted) +
                          " segment(s) not an edge or a chain of edges of the triangles (deltamesh.check() "
                          "lists the problems); mesh them in with triangulate(mesh, 'rp') first");
  py::gil_scoped_release nogil;
  if (*output_format_for(path) == OutputFormat::Poly) {
    TriangleWriteOptions w;
    w.first_index = first_index;
    w.write_markers = markers;
    w.holes = r.nodes.holes;
    w.regions = r.nodes.regions;
    write_poly(r.mesh, path, w);
    return;
  }
  OutputOptions oo;
  oo.first_index = first_index;
  oo.write_markers = markers;
  write_output(r.mesh, path, oo);
}

namespace {

// The Delaunay triangulation of points (no segments), for delaunay(),
// convex_hull() and voronoi(); no triangles when the points are collinear.
Mesh delaunay_mesh(py::handle vertices) {
  InputArrays a{};
  a.vertices = vertices;
  Input in = read_input(a);
  if (all_collinear(in.run.pslg.points)) return Mesh{};
  TriangulateOptions topt;
  topt.use_segments = false;
  py::gil_scoped_release nogil;
  return triangulate(in.run.pslg, topt);
}

}  // namespace

py::array_t<std::int32_t> delaunay_triangles(py::handle vertices) {
  const Mesh mesh = delaunay_mesh(vertices);
  std::vector<std::int32_t> t;
  for (TriId i = 0; i < mesh.num_triangle_slots(); ++i)
    if (mesh.is_real(i))
      for (const VertexId v : mesh.triangle(i)) t.push_back(static_cast<std::int32_t>(v));
  return array_2d(t, 3);
}

// Triangle's orientation and order: the hull cycle from its lowest-leftmost
// vertex, each edge with the interior on its right.
py::array_t<std::int32_t> hull_segments(py::handle vertices) {
  const Mesh mesh = delaunay_mesh(vertices);
  std::vector<OutEdge> ccw;
  for (HalfEdgeId e = 0; e < mesh.triangle_vertices().size(); ++e)
    if (mesh.is_real(tri_of(e)) && real_twin(mesh, e) == kNone)
      ccw.push_back({static_cast<std::int32_t>(mesh.origin(e)), static_cast<std::int32_t>(mesh.dest(e)), 0, true});
  std::vector<std::int32_t> s;
  for (const OutEdge& e : triangle_boundary_order(mesh, std::move(ccw))) s.insert(s.end(), {e.a, e.b});
  return array_2d(s, 2);
}

// The `triangle` package's voronoi(): (points, edges, ray_origins, ray_directions).
py::tuple voronoi_tuple(py::handle vertices) {
  const Mesh mesh = delaunay_mesh(vertices);
  py::dict d = voronoi_arrays(mesh);
  return py::make_tuple(d["vertices"], d["edges"], d["ray_origins"], d["ray_directions"]);
}

}  // namespace deltamesh::python
