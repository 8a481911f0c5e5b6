// Metric tensors: 2x2 symmetric algebra (eigen-decomposition, log-Euclidean
// mean, intersection), metric fields over a background mesh, lengths and
// qualities in a metric, and how well a mesh fits a field.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "algo/adapt/background.hpp"
#include "algo/adapt/metric_math.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/metric.hpp"

namespace deltamesh {

namespace {
constexpr double kMinEigenRatio = 1e-24;  // aspect ratio 1e12
}

Eigen2 eigen(const Metric& m) {
  const double mean = 0.5 * (m.m11 + m.m22), half = 0.5 * (m.m11 - m.m22);
  const double r = std::hypot(half, m.m12);
  // The larger eigenvalue's eigenvector makes angle theta with x.
  const double theta = 0.5 * std::atan2(m.m12, half);
  const double l2 = mean + r;
  // The smaller one from the determinant when mean - r would cancel.
  const double l1 = mean > 0 && l2 > 0 ? (m.m11 * m.m22 - m.m12 * m.m12) / l2 : mean - r;
  return {l1, l2, -std::sin(theta), std::cos(theta)};
}

Metric from_eigen(double l1, double l2, double c, double s) {
  return {l1 * c * c + l2 * s * s, (l1 - l2) * c * s, l1 * s * s + l2 * c * c};
}

bool is_metric(const Metric& m) { return metric_problem(m).empty(); }

std::string metric_problem(const Metric& m) {
  char buf[200];
  if (!std::isfinite(m.m11) || !std::isfinite(m.m12) || !std::isfinite(m.m22)) return "has a non-finite entry";
  const Eigen2 e = eigen(m);
  if (!(e.l1 > 0) || !(m.m11 > 0) || !(m.m11 * m.m22 - m.m12 * m.m12 > 0)) {
    std::snprintf(buf, sizeof buf, "is not positive definite (eigenvalues %.6g and %.6g)", e.l1, e.l2);
    return buf;
  }
  if (!(e.l1 > kMinEigenRatio * e.l2)) {
    std::snprintf(buf, sizeof buf, "is degenerate (eigenvalues %.6g and %.6g: aspect ratio above 1e12)", e.l1, e.l2);
    return buf;
  }
  return "";
}

double metric_length(const Metric& m, double dx, double dy) {
  const double q = m.m11 * dx * dx + 2 * m.m12 * dx * dy + m.m22 * dy * dy;
  return std::sqrt(std::max(q, 0.0));
}

Metric log_euclidean_mean(std::span<const Metric> m, std::span<const double> w) {
  Metric sum{0, 0, 0};
  for (std::size_t i = 0; i < m.size(); ++i) {
    const Metric l = adaptation::log_metric(m[i]);
    sum.m11 += w[i] * l.m11;
    sum.m12 += w[i] * l.m12;
    sum.m22 += w[i] * l.m22;
  }
  return adaptation::exp_sym(sum);
}

Metric intersect(const Metric& a, const Metric& b) {
  // In the coordinates where a is the identity (x = a^-1/2 y), b becomes
  // c = a^-1/2 b a^-1/2; the intersection there keeps, along each
  // eigenvector of c, the larger of 1 and c's eigenvalue.
  const Eigen2 ea = eigen(a);
  const Metric half = from_eigen(std::sqrt(ea.l1), std::sqrt(ea.l2), ea.c, ea.s);
  const Metric inv_half = from_eigen(1 / std::sqrt(ea.l1), 1 / std::sqrt(ea.l2), ea.c, ea.s);
  using adaptation::sandwich;
  const Metric c = sandwich(inv_half, b);
  const Eigen2 ec = eigen(c);
  const Metric d = from_eigen(std::max(1.0, ec.l1), std::max(1.0, ec.l2), ec.c, ec.s);
  return sandwich(half, d);
}

double edge_length_in_metrics(const Point& p, const Point& q, const Metric& mp, const Metric& mq) {
  const double dx = q.x - p.x, dy = q.y - p.y;
  const double la = metric_length(mp, dx, dy), lb = metric_length(mq, dx, dy);
  if (!(la > 0) || !(lb > 0)) return 0.5 * (la + lb);
  const double r = lb / la;
  if (std::fabs(r - 1) < 1e-6) return 0.5 * (la + lb);
  return (lb - la) / std::log(r);
}

double metric_quality(const Point& a, const Point& b, const Point& c, const Metric& m) {
  const double area = 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
  const double det = m.m11 * m.m22 - m.m12 * m.m12;
  const double l2 = std::pow(metric_length(m, b.x - a.x, b.y - a.y), 2) +
                    std::pow(metric_length(m, c.x - b.x, c.y - b.y), 2) +
                    std::pow(metric_length(m, a.x - c.x, a.y - c.y), 2);
  if (!(l2 > 0)) return 0;
  return 4 * std::sqrt(3.0) * area * std::sqrt(std::max(det, 0.0)) / l2;
}

namespace {

// Metrics at the vertices of a copy of a background mesh, kept as their
// logarithms (one eigen-decomposition per query).
class BackgroundMetric {
 public:
  BackgroundMetric(const Mesh& bg, std::span<const Metric> metrics) : bg_(bg) {
    if (metrics.size() != bg.num_vertices())
      throw InputError(std::to_string(metrics.size()) + " metrics for a mesh of " +
                       std::to_string(bg.num_vertices()) + " vertices");
    logs_.reserve(metrics.size());
    for (std::size_t i = 0; i < metrics.size(); ++i) {
      const std::string why = metric_problem(metrics[i]);
      if (!why.empty()) throw InputError("the metric tensor of vertex " + std::to_string(i) + " " + why, i);
      logs_.push_back(adaptation::log_metric(metrics[i]));
    }
  }

  Metric operator()(double x, double y) const {
    const adaptation::Weights w = bg_.weights({x, y});
    if (w.n == 0) return {};
    Metric sum{0, 0, 0};
    for (int i = 0; i < w.n; ++i) {
      const Metric& l = logs_[w.v[i]];
      sum.m11 += w.w[i] * l.m11;
      sum.m12 += w.w[i] * l.m12;
      sum.m22 += w.w[i] * l.m22;
    }
    return adaptation::exp_sym(sum);
  }

 private:
  adaptation::BackgroundMesh bg_;
  std::vector<Metric> logs_;
};

}  // namespace

MetricField metric_field_from_vertices(const Mesh& background, std::span<const Metric> metrics) {
  auto field = std::make_shared<BackgroundMetric>(background, metrics);
  return [field](double x, double y) { return (*field)(x, y); };
}

std::string MetricFit::summary() const {
  char buf[300];
  std::snprintf(buf, sizeof buf,
                "%zu edges, %.1f%% with metric length in [1/sqrt 2, sqrt 2] (min %.3g, mean %.3g, max %.3g); "
                "anisotropic quality min %.3f, mean %.3f",
                edges, 100 * within, min_length, mean_length, max_length, min_quality, mean_quality);
  return buf;
}

MetricFit metric_fit(const Mesh& mesh, const MetricField& field) {
  MetricFit f;
  const std::size_t n = mesh.num_vertices();
  std::vector<Metric> m(n), lg(n);
  std::vector<std::uint8_t> known(n, 0);
  const auto at = [&](VertexId v) -> const Metric& {
    if (!known[v]) {
      const Point& p = mesh.point(v);
      m[v] = field(p.x, p.y);
      const std::string why = metric_problem(m[v]);
      if (!why.empty())
        throw InputError("the metric field at (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ") " + why);
      lg[v] = adaptation::log_metric(m[v]);
      known[v] = 1;
    }
    return m[v];
  };
  f.min_length = INFINITY;
  f.min_quality = INFINITY;
  double sum_len = 0, sum_q = 0;
  std::size_t within = 0, tris = 0;
  for (TriId t = 0; t < mesh.num_triangle_slots(); ++t) {
    if (!mesh.is_real(t)) continue;
    const auto tv = mesh.triangle(t);
    for (int i = 0; i < 3; ++i) {
      const HalfEdgeId e = 3 * t + i;
      const HalfEdgeId tw = mesh.twin(e);
      if (tw != kNone && mesh.is_real(tri_of(tw)) && tw < e) continue;
      const VertexId a = mesh.origin(e), b = mesh.dest(e);
      const double l = edge_length_in_metrics(mesh.point(a), mesh.point(b), at(a), at(b));
      ++f.edges;
      sum_len += l;
      f.min_length = std::min(f.min_length, l);
      f.max_length = std::max(f.max_length, l);
      if (l >= M_SQRT1_2 && l <= M_SQRT2) ++within;
    }
    for (VertexId v : tv) at(v);
    const Metric mt = adaptation::exp_sym(adaptation::mean3(lg[tv[0]], lg[tv[1]], lg[tv[2]]));
    const double q = metric_quality(mesh.point(tv[0]), mesh.point(tv[1]), mesh.point(tv[2]), mt);
    sum_q += q;
    f.min_quality = std::min(f.min_quality, q);
    ++tris;
  }
  if (f.edges) {
    f.within = double(within) / double(f.edges);
    f.mean_length = sum_len / double(f.edges);
  } else {
    f.min_length = 0;
  }
  if (tris) f.mean_quality = sum_q / double(tris);
  else f.min_quality = 0;
  return f;
}

}  // namespace deltamesh
