// Triangle angle measures, one home each (quality report, writers, adapt).
// All use atan2 of the cross and dot products: accurate for tiny and
// near-180° angles alike, where acos of a rounded cosine is not.
#pragma once
#include <algorithm>
#include <cmath>
#include <numbers>

#include "deltamesh/geometry.hpp"

namespace deltamesh {

// abc scaled by a power of two (exact, unless a coordinate far below the
// largest underflows) so that its largest coordinate magnitude is in
// [1/2, 1): products of differences then neither overflow nor underflow,
// whatever the triangle's scale. `e` receives the exponent: lengths in the
// original are the scaled ones times 2^e, areas times 2^2e.
inline void scale_triangle(const Point& a, const Point& b, const Point& c, Point out[3], int& e) {
  const double m = std::max({std::fabs(a.x), std::fabs(a.y), std::fabs(b.x), std::fabs(b.y), std::fabs(c.x),
                             std::fabs(c.y)});
  e = 0;
  if (m > 0 && std::isfinite(m)) std::frexp(m, &e);
  out[0] = {std::ldexp(a.x, -e), std::ldexp(a.y, -e)};
  out[1] = {std::ldexp(b.x, -e), std::ldexp(b.y, -e)};
  out[2] = {std::ldexp(c.x, -e), std::ldexp(c.y, -e)};
}

// The local index i of a triangle's shortest edge (3t + i) from its squared
// lengths, as refinement and the statistics both choose it: a later edge
// wins only when shorter by more than a relative 2^-26, so the two equal
// sides of an isosceles triangle (exact in the input, or made by a split)
// are not told apart by rounding (an input scaled by 10^k), which would
// move the off-centre to the other side.
inline int shortest_edge_index(const double l2[3]) {
  constexpr double kShorter = 1.0 - 0x1p-26;
  int s = 0;
  if (l2[1] < l2[0] * kShorter) s = 1;
  if (l2[2] < l2[s] * kShorter) s = 2;
  return s;
}

// Whether abc's products of differences may overflow or lose precision to
// underflow (its edges are at least an ulp of its largest coordinate, about
// 2^-53 of it, so a largest magnitude within 2^+-300 keeps them safe).
inline bool needs_scaling(const Point& a, const Point& b, const Point& c) {
  const double m = std::max({std::fabs(a.x), std::fabs(a.y), std::fabs(b.x), std::fabs(b.y), std::fabs(c.x),
                             std::fabs(c.y)});
  return !(m < 0x1p300 && m > 0x1p-300) && m > 0 && std::isfinite(m);
}

// The angle at a of triangle abc, in radians. Scale-free: a triangle whose
// products would overflow or underflow is measured scaled (scale_triangle).
inline double angle_at_rad(const Point& a, const Point& b, const Point& c) {
  if (!needs_scaling(a, b, c)) {
    const double ux = b.x - a.x, uy = b.y - a.y, wx = c.x - a.x, wy = c.y - a.y;
    return std::atan2(std::fabs(ux * wy - uy * wx), ux * wx + uy * wy);
  }
  Point s[3];
  int e;
  scale_triangle(a, b, c, s, e);
  const double sux = s[1].x - s[0].x, suy = s[1].y - s[0].y, swx = s[2].x - s[0].x, swy = s[2].y - s[0].y;
  return std::atan2(std::fabs(sux * swy - suy * swx), sux * swx + suy * swy);
}

// The angle at a of triangle abc, in degrees.
inline double angle_at_deg(const Point& a, const Point& b, const Point& c) {
  return angle_at_rad(a, b, c) * (180.0 / std::numbers::pi);
}

// The smallest of the three angles of abc, in degrees (all three measured).
inline double min_angle_deg(const Point& a, const Point& b, const Point& c) {
  return std::min({angle_at_rad(a, b, c), angle_at_rad(b, c, a), angle_at_rad(c, a, b)}) * (180.0 / std::numbers::pi);
}

// The smallest angle of abc in degrees, measured once: at the apex opposite
// the shortest edge (lengths by hypot). 0 for a degenerate triangle. What the
// writers report per triangle (VTK, GeoJSON, SVG).
inline double smallest_angle_deg(const Point& a, const Point& b, const Point& c) {
  if (needs_scaling(a, b, c)) {  // measured scaled
    Point s[3];
    int e;
    scale_triangle(a, b, c, s, e);
    return smallest_angle_deg(s[0], s[1], s[2]);
  }
  const double ab = std::hypot(b.x - a.x, b.y - a.y);
  const double bc = std::hypot(c.x - b.x, c.y - b.y);
  const double ca = std::hypot(a.x - c.x, a.y - c.y);
  const Point *apex, *p, *q;
  if (ab <= bc && ab <= ca) {
    apex = &c, p = &a, q = &b;
  } else if (bc <= ca) {
    apex = &a, p = &b, q = &c;
  } else {
    apex = &b, p = &c, q = &a;
  }
  const double ux = p->x - apex->x, uy = p->y - apex->y;
  const double vx = q->x - apex->x, vy = q->y - apex->y;
  const double cross = std::fabs(ux * vy - uy * vx);
  const double dot = ux * vx + uy * vy;
  if (cross == 0.0 && dot == 0.0) return 0.0;
  return std::atan2(cross, dot) * 180.0 / std::numbers::pi;
}

}  // namespace deltamesh
