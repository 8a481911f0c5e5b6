// The anisotropic step of fuzz_adapt: adapt_to_metric() to a metric field
// drawn from the bytes: a constant tensor, rotating directions, a layer
// (aspect ratios up to 1:10^4), per-vertex tensors over the mesh (some
// possibly not metrics, or the metric of a tanh front through
// recover_hessian, metric_from_hessian and gradate_metric), or a field
// that is not a metric somewhere.
//
// A bug is: an exception other than InputError; an InputError when every
// tensor given was a metric, or none when the field is never one (a
// metric_field_from_vertices with a bad tensor must throw); after the step,
// a mesh the validator rejects (no Delaunay property asked; the input
// segments as chains when given); the domain's area or a marker's
// constrained length changed; protected vertices moved or renumbered; more
// vertices than the budget; stats that do not match the mesh.
#pragma once
#include <fuzzer/FuzzedDataProvider.h>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "deltamesh/errors.hpp"
#include "deltamesh/metric.hpp"
#include "deltamesh/validate.hpp"
#include "fuzz_util.hpp"

namespace deltamesh::fuzz {

struct MetricShape {
  double area = 0, scale = 0;
  std::map<int, double> length;  // constrained length per marker
  // Per marker, how much longer its edges can be than the straight
  // segments they follow when each vertex may lie `off` away from them:
  // an edge of length l whose ends are off the line by up to `off` each is
  // at most (2 off)^2 / l longer than its projection (sqrt(l^2 + t^2) - l <= t^2 / l).
  std::map<int, double> slack;
};

inline MetricShape metric_shape(const Mesh& m, double off = 0) {
  MetricShape s;
  for (TriId t = 0; t < m.num_triangle_slots(); ++t) {
    if (!m.is_real(t)) continue;
    const auto v = m.triangle(t);
    const Point &a = m.point(v[0]), &b = m.point(v[1]), &c = m.point(v[2]);
    s.area += 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
    s.scale += 0.5 * (std::fabs((b.x - a.x) * (c.y - a.y)) + std::fabs((b.y - a.y) * (c.x - a.x)));
    for (int i = 0; i < 3; ++i) {
      const HalfEdgeId e = 3 * t + i;
      if (!m.is_constrained(e) && m.twin(e) != kNone) continue;
      if (m.twin(e) != kNone && m.twin(e) < e) continue;
      const Point &p = m.point(m.origin(e)), &q = m.point(m.dest(e));
      const double l = std::hypot(p.x - q.x, p.y - q.y);
      s.length[m.edge_marker(e)] += l;
      if (l > 0) s.slack[m.edge_marker(e)] += 4 * off * off / l;
    }
  }
  return s;
}

// Metrics of a tanh front across the mesh (width and direction from the
// bytes) through the pipeline of bench_aniso: recover_hessian,
// metric_from_hessian (to a complexity or a tolerance), gradate_metric.
// Each must take the mesh as it is (any shape, stretched stars, vertices
// in no triangle) and give a metric at every used vertex. False when the
// sizes would leave the range where tensors are finite (not this test).
inline bool hessian_metrics(FuzzedDataProvider& in, const Mesh& mesh, double lox, double loy, double diag,
                            double angle, double aspect, std::vector<Metric>& m) {
  const double width = diag * std::ldexp(1.0, -in.ConsumeIntegralInRange<int>(0, 12));
  const double c = std::cos(angle), s = std::sin(angle);
  MetricScaling sc;
  sc.h_max = diag;
  sc.h_min = diag * 1e-6;
  sc.max_aspect = aspect;
  if (!(1 / (sc.h_max * sc.h_max) > 1e-250) || !(1 / (sc.h_min * sc.h_min) < 1e250)) return false;
  if (in.ConsumeBool())
    sc.complexity = in.ConsumeIntegralInRange<int>(1, 2000);
  else
    sc.tolerance = std::ldexp(1.0, -in.ConsumeIntegralInRange<int>(1, 20));
  sc.p = in.ConsumeIntegralInRange<int>(0, 3);
  const double beta = 1 + in.ConsumeIntegralInRange<int>(1, 40) / 10.0;
  std::vector<double> u(mesh.num_vertices());
  for (VertexId v = 0; v < mesh.num_vertices(); ++v) {
    const Point& p = mesh.point(v);
    u[v] = std::tanh((c * (p.x - lox) + s * (p.y - loy)) / width - 0.5 * diag / width);
  }
  try {
    const std::vector<Metric> h = recover_hessian(mesh, u);
    for (const Metric& x : h)
      DELTAMESH_FUZZ_CHECK(std::isfinite(x.m11) && std::isfinite(x.m12) && std::isfinite(x.m22),
                           "recover_hessian gave a non-finite Hessian");
    m = metric_from_hessian(mesh, h, sc);
    gradate_metric(mesh, m, beta);
  } catch (const InputError& e) {
    fail(std::string("the Hessian metric pipeline refused a mesh: ") + e.what());
  } catch (...) {
    unexpected_exception("the Hessian metric pipeline");
  }
  for (VertexId v = 0; v < mesh.num_vertices(); ++v)
    if (mesh.out_edge(v) != kNone)
      DELTAMESH_FUZZ_CHECK(is_metric(m[v]), "the Hessian metric pipeline gave vertex " + std::to_string(v) +
                                                " a tensor that is not a metric: " + metric_problem(m[v]));
  return true;
}

// Runs one anisotropic adaptation; protect: ids below it must stay put.
inline void metric_step(FuzzedDataProvider& in, Mesh& mesh, const Pslg* input, std::size_t protect, bool verbose) {
  if (mesh.num_triangles() == 0) return;
  double lox = INFINITY, hix = -INFINITY, loy = INFINITY, hiy = -INFINITY;
  for (const Point& p : mesh.points())
    lox = std::min(lox, p.x), hix = std::max(hix, p.x), loy = std::min(loy, p.y), hiy = std::max(hiy, p.y);
  const double diag = std::hypot(hix - lox, hiy - loy);
  if (!(diag > 0) || !std::isfinite(diag)) return;
  const int kind = in.ConsumeIntegralInRange<int>(0, 5);
  const double h_long = diag * std::ldexp(1.0, -in.ConsumeIntegralInRange<int>(1, 5));
  const double aspect = std::pow(10.0, in.ConsumeIntegralInRange<int>(0, 4));  // up to 1:10^4
  const double angle = in.ConsumeFloatingPointInRange<double>(0, M_PI);
  const double turn = in.ConsumeFloatingPointInRange<double>(-20, 20) / diag;  // rotating directions
  const double cx = lox + in.ConsumeProbability<double>() * (hix - lox);
  // Sizes whose tensors over- or underflow are no metrics: not this test.
  const double l_small = 1 / (h_long * h_long), l_big = l_small * aspect * aspect;
  if (!(l_small > 1e-250) || !(l_big < 1e250)) return;
  const auto tensor = [&](double h1, double h2, double a) {
    return from_eigen(1 / (h1 * h1), 1 / (h2 * h2), std::cos(a), std::sin(a));
  };
  MetricField field;
  bool all_bad = false, some_bad = false;
  std::string what = "metric kind " + std::to_string(kind);
  try {
    switch (kind) {
      case 0:  // constant
        field = [=](double, double) { return tensor(h_long, h_long / aspect, angle); };
        break;
      case 1:  // rotating directions
        field = [=](double x, double y) { return tensor(h_long, h_long / aspect, angle + turn * (x + 0.5 * y)); };
        break;
      case 2:  // a layer along x = cx, thin across it
        field = [=](double x, double) {
          const double d = std::fabs(x - cx) / diag;
          return tensor(std::min(h_long, h_long / aspect + d * h_long), h_long, 0.0);
        };
        break;
      case 3: {  // per-vertex tensors, some maybe not metrics
        std::vector<Metric> m(mesh.num_vertices());
        if (in.ConsumeBool()) {  // or from a field: recover_hessian, metric_from_hessian, gradate_metric
          if (!hessian_metrics(in, mesh, lox, loy, diag, angle, aspect, m)) return;
          what += " (from a recovered Hessian)";
        } else {
          for (Metric& t : m) {
            const int pick = in.ConsumeIntegralInRange<int>(0, 15);
            t = tensor(h_long * (1 + pick % 4) / 4, h_long / aspect, angle + 0.3 * pick);
            if (pick == 15) {
              static constexpr Metric kBad[] = {{1, 2, 1}, {-1, 0, 1}, {1, 1, 1}, {NAN, 0, 1}, {1, 0, 1e-30}};
              t = kBad[in.ConsumeIntegralInRange<int>(0, 4)];
              some_bad = true;
            }
          }
        }
        try {
          field = metric_field_from_vertices(mesh, m);
        } catch (const InputError&) {
          DELTAMESH_FUZZ_CHECK(some_bad, what + ": metric_field_from_vertices threw for metrics only");
          return;
        } catch (...) {
          unexpected_exception("metric_field_from_vertices");
        }
        DELTAMESH_FUZZ_CHECK(!some_bad, what + ": metric_field_from_vertices took a tensor that is not a metric");
        break;
      }
      case 4:  // not a metric anywhere
        all_bad = true;
        field = [=](double, double) { return Metric{1, aspect, 1}; };
        if (aspect < 2) field = [](double, double) { return Metric{0, 0, 0}; };
        break;
      default:  // degenerate on one side of x = cx
        some_bad = true;
        field = [=](double x, double) { return x > cx ? Metric{1, 0, 1e-30} : tensor(h_long, h_long / aspect, angle); };
        break;
    }
  } catch (...) {
    unexpected_exception("metric setup");
  }
  const MetricShape before = metric_shape(mesh);
  // Protected vertices keep their coordinates; vertices in no triangle are
  // dropped, so a protected one's new id is the number of used ones before it.
  std::vector<std::uint8_t> used(mesh.num_vertices(), 0);
  for (VertexId v = 0; v < mesh.num_vertices(); ++v) used[v] = mesh.out_edge(v) != kNone;
  std::size_t used_before = 0;
  for (std::uint8_t u : used) used_before += u;
  std::vector<std::pair<VertexId, Point>> kept;
  for (VertexId v = 0, id = 0; v < std::min(protect, mesh.num_vertices()); ++v)
    if (used[v]) kept.push_back({id++, mesh.point(v)});
  for (VertexId v = 0; v < std::min(protect, mesh.num_vertices()); ++v)
    if (!used[v]) input = nullptr;  // the input's ids no longer match
  MetricAdaptOptions o;
  o.protect_first = protect;
  o.iterations = in.ConsumeIntegralInRange<int>(1, 6);
  o.smooth_passes = in.ConsumeIntegralInRange<int>(0, 2);
  o.split_segments = in.ConsumeBool();
  o.max_vertices = 1500;
  if (verbose)
    std::fprintf(stderr, "--- metric kind %d h_long %.17g aspect %g angle %.17g turn %.17g cx %.17g iterations %d smooth %d split_segments %d\n",
                 kind, h_long, aspect, angle, turn, cx, o.iterations, o.smooth_passes, int(o.split_segments));
  MetricAdaptStats st;
  try {
    st = adapt_to_metric(mesh, field, o);
  } catch (const InputError& e) {
    DELTAMESH_FUZZ_CHECK(some_bad || all_bad, what + ": InputError for a metric field: " + e.what());
    DELTAMESH_FUZZ_CHECK(std::string(e.what()).find("metric field at") != std::string::npos,
                         what + ": the error does not name the point: " + e.what());
    return;
  } catch (...) {
    unexpected_exception("adapt_to_metric");
  }
  DELTAMESH_FUZZ_CHECK(!all_bad, what + ": a field that is never a metric was accepted");
  if (verbose) std::fprintf(stderr, "--- %s: %s\n", what.c_str(), st.summary().c_str());
  CheckOptions co;
  co.delaunay = false;
  co.convex_hull = false;
  co.pslg = input;
  const CheckReport rep = check(mesh, co);
  DELTAMESH_FUZZ_CHECK(rep.ok(), what + ": the validator rejects the mesh: " + rep.summary());
  DELTAMESH_FUZZ_CHECK(st.triangles == mesh.num_triangles(), what + ": " + st.summary());
  DELTAMESH_FUZZ_CHECK(mesh.num_vertices() <= std::max(used_before, o.max_vertices), what + ": vertex budget exceeded");
  for (const auto& [id, p] : kept)
    DELTAMESH_FUZZ_CHECK(id < mesh.num_vertices() && mesh.point(id).x == p.x && mesh.point(id).y == p.y,
                         what + ": protected vertex " + std::to_string(id) + " moved or went");
  // Split points on slanted segments are rounded off their line by about
  // half an ulp of the coordinates: the area changes by up to that times
  // the segment's length per split, and the constrained length grows by up
  // to the edges' slack (MetricShape) with two ulps off the line (a split
  // point is the rounded midpoint of two that may be off already). Where
  // segment pieces are a few ulps long, that is what the length can tell.
  const double max_abs = std::max({std::fabs(lox), std::fabs(hix), std::fabs(loy), std::fabs(hiy)});
  const MetricShape after = metric_shape(mesh, 2 * max_abs * 0x1p-52);
  const double tol = 1e-9 * std::max(before.scale, diag * diag) + double(st.splits + 1) * 4.5e-16 * max_abs * diag;
  DELTAMESH_FUZZ_CHECK(std::fabs(after.area - before.area) <= tol, what + ": the domain's area changed");
  for (const auto& [marker, len] : before.length) {
    const auto it = after.length.find(marker);
    const double got = it == after.length.end() ? 0.0 : it->second;
    const double slack = after.slack.count(marker) ? after.slack.at(marker) : 0.0;
    char buf[160];
    std::snprintf(buf, sizeof buf, " changed: %.17g -> %.17g (rounding slack %.3g)", len, got, slack);
    DELTAMESH_FUZZ_CHECK(std::fabs(got - len) <= 1e-9 * std::max(len, diag) + slack,
                         what + ": constrained length of marker " + std::to_string(marker) + buf);
  }
}

}  // namespace deltamesh::fuzz
