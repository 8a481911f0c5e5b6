// -r and --adapt: an existing mesh rebuilt from its triangle list, with new
// segments inserted and holes carved (Triangle's -r -p).
#include "deltamesh/second_order.hpp"
#include "pipeline/steps.hpp"

namespace deltamesh::pipeline {

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
    seeds.holes = nodes.holes;
    seeds.regions = nodes.regions;
    carve_mesh(mesh, seeds, dopt, &res.stats.domain);
    if (res.stats.domain.triangles_removed) finish_vertex_markers(mesh);
    phases.add("holes, regions", t);
    for (std::string& w : domain_warnings(res.stats.domain, mesh.num_triangles(), true))
      res.stats.warnings.push_back(std::move(w));
  }
  if (plan.domain.convex_hull) {
    // With -r, -c makes the mesh boundary (holes included) into segments.
    for (HalfEdgeId e = 0; e < mesh.triangle_vertices().size(); ++e)
      if (mesh.twin(e) == kNone && !mesh.is_constrained(e)) mesh.constrain_edge(e, 0);
  }
}

}  // namespace deltamesh::pipeline
