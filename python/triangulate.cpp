// triangulate() and adapt(): arrays in, the library's pipeline (run()) with
// the GIL released, a dict out; warnings as Python warnings.
#include <cmath>
#include <exception>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "bindings.hpp"

namespace deltamesh::python {

namespace {

// A Python size function called from the refining thread: it takes the GIL
// for each call; the first exception (or a non-finite value) stops the
// calls and is re-raised when refinement returns.
struct SizeCallback {
  py::object fn;
  const char* name = "";
  std::exception_ptr error;
  std::string bad_value;
  std::function<double(double, double)> make() {
    if (!given(fn)) return {};
    return [this](double x, double y) -> double {
      if (error || !bad_value.empty()) return -1.0;
      py::gil_scoped_acquire gil;
      try {
        const py::object r = fn(x, y);
        const double v = PyFloat_AsDouble(r.ptr());  // TypeError for a non-number
        if (v == -1.0 && PyErr_Occurred()) throw py::error_already_set();
        if (!std::isfinite(v)) {
          bad_value = std::string(name) + " returned " + number_text(v) + " at (" + number_text(x) + ", " +
                      number_text(y) + "); it must return a finite area or length (<= 0: no bound)";
          return -1.0;
        }
        return v;
      } catch (...) {
        error = std::current_exception();
        return -1.0;
      }
    };
  }
  void rethrow() const {
    if (error) std::rethrow_exception(error);
    if (!bad_value.empty()) throw py::value_error(bad_value);
  }
};


void warn(const std::string& message) {
  if (PyErr_WarnEx(PyExc_UserWarning, message.c_str(), 2) < 0) throw py::error_already_set();
}

// -C found problems: deltamesh.CheckError with the list.
void raise_check_problems(const RunResult& res) {
  if (!res.check || res.check->ok()) return;
  py::list problems;
  for (const std::string& p : res.check->problems) problems.append(p);
  raise_with(g_exc.check, "-C: " + res.check->summary(), {{"problems", problems}});
  throw py::error_already_set();
}

// Runs the pipeline without the GIL (size functions take it per call).
RunResult run_released(const Plan& plan, Input& in) {
  py::gil_scoped_release nogil;
  return run(plan, std::move(in.run));
}

// trace=PATH (or '--trace PATH' in the switches): the run's steps as JSON
// Lines (docs/trace.md), the file written whole or not at all.
std::string trace_path_of(const py::object& trace, const std::optional<std::string>& from_switches) {
  if (given(trace)) return py::str(trace).cast<std::string>();
  return from_switches.value_or("");
}

py::object collinear_result(const Input& in, const Plan& plan, const OutputSwitches& sw, bool want_stats) {
  const Pslg& g = in.run.pslg;
  py::dict out;
  if (!sw.no_node) {
    std::vector<double> xy;
    for (const Point& q : g.points) xy.insert(xy.end(), {q.x, q.y});
    out["vertices"] = array_2d(xy, 2);
    if (plan.markers) {
      std::vector<std::int32_t> m(g.points.size(), 0);
      for (std::size_t i = 0; i < std::min(m.size(), g.point_markers.size()); ++i) m[i] = g.point_markers[i];
      out["vertex_markers"] = array_2d(m, 1);
    }
    if (g.num_point_attributes) out["vertex_attributes"] = array_2d(g.point_attributes, g.num_point_attributes);
  }
  const std::string why = "all " + std::to_string(g.points.size()) + " points are collinear: no triangles";
  if (!plan.quiet) warn("deltamesh: " + why);
  if (!want_stats) return out;
  py::dict st;
  st["input_vertices"] = g.points.size();
  st["vertices"] = g.points.size();
  st["triangles"] = 0;
  st["complete"] = true;
  st["refined"] = false;
  st["warnings"] = py::make_tuple(why);
  return py::make_tuple(out, st);
}

py::object run_plan(Input in, Plan plan, py::object max_area_fn, py::object max_edge_fn, const OutputSwitches& sw,
                    bool want_stats, const std::string& trace_path = "") {
  SizeCallback area{std::move(max_area_fn), "max_area_fn", {}, {}};
  SizeCallback edge{std::move(max_edge_fn), "max_edge_fn", {}, {}};
  if (plan.mesh_input() && !in.has_triangles)
    throw py::value_error("switch -r refines a mesh: the input needs 'triangles' (and 'vertices')");
  if (plan.mesh_input() && plan.refine.input_area_bounds && in.run.triangle_area_bounds.empty())
    throw py::value_error(
        "switches -r with -a and no number read per-triangle bounds: the input needs 'triangle_max_area'");
  if (!plan.mesh_input() && all_collinear(in.run.pslg.points)) return collinear_result(in, plan, sw, want_stats);
  plan.refine.max_area_at = area.make();
  plan.refine.max_edge_at = edge.make();
  Pslg seeds;  // segments (their order), holes and regions, written back with 'p'
  seeds.segments = in.run.pslg.segments;
  seeds.holes = in.run.pslg.holes;
  seeds.regions = in.run.pslg.regions;
  std::unique_ptr<TraceFile> trace;
  if (!trace_path.empty()) {
    trace = std::make_unique<TraceFile>(trace_path);
    plan.trace = &trace->observer();
  }
  const RunResult res = run_released(plan, in);
  area.rethrow();
  edge.rethrow();
  if (trace) trace->commit();
  raise_check_problems(res);
  py::dict out = mesh_dict(res, plan, seeds, sw);
  if (!plan.quiet) {
    for (const std::string& w : res.warnings()) warn("deltamesh: " + w);
    if (!res.complete())
      warn("deltamesh: refinement stopped before the requested quality: " + res.stats.refine.summary());
  }
  if (plan.verbose) {
    py::print("deltamesh:", res.mesh.num_vertices(), "vertices,", res.mesh.num_triangles(), "triangles in",
              res.seconds * 1e3, "ms", py::arg("file") = py::module_::import("sys").attr("stderr"));
    if (res.refined)
      py::print("deltamesh: refine:", res.stats.refine.summary(),
                py::arg("file") = py::module_::import("sys").attr("stderr"));
  }
  if (want_stats) return py::make_tuple(out, stats_dict(res));
  return out;
}

}  // namespace

void apply_threads(Plan& plan, const py::object& threads) {
  if (threads.is_none()) return;
  if (!py::isinstance<py::int_>(threads) || py::isinstance<py::bool_>(threads))
    throw py::type_error("threads: an int (0: every hardware thread, 1: sequential)");
  const long long n = threads.cast<long long>();
  if (n < 0 || n > 4096) throw py::value_error("threads: " + std::to_string(n) + ": a thread count from 0 to 4096");
  plan.threads = static_cast<unsigned>(n);
}

py::object triangulate_dict(const py::dict& tri, const std::string& opts, py::object max_area_fn,
                            py::object max_edge_fn, bool stats, py::object trace, py::object threads) {
  CommandLine cl = parse_switches(opts);
  apply_threads(cl.plan, threads);
  OutputSwitches sw;
  sw.no_node = cl.no_node;
  sw.no_ele = cl.no_ele;
  sw.no_poly = cl.no_poly;
  sw.voronoi = cl.voronoi;
  return run_plan(read_input(arrays_from_dict(tri)), cl.plan, std::move(max_area_fn), std::move(max_edge_fn), sw,
                  stats, trace_path_of(trace, cl.trace_path));
}

// adapt(mesh, size, opts): the mesh rebuilt as for 'r' (with 'p' when it has
// segments), then coarsened and refined to the size field (and smoothed).
// Per-vertex sizes: vertices that inserting the segments adds take the mean
// of their neighbours' sizes, as with the command line's --adapt.
py::dict adapt_dict(const py::dict& tri, py::object size, const std::string& opts, int smooth, py::object metric) {
  if (given(metric)) {
    if (given(size)) throw py::value_error("adapt: give a size or a metric, not both");
    return adapt_metric_dict(tri, metric, opts, smooth);
  }
  if (!given(size)) throw py::value_error("adapt: needs a size (or metric=...)");
  Input in = read_input(arrays_from_dict(tri));
  if (!in.has_triangles) throw py::value_error("adapt: the mesh needs 'triangles' (and 'vertices')");
  const CommandLine cl = parse_switches(opts);
  Plan plan = cl.plan;
  if (cl.refine || plan.order == 2 || plan.refine.conforming_delaunay)
    throw py::value_error("adapt: switches r, o2 and D do not apply (the mesh is always rebuilt and refined)");
  if (smooth < 0) throw py::value_error("adapt: smooth must be >= 0 passes");
  plan.input = InputKind::Adapt;
  plan.mesh_segments = cl.poly || in.has_segments;
  plan.smooth = smooth;
  // The size field: a function of (x, y), or one size per given vertex.
  SizeCallback fn{py::none(), "size", {}, {}};
  if (PyCallable_Check(size.ptr())) {
    fn.fn = size;
    in.run.size = fn.make();
  } else {
    const Doubles d = to_doubles(size, "size", 1);
    if (d.rows != in.run.pslg.points.size())
      throw py::value_error("size: has " + std::to_string(d.rows) + " values, expected one per vertex (" +
                            std::to_string(in.run.pslg.points.size()) + ")");
    in.run.vertex_sizes = d.v;
  }
  Pslg seeds;
  seeds.holes = in.run.pslg.holes;
  seeds.regions = in.run.pslg.regions;
  const RunResult res = run_released(plan, in);
  fn.rethrow();
  raise_check_problems(res);
  py::dict out = mesh_dict(res, plan, seeds);
  py::dict stats = stats_dict(res);
  const AdaptStats& st = res.adapt;
  py::dict a;
  a["removed"] = st.removed;
  a["inserted"] = st.inserted;
  a["smoothed"] = st.smooth.moved;
  a["resplit"] = st.resplit;
  a["triangles"] = st.triangles;
  a["complete"] = st.complete;
  a["seconds"] = st.seconds;
  a["summary"] = st.summary();
  stats["adapt"] = a;
  out["stats"] = stats;
  if (!plan.quiet && !st.complete)
    warn("deltamesh: adaptation stopped before the requested quality: " + st.refine.summary());
  return out;
}

py::object triangulate_kw(py::object vertices, py::object segments, py::object holes, py::object regions,
                        py::object vertex_markers, py::object vertex_attributes, py::object segment_markers,
                        py::object triangles, py::object triangle_attributes, py::object triangle_max_area,
                        py::object min_angle, py::object max_area, bool regional_area, py::object max_steiner,
                        py::object max_area_fn, py::object max_edge_fn, bool conforming_delaunay,
                        const std::string& segment_splitting, bool convex_hull, bool regional_attributes,
                        bool ignore_holes, const std::string& fill, const std::string& cdt, bool strict,
                        const std::string& steiner, const std::string& encroachment, const std::string& order,
                        py::object time_limit, bool jettison, bool second_order, bool edges, bool neighbors, bool check,
                        bool markers, bool quiet, bool stats, py::object trace, py::object threads) {
  if (py::isinstance<py::dict>(vertices))
    throw py::value_error("vertices: got a dict; for Triangle's form call triangulate(dict, 'switches')");
  Keywords k;
  k.min_angle = min_angle;
  k.max_area = max_area;
  k.max_steiner = max_steiner;
  k.time_limit = time_limit;
  k.segments = given(segments);
  k.triangles = given(triangles);
  k.regional_area = regional_area;
  k.conforming_delaunay = conforming_delaunay;
  k.segment_splitting = segment_splitting;
  k.fill = fill;
  k.cdt = cdt;
  k.steiner = steiner;
  k.encroachment = encroachment;
  k.order = order;
  k.convex_hull = convex_hull;
  k.regional_attributes = regional_attributes;
  k.ignore_holes = ignore_holes;
  k.strict = strict;
  k.jettison = jettison;
  k.second_order = second_order;
  k.edges = edges;
  k.neighbors = neighbors;
  k.check = check;
  k.markers = markers;
  k.quiet = quiet;
  Plan plan = keyword_plan(k);
  apply_threads(plan, threads);
  const InputArrays a{vertices, vertex_markers, vertex_attributes,   segments,         segment_markers, holes,
                      regions,  triangles,      triangle_attributes, triangle_max_area};
  return run_plan(read_input(a), plan, std::move(max_area_fn), std::move(max_edge_fn), {}, stats,
                  trace_path_of(trace, {}));
}

}  // namespace deltamesh::python
