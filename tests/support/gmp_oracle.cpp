#include "support/gmp_oracle.hpp"

#include <algorithm>
#include <bit>
#include <climits>
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace deltamesh::oracle {

namespace {

// Exponent of the lowest set bit of v (v = odd integer * 2^result); INT_MAX for 0.
int low_bit_exponent(double v) {
  if (v == 0.0) return INT_MAX;
  if (!std::isfinite(v)) throw std::invalid_argument("GmpOracle: non-finite input");
  int e;
  const double m = std::frexp(v, &e);  // v = m * 2^e, 0.5 <= |m| < 1
  const auto mant = static_cast<std::int64_t>(std::ldexp(m, 53));
  const auto umag = static_cast<std::uint64_t>(mant < 0 ? -mant : mant);
  return e - 53 + std::countr_zero(umag);
}

int sgn(const mpz_class& v) { return mpz_sgn(v.get_mpz_t()); }

}  // namespace

void GmpOracle::to_mpz(mpz_class& out, double v, int shift) {
  if (v == 0.0) {
    out = 0;
    return;
  }
  int e;
  const double m = std::frexp(v, &e);
  const auto mant = static_cast<std::int64_t>(std::ldexp(m, 53));
  const int exp2 = e - 53 + shift;
  mpz_set_si(out.get_mpz_t(), static_cast<long>(mant));
  if (exp2 >= 0) {
    mpz_mul_2exp(out.get_mpz_t(), out.get_mpz_t(), static_cast<mp_bitcnt_t>(exp2));
  } else {
    // The trailing zeros of the mantissa cover the negative exponent.
    mpz_tdiv_q_2exp(out.get_mpz_t(), out.get_mpz_t(), static_cast<mp_bitcnt_t>(-exp2));
  }
}

int GmpOracle::orient2d(const Point& a, const Point& b, const Point& c) {
  const Point* p[3] = {&a, &b, &c};
  int low = INT_MAX;
  for (const Point* q : p) low = std::min({low, low_bit_exponent(q->x), low_bit_exponent(q->y)});
  const int shift = low == INT_MAX ? 0 : -low;
  for (int i = 0; i < 3; ++i) {
    to_mpz(x_[i], p[i]->x, shift);
    to_mpz(y_[i], p[i]->y, shift);
  }
  mpz_sub(dx_[0].get_mpz_t(), x_[0].get_mpz_t(), x_[2].get_mpz_t());
  mpz_sub(dy_[0].get_mpz_t(), y_[0].get_mpz_t(), y_[2].get_mpz_t());
  mpz_sub(dx_[1].get_mpz_t(), x_[1].get_mpz_t(), x_[2].get_mpz_t());
  mpz_sub(dy_[1].get_mpz_t(), y_[1].get_mpz_t(), y_[2].get_mpz_t());
  mpz_mul(t0_.get_mpz_t(), dx_[0].get_mpz_t(), dy_[1].get_mpz_t());
  mpz_mul(t1_.get_mpz_t(), dy_[0].get_mpz_t(), dx_[1].get_mpz_t());
  return mpz_cmp(t0_.get_mpz_t(), t1_.get_mpz_t()) > 0 ? 1 : (mpz_cmp(t0_.get_mpz_t(), t1_.get_mpz_t()) < 0 ? -1 : 0);
}

int GmpOracle::lifted_sign() {
  acc_ = 0;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    mpz_mul(t0_.get_mpz_t(), dx_[j].get_mpz_t(), dy_[k].get_mpz_t());
    mpz_submul(t0_.get_mpz_t(), dx_[k].get_mpz_t(), dy_[j].get_mpz_t());
    mpz_addmul(acc_.get_mpz_t(), lift_[i].get_mpz_t(), t0_.get_mpz_t());
  }
  return sgn(acc_);
}

int GmpOracle::incircle(const Point& a, const Point& b, const Point& c, const Point& d) {
  const Point* p[4] = {&a, &b, &c, &d};
  int low = INT_MAX;
  for (const Point* q : p) low = std::min({low, low_bit_exponent(q->x), low_bit_exponent(q->y)});
  const int shift = low == INT_MAX ? 0 : -low;
  for (int i = 0; i < 4; ++i) {
    to_mpz(x_[i], p[i]->x, shift);
    to_mpz(y_[i], p[i]->y, shift);
  }
  for (int i = 0; i < 3; ++i) {
    mpz_sub(dx_[i].get_mpz_t(), x_[i].get_mpz_t(), x_[3].get_mpz_t());
    mpz_sub(dy_[i].get_mpz_t(), y_[i].get_mpz_t(), y_[3].get_mpz_t());
    mpz_mul(lift_[i].get_mpz_t(), dx_[i].get_mpz_t(), dx_[i].get_mpz_t());
    mpz_addmul(lift_[i].get_mpz_t(), dy_[i].get_mpz_t(), dy_[i].get_mpz_t());
  }
  return lifted_sign();
}

int GmpOracle::orient3d_lifted(const Point& a, const Point& b, const Point& c, const Point& d, double wa,
                               double wb, double wc, double wd) {
  const Point* p[4] = {&a, &b, &c, &d};
  const double w[4] = {wa, wb, wc, wd};
  int low = INT_MAX;
  for (const Point* q : p) low = std::min({low, low_bit_exponent(q->x), low_bit_exponent(q->y)});
  int wlow = INT_MAX;
  for (double v : w) wlow = std::min(wlow, low_bit_exponent(v));
  // Coordinates scale by 2^shift, weights by 2^(2 shift); both must become integers.
  int shift = 0;
  if (low != INT_MAX || wlow != INT_MAX) {
    shift = INT_MIN;
    if (low != INT_MAX) shift = -low;
    if (wlow != INT_MAX) {
      const int n = -wlow;
      shift = std::max(shift, n >= 0 ? (n + 1) / 2 : n / 2);  // ceil(n / 2)
    }
  }
  for (int i = 0; i < 4; ++i) {
    to_mpz(x_[i], p[i]->x, shift);
    to_mpz(y_[i], p[i]->y, shift);
    to_mpz(w_[i], w[i], 2 * shift);
  }
  for (int i = 0; i < 3; ++i) {
    mpz_sub(dx_[i].get_mpz_t(), x_[i].get_mpz_t(), x_[3].get_mpz_t());
    mpz_sub(dy_[i].get_mpz_t(), y_[i].get_mpz_t(), y_[3].get_mpz_t());
    // lift = dx^2 + dy^2 - (w_i - w_d)
    mpz_mul(lift_[i].get_mpz_t(), dx_[i].get_mpz_t(), dx_[i].get_mpz_t());
    mpz_addmul(lift_[i].get_mpz_t(), dy_[i].get_mpz_t(), dy_[i].get_mpz_t());
    mpz_sub(lift_[i].get_mpz_t(), lift_[i].get_mpz_t(), w_[i].get_mpz_t());
    mpz_add(lift_[i].get_mpz_t(), lift_[i].get_mpz_t(), w_[3].get_mpz_t());
  }
  return lifted_sign();
}

namespace {

int sgn(const mpq_class& v) { return sgn(v.get_num()); }

// det [[ax ay az 1] [bx by bz 1] [cx cy cz 1] [dx dy dz 1]] with z = x^2 + y^2 - w,
// by cofactor expansion of the translated 3x3 determinant.
int lifted_mpq(const Point& a, const Point& b, const Point& c, const Point& d, double wa, double wb, double wc,
               double wd) {
  const Point* p[4] = {&a, &b, &c, &d};
  const double w[4] = {wa, wb, wc, wd};
  mpq_class x[4], y[4], z[4];
  for (int i = 0; i < 4; ++i) {
    x[i] = p[i]->x;
    y[i] = p[i]->y;
    z[i] = x[i] * x[i] + y[i] * y[i] - mpq_class(w[i]);
  }
  mpq_class m[3][3];
  for (int i = 0; i < 3; ++i) {
    m[i][0] = x[i] - x[3];
    m[i][1] = y[i] - y[3];
    m[i][2] = z[i] - z[3];
  }
  const mpq_class det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                        m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                        m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  return sgn(det);
}

}  // namespace

int orient2d_mpq(const Point& a, const Point& b, const Point& c) {
  const mpq_class ax(a.x), ay(a.y), bx(b.x), by(b.y), cx(c.x), cy(c.y);
  const mpq_class det = (ax - cx) * (by - cy) - (ay - cy) * (bx - cx);
  return sgn(det);
}

int incircle_mpq(const Point& a, const Point& b, const Point& c, const Point& d) {
  return lifted_mpq(a, b, c, d, 0.0, 0.0, 0.0, 0.0);
}

int orient3d_lifted_mpq(const Point& a, const Point& b, const Point& c, const Point& d, double wa, double wb,
                        double wc, double wd) {
  return lifted_mpq(a, b, c, d, wa, wb, wc, wd);
}

}  // namespace deltamesh::oracle
