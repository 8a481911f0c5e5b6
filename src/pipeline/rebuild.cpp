// -r and --adapt: an existing mesh rebuilt from its triangle list, with new
// segments inserted and holes carved (Triangle's -r -p).
#include "deltamesh/second_order.hpp"
#include "pipeline/steps.hpp"

namespace deltamesh::pipeline {

namespace {

// Without -p nothing keeps the line between two triangle attributes: flips
// and new points move it, and new triangles there may take the attribute
// of the other side. Said once, when the mesh changes (we warn rather than
// constrain those edges: Triangle's -r does the same, and -p is the way).
void warn_attribute_boundaries(const Plan& plan, const Mesh& mesh, RunResult& res) {
  const bool changes = plan.refine.requested() || plan.input == InputKind::Adapt || plan.smooth > 0;
  const std::size_t na = mesh.num_triangle_attributes();
  if (!changes || na == 0) return;
  const std::vector<double>& attr = mesh.triangle_attributes();
  std::size_t edges = 0;
  for (HalfEdgeId e = 0; e < mesh.triangle_vertices().size(); ++e) {
    const HalfEdgeId f = mesh.twin(e);
    if (f == kNone || f < e || mesh.is_constrained(e)) continue;
    const std::size_t t = e / 3, u = f / 3;
    for (std::size_t k = 0; k < na; ++k)
      if (attr[t * na + k] != attr[u * na + k]) {
        ++edges;
        break;
      }
  }
  if (edges)
    res.stats.warnings.push_back(
        "the triangle attributes differ across " + std::to_string(edges) + (edges == 1 ? " edge" : " edges") +
        " that are not segments: without -p the refinement does not keep that line, and triangles near it may "
        "take the other side's attribute (give -p with FILE.poly's segments to keep it)");
}

}  // namespace

void rebuild_mesh(const Plan& plan, RunInput& in, RunResult& res, Phases& phases) {
  drop_midside_nodes(in);  // a 6-node mesh is rebuilt as its corner mesh
  auto t = Clock::now();
  Pslg& nodes = in.pslg;
  if (!plan.mesh_segments) nodes.segments.clear();  // without -p, segments are not used
  RebuildOptions ropt;
  // -ra: per-triangle bounds, set before segments are inserted so they stay
  // with their triangles.
  if (plan.refine.input_area_bounds) ropt.area_bounds = in.triangle_area_bounds;
  ropt.method = plan.method;
  ropt.strict = plan.strict;
  res.mesh = mesh_from_triangles(nodes, in.triangles, in.num_triangle_attributes, in.triangle_attributes, ropt,
                                 &res.inserted);
  res.stats.input_vertices = nodes.points.size();
  res.stats.input_segments = nodes.segments.size();
  phases.add("rebuild mesh", t);
  Mesh& mesh = res.mesh;
  if (!plan.mesh_segments) warn_attribute_boundaries(plan, mesh, res);
  if (plan.mesh_segments) {
    if (res.inserted.inserted) phases.out.push_back({"  of which segment insertion", res.inserted.seconds});
    if (plan.check) {
      // Every segment a chain of constrained edges after insertion
      // (checked before holes are carved).
      t = Clock::now();
      CheckOptions co;
      co.delaunay = false;
      co.convex_hull = false;
      co.pslg = &nodes;
      res.stats.segment_check = check(mesh, co);
      phases.add("check segments", t);
    }
    // Holes (in the mesh: carved; outside it, as in a .poly written with
    // the mesh: nothing to do) and, with -A, regional attributes. Area
    // bounds come from the triangles' own (-ra), as in Triangle.
    t = Clock::now();
    DomainOptions dopt;
    dopt.ignore_holes = plan.domain.ignore_holes;
    dopt.regional_attributes = plan.domain.regional_attributes;
    Pslg seeds;
    seeds.first_index = nodes.first_index;  // warnings number points as the file does
    seeds.holes = nodes.holes;
    seeds.regions = nodes.regions;
    carve_mesh(mesh, seeds, dopt, &res.stats.domain);
    if (res.stats.domain.triangles_removed) finish_vertex_markers(mesh);
    phases.add("holes, regions", t);
    for (std::string& w : domain_warnings(res.stats.domain, mesh.num_triangles(), true, &seeds))
      res.stats.warnings.push_back(std::move(w));
  }
  if (plan.domain.convex_hull) {
    // With -r, -c makes the mesh boundary (holes included) into segments.
    for (HalfEdgeId e = 0; e < mesh.triangle_vertices().size(); ++e)
      if (mesh.twin(e) == kNone && !mesh.is_constrained(e)) mesh.constrain_edge(e, 0);
  }
}

}  // namespace deltamesh::pipeline
