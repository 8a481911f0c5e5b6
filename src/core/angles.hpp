// Triangle angle measures, one home each (quality report, writers, adapt).
// All use atan2 of the cross and dot products: accurate for tiny and
// near-180° angles alike, where acos of a rounded cosine is not.
#pragma once
#include <algorithm>
#include <cmath>
#include <numbers>

#include "deltamesh/geometry.hpp"

namespace deltamesh {

// The angle at a of triangle abc, in radians.
inline double angle_at_rad(const Point& a, const Point& b, const Point& c) {
  const double ux = b.x - a.x, uy = b.y - a.y, wx = c.x - a.x, wy = c.y - a.y;
  return std::atan2(std::fabs(ux * wy - uy * wx), ux * wx + uy * wy);
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
