// adapt(mesh, metric=...): adaptation to a metric tensor field (metric.hpp's
// adapt_to_metric through the pipeline), the metric an (n, 3) array of
// m11 m12 m22 per vertex or a function (x, y) -> (m11, m12, m22).
#include <exception>

#include "bindings.hpp"

namespace deltamesh::python {

namespace {

// Leaves adapt_to_metric when the Python function failed (the error is kept
// and raised once the GIL is back).
struct CallbackFailed {};

struct MetricCallback {
  py::object fn;
  std::exception_ptr error;
  std::string bad_value;
  MetricField make() {
    return [this](double x, double y) -> Metric {
      if (error || !bad_value.empty()) throw CallbackFailed{};
      py::gil_scoped_acquire gil;
      try {
        const py::object r = fn(x, y);
        if (!py::isinstance<py::sequence>(r) || py::len(r) != 3) {
          bad_value = "metric(x, y) must return three numbers m11, m12, m22";
          throw CallbackFailed{};
        }
        const py::sequence s = r;
        return {s[0].cast<double>(), s[1].cast<double>(), s[2].cast<double>()};
      } catch (const CallbackFailed&) {
        throw;
      } catch (...) {
        error = std::current_exception();
        throw CallbackFailed{};
      }
    };
  }
};

}  // namespace

py::dict adapt_metric_dict(const py::dict& tri, py::object metric, const std::string& opts, int smooth) {
  Input in = read_input(arrays_from_dict(tri));
  if (!in.has_triangles) throw py::value_error("adapt: the mesh needs 'triangles' (and 'vertices')");
  const CommandLine cl = parse_switches(opts);
  Plan plan = cl.plan;
  if (cl.refine || plan.order == 2 || plan.refine.conforming_delaunay)
    throw py::value_error("adapt: switches r, o2 and D do not apply (the mesh is always rebuilt and adapted)");
  if (smooth < 0) throw py::value_error("adapt: smooth must be >= 0 passes");
  plan.input = InputKind::Adapt;
  plan.mesh_segments = cl.poly || in.has_segments;
  plan.smooth = smooth;
  MetricCallback cb{py::none(), {}, {}};
  if (PyCallable_Check(metric.ptr())) {
    cb.fn = metric;
    in.run.metric = cb.make();
  } else {
    const Doubles d = to_doubles(metric, "metric", 3);
    if (d.rows != in.run.pslg.points.size())
      throw py::value_error("metric: has " + std::to_string(d.rows) + " rows, expected one (m11, m12, m22) per vertex (" +
                            std::to_string(in.run.pslg.points.size()) + ")");
    for (std::size_t i = 0; i < d.rows; ++i) in.run.vertex_metrics.push_back({d.v[3 * i], d.v[3 * i + 1], d.v[3 * i + 2]});
  }
  Pslg seeds;
  seeds.holes = in.run.pslg.holes;
  seeds.regions = in.run.pslg.regions;
  RunResult res;
  bool failed = false;
  {
    py::gil_scoped_release nogil;
    try {
      res = run(plan, std::move(in.run));
    } catch (const CallbackFailed&) {
      failed = true;
    }
  }
  if (cb.error) std::rethrow_exception(cb.error);
  if (failed || !cb.bad_value.empty()) throw py::value_error(cb.bad_value.empty() ? "metric(x, y) failed" : cb.bad_value);
  if (res.check && !res.check->ok()) {
    py::list problems;
    for (const std::string& p : res.check->problems) problems.append(p);
    raise_with(g_exc.check, "-C: " + res.check->summary(), {{"problems", problems}});
    throw py::error_already_set();
  }
  py::dict out = mesh_dict(res, plan, seeds);
  py::dict stats = stats_dict(res);
  const MetricAdaptStats& st = res.metric_adapt;
  py::dict a;
  a["splits"] = st.splits;
  a["collapses"] = st.collapses;
  a["swaps"] = st.swaps;
  a["moves"] = st.moves;
  a["iterations"] = st.iterations;
  a["triangles"] = st.triangles;
  a["seconds"] = st.seconds;
  a["summary"] = st.summary();
  if (res.metric_fit) {
    a["edges_within"] = res.metric_fit->within;  // share of edges with metric length in [1/sqrt 2, sqrt 2]
    a["mean_quality"] = res.metric_fit->mean_quality;
    a["min_quality"] = res.metric_fit->min_quality;
    a["fit"] = res.metric_fit->summary();
  }
  stats["adapt"] = a;
  out["stats"] = stats;
  return out;
}

}  // namespace deltamesh::python
