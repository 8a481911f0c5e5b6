// Exact floating-point expansion arithmetic, following the method published in
// J. R. Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast
// Robust Geometric Predicates", Discrete & Computational Geometry 18 (1997).
// Written for this project from the paper's description.
//
// An expansion is an array e[0..n) of doubles whose exact (real) sum is the
// value it represents. The components are sorted by increasing magnitude and
// (strongly) nonoverlapping, so the last nonzero component carries the sign.
// Every function keeps at least one component (a lone 0.0 for the value zero).
//
// Exactness requires IEEE binary64 with round-to-nearest-even, no fused
// multiply-add (the project compiles with -ffp-contract=off), no overflow,
// and every exact intermediate being a multiple of 2^-1074 (then gradual
// underflow never rounds). predicates.cpp bounds the input range so that
// both conditions hold for the predicates built here.
#pragma once
#include <cmath>

namespace deltamesh::detail {

// 2^ceil(53/2) + 1: Veltkamp/Dekker splitting constant for binary64.
inline constexpr double kSplitter = 134217729.0;
// Unit roundoff of binary64 (half an ulp of 1).
inline constexpr double kEpsilon = 0x1p-53;

// ---------------------------------------------------------------------------
// Error-free transformations of two doubles.

// s + err == a + b exactly, s = fl(a + b).
inline void two_sum(double a, double b, double& s, double& err) {
  s = a + b;
  const double b_virtual = s - a;
  const double a_virtual = s - b_virtual;
  err = (a - a_virtual) + (b - b_virtual);
}

// As two_sum, but requires |a| >= |b| (or a == 0); three flops fewer.
inline void fast_two_sum(double a, double b, double& s, double& err) {
  s = a + b;
  err = b - (s - a);
}

// d + err == a - b exactly, d = fl(a - b).
inline void two_diff(double a, double b, double& d, double& err) {
  d = a - b;
  const double b_virtual = a - d;
  const double a_virtual = d + b_virtual;
  err = (a - a_virtual) + (b_virtual - b);
}

// The roundoff of an already computed d = fl(a - b).
inline double two_diff_tail(double a, double b, double d) {
  const double b_virtual = a - d;
  const double a_virtual = d + b_virtual;
  return (a - a_virtual) + (b_virtual - b);
}

// hi + lo == a with hi, lo each fitting in 26 bits (plus sign).
inline void split(double a, double& hi, double& lo) {
  const double c = kSplitter * a;
  const double big = c - a;
  hi = c - big;
  lo = a - hi;
}

// p + err == a * b exactly, p = fl(a * b), with b already split.
inline void two_product_presplit(double a, double b, double bhi, double blo, double& p, double& err) {
  p = a * b;
  double ahi, alo;
  split(a, ahi, alo);
  const double e1 = p - ahi * bhi;
  const double e2 = e1 - alo * bhi;
  const double e3 = e2 - ahi * blo;
  err = alo * blo - e3;
}

// p + err == a * b exactly, p = fl(a * b).
inline void two_product(double a, double b, double& p, double& err) {
  double bhi, blo;
  split(b, bhi, blo);
  two_product_presplit(a, b, bhi, blo, p, err);
}

// p + err == a * a exactly.
inline void two_square(double a, double& p, double& err) {
  p = a * a;
  double ahi, alo;
  split(a, ahi, alo);
  const double e1 = p - ahi * ahi;
  const double e3 = e1 - (ahi + ahi) * alo;
  err = alo * alo - e3;
}

// (a1 + a0) - (b1 + b0) as a 4-component expansion h (no zero elimination),
// for 2-component expansions {a0, a1} and {b0, b1}: the paper's Expansion-Sum,
// i.e. grow {a0, a1} by -b0, then grow the upper two components by -b1.
inline void two_two_diff(double a1, double a0, double b1, double b0, double h[4]) {
  double q, t0, t1;
  two_diff(a0, b0, q, h[0]);  // grow {a0, a1} by -b0 -> {h0, t0, t1}
  two_sum(a1, q, t1, t0);
  two_diff(t0, b1, q, h[1]);  // grow {t0, t1} by -b1 -> {h1, h2, h3}
  two_sum(t1, q, h[3], h[2]);
}

// ---------------------------------------------------------------------------
// Expansion operations. Output arrays must not alias inputs.

// h = e + b. h needs room for elen + 1 components. Returns the length of h.
inline int grow_expansion_zeroelim(int elen, const double* e, double b, double* h) {
  double q = b;
  int hlen = 0;
  for (int i = 0; i < elen; ++i) {
    double hh;
    two_sum(q, e[i], q, hh);
    if (hh != 0.0) h[hlen++] = hh;
  }
  if (q != 0.0 || hlen == 0) h[hlen++] = q;
  return hlen;
}

// h = e + f (the paper's Fast-Expansion-Sum with zero elimination).
// h needs room for elen + flen components. Returns the length of h.
inline int fast_expansion_sum_zeroelim(int elen, const double* e, int flen, const double* f, double* h) {
  int ei = 0, fi = 0;
  // Merge by increasing magnitude.
  auto take = [&]() -> double {
    if (fi >= flen || (ei < elen && std::fabs(e[ei]) <= std::fabs(f[fi]))) return e[ei++];
    return f[fi++];
  };
  double q = take();
  int hlen = 0;
  double hh;
  if (ei + fi < elen + flen) {
    const double g = take();  // |g| >= |q| by the merge order
    fast_two_sum(g, q, q, hh);
    if (hh != 0.0) h[hlen++] = hh;
    while (ei + fi < elen + flen) {
      two_sum(q, take(), q, hh);
      if (hh != 0.0) h[hlen++] = hh;
    }
  }
  if (q != 0.0 || hlen == 0) h[hlen++] = q;
  return hlen;
}

// h = e * b (the paper's Scale-Expansion with zero elimination).
// h needs room for 2 * elen components. Returns the length of h.
inline int scale_expansion_zeroelim(int elen, const double* e, double b, double* h) {
  double bhi, blo;
  split(b, bhi, blo);
  double q, hh;
  int hlen = 0;
  two_product_presplit(e[0], b, bhi, blo, q, hh);
  if (hh != 0.0) h[hlen++] = hh;
  for (int i = 1; i < elen; ++i) {
    double p1, p0, s;
    two_product_presplit(e[i], b, bhi, blo, p1, p0);
    two_sum(q, p0, s, hh);
    if (hh != 0.0) h[hlen++] = hh;
    fast_two_sum(p1, s, q, hh);
    if (hh != 0.0) h[hlen++] = hh;
  }
  if (q != 0.0 || hlen == 0) h[hlen++] = q;
  return hlen;
}

// Size of the work array expansion_product needs.
inline constexpr int expansion_product_work(int elen, int flen) { return 2 * elen * flen + 2 * elen; }

// h = e * f, as the sum over the components of f of e scaled by them.
// h needs room for 2 * elen * flen components and work for
// expansion_product_work(elen, flen). Pass the shorter expansion as f.
inline int expansion_product(int elen, const double* e, int flen, const double* f, double* h, double* work) {
  if (flen == 1) return scale_expansion_zeroelim(elen, e, f[0], h);
  double* term = work;
  double* other = work + 2 * elen;
  // flen - 1 sums alternate between two buffers; start where the last lands in h.
  double* acc = ((flen - 1) % 2 == 0) ? h : other;
  double* next = (acc == h) ? other : h;
  int acclen = scale_expansion_zeroelim(elen, e, f[0], acc);
  for (int j = 1; j < flen; ++j) {
    const int tlen = scale_expansion_zeroelim(elen, e, f[j], term);
    acclen = fast_expansion_sum_zeroelim(acclen, acc, tlen, term, next);
    double* t = acc;
    acc = next;
    next = t;
  }
  return acclen;
}

// Negates every component in place (exact).
inline void negate_expansion(int elen, double* e) {
  for (int i = 0; i < elen; ++i) e[i] = -e[i];
}

// Floating-point approximation of the value (components summed smallest first).
inline double estimate(int elen, const double* e) {
  double q = e[0];
  for (int i = 1; i < elen; ++i) q += e[i];
  return q;
}

// An approximation of the value whose sign is exactly the sign of the value:
// the estimate, unless rounding flipped or zeroed it, else the most
// significant nonzero component.
inline double signed_estimate(int elen, const double* e) {
  int top = elen - 1;
  while (top > 0 && e[top] == 0.0) --top;
  const double lead = e[top];
  const double est = estimate(elen, e);
  if ((est > 0.0 && lead > 0.0) || (est < 0.0 && lead < 0.0)) return est;
  return lead;
}

}  // namespace deltamesh::detail
