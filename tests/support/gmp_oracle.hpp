// Exact oracles for the geometric predicates, computed with GMP.
//
// GmpOracle is the fast one: every finite double is an integer times a power
// of two, so it scales all inputs of one query by a common power of two to
// integers (exactly, via frexp) and evaluates the homogeneous polynomial with
// preallocated mpz integers -- no rationals, no allocation per query after
// warm-up. Scaling by 2^s multiplies orient2d by 2^(2s) and incircle /
// orient3d_lifted by 2^(4s) (weights are scaled by 2^(2s)), so signs are kept.
//
// The *_mpq functions are the obviously-correct slow reference (mpq_class,
// straight from the determinant formulas) used to validate GmpOracle.
#pragma once
#include <gmpxx.h>

#include "deltamesh/geometry.hpp"

namespace deltamesh::oracle {

// -1, 0 or +1.
inline int sign_of(double v) { return (v > 0.0) - (v < 0.0); }

class GmpOracle {
 public:
  // Signs of the exact determinants, with the conventions of predicates.hpp.
  int orient2d(const Point& a, const Point& b, const Point& c);
  int incircle(const Point& a, const Point& b, const Point& c, const Point& d);
  int orient3d_lifted(const Point& a, const Point& b, const Point& c, const Point& d, double wa, double wb,
                      double wc, double wd);

 private:
  // Sets out = v * 2^shift, which must be an integer.
  static void to_mpz(mpz_class& out, double v, int shift);
  // Sign of sum over cyclic (i,j,k) of lift_i * (dx_j dy_k - dx_k dy_j) where
  // dx_[i], dy_[i], lift_[i] are already set.
  int lifted_sign();

  mpz_class x_[4], y_[4], w_[4];
  mpz_class dx_[3], dy_[3], lift_[3];
  mpz_class t0_, t1_, acc_;
};

// Slow reference evaluations with mpq_class.
int orient2d_mpq(const Point& a, const Point& b, const Point& c);
int incircle_mpq(const Point& a, const Point& b, const Point& c, const Point& d);
int orient3d_lifted_mpq(const Point& a, const Point& b, const Point& c, const Point& d, double wa, double wb,
                        double wc, double wd);

}  // namespace deltamesh::oracle
