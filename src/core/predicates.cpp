// Exact stages of the robust predicates (see predicates.hpp for the inline
// floating-point filters) and the input range check.
//
// Method: J. R. Shewchuk, "Adaptive Precision Floating-Point Arithmetic and
// Fast Robust Geometric Predicates" (1997) -- error-bound constants, the
// staged orient2d, the B stage of incircle. Written for this project from the
// paper's description; the expansion arithmetic lives in expansion.hpp.
//
// Supported input range
// ---------------------
// Expansion arithmetic is exact only if nothing overflows and no rounding
// happens in the subnormal range. We accept a coordinate c iff it is finite
// and c == 0 or 2^-200 <= |c| <= 2^200 (about 6.2e-61 .. 1.6e60).
//
// Overflow (upper bound 2^200): coordinate differences are <= 2^201, squared
// lengths <= 2^403, lifted values (x^2 + y^2 - w, with |w| <= 2^400) < 2^404,
// 2x2 minors <= 2^403, so every degree-4 term of incircle/orient3d_lifted is
// below 2^807 and the determinant, its permanent and every expansion
// component built from them stay below ~2^811. Dekker splitting multiplies a
// factor (at most a degree-3 value, < 2^610) by 2^27 + 1. All of that is far
// below DBL_MAX ~ 2^1024; the ~2^200 headroom leaves room for callers'
// degree-5 expressions. 2^200 is the smallest power of two that still admits
// inputs of magnitude 1e60.
//
// Underflow (lower bound 2^-200): a double with |c| >= 2^-200 is an integer
// multiple of u = 2^-252 (53-bit significand), and so is every difference.
// Every exact intermediate of a degree-d predicate (products, their rounded
// values, roundoff terms, sums) is then a multiple of u^d; for d = 4 that is
// 2^-1008 >= 2^-1074, the spacing of subnormals. A multiple of 2^-1074 with at
// most 53 significant bits is representable even when subnormal, so Two-Sum
// and Two-Product stay exact, and rounding only ever happens in the normal
// range, where the relative error bounds of the filters hold. (A nonzero
// |c| < 2^-216 could break this: 4 * (216 + 52) > 1074.) Weights of
// orient3d_lifted scale like squared coordinates: 0 or 2^-400 <= |w| <= 2^400.
//
// The only operation that may still round in the subnormal range is the
// product errbound = constant * permanent of a degree-4 predicate; those
// comparisons are strict, so by monotonicity of rounding a rounded-down bound
// can never admit a wrong sign (|det| > fl(x) implies |det| > x for a
// representable det). orient2d's bounds scale a degree-2 sum >= u^2 = 2^-504
// and stay normal, so its inline filter may compare with >=.

#include "deltamesh/predicates.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>

#include "core/expansion.hpp"
#include "deltamesh/errors.hpp"

namespace deltamesh {

namespace detail {

const double kOrientErrA = (3.0 + 16.0 * kEpsilon) * kEpsilon;
const double kIncircleErrA = (10.0 + 96.0 * kEpsilon) * kEpsilon;

namespace {

constexpr double kResultErr = (3.0 + 8.0 * kEpsilon) * kEpsilon;
constexpr double kOrientErrB = (2.0 + 12.0 * kEpsilon) * kEpsilon;
constexpr double kOrientErrC = (9.0 + 64.0 * kEpsilon) * kEpsilon * kEpsilon;
constexpr double kIncircleErrB = (4.0 + 48.0 * kEpsilon) * kEpsilon;
// orient3d_lifted filter: each monomial of the determinant passes through at
// most 12 roundings (2 differences, the weight difference, 3 for the lifted
// value, 2 for the minor, the product, 2 sums), and the computed permanent
// underestimates the exact one by at most 12 roundings, so the error is below
// (12 + 210 eps) eps * permanent; we use a comfortable (16 + 256 eps) eps.
constexpr double kLiftedErrA = (16.0 + 256.0 * kEpsilon) * kEpsilon;

// A coordinate difference a - b as an exact expansion of one or two components.
struct Diff {
  double v[2];
  int n;
};

inline Diff make_diff(double head, double tail) {
  Diff r;
  if (tail != 0.0) {
    r.v[0] = tail;
    r.v[1] = head;
    r.n = 2;
  } else {
    r.v[0] = head;
    r.n = 1;
  }
  return r;
}

// Exponents of the leading and of the lowest set bit of a finite nonzero
// normal double; false for zero, subnormals, infinities and NaN.
inline bool bit_span(double v, int& lead, int& low) {
  // __builtin_bit_cast, not std::bit_cast: Emscripten 3.1.6's libc++ (the web build) lacks the latter.
  const auto bits = __builtin_bit_cast(std::uint64_t, v);
  const int e = static_cast<int>((bits >> 52) & 0x7ff);
  if (e == 0 || e == 0x7ff) return false;
  const std::uint64_t m = (bits & ((std::uint64_t{1} << 52) - 1)) | (std::uint64_t{1} << 52);
  lead = e - 1023;
  low = e - 1075 + std::countr_zero(m);
  return true;
}

// True if the nonzero values are integers below 2^12 in units of 2^q, q their
// lowest set bit (q = INT_MAX when all are zero). Then incircle's degree-4
// polynomial evaluated in doubles only forms integers below 2^53 in units of
// 2^4q: squares and products < 2^24, lifted values and minors < 2^25, terms
// < 2^50, the sum < 3 * 2^50 -- all exact. The bounds on q keep 2^4q clear of
// the subnormal range and the values far from overflow even for inputs
// outside the supported range.
inline bool small_integers(const double* v, int n, int& q) {
  int hi = std::numeric_limits<int>::min(), lo = std::numeric_limits<int>::max();
  for (int i = 0; i < n; ++i) {
    if (v[i] == 0.0) continue;
    int lead, low;
    if (!bit_span(v[i], lead, low)) return false;
    hi = std::max(hi, lead);
    lo = std::min(lo, low);
  }
  q = lo;
  return hi == std::numeric_limits<int>::min() || (hi - lo <= 11 && lo >= -260 && hi <= 240);
}

// Exact 2x2 minor p*q - r*s of doubles as a 4-component expansion.
inline void minor_expansion(double p, double q, double r, double s, double h[4]) {
  double p1, p0, r1, r0;
  two_product(p, q, p1, p0);
  two_product(r, s, r1, r0);
  two_two_diff(p1, p0, r1, r0, h);
}

// (minor) * (dx^2 + dy^2) for doubles dx, dy and a 4-component minor: <= 32 components.
inline int lift_times_minor(const double minor[4], double dx, double dy, double* h) {
  double t8[8], x16[16], y16[16];
  int len = scale_expansion_zeroelim(4, minor, dx, t8);
  const int xlen = scale_expansion_zeroelim(len, t8, dx, x16);
  len = scale_expansion_zeroelim(4, minor, dy, t8);
  const int ylen = scale_expansion_zeroelim(len, t8, dy, y16);
  return fast_expansion_sum_zeroelim(xlen, x16, ylen, y16, h);
}

// Largest lengths of the exact lifted determinant below.
constexpr int kProdLen = 8;                   // (2 comps) * (2 comps)
constexpr int kMinorLen = 2 * kProdLen;       // 16
constexpr int kLiftLen = 2 * kProdLen + 2;    // 18: dx^2 + dy^2 - w
constexpr int kTermLen = 2 * kMinorLen * kLiftLen;  // 576
constexpr int kDetLen = 3 * kTermLen;         // 1728

// Exact value (sign exact, magnitude approximate) of
//   sum over cyclic (i, j, k) of lift_i * (dx_j * dy_k - dx_k * dy_j),
//   lift_i = dx_i^2 + dy_i^2 - w_i,
// with every dx, dy, w given exactly as a Diff. w == nullptr means all w_i = 0.
// Zero elimination keeps this cheap when the Diffs have a single component.
double lifted_det_exact(const Diff dx[3], const Diff dy[3], const Diff* w) {
  double acc_buf[2][kDetLen];
  double* acc = acc_buf[0];
  double* next = acc_buf[1];
  int acclen = 0;
  double work[expansion_product_work(kMinorLen, kLiftLen)];
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    double p[kProdLen], q[kProdLen], minor[kMinorLen];
    const int plen = expansion_product(dx[j].n, dx[j].v, dy[k].n, dy[k].v, p, work);
    const int qlen = expansion_product(dx[k].n, dx[k].v, dy[j].n, dy[j].v, q, work);
    negate_expansion(qlen, q);
    const int mlen = fast_expansion_sum_zeroelim(plen, p, qlen, q, minor);

    double sx[kProdLen], sy[kProdLen], sq[2 * kProdLen], lift[kLiftLen];
    const int sxlen = expansion_product(dx[i].n, dx[i].v, dx[i].n, dx[i].v, sx, work);
    const int sylen = expansion_product(dy[i].n, dy[i].v, dy[i].n, dy[i].v, sy, work);
    const int sqlen = fast_expansion_sum_zeroelim(sxlen, sx, sylen, sy, sq);
    const double* l = sq;
    int llen = sqlen;
    if (w != nullptr) {
      const double nw[2] = {-w[i].v[0], -w[i].v[1]};
      llen = fast_expansion_sum_zeroelim(sqlen, sq, w[i].n, nw, lift);
      l = lift;
    }

    double term[kTermLen];
    const int tlen = llen <= mlen ? expansion_product(mlen, minor, llen, l, term, work)
                                  : expansion_product(llen, l, mlen, minor, term, work);
    if (i == 0) {
      for (int t = 0; t < tlen; ++t) acc[t] = term[t];
      acclen = tlen;
    } else {
      acclen = fast_expansion_sum_zeroelim(acclen, acc, tlen, term, next);
      double* swap = acc;
      acc = next;
      next = swap;
    }
  }
  return signed_estimate(acclen, acc);
}

}  // namespace

double orient2d_adapt(const Point& a, const Point& b, const Point& c, double detsum) {
  const double acx = a.x - c.x, bcx = b.x - c.x;
  const double acy = a.y - c.y, bcy = b.y - c.y;

  // Stage B: the determinant of the rounded differences, exactly.
  double bexp[4];
  minor_expansion(acx, bcy, acy, bcx, bexp);
  double det = estimate(4, bexp);
  double errbound = kOrientErrB * detsum;
  if (det > errbound || -det > errbound) return det;

  const double acxt = two_diff_tail(a.x, c.x, acx);
  const double bcxt = two_diff_tail(b.x, c.x, bcx);
  const double acyt = two_diff_tail(a.y, c.y, acy);
  const double bcyt = two_diff_tail(b.y, c.y, bcy);
  // Exact differences: stage B was the exact determinant.
  if (acxt == 0.0 && acyt == 0.0 && bcxt == 0.0 && bcyt == 0.0) return signed_estimate(4, bexp);

  // Stage C: add the first-order tail terms in floating point.
  errbound = kOrientErrC * detsum + kResultErr * std::fabs(det);
  det += (acx * bcyt + bcy * acxt) - (acy * bcxt + bcx * acyt);
  if (det > errbound || -det > errbound) return det;

  // Stage D: (acx + acxt)(bcy + bcyt) - (acy + acyt)(bcx + bcxt), exactly.
  double u[4], c1[8], c2[12], d[16];
  minor_expansion(acxt, bcy, acyt, bcx, u);
  const int c1len = fast_expansion_sum_zeroelim(4, bexp, 4, u, c1);
  minor_expansion(acx, bcyt, acy, bcxt, u);
  const int c2len = fast_expansion_sum_zeroelim(c1len, c1, 4, u, c2);
  minor_expansion(acxt, bcyt, acyt, bcxt, u);
  const int dlen = fast_expansion_sum_zeroelim(c2len, c2, 4, u, d);
  return signed_estimate(dlen, d);
}

double incircle_adapt(const Point& a, const Point& b, const Point& c, const Point& d, double permanent) {
  const double adx = a.x - d.x, bdx = b.x - d.x, cdx = c.x - d.x;
  const double ady = a.y - d.y, bdy = b.y - d.y, cdy = c.y - d.y;
  const Diff dx[3] = {make_diff(adx, two_diff_tail(a.x, d.x, adx)), make_diff(bdx, two_diff_tail(b.x, d.x, bdx)),
                      make_diff(cdx, two_diff_tail(c.x, d.x, cdx))};
  const Diff dy[3] = {make_diff(ady, two_diff_tail(a.y, d.y, ady)), make_diff(bdy, two_diff_tail(b.y, d.y, bdy)),
                      make_diff(cdy, two_diff_tail(c.y, d.y, cdy))};
  const bool exact_diffs = dx[0].n == 1 && dx[1].n == 1 && dx[2].n == 1 && dy[0].n == 1 && dy[1].n == 1 && dy[2].n == 1;

  if (exact_diffs) {
    // Cocircular grids land here. Small integer differences (in units of
    // their lowest common bit) make plain floating point exact.
    const double v[6] = {adx, ady, bdx, bdy, cdx, cdy};
    int q;
    if (small_integers(v, 6, q)) {
      const double alift = adx * adx + ady * ady;
      const double blift = bdx * bdx + bdy * bdy;
      const double clift = cdx * cdx + cdy * cdy;
      return alift * (bdx * cdy - cdx * bdy) + blift * (cdx * ady - adx * cdy) + clift * (adx * bdy - bdx * ady);
    }
  }

  // Stage B: the determinant of the rounded differences, exactly.
  double bc[4], ca[4], ab[4];
  minor_expansion(bdx, cdy, cdx, bdy, bc);
  minor_expansion(cdx, ady, adx, cdy, ca);
  minor_expansion(adx, bdy, bdx, ady, ab);
  double at[32], bt[32], ct[32], abt[64], fin[96];
  const int alen = lift_times_minor(bc, adx, ady, at);
  const int blen = lift_times_minor(ca, bdx, bdy, bt);
  const int clen = lift_times_minor(ab, cdx, cdy, ct);
  const int ablen = fast_expansion_sum_zeroelim(alen, at, blen, bt, abt);
  const int finlen = fast_expansion_sum_zeroelim(ablen, abt, clen, ct, fin);
  // Exact differences: stage B is the exact determinant.
  if (exact_diffs) return signed_estimate(finlen, fin);
  const double det = estimate(finlen, fin);
  const double errbound = kIncircleErrB * permanent;
  if (det > errbound || -det > errbound) return det;

  // Otherwise evaluate the whole determinant exactly.
  return lifted_det_exact(dx, dy, nullptr);
}

}  // namespace detail

double orient3d_lifted(const Point& a, const Point& b, const Point& c, const Point& d, double wa, double wb,
                       double wc, double wd) {
  const double adx = a.x - d.x, bdx = b.x - d.x, cdx = c.x - d.x;
  const double ady = a.y - d.y, bdy = b.y - d.y, cdy = c.y - d.y;
  const double aw = wa - wd, bw = wb - wd, cw = wc - wd;
  const double asq = adx * adx + ady * ady;
  const double bsq = bdx * bdx + bdy * bdy;
  const double csq = cdx * cdx + cdy * cdy;
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  const double cdxady = cdx * ady, adxcdy = adx * cdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady;
  const double det = (asq - aw) * (bdxcdy - cdxbdy) + (bsq - bw) * (cdxady - adxcdy) + (csq - cw) * (adxbdy - bdxady);
  const double permanent = (std::fabs(bdxcdy) + std::fabs(cdxbdy)) * (asq + std::fabs(aw)) +
                           (std::fabs(cdxady) + std::fabs(adxcdy)) * (bsq + std::fabs(bw)) +
                           (std::fabs(adxbdy) + std::fabs(bdxady)) * (csq + std::fabs(cw));
  const double errbound = detail::kLiftedErrA * permanent;
  if (det > errbound || -det > errbound) return det;

  using detail::make_diff;
  using detail::two_diff_tail;
  const detail::Diff dx[3] = {make_diff(adx, two_diff_tail(a.x, d.x, adx)),
                              make_diff(bdx, two_diff_tail(b.x, d.x, bdx)),
                              make_diff(cdx, two_diff_tail(c.x, d.x, cdx))};
  const detail::Diff dy[3] = {make_diff(ady, two_diff_tail(a.y, d.y, ady)),
                              make_diff(bdy, two_diff_tail(b.y, d.y, bdy)),
                              make_diff(cdy, two_diff_tail(c.y, d.y, cdy))};
  const detail::Diff w[3] = {make_diff(aw, two_diff_tail(wa, wd, aw)), make_diff(bw, two_diff_tail(wb, wd, bw)),
                             make_diff(cw, two_diff_tail(wc, wd, cw))};
  bool exact = true;
  for (int i = 0; i < 3; ++i) exact = exact && dx[i].n == 1 && dy[i].n == 1 && w[i].n == 1;
  if (exact) {
    // Grids land here. If the coordinate differences are integers below 2^12
    // in units of 2^q and the weight differences integers below 2^25 in units
    // of 2^2q, every value the filter formed is an integer below 2^53 in
    // units of 2^4q (lifted values < 2^26, minors < 2^25, terms < 2^51, the
    // sum < 3 * 2^51), so det above is exact.
    const double v[6] = {adx, ady, bdx, bdy, cdx, cdy};
    int q;
    if (detail::small_integers(v, 6, q)) {
      if (q == std::numeric_limits<int>::max()) return det;  // all minors are 0
      bool small = true;
      for (const double wv : {aw, bw, cw}) {
        int lead, low;
        if (wv != 0.0 && !(detail::bit_span(wv, lead, low) && low >= 2 * q && lead <= 2 * q + 24)) small = false;
      }
      if (small) return det;
    }
  }
  return detail::lifted_det_exact(dx, dy, w);
}

const double kMaxCoordinate = 0x1p200;
const double kMinCoordinate = 0x1p-200;
const double kMaxWeight = 0x1p400;
const double kMinWeight = 0x1p-400;

namespace {

std::string format_double(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string format_limit(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

// Empty if v is acceptable, else the problem ("is NaN", ...), for a value
// named `name` with the given magnitude limits.
std::string range_problem(double v, const char* name, double max_mag, const char* max_pow, double min_mag,
                          const char* min_pow) {
  if (std::isnan(v)) return "is NaN";
  if (std::isinf(v)) return "is infinite";
  const double m = std::fabs(v);
  // Built with append: GCC 12 warns falsely (-Wrestrict) on "literal" + string&&.
  std::string s;
  if (m > max_mag) {
    s.append("is out of range: |").append(name).append("| = ").append(format_double(m));
    s.append(" exceeds the supported magnitude ").append(format_limit(max_mag)).append(" = ").append(max_pow);
    s.append(" (the exact predicates would overflow)");
  } else if (m != 0.0 && m < min_mag) {
    s.append("is out of range: |").append(name).append("| = ").append(format_double(m));
    s.append(" is nonzero but below the supported magnitude ").append(format_limit(min_mag)).append(" = ");
    s.append(min_pow).append(" (the exact predicates would underflow)");
  }
  return s;
}

}  // namespace

void check_coordinates(std::span<const Point> points) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Point& p = points[i];
    // Fast path: one comparison chain per coordinate (NaN fails every test).
    const double ax = std::fabs(p.x), ay = std::fabs(p.y);
    const bool x_ok = ax <= kMaxCoordinate && (ax >= kMinCoordinate || ax == 0.0);
    const bool y_ok = ay <= kMaxCoordinate && (ay >= kMinCoordinate || ay == 0.0);
    if (x_ok && y_ok) continue;
    const bool bad_x = !x_ok;
    const char* name = bad_x ? "x" : "y";
    const std::string problem =
        range_problem(bad_x ? p.x : p.y, name, kMaxCoordinate, "2^200", kMinCoordinate, "2^-200");
    std::string what("coordinate ");
    what.append(name).append(" of point ").append(std::to_string(i)).append(" ").append(problem);
    throw VertexError(what, i, std::string("coordinate ") + name + " " + problem);
  }
}

void check_weights(std::span<const double> weights) {
  for (std::size_t i = 0; i < weights.size(); ++i) {
    const double w = weights[i];
    const double m = std::fabs(w);
    if (m <= kMaxWeight && (m >= kMinWeight || m == 0.0)) continue;
    std::string what("weight of point ");
    what.append(std::to_string(i)).append(" ");
    what.append(range_problem(w, "w", kMaxWeight, "2^400", kMinWeight, "2^-400"));
    throw InputError(what, i);
  }
}

}  // namespace deltamesh
