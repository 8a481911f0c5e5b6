// Metrics from a P1 field: Hessian recovery by a least-squares quadratic
// fit on vertex patches, scaling to a complexity or a tolerance, and
// gradation control.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "algo/adapt/common.hpp"
#include "algo/adapt/metric_math.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/metric.hpp"

namespace deltamesh {

namespace {

constexpr std::size_t kMinPatch = 7;  // points for a least-squares fit of 6 coefficients
constexpr int kMaxRings = 4;

// Least squares for c in sum_i (phi_i . c - u_i)^2, by the normal equations
// with partial pivoting (6 unknowns, coordinates scaled to O(1)). Returns
// false when the patch cannot determine a quadratic (e.g. collinear).
bool solve6(std::array<std::array<double, 7>, 6>& a, std::array<double, 6>& c) {
  double scale = 0;
  for (int i = 0; i < 6; ++i) scale = std::max(scale, std::fabs(a[i][i]));
  if (!(scale > 0)) return false;
  for (int col = 0; col < 6; ++col) {
    int piv = col;
    for (int r = col + 1; r < 6; ++r)
      if (std::fabs(a[r][col]) > std::fabs(a[piv][col])) piv = r;
    if (!(std::fabs(a[piv][col]) > 1e-12 * scale)) return false;
    std::swap(a[piv], a[col]);
    for (int r = col + 1; r < 6; ++r) {
      const double f = a[r][col] / a[col][col];
      for (int k = col; k < 7; ++k) a[r][k] -= f * a[col][k];
    }
  }
  for (int r = 5; r >= 0; --r) {
    double s = a[r][6];
    for (int k = r + 1; k < 6; ++k) s -= a[r][k] * c[k];
    c[r] = s / a[r][r];
  }
  return true;
}

// The Hessian of the least-squares quadratic through the values on
// `patch` (patch[0] is the centre vertex). The fit is made in the patch's
// principal axes, each scaled by the patch's extent along it, so a patch
// stretched as much as an anisotropic mesh's stars stays well conditioned
// (quadratics are closed under affine maps: the same fit, better rounded).
// False when the points do not determine a quadratic.
bool fit_hessian(const Mesh& mesh, std::span<const double> values, const std::vector<VertexId>& patch, Metric& h) {
  const Point& o = mesh.point(patch[0]);
  Metric cov{0, 0, 0};
  for (VertexId w : patch) {
    const double dx = mesh.point(w).x - o.x, dy = mesh.point(w).y - o.y;
    cov.m11 += dx * dx, cov.m12 += dx * dy, cov.m22 += dy * dy;
  }
  if (!(cov.m11 + cov.m22 > 0) || !std::isfinite(cov.m11 + cov.m22)) return false;
  const Eigen2 e = eigen(cov);
  // Axis 1 = (-s, c) (smaller spread), axis 2 = (c, s); extents along them.
  double s1 = 0, s2 = 0;
  for (VertexId w : patch) {
    const double dx = mesh.point(w).x - o.x, dy = mesh.point(w).y - o.y;
    s1 = std::max(s1, std::fabs(-e.s * dx + e.c * dy));
    s2 = std::max(s2, std::fabs(e.c * dx + e.s * dy));
  }
  if (!(s1 > 0) || !(s2 > 0)) return false;
  // xi = J d with J's rows axis_i / s_i.
  const double j11 = -e.s / s1, j12 = e.c / s1, j21 = e.c / s2, j22 = e.s / s2;
  std::array<std::array<double, 7>, 6> a{};
  for (VertexId w : patch) {
    const double dx = mesh.point(w).x - o.x, dy = mesh.point(w).y - o.y;
    const double x = j11 * dx + j12 * dy, y = j21 * dx + j22 * dy;
    const std::array<double, 6> phi{1, x, y, 0.5 * x * x, x * y, 0.5 * y * y};
    for (int i = 0; i < 6; ++i) {
      for (int k = 0; k < 6; ++k) a[i][k] += phi[i] * phi[k];
      a[i][6] += phi[i] * values[w];
    }
  }
  std::array<double, 6> c{};
  if (!solve6(a, c)) return false;
  // H = J^T Hxi J.
  const double p11 = c[3] * j11 + c[4] * j21, p12 = c[3] * j12 + c[4] * j22;  // (Hxi J) row 1
  const double p21 = c[4] * j11 + c[5] * j21, p22 = c[4] * j12 + c[5] * j22;  // row 2
  h = {j11 * p11 + j21 * p21, j11 * p12 + j21 * p22, j12 * p12 + j22 * p22};
  return std::isfinite(h.m11) && std::isfinite(h.m12) && std::isfinite(h.m22);
}

}  // namespace

std::vector<Metric> recover_hessian(const Mesh& mesh, std::span<const double> values) {
  const std::size_t n = mesh.num_vertices();
  if (values.size() != n)
    throw InputError(std::to_string(values.size()) + " values for a mesh of " + std::to_string(n) + " vertices");
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(values[i])) throw InputError("the value at vertex " + std::to_string(i) + " is not finite", i);
  std::vector<Metric> hess(n, Metric{0, 0, 0});
  std::vector<std::uint32_t> seen(n, 0);
  std::uint32_t stamp = 0;
  std::vector<VertexId> patch, ring, next, nbr;
  std::vector<HalfEdgeId> scratch;
  for (VertexId v = 0; v < n; ++v) {
    if (mesh.out_edge(v) == kNone) continue;
    ++stamp;
    patch.assign(1, v);
    seen[v] = stamp;
    ring.assign(1, v);
    // The smallest patch of whole rings that determines a quadratic: the
    // one-ring when it has enough points (most interior vertices), else
    // more rings. The smaller the patch, the less a layer thinner than it
    // is smoothed away.
    for (int r = 0; r < kMaxRings && !ring.empty(); ++r) {
      next.clear();
      for (VertexId w : ring) {
        adaptation::neighbors_of(mesh, w, scratch, nbr);
        for (VertexId u : nbr)
          if (seen[u] != stamp) {
            seen[u] = stamp;
            next.push_back(u);
            patch.push_back(u);
          }
      }
      ring.swap(next);
      if (patch.size() >= kMinPatch && fit_hessian(mesh, values, patch, hess[v])) break;
    }
  }
  return hess;
}

std::vector<Metric> metric_from_hessian(const Mesh& mesh, std::span<const Metric> hessians,
                                        const MetricScaling& sc) {
  const std::size_t n = mesh.num_vertices();
  if (hessians.size() != n)
    throw InputError(std::to_string(hessians.size()) + " Hessians for a mesh of " + std::to_string(n) + " vertices");
  if (!(sc.h_min > 0) || !(sc.h_max >= sc.h_min) || !(sc.max_aspect >= 1))
    throw InputError("metric scaling needs 0 < h_min <= h_max and max_aspect >= 1");
  if (sc.complexity <= 0 && !(sc.tolerance > 0)) throw InputError("metric scaling needs a complexity or a tolerance > 0");
  const double lmin = 1 / (sc.h_max * sc.h_max), lmax = 1 / (sc.h_min * sc.h_min);
  // |H| with its eigenvalues floored (a flat field asks for h_max), then
  // the local Lp factor det^(-1/(2p+2)).
  std::vector<Metric> m(n, isotropic_metric(sc.h_max));
  for (std::size_t i = 0; i < n; ++i) {
    const Metric& h = hessians[i];
    if (!std::isfinite(h.m11) || !std::isfinite(h.m12) || !std::isfinite(h.m22))
      throw InputError("the Hessian at vertex " + std::to_string(i) + " has a non-finite entry", i);
    const Eigen2 e = eigen(h);
    const double floor = sc.complexity > 0 ? 1e-12 : lmin * sc.tolerance * 4.5;
    const double l1 = std::max(std::fabs(e.l1), floor), l2 = std::max(std::fabs(e.l2), floor);
    double k = 1;
    if (sc.complexity > 0 && sc.p > 0) k = std::pow(l1 * l2, -1 / (2 * sc.p + 2));
    m[i] = from_eigen(k * l1, k * l2, e.c, e.s);
  }
  // N = D * integral of sqrt(det M) (P1 quadrature of the vertex values).
  const auto complexity = [&](const std::vector<Metric>& met) {
    double integral = 0;
    for (TriId t = 0; t < mesh.num_triangle_slots(); ++t) {
      if (!mesh.is_real(t)) continue;
      const auto v = mesh.triangle(t);
      const Point &a = mesh.point(v[0]), &b = mesh.point(v[1]), &c = mesh.point(v[2]);
      const double area = 0.5 * std::fabs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
      double s = 0;
      for (VertexId w : v) s += std::sqrt(std::max(0.0, met[w].m11 * met[w].m22 - met[w].m12 * met[w].m12));
      integral += area * s / 3;
    }
    return integral;
  };
  // The global factor, then the size and aspect bounds per vertex.
  const auto bounded = [&](double global) {
    std::vector<Metric> out(n);
    for (std::size_t i = 0; i < n; ++i) {
      Eigen2 e = eigen(adaptation::scaled(m[i], global));
      if (!std::isfinite(e.l1) || !std::isfinite(e.l2)) {
        // A tiny domain asks for a factor whose product overflows: scale the
        // eigenvalues instead (an infinite one is clamped to h_min's).
        e = eigen(m[i]);
        const double g = std::min(global, std::numeric_limits<double>::max());
        e.l1 *= g;
        e.l2 *= g;
      }
      double l2 = std::clamp(e.l2, lmin, lmax);
      double l1 = std::clamp(e.l1, lmin, lmax);
      l1 = std::max(l1, l2 / (sc.max_aspect * sc.max_aspect));
      out[i] = from_eigen(l1, l2, e.c, e.s);
    }
    return out;
  };
  if (!(sc.complexity > 0)) return bounded(2.0 / 9.0 / sc.tolerance);
  const double integral = complexity(m);
  if (!(integral > 0)) throw InputError("metric scaling to a complexity needs a mesh with triangles");
  // The bounds move the complexity off the target where they bind (a flat
  // field at h_max, a front at h_min): the factor is corrected until the
  // bounded metric reaches it (fixed point g <- g N / N(g); N(g) grows with
  // g, and only the unbound vertices answer, so a few steps suffice). When
  // the bounds decide everything it cannot move, and the last try is kept.
  double global = sc.complexity / integral;
  std::vector<Metric> out = bounded(global);
  for (int step = 0; step < 30; ++step) {
    const double got = complexity(out);
    if (!(got > 0) || std::fabs(got - sc.complexity) <= 1e-9 * sc.complexity) break;
    const double next = global * sc.complexity / got;
    if (!std::isfinite(next) || next == global) break;
    global = next;
    out = bounded(global);
  }
  return out;
}

int gradate_metric(const Mesh& mesh, std::vector<Metric>& m, double beta) {
  if (m.size() != mesh.num_vertices())
    throw InputError(std::to_string(m.size()) + " metrics for a mesh of " + std::to_string(mesh.num_vertices()) +
                     " vertices");
  if (!(beta > 1) || !std::isfinite(beta)) throw InputError("the gradation must be a number above 1");
  for (std::size_t i = 0; i < m.size(); ++i)
    if (mesh.out_edge(static_cast<VertexId>(i)) != kNone) {
      const std::string why = metric_problem(m[i]);
      if (!why.empty()) throw InputError("the metric tensor of vertex " + std::to_string(i) + " " + why, i);
    }
  const double lnb = std::log(beta);
  // Grows M_from along the edge to `to` and intersects M_to with it.
  const auto limit = [&](VertexId from, VertexId to) {
    const Point &p = mesh.point(from), &q = mesh.point(to);
    const double l = metric_length(m[from], q.x - p.x, q.y - p.y);
    const double eta = 1 + l * lnb;
    const Metric grown = adaptation::scaled(m[from], 1 / (eta * eta));
    // Relative to M_to in its own directions, so a change across a thin
    // direction counts as much as along a long one.
    if (adaptation::excess(m[to], grown) <= 1 + 1e-3) return false;
    m[to] = intersect(m[to], grown);
    return true;
  };
  int sweeps = 0;
  for (; sweeps < 50; ++sweeps) {
    bool changed = false;
    for (HalfEdgeId e = 0; e < mesh.triangle_vertices().size(); ++e) {
      if (!mesh.is_real(tri_of(e))) continue;
      const HalfEdgeId tw = mesh.twin(e);
      if (tw != kNone && tw < e) continue;
      const VertexId a = mesh.origin(e), b = mesh.dest(e);
      changed |= limit(a, b);
      changed |= limit(b, a);
    }
    if (!changed) break;
  }
  return sweeps;
}

}  // namespace deltamesh
