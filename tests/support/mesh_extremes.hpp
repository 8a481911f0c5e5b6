// Measured extremes of a mesh and the carved CDT the parallel refinement
// tests start from.
#pragma once
#include <algorithm>
#include <cmath>
#include <numbers>

#include "deltamesh/mesh.hpp"
#include "deltamesh/triangulate.hpp"

namespace deltamesh::test {

// A carved CDT of `g` (no refinement yet), built on one thread.
inline Mesh carved_cdt(const Pslg& g) {
  TriangulateOptions o;
  o.threads = 1;
  return triangulate(g, o);
}

struct MeshExtremes {
  double smallest_angle_deg = 180;
  double largest_area = 0;
};

// The smallest angle of any triangle and the largest area, in floating point.
inline MeshExtremes extremes(const Mesh& m) {
  MeshExtremes x;
  for (TriId t = 0; t < m.num_triangle_slots(); ++t) {
    if (!m.is_real(t)) continue;
    const auto v = m.triangle(t);
    for (int i = 0; i < 3; ++i) {
      const Point a = m.point(v[i]), b = m.point(v[(i + 1) % 3]), c = m.point(v[(i + 2) % 3]);
      const double ux = b.x - a.x, uy = b.y - a.y, wx = c.x - a.x, wy = c.y - a.y;
      const double cross = std::abs(ux * wy - uy * wx);
      x.smallest_angle_deg = std::min(x.smallest_angle_deg, std::atan2(cross, ux * wx + uy * wy) * 180 / std::numbers::pi);
      if (i == 0) x.largest_area = std::max(x.largest_area, 0.5 * cross);
    }
  }
  return x;
}

}  // namespace deltamesh::test
