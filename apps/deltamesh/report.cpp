// What the command line prints about a run (not with -Q): a summary line per
// step, the files written, and with -V notes, statistics and timings.
#include <algorithm>
#include <cstdio>
#include <fstream>

#include "cli.hpp"

namespace deltamesh::cli {

namespace {

std::string plural(std::size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

}  // namespace

std::string check_summary(const Session& s, const RunResult& r) {
  CheckReport c = *r.check;
  if (!c.segments_checked) c.segments_checked = r.stats.segment_check.segments_checked;
  std::string summary = c.summary();
  if (!c.delaunay_checked)
    summary += s.plan.mesh_input() ? " (a mesh read with -r need not be Delaunay unless refined)"
                                   : " (--cdt=ct need not make it)";
  return summary;
}

QualityReport quality(const Session& s, const RunResult& r) {
  const RefinementPlan& rp = s.plan.refine;
  QualityOptions q;
  q.min_angle_deg = rp.quality ? rp.min_angle.value_or(20.0) : 0.0;
  q.max_area = rp.max_area.value_or(-1.0);
  if (r.refined) q.input_vertices = r.stats.refine.input_vertices;
  QualityReport rep = quality_report(r.mesh, q, r.refined ? &r.stats.refine : nullptr);
  rep.metric = r.metric_fit;
  return rep;
}

void write_stats(const Session& s, const RunResult& r) {
  const std::string json = quality(s, r).json();
  if (s.cl.stats_path.empty()) {
    std::printf("%s\n", json.c_str());
    return;
  }
  std::ofstream f(s.cl.stats_path);
  f << json << "\n";
  f.close();
  if (!f) throw IoError("cannot write '" + s.cl.stats_path + "' (--stats=json:FILE)");
}

void report(const Session& s, const RunResult& r, const std::vector<std::string>& written, std::FILE* out) {
  const CommandLine& cl = s.cl;
  const Plan& plan = s.plan;
  const TriangulateStats& st = r.stats;
  const Mesh& mesh = r.mesh;
  const RefineStats& refine_stats = r.stats.refine;
  std::size_t boundary = 0;
  for (HalfEdgeId e = 0; e < mesh.triangle_vertices().size(); ++e)
    if (mesh.twin(e) == kNone) ++boundary;
  if (plan.verbose > 0) {
    static const char* const notes[][2] = {
        {"i", "incremental insertion: deltamesh inserts incrementally in Hilbert order; the Delaunay triangulation is the same"},
        {"F", "Fortune's sweepline: deltamesh inserts incrementally in Hilbert order; the Delaunay triangulation is the same"},
        {"l", "vertical cuts only: deltamesh does not use divide-and-conquer; no effect"},
        {"X", "no exact arithmetic: deltamesh's predicates are always exact (adaptive); no effect"},
        {"s", "segments forced in by splitting: deltamesh recovers segments in a constrained triangulation; "
              "add -D for a conforming Delaunay mesh"},
    };
    for (char c : cl.compat_notes)
      for (const auto& n : notes)
        if (n[0][0] == c) std::fprintf(out, "Note: -%c: %s\n", c, n[1]);
    if (s.geojson) {
      const GeoJsonInfo& g = s.geojson_info;
      std::fprintf(out, "GeoJSON: %s, %s, %s (%s), %s skipped, %zu unclosed closed, %zu degenerate ignored, "
                  "%s merged, %s kept once, %s (%zu not placed)",
                  plural(g.features, "feature", "features").c_str(), plural(g.polygons, "polygon", "polygons").c_str(),
                  plural(g.rings, "ring", "rings").c_str(), plural(g.holes, "hole", "holes").c_str(),
                  plural(g.skipped_geometries, "other geometry", "other geometries").c_str(), g.unclosed_rings,
                  g.degenerate_rings, plural(g.duplicate_points, "duplicate point", "duplicate points").c_str(),
                  plural(g.duplicate_segments, "shared segment", "shared segments").c_str(),
                  plural(g.seeds, "region seed", "region seeds").c_str(), g.seeds_failed);
      if (!g.categories.empty()) {
        std::fprintf(out, "; categories:");
        for (std::size_t i = 0; i < g.categories.size(); ++i) std::fprintf(out, " %zu=%s", i + 1, g.categories[i].c_str());
      }
      std::fprintf(out, "\n");
    }
  }
  if (plan.mesh_input()) {
    std::fprintf(out, "Mesh read: %zu vertices, %zu triangles", r.read_vertices, r.read_triangles);
    if (plan.mesh_segments) {
      std::fprintf(out, "; %s (%zu already edges, %zu inserted, %s added)",
                  plural(r.inserted.segments, "segment", "segments").c_str(), r.inserted.already_present,
                  r.inserted.inserted, plural(r.inserted.vertices_added, "vertex", "vertices").c_str());
      if (st.domain.holes_used) std::fprintf(out, ", %s carved", plural(st.domain.holes_used, "hole", "holes").c_str());
    }
    std::fprintf(out, "\n");
  } else if (plan.uses_segments()) {
    std::fprintf(out, "Constrained Delaunay triangulation: %s, %s", plural(st.input_vertices, "input vertex", "input vertices").c_str(),
                plural(st.input_segments, "segment", "segments").c_str());
    if (st.input_holes) std::fprintf(out, ", %s", plural(st.input_holes, "hole", "holes").c_str());
    // The triangulation's own count; refinement's line gives the final one.
    std::fprintf(out, " -> %s\n", plural(st.triangulated, "triangle", "triangles").c_str());
  } else {
    std::fprintf(out, "Delaunay triangulation: %s", plural(st.input_vertices, "input vertex", "input vertices").c_str());
    if (st.duplicate_vertices)
      std::fprintf(out, " (%s merged)", plural(st.duplicate_vertices, "duplicate", "duplicates").c_str());
    if (r.refined)
      std::fprintf(out, " -> %s\n", plural(st.triangulated, "triangle", "triangles").c_str());
    else
      std::fprintf(out, ", %s, %s\n", plural(mesh.num_triangles(), "triangle", "triangles").c_str(),
                   plural(boundary, "hull edge", "hull edges").c_str());
  }
  if (r.adapted) std::fprintf(out, "Coarsened: %s\n", r.adapt.coarsen.summary().c_str());
  if (r.refined) {
    std::fprintf(out, "Quality mesh: %s, %s; %s\n", plural(mesh.num_vertices(), "vertex", "vertices").c_str(),
                 plural(mesh.num_triangles(), "triangle", "triangles").c_str(), refine_stats.summary().c_str());
    if (refine_stats.stalled)
      std::fprintf(stderr,
                   "deltamesh: warning: %g° is out of reach: refinement stopped making progress near (%g, %g) "
                   "(radius %g); kept a mesh with smallest angle %g° outside small input angles\n",
                   refine_stats.min_angle_deg, refine_stats.stall_x, refine_stats.stall_y, refine_stats.stall_radius,
                   refine_stats.reached_angle_deg);
    else if (refine_stats.budget_exhausted || refine_stats.time_exhausted)
      std::fprintf(stderr, "deltamesh: warning: refinement stopped by its budget before reaching the requested quality\n");
    else if (!refine_stats.complete)
      std::fprintf(stderr, "deltamesh: warning: bounds not met: %s\n", refine_stats.unmet().c_str());
  }
  if (r.adapted) std::fprintf(out, "Adapted: %s\n", r.adapt.summary().c_str());
  if (r.metric_adapted) std::fprintf(out, "Adapted to the metric: %s\n", r.metric_adapt.summary().c_str());
  if (r.metric_fit) std::fprintf(out, "Metric fit: %s\n", r.metric_fit->summary().c_str());
  if (r.adapted && r.adapt.smooth.passes) std::fprintf(out, "Smoothed: %s\n", r.adapt.smooth.summary().c_str());
  if (r.smoothed) {
    std::fprintf(out, "Smoothed: %s", r.smooth.summary().c_str());
    if (r.resplit) std::fprintf(out, " (then %zu points to restore the refinement bounds)", r.resplit);
    std::fprintf(out, "\n");
  }
  for (const std::string& w : written) std::fprintf(out, "  wrote %s\n", w.c_str());
  if (r.check && r.check->ok()) std::fprintf(out, "Check: %s\n", check_summary(s, r).c_str());
  if (plan.verbose > 0) {
    std::fprintf(out, "Statistics:\n");
    if (!plan.mesh_input()) {
      std::fprintf(out, "  input vertices:            %zu\n", st.input_vertices);
      std::fprintf(out, "  duplicate vertices merged: %zu\n", st.duplicate_vertices);
    }
    if (plan.input == InputKind::Pslg) {
      std::fprintf(out, "  input segments:            %zu\n", st.input_segments);
      std::fprintf(out, "  segments already edges:    %zu (of the Delaunay triangulation)\n",
                  st.cdt.segments_already_present);
      std::fprintf(out, "  segments recovered:        %zu (%zu flips)\n",
                  st.cdt.segments_inserted - std::min(st.cdt.segments_inserted, st.cdt.segments_already_present),
                  st.cdt.flips);
      std::fprintf(out, "  intersections resolved:    %zu (%zu vertices added)\n", st.cdt.intersections,
                  st.steiner_vertices);
      std::fprintf(out, "  vertices on segments:      %zu\n", st.cdt.vertices_on_segments);
      std::fprintf(out, "  overlapping segments:      %zu merged\n", st.cdt.overlaps_merged);
      std::fprintf(out, "  zero-length segments:      %zu ignored\n", st.cdt.zero_length_segments);
      std::fprintf(out, "  holes:                     %zu (%zu used, %zu ignored)%s\n", st.input_holes,
                  st.domain.holes_used, st.domain.holes_ignored, plan.domain.ignore_holes ? " -O: not applied" : "");
      if (plan.domain.regional_attributes)
        std::fprintf(out, "  regions:                   %zu (%zu used, %zu ignored)\n", st.input_regions,
                    st.domain.regions_used, st.domain.regions_ignored);
      else if (plan.refine.input_area_bounds)
        std::fprintf(out, "  regions:                   %zu (area bounds used by -a; attributes not used without -A)\n",
                     st.input_regions);
      else
        std::fprintf(out, "  regions:                   %zu (not used without -A or -a)\n", st.input_regions);
      std::fprintf(out, "  triangles removed:         %zu\n", st.domain.triangles_removed);
      if (plan.domain.convex_hull) std::fprintf(out, "  hull segments added:       %zu\n", st.domain.hull_segments_added);
    }
    if (plan.mesh_segments) {
      std::fprintf(out, "  segments:                  %zu (%zu already edges, %zu inserted, %zu zero-length ignored)\n",
                  r.inserted.segments, r.inserted.already_present, r.inserted.inserted, r.inserted.zero_length);
      std::fprintf(out, "  intersections resolved:    %zu (%zu vertices added)\n", r.inserted.cdt.intersections,
                  r.inserted.vertices_added);
      std::fprintf(out, "  vertices on segments:      %zu\n", r.inserted.cdt.vertices_on_segments);
      std::fprintf(out, "  holes:                     %zu (%zu carved, %zu outside the mesh, %zu ignored)%s\n",
                  s.holes.size(), st.domain.holes_used, st.domain.holes_outside, st.domain.holes_ignored,
                  plan.domain.ignore_holes ? " -O: not applied" : "");
      std::fprintf(out, "  triangles removed:         %zu\n", st.domain.triangles_removed);
    }
    if (plan.mesh_input() && r.refined) std::fprintf(out, "  Delaunay flips:            %zu (before refinement)\n", r.delaunay_flips);
    std::fprintf(out, "  vertices in output:        %zu\n", mesh.num_vertices());
    std::fprintf(out, "  triangles:                 %zu\n", mesh.num_triangles());
    std::fprintf(out, "  edges:                     %zu (%zu on the boundary)\n", (3 * mesh.num_triangles() + boundary) / 2,
                boundary);
    if (!plan.mesh_input()) std::fprintf(out, "  segments in output:        %zu\n", st.segments);
    std::fprintf(out, "  mesh memory:               %.1f MB (%.1f bytes per triangle)\n", mesh.memory_bytes() / 1e6,
                mesh.num_triangles() ? double(mesh.memory_bytes()) / double(mesh.num_triangles()) : 0.0);
    if (r.refined) std::fputs(quality(s, r).text().c_str(), out);
    std::fprintf(out, "Timings:\n");
    for (const PhaseTime& p : s.phases) std::fprintf(out, "  %-38s %9.3f ms\n", p.name.c_str(), p.seconds * 1e3);
  }
}

}  // namespace deltamesh::cli
