// Robust geometric predicates: a floating-point filter decides most cases
// inline; uncertain cases fall back to exact adaptive expansion arithmetic
// (Shewchuk's published method, written for this project). The returned
// value's sign is exact; its magnitude is an approximation.
#pragma once
#include <cmath>
#include <span>

#include "deltamesh/geometry.hpp"

namespace deltamesh {

namespace detail {
// Error-bound constants (epsilon = 2^-53) and exact fallbacks, in predicates.cpp.
extern const double kOrientErrA;
extern const double kIncircleErrA;
double orient2d_adapt(const Point& a, const Point& b, const Point& c, double detsum);
double incircle_adapt(const Point& a, const Point& b, const Point& c, const Point& d, double permanent);
}  // namespace detail

// > 0 if a, b, c turn counter-clockwise, < 0 clockwise, 0 if collinear.
inline double orient2d(const Point& a, const Point& b, const Point& c) {
  const double detleft = (a.x - c.x) * (b.y - c.y);
  const double detright = (a.y - c.y) * (b.x - c.x);
  const double det = detleft - detright;
  double detsum;
  if (detleft > 0.0) {
    if (detright <= 0.0) return det;
    detsum = detleft + detright;
  } else if (detleft < 0.0) {
    if (detright >= 0.0) return det;
    detsum = -detleft - detright;
  } else {
    return det;
  }
  const double errbound = detail::kOrientErrA * detsum;
  if (det >= errbound || -det >= errbound) return det;
  return detail::orient2d_adapt(a, b, c, detsum);
}

// > 0 if d lies inside the circle through a, b, c (given counter-clockwise),
// < 0 outside, 0 on it.
inline double incircle(const Point& a, const Point& b, const Point& c, const Point& d) {
  const double adx = a.x - d.x, bdx = b.x - d.x, cdx = c.x - d.x;
  const double ady = a.y - d.y, bdy = b.y - d.y, cdy = c.y - d.y;
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  const double alift = adx * adx + ady * ady;
  const double cdxady = cdx * ady, adxcdy = adx * cdy;
  const double blift = bdx * bdx + bdy * bdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady;
  const double clift = cdx * cdx + cdy * cdy;
  const double det = alift * (bdxcdy - cdxbdy) + blift * (cdxady - adxcdy) + clift * (adxbdy - bdxady);
  const double permanent = (std::fabs(bdxcdy) + std::fabs(cdxbdy)) * alift +
                           (std::fabs(cdxady) + std::fabs(adxcdy)) * blift +
                           (std::fabs(adxbdy) + std::fabs(bdxady)) * clift;
  const double errbound = detail::kIncircleErrA * permanent;
  if (det > errbound || -det > errbound) return det;
  return detail::incircle_adapt(a, b, c, d, permanent);
}

// Coordinates the predicates can decide exactly: finite, and within the
// magnitude range documented by these constants (see predicates.cpp for why).
extern const double kMaxCoordinate;
// Throws InputError naming the index of the first point that is NaN, infinite
// or outside the supported magnitude range.
void check_coordinates(std::span<const Point> points);

// --- Range of the exact predicates and the lifted (weighted) predicate. ---

// Smallest nonzero coordinate magnitude the predicates accept (2^-200); with
// kMaxCoordinate (2^200) it bounds every intermediate away from overflow and
// from rounding in the subnormal range (see predicates.cpp for why).
extern const double kMinCoordinate;
// Weights of orient3d_lifted scale like squared coordinates: finite, and 0 or
// kMinWeight (2^-400) <= |w| <= kMaxWeight (2^400).
extern const double kMaxWeight;
extern const double kMinWeight;
// Throws InputError naming the index of the first weight that is NaN,
// infinite or outside [kMinWeight, kMaxWeight] in magnitude (0 is accepted).
void check_weights(std::span<const double> weights);

// Sign of det [[ax ay ax^2+ay^2-wa 1] [bx by bx^2+by^2-wb 1]
//              [cx cy cx^2+cy^2-wc 1] [dx dy dx^2+dy^2-wd 1]]:
// the weighted (power) incircle test. > 0 when d lies inside the power circle
// of the counter-clockwise a, b, c (its lifted point below their plane), < 0
// outside, 0 on it; with all weights 0 it has the sign of incircle(a, b, c, d).
// Exact for points passing check_coordinates and weights passing check_weights.
double orient3d_lifted(const Point& a, const Point& b, const Point& c, const Point& d, double wa, double wb,
                       double wc, double wd);

}  // namespace deltamesh
