// Small symmetric 2x2 helpers shared by the metric code.
#pragma once
#include <cmath>

#include "deltamesh/metric.hpp"

namespace deltamesh::adaptation {

// Matrix logarithm of a metric (eigenvalues' logarithms).
inline Metric log_metric(const Metric& m) {
  const Eigen2 e = eigen(m);
  return from_eigen(std::log(e.l1), std::log(e.l2), e.c, e.s);
}

// Matrix exponential of a symmetric matrix: a metric.
inline Metric exp_sym(const Metric& l) {
  const Eigen2 e = eigen(l);
  return from_eigen(std::exp(e.l1), std::exp(e.l2), e.c, e.s);
}

// s m s for symmetric s and m.
inline Metric sandwich(const Metric& s, const Metric& m) {
  // t = s m (general), then t s.
  const double t11 = s.m11 * m.m11 + s.m12 * m.m12, t12 = s.m11 * m.m12 + s.m12 * m.m22;
  const double t21 = s.m12 * m.m11 + s.m22 * m.m12, t22 = s.m12 * m.m12 + s.m22 * m.m22;
  return {t11 * s.m11 + t12 * s.m12, t11 * s.m12 + t12 * s.m22, t21 * s.m12 + t22 * s.m22};
}

inline Metric mean3(const Metric& a, const Metric& b, const Metric& c) {
  return {(a.m11 + b.m11 + c.m11) / 3, (a.m12 + b.m12 + c.m12) / 3, (a.m22 + b.m22 + c.m22) / 3};
}

inline Metric scaled(const Metric& m, double k) { return {k * m.m11, k * m.m12, k * m.m22}; }

// The largest eigenvalue of a^-1/2 b a^-1/2: above 1 when b asks for a
// smaller size than a in some direction (and intersect(a, b) != a).
inline double excess(const Metric& a, const Metric& b) {
  const Eigen2 ea = eigen(a);
  const Metric inv_half = from_eigen(1 / std::sqrt(ea.l1), 1 / std::sqrt(ea.l2), ea.c, ea.s);
  return eigen(sandwich(inv_half, b)).l2;
}

}  // namespace deltamesh::adaptation
