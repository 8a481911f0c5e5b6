// run(): one pipeline for every front end. Points and PSLGs go through
// triangulate(); meshes (-r, --adapt) are rebuilt (rebuild.cpp), flipped to a
// constrained Delaunay triangulation and refined or adapted; then smoothing,
// -j, -C and -o2, in the command line's order.
#include <algorithm>
#include <cmath>
#include <chrono>
#include <utility>

#include "algo/normalize.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/pipeline.hpp"
#include "deltamesh/second_order.hpp"
#include "pipeline/steps.hpp"
#include "mesh/trace_hooks.hpp"

namespace deltamesh {

bool RefinementPlan::requested() const {
  return quality || max_area || input_area_bounds || steiner_budget || conforming_delaunay || max_area_at ||
         max_edge_at;
}

RefineOptions RefinementPlan::options() const {
  RefineOptions r;
  r.min_angle_deg = quality ? min_angle.value_or(20.0) : 0.0;
  r.max_area = max_area.value_or(-1.0);
  r.use_triangle_area_bounds = input_area_bounds;
  r.max_area_at = max_area_at;
  r.max_edge_at = max_edge_at;
  r.steiner = steiner;
  r.encroachment = encroachment;
  r.order = order;
  r.segment_splitting = no_boundary_steiner == 0   ? SegmentSplitting::All
                        : no_boundary_steiner == 1 ? SegmentSplitting::InteriorOnly
                                                   : SegmentSplitting::None;
  r.conforming_delaunay = conforming_delaunay;
  if (steiner_budget) r.max_steiner = static_cast<std::size_t>(*steiner_budget);
  r.time_limit_seconds = time_limit;
  return r;
}

std::size_t drop_midside_nodes(RunInput& in) {
  if (in.midside.empty()) return 0;
  if (!in.vertex_sizes.empty() || !in.vertex_metrics.empty())
    throw InputError("adaptation to per-vertex sizes needs a 3-node mesh; the triangles given have 6 nodes");
  const std::size_t dropped = drop_midpoint_nodes(in.pslg, in.triangles, in.midside);
  in.midside.clear();
  return dropped;
}

namespace pipeline {

void Phases::add(std::string name, Clock::time_point since) {
  out.push_back({std::move(name), std::chrono::duration<double>(Clock::now() - since).count()});
}

RefineOptions refine_options(const Plan& plan) {
  RefineOptions r = plan.refine.options();
  r.progress = plan.progress;
  r.threads = plan.threads;
  return r;
}

namespace {

// A mesh read with -r or --adapt appears in the trace whole: its vertices,
// then its triangles in one event (the rebuild itself is not traced).
void trace_rebuilt_mesh(TraceObserver& o, Mesh& mesh) {
  mesh.set_trace(&o);
  detail::TraceAccess::phase(o, "read");
  detail::TraceAccess::points(o, 0, mesh.points());
  std::vector<TriId> all(mesh.num_triangle_slots());
  for (TriId t = 0; t < all.size(); ++t) all[t] = t;
  detail::TraceAccess::slots(o, detail::trace_event(TraceKind::Insert, TraceReason::None),
                             mesh.triangle_vertices().data(), all);
}

// Points and PSLGs: triangulate() does the whole job up to markers.
void triangulate_input(const Plan& plan, const RunInput& in, RunResult& res, Phases& phases) {
  const bool segments = plan.input == InputKind::Pslg;
  TriangulateOptions topt;
  topt.use_segments = segments;
  topt.method = plan.method;
  topt.strict = plan.strict;
  topt.domain.fill = plan.domain.fill;
  topt.domain.keep_convex_hull = plan.domain.convex_hull;
  topt.domain.ignore_holes = plan.domain.ignore_holes;
  topt.domain.regional_attributes = plan.domain.regional_attributes && segments;
  topt.domain.regional_area_bounds = plan.refine.input_area_bounds && segments;
  topt.check_segments = plan.check && segments;
  if (plan.refine.requested()) {
    topt.refine = plan.refine.options();
    topt.refine->threads = plan.threads;
  }
  topt.progress = plan.progress;
  topt.trace = plan.trace;
  topt.threads = plan.threads;
  res.mesh = triangulate(in.pslg, topt, &res.stats);
  res.refined = topt.refine.has_value();
  const TriangulateStats& st = res.stats;
  if (segments) {
    phases.out.push_back({std::string("constrained triangulation (") + std::string(to_string(plan.method)) + ")",
                          st.triangulate_seconds});
    phases.out.push_back({"  of which segments", st.cdt.segments_seconds});
    if (topt.check_segments) phases.out.push_back({"check segments", st.check_seconds});
    phases.out.push_back({"domain (holes, regions)", st.domain_seconds});
  } else {
    phases.out.push_back({"Delaunay triangulation", st.triangulate_seconds});
    if (plan.domain.convex_hull) phases.out.push_back({"hull segments", st.domain_seconds});
  }
  if (res.refined) phases.out.push_back({"refine", st.refine_seconds});
  phases.out.push_back({"markers and attributes", st.finish_seconds});
}

// One size per mesh vertex: the input's, and for vertices appended since
// (segment crossings of -r -p) the mean of their neighbours' sizes (the
// mean of all when no neighbour has one).
std::vector<double> vertex_sizes(const Mesh& mesh, const std::vector<double>& given) {
  std::vector<double> sizes = given;
  const std::size_t n = given.size();
  double mean = 0;
  for (double h : given) mean += h / double(std::max<std::size_t>(n, 1));
  for (VertexId v = static_cast<VertexId>(n); v < mesh.num_vertices(); ++v) {
    double sum = 0;
    std::size_t k = 0;
    mesh.for_each_out_edge(v, [&](HalfEdgeId e) {
      if (mesh.dest(e) < n) {
        sum += given[mesh.dest(e)];
        ++k;
      }
      return true;
    });
    sizes.push_back(k ? sum / double(k) : mean);
  }
  return sizes;
}

// One metric per mesh vertex: the input's, and for vertices appended since
// their neighbours' log-Euclidean mean (as vertex_sizes).
std::vector<Metric> vertex_metrics(const Mesh& mesh, const std::vector<Metric>& given) {
  std::vector<Metric> out = given;
  const std::size_t n = given.size();
  std::vector<Metric> near;
  std::vector<double> w;
  for (VertexId v = static_cast<VertexId>(n); v < mesh.num_vertices(); ++v) {
    near.clear();
    mesh.for_each_out_edge(v, [&](HalfEdgeId e) {
      if (mesh.dest(e) < n) near.push_back(given[mesh.dest(e)]);
      return true;
    });
    if (near.empty()) near = given;
    w.assign(near.size(), 1.0 / double(near.size()));
    out.push_back(near.empty() ? Metric{} : log_euclidean_mean(near, w));
  }
  return out;
}

// Adapt to a metric field (split, collapse, swap, smooth in the metric).
void adapt_mesh_to_metric(const Plan& plan, RunInput& in, RunResult& res) {
  Mesh& mesh = res.mesh;
  MetricField field = in.metric;
  if (!field) {
    if (in.vertex_metrics.size() != in.pslg.points.size())
      throw InputError("has " + std::to_string(in.vertex_metrics.size()) + " metrics for " +
                       std::to_string(in.pslg.points.size()) + " vertices");
    field = metric_field_from_vertices(mesh, vertex_metrics(mesh, in.vertex_metrics));
  }
  MetricAdaptOptions mo;
  mo.split_segments = plan.refine.no_boundary_steiner == 0;
  if (plan.smooth >= 0) mo.smooth_passes = plan.smooth;
  res.metric_adapt = adapt_to_metric(mesh, field, mo);
  res.metric_fit = metric_fit(mesh, field);
  res.metric_adapted = true;
}

// Meshes: rebuilt, then adapted, refined or (for smoothing) flipped to a CDT.
void process_mesh(const Plan& plan, RunInput& in, RunResult& res, Phases& phases) {
  rebuild_mesh(plan, in, res, phases);
  res.read_vertices = res.mesh.num_vertices();
  res.read_triangles = res.mesh.num_triangles();
  Mesh& mesh = res.mesh;
  if (plan.trace) trace_rebuilt_mesh(*plan.trace, mesh);
  if (plan.input == InputKind::Adapt && (in.metric || !in.vertex_metrics.empty())) {
    const auto t = Clock::now();
    adapt_mesh_to_metric(plan, in, res);
    finish_vertex_markers(mesh);
    phases.add("adapt to the metric (split, collapse, swap, smooth)", t);
  } else if (plan.input == InputKind::Adapt) {
    // Sizes at the vertices of the mesh as rebuilt, then the CDT flips
    // refinement needs, coarsening and refinement to them.
    const auto t = Clock::now();
    SizeField h = in.size;
    if (!h) {
      if (in.vertex_sizes.size() != in.pslg.points.size())
        throw InputError("has " + std::to_string(in.vertex_sizes.size()) + " sizes for " +
                         std::to_string(in.pslg.points.size()) + " vertices");
      h = size_field_from_vertices(mesh, vertex_sizes(mesh, in.vertex_sizes));
    }
    if (plan.trace) detail::TraceAccess::phase(*plan.trace, "flips");
    res.delaunay_flips = make_constrained_delaunay(mesh);
    if (plan.trace) detail::TraceAccess::phase(*plan.trace, "adapt");
    AdaptOptions aopt;
    aopt.refine = refine_options(plan);
    if (plan.smooth >= 0) aopt.smooth_passes = plan.smooth;
    res.adapt = adapt(mesh, h, aopt);
    res.stats.refine = res.adapt.refine;
    finish_vertex_markers(mesh);
    res.refined = res.adapted = true;
    phases.add("adapt (coarsen + refine)", t);
  } else if (plan.refine.requested()) {
    // Refinement needs a constrained Delaunay triangulation; a mesh from
    // another tool need not be one (on a CDT this flips nothing).
    auto t = Clock::now();
    if (plan.trace) detail::TraceAccess::phase(*plan.trace, "flips");
    res.delaunay_flips = make_constrained_delaunay(mesh);
    phases.add("constrained Delaunay flips", t);
    t = Clock::now();
    if (plan.trace) detail::TraceAccess::phase(*plan.trace, "refine");
    res.stats.refine = refine(mesh, refine_options(plan));
    finish_vertex_markers(mesh);
    res.refined = true;
    phases.add("refine", t);
  } else if (plan.smooth > 0) {
    // Smoothing keeps a constrained Delaunay triangulation: start from one.
    const auto t = Clock::now();
    if (plan.trace) detail::TraceAccess::phase(*plan.trace, "flips");
    res.delaunay_flips = make_constrained_delaunay(mesh);
    phases.add("constrained Delaunay flips", t);
  }
}

// --smooth=N after meshing or refinement (Adapt smooths in adapt()).
// Vertices below `protect` stay. After a refinement, what smoothing left
// outside its bounds is refined again within what is left of its budgets:
// a flip may lengthen an edge, and a move keeps its star's smallest angle,
// which may already be below -q's bound (seldom: a few points).
void smooth_mesh(const Plan& plan, std::size_t protect, RunResult& res, Phases& phases) {
  if (plan.smooth <= 0 || res.mesh.num_triangles() == 0) return;
  const auto t = Clock::now();
  if (plan.trace) detail::TraceAccess::phase(*plan.trace, "smooth");
  SmoothOptions so;
  so.passes = plan.smooth;
  so.protect_first = protect;
  if (res.refined) {
    const RefineOptions ropt = refine_options(plan);
    so.max_area = ropt.max_area;
    res.smooth = smooth_refined(res.mesh, so, ropt, res.stats.refine, &res.resplit);
    if (res.resplit) finish_vertex_markers(res.mesh);
  } else {
    res.smooth = smooth(res.mesh, so);
  }
  res.smoothed = true;
  phases.add("smooth", t);
}

// -C: the validator, with what the input promises. A point set's Delaunay
// triangulation covers its convex hull; a carved domain need not be
// convex; a mesh read with -r need not be Delaunay unless refined (flipped
// to a CDT first) or smoothed.
void check_result(const Plan& plan, RunResult& res, Phases& phases) {
  const auto t = Clock::now();
  CheckOptions copt;
  copt.convex_hull = !plan.uses_segments() && !plan.mesh_input() && !res.refined;  // split hull edges bend
  copt.delaunay = plan.mesh_input() ? res.refined || res.smoothed : plan.method != CdtMethod::Ct || res.smoothed;
  CheckReport report = check(res.mesh, copt);
  // Every segment was a chain of constrained edges before carving (checked
  // then), and with -p carving left a boundary made of segments only.
  for (const std::string& p : res.stats.segment_check.problems) report.problems.push_back("before carving: " + p);
  if (plan.input == InputKind::Pslg)
    for (const std::string& p : check_domain_boundary(res.mesh)) report.problems.push_back(p);
  res.check = std::move(report);
  phases.add("check", t);
}

// The input and every size in the plan in the frame (algo/normalize.hpp):
// the run meshes there and restore_result maps back.
void normalize_input(const detail::Frame& f, Plan& plan, RunInput& in) {
  detail::scale_vertices(f, in.pslg.points, plan.threads);
  detail::scale_seeds(f, in.pslg.holes);
  std::vector<Point> seeds;
  for (const RegionSeed& r : in.pslg.regions) seeds.push_back(r.p);
  detail::scale_seeds(f, seeds);
  for (std::size_t i = 0; i < seeds.size(); ++i) {
    in.pslg.regions[i].p = seeds[i];
    in.pslg.regions[i].max_area = f.area_to(in.pslg.regions[i].max_area);
  }
  for (double& a : in.triangle_area_bounds) a = f.area_to(a);
  for (double& h : in.vertex_sizes) h = f.length_to(h);
  in.size = f.length_field_to(std::move(in.size));
  // A metric measures lengths: in a frame 2^k larger, its entries are 2^-2k
  // times the user's (exact but for overflow, like the sizes).
  const auto metric_to = [k = f.k](Metric m) {
    return Metric{std::ldexp(m.m11, -2 * k), std::ldexp(m.m12, -2 * k), std::ldexp(m.m22, -2 * k)};
  };
  for (Metric& m : in.vertex_metrics) m = metric_to(m);
  if (in.metric && !f.identity())
    in.metric = [user = std::move(in.metric), metric_to, k = f.k](double x, double y) {
      return metric_to(user(std::ldexp(x, -k), std::ldexp(y, -k)));
    };
  RefinementPlan& r = plan.refine;
  if (r.max_area) r.max_area = f.area_to(*r.max_area);
  r.max_area_at = f.area_field_to(std::move(r.max_area_at));
  r.max_edge_at = f.length_field_to(std::move(r.max_edge_at));
}

// The hole and region points as the user gave them, for messages.
Pslg seeds_of(const Pslg& pslg) {
  Pslg seeds;
  seeds.holes = pslg.holes;
  seeds.regions = pslg.regions;
  seeds.first_index = pslg.first_index;
  return seeds;
}

// The domain's warnings name ignored hole and region points by their
// coordinates: those of the user's input, not of the frame.
void rename_seed_warnings(const Pslg& user, const Pslg& framed, bool existing_mesh, RunResult& res) {
  const DomainStats& d = res.stats.domain;
  if (!d.holes_ignored && !d.regions_ignored) return;
  const std::vector<std::string> from = domain_warnings(d, 1, existing_mesh, &framed);
  const std::vector<std::string> to = domain_warnings(d, 1, existing_mesh, &user);
  for (std::string& w : res.stats.warnings)
    for (std::size_t i = 0; i < from.size() && i < to.size(); ++i)
      if (w == from[i]) w = to[i];
}

void restore_result(const detail::Frame& f, RunResult& res) {
  detail::restore(f, res.mesh);
  detail::restore(f, res.stats.refine);
  detail::restore(f, res.adapt.refine);
}

}  // namespace
}  // namespace pipeline

RunResult run(const Plan& user_plan, RunInput input) {
  using namespace pipeline;
  const auto t0 = Clock::now();
  // Meshed in a power-of-two frame where the exact predicates and every
  // measure are safe, whatever the input's scale (docs/robustness.md).
  const detail::Frame frame = detail::frame_for(input.pslg.points, user_plan.threads);
  Plan plan = user_plan;
  const Pslg user_seeds = seeds_of(input.pslg);
  normalize_input(frame, plan, input);
  const Pslg framed_seeds = seeds_of(input.pslg);
  detail::TraceFrameScope in_frame(plan.trace, frame.k);
  RunResult res;
  Phases phases{res.phases};
  const std::vector<std::string> unused = unused_settings(plan);
  if (plan.mesh_input()) {
    process_mesh(plan, input, res, phases);
    if (plan.input != InputKind::Adapt) smooth_mesh(plan, 0, res, phases);
  } else {
    triangulate_input(plan, input, res, phases);
    smooth_mesh(plan, input.pslg.points.size(), res, phases);  // the input's vertices stay
  }
  // The steps reset the stats: the no-effect notes go first now.
  res.stats.warnings.insert(res.stats.warnings.begin(), unused.begin(), unused.end());
  if (plan.jettison) res.mesh.remove_unused_vertices();
  if (plan.trace) {
    detail::TraceAccess::resync(*plan.trace, res.mesh.triangle_vertices(), "run");
    TraceEvent end;
    end.kind = TraceKind::End;
    end.count = res.mesh.num_vertices();
    end.edge[0] = static_cast<VertexId>(res.mesh.num_triangles());
    detail::TraceAccess::plain(*plan.trace, end);
    res.mesh.set_trace(nullptr);  // the observer may not outlive the run
    in_frame.end();
  }
  if (plan.check) check_result(plan, res, phases);
  // After -j and -C, which see the linear mesh.
  if (plan.order == 2) res.midside = add_midpoint_nodes(res.mesh);
  restore_result(frame, res);
  rename_seed_warnings(user_seeds, framed_seeds, plan.mesh_input(), res);
  res.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return res;
}

}  // namespace deltamesh
