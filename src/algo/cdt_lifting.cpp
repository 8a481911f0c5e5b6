// Event times of the lifting-map segment insertion: filtered intervals and
// exact comparisons (see cdt_lifting.hpp).
#include "algo/cdt_lifting.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "core/expansion.hpp"
#include "deltamesh/predicates.hpp"

namespace deltamesh::detail {

namespace {

// An exact value as a nonoverlapping expansion (at least one component).
using Exp = std::vector<double>;

Exp exact_diff(double x, double y) {
  double d, err;
  two_diff(x, y, d, err);
  if (err == 0.0) return {d};
  return {err, d};
}

Exp add(const Exp& e, const Exp& f) {
  Exp h(e.size() + f.size());
  h.resize(static_cast<std::size_t>(fast_expansion_sum_zeroelim(static_cast<int>(e.size()), e.data(),
                                                                static_cast<int>(f.size()), f.data(), h.data())));
  return h;
}

Exp negate(Exp e) {
  negate_expansion(static_cast<int>(e.size()), e.data());
  return e;
}

Exp sub(const Exp& e, const Exp& f) { return add(e, negate(f)); }

Exp mul(const Exp& x, const Exp& y) {
  const Exp& e = x.size() >= y.size() ? x : y;  // the longer one
  const Exp& f = x.size() >= y.size() ? y : x;
  const int elen = static_cast<int>(e.size()), flen = static_cast<int>(f.size());
  Exp h(static_cast<std::size_t>(2 * elen * flen));
  std::vector<double> work(static_cast<std::size_t>(expansion_product_work(elen, flen)));
  h.resize(static_cast<std::size_t>(expansion_product(elen, e.data(), flen, f.data(), h.data(), work.data())));
  return h;
}

int sign(const Exp& e) {
  const double top = e.back();  // zero elimination keeps the leading component nonzero unless the value is 0
  return top > 0.0 ? 1 : (top < 0.0 ? -1 : 0);
}

// D = det [[a-d, |a-d|²], [b-d, |b-d|²], [c-d, |c-d|²]] exactly (the lifted
// 4x4 determinant of a, b, c, d at t = 0).
Exp exact_d(const Point& a, const Point& b, const Point& c, const Point& d) {
  const Exp adx = exact_diff(a.x, d.x), ady = exact_diff(a.y, d.y);
  const Exp bdx = exact_diff(b.x, d.x), bdy = exact_diff(b.y, d.y);
  const Exp cdx = exact_diff(c.x, d.x), cdy = exact_diff(c.y, d.y);
  const Exp alift = add(mul(adx, adx), mul(ady, ady));
  const Exp blift = add(mul(bdx, bdx), mul(bdy, bdy));
  const Exp clift = add(mul(cdx, cdx), mul(cdy, cdy));
  const Exp bc = sub(mul(bdx, cdy), mul(cdx, bdy));
  const Exp ca = sub(mul(cdx, ady), mul(adx, cdy));
  const Exp ab = sub(mul(adx, bdy), mul(bdx, ady));
  return add(add(mul(alift, bc), mul(blift, ca)), mul(clift, ab));
}

// K = (by-ay)(dx-cx) - (bx-ax)(dy-cy) exactly.
Exp exact_k(const Point& a, const Point& b, const Point& c, const Point& d) {
  return sub(mul(exact_diff(b.y, a.y), exact_diff(d.x, c.x)), mul(exact_diff(b.x, a.x), exact_diff(d.y, c.y)));
}

// orient2d(a, b, v) exactly.
Exp exact_orient(const Point& a, const Point& b, const Point& v) {
  return sub(mul(exact_diff(b.x, a.x), exact_diff(v.y, a.y)), mul(exact_diff(b.y, a.y), exact_diff(v.x, a.x)));
}

// The height rate s(v): -orient2d(a, b, v) right of ab, 0 elsewhere.
Exp exact_rate(const Point& a, const Point& b, const Point& v, bool right) {
  if (!right) return {0.0};
  return negate(exact_orient(a, b, v));
}

// R1 = det [[x-q, s(x)-s(q)], [y-q, s(y)-s(q)], [p-q, s(p)-s(q)]] exactly.
Exp exact_r1(const Point& a, const Point& b, const Quad& k) {
  const Exp sq = exact_rate(a, b, k.q, k.rq);
  const Exp zx = sub(exact_rate(a, b, k.x, k.rx), sq);
  const Exp zy = sub(exact_rate(a, b, k.y, k.ry), sq);
  const Exp zp = sub(exact_rate(a, b, k.p, k.rp), sq);
  const Exp ux = exact_diff(k.x.x, k.q.x), wx = exact_diff(k.x.y, k.q.y);
  const Exp uy = exact_diff(k.y.x, k.q.x), wy = exact_diff(k.y.y, k.q.y);
  const Exp up = exact_diff(k.p.x, k.q.x), wp = exact_diff(k.p.y, k.q.y);
  const Exp mx = sub(mul(uy, wp), mul(up, wy));
  const Exp my = sub(mul(up, wx), mul(ux, wp));
  const Exp mp = sub(mul(ux, wy), mul(uy, wx));
  return add(add(mul(zx, mx), mul(zy, my)), mul(zp, mp));
}

// Floating-point R0 (the incircle determinant, as incircle's filter forms
// it) with its error bound.
void float_r0(const Point& a, const Point& b, const Point& c, const Point& d, double& value, double& err) {
  const double adx = a.x - d.x, bdx = b.x - d.x, cdx = c.x - d.x;
  const double ady = a.y - d.y, bdy = b.y - d.y, cdy = c.y - d.y;
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  const double alift = adx * adx + ady * ady;
  const double cdxady = cdx * ady, adxcdy = adx * cdy;
  const double blift = bdx * bdx + bdy * bdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady;
  const double clift = cdx * cdx + cdy * cdy;
  value = alift * (bdxcdy - cdxbdy) + blift * (cdxady - adxcdy) + clift * (adxbdy - bdxady);
  const double permanent = (std::fabs(bdxcdy) + std::fabs(cdxbdy)) * alift +
                           (std::fabs(cdxady) + std::fabs(adxcdy)) * blift +
                           (std::fabs(adxbdy) + std::fabs(bdxady)) * clift;
  err = kIncircleErrA * permanent;
}

// An interval for -num / den from approximations with absolute error bounds
// (den known positive within its bound).
EventTime ratio_interval(double num, double enum_, double den, double eden) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  EventTime r;
  r.t = den != 0.0 ? -num / den : 0.0;
  if (!(den - eden > 0.0) || !std::isfinite(num) || !std::isfinite(den)) {
    r.lo = -kInf;
    r.hi = kInf;
    return r;
  }
  // |n/d - n~/d~| <= (en + |t~| ed) / (d~ - ed); the factors cover the
  // roundings of this bound and of t~ itself.
  const double at = std::fabs(r.t);
  const double err =
      (enum_ + at * eden) / (den - eden) * (1.0 + 1e-10) + at * 1e-15 + std::numeric_limits<double>::denorm_min();
  r.lo = r.t - err;
  r.hi = r.t + err;
  return r;
}

}  // namespace

KineticEvent kinetic_event(const Point& a, const Point& b, const Quad& k) {
  KineticEvent ev;
  // R1 in floating point with an error bound.
  const double bax = b.x - a.x, bay = b.y - a.y;
  double s[4], es[4];
  const Point* v[4] = {&k.x, &k.y, &k.p, &k.q};
  const bool right[4] = {k.rx, k.ry, k.rp, k.rq};
  for (int i = 0; i < 4; ++i) {
    if (!right[i]) {
      s[i] = es[i] = 0.0;
      continue;
    }
    const double l = bax * (v[i]->y - a.y), r = bay * (v[i]->x - a.x);
    s[i] = -(l - r);
    es[i] = kOrientErrA * (std::fabs(l) + std::fabs(r));
  }
  double r1 = 0.0, e1 = 0.0, perm = 0.0;
  {
    const double ux = k.x.x - k.q.x, wx = k.x.y - k.q.y;
    const double uy = k.y.x - k.q.x, wy = k.y.y - k.q.y;
    const double up = k.p.x - k.q.x, wp = k.p.y - k.q.y;
    const double ml[3] = {uy * wp, up * wx, ux * wy};
    const double mr[3] = {up * wy, ux * wp, uy * wx};
    for (int i = 0; i < 3; ++i) {
      const double m = ml[i] - mr[i];
      const double em = kOrientErrA * (std::fabs(ml[i]) + std::fabs(mr[i]));
      const double z = s[i] - s[3];
      const double ez = (es[i] + es[3]) * (1.0 + 1e-12) + 2.0 * kEpsilon * std::fabs(z);
      r1 += z * m;
      e1 += ez * (std::fabs(m) + em) + std::fabs(z) * em;
      perm += std::fabs(z * m);
    }
    e1 = (e1 + 4.0 * kEpsilon * perm) * (1.0 + 1e-10);
  }
  int sign_r1;
  if (r1 > e1)
    sign_r1 = 1;
  else if (r1 < -e1)
    sign_r1 = -1;
  else
    sign_r1 = sign(exact_r1(a, b, k));
  if (sign_r1 <= 0) return ev;
  ev.happens = true;
  double r0, e0;
  float_r0(k.x, k.y, k.p, k.q, r0, e0);
  ev.time = ratio_interval(r0, e0, r1, e1);
  return ev;
}

int compare_kinetic_times(const Point& a, const Point& b, const Quad& k1, const Quad& k2) {
  // t = -R0 / R1 with R1 > 0: t1 - t2 has the sign of R0_2 R1_1 - R0_1 R1_2,
  // a degree-8 polynomial. Scaling every point by the same power of two
  // (exact) scales R0 and R1 alike and keeps the sign; bringing the largest
  // coordinate near 1 keeps the products clear of overflow, and of underflow
  // as long as the nonzero coordinates span at most 2^80 (the caller's check).
  int e = 0;
  double big = 0.0;
  for (const Point* q : {&a, &b, &k1.x, &k1.y, &k1.p, &k1.q, &k2.x, &k2.y, &k2.p, &k2.q})
    big = std::max({big, std::fabs(q->x), std::fabs(q->y)});
  if (big > 0.0) std::frexp(big, &e);
  auto s = [&](const Point& q) { return Point{std::ldexp(q.x, -e), std::ldexp(q.y, -e)}; };
  auto sq = [&](const Quad& k) { return Quad{s(k.x), s(k.y), s(k.p), s(k.q), k.rx, k.ry, k.rp, k.rq}; };
  const Point sa = s(a), sb = s(b);
  const Quad q1 = sq(k1), q2 = sq(k2);
  const Exp r0a = exact_d(q1.x, q1.y, q1.p, q1.q), r1a = exact_r1(sa, sb, q1);
  const Exp r0b = exact_d(q2.x, q2.y, q2.p, q2.q), r1b = exact_r1(sa, sb, q2);
  return sign(sub(mul(r0b, r1a), mul(r0a, r1b)));
}

EventTime seed_event_time(const Point& a, const Point& b, const Point& c, const Point& d) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // D in floating point, computed exactly as incircle's filter does, so its
  // error bound applies.
  const double adx = a.x - d.x, bdx = b.x - d.x, cdx = c.x - d.x;
  const double ady = a.y - d.y, bdy = b.y - d.y, cdy = c.y - d.y;
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  const double alift = adx * adx + ady * ady;
  const double cdxady = cdx * ady, adxcdy = adx * cdy;
  const double blift = bdx * bdx + bdy * bdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady;
  const double clift = cdx * cdx + cdy * cdy;
  const double dd = alift * (bdxcdy - cdxbdy) + blift * (cdxady - adxcdy) + clift * (adxbdy - bdxady);
  const double permanent = (std::fabs(bdxcdy) + std::fabs(cdxbdy)) * alift +
                           (std::fabs(cdxady) + std::fabs(adxcdy)) * blift +
                           (std::fabs(adxbdy) + std::fabs(bdxady)) * clift;
  const double ed = kIncircleErrA * permanent;
  // K as orient2d's filter computes its determinant.
  const double kl = (b.y - a.y) * (d.x - c.x);
  const double kr = (b.x - a.x) * (d.y - c.y);
  const double kk = kl - kr;
  const double ek = kOrientErrA * (std::fabs(kl) + std::fabs(kr));
  EventTime r;
  const double ak = std::fabs(kk);
  if (!(ak > ek) || !std::isfinite(dd) || !std::isfinite(kk)) {
    r.t = kk != 0.0 ? dd / kk : 0.0;
    r.lo = -kInf;
    r.hi = kInf;
    return r;
  }
  r.t = dd / kk;
  // |D/K - D~/K~| <= (eD |K~| + |D~| eK) / (|K| |K~|) <= (eD + |t~| eK) / (|K~| - eK);
  // the factors cover the roundings of this bound and of t~ itself.
  const double at = std::fabs(r.t);
  const double err = (ed + at * ek) / (ak - ek) * (1.0 + 1e-10) + at * 1e-15 + std::numeric_limits<double>::denorm_min();
  r.lo = r.t - err;
  r.hi = r.t + err;
  return r;
}

int compare_seed_event_times(const Point& a0, const Point& b0, const Point& c10, const Point& d10,
                             const Point& c20, const Point& d20) {
  // Degree 6: scaled by a power of two first, as in compare_kinetic_times.
  int e = 0;
  double big = 0.0;
  for (const Point* q : {&a0, &b0, &c10, &d10, &c20, &d20}) big = std::max({big, std::fabs(q->x), std::fabs(q->y)});
  if (big > 0.0) std::frexp(big, &e);
  auto s = [&](const Point& q) { return Point{std::ldexp(q.x, -e), std::ldexp(q.y, -e)}; };
  const Point a = s(a0), b = s(b0), c1 = s(c10), d1 = s(d10), c2 = s(c20), d2 = s(d20);
  const Exp dv1 = exact_d(a, b, c1, d1), kv1 = exact_k(a, b, c1, d1);
  const Exp dv2 = exact_d(a, b, c2, d2), kv2 = exact_k(a, b, c2, d2);
  // t1 - t2 = (D1 K2 - D2 K1) / (K1 K2).
  const int sd = sign(sub(mul(dv1, kv2), mul(dv2, kv1)));
  const int sk = sign(kv1) * sign(kv2);
  return sd * sk;
}

}  // namespace deltamesh::detail
