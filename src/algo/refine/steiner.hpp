// Steiner points of Delaunay refinement, the part on R2's hot path: the
// circumcentre (Ruppert 1995) and Üngör's off-centre (LATIN 2004). Inline
// because decide() computes one per bad triangle; the best point is in
// steiner.cpp.
#pragma once
#include <cmath>

#include "algo/refine/refiner.hpp"
#include "deltamesh/predicates.hpp"

namespace deltamesh::refinement {

// The circumcentre of bad triangle t, or with SteinerRule::Offcenter/Best and
// a skinny t its off-centre when that is nearer to the shortest edge PQ
// (offcenter tells which). The circumcentre is computed relative to P with
// the adaptive orient2d as its denominator, accurate for skinny triangles.
Point Refiner::steiner_point(TriId t, const Eval& ev, bool& offcenter) const {
  offcenter = false;
  const HalfEdgeId e = 3 * t + ev.shortest;
  const Point P = pts_[tv_[e]];
  const Point Q = pts_[tv_[next_edge(e)]];
  const Point R = pts_[tv_[prev_edge(e)]];
  const double dx = Q.x - P.x, dy = Q.y - P.y, ex = R.x - P.x, ey = R.y - P.y;
  const double l2 = dx * dx + dy * dy, e2 = ex * ex + ey * ey;
  const double det = orient2d(P, Q, R);
  const double den = 0.5 / det;
  const double ux = (ey * l2 - dy * e2) * den, uy = (dx * e2 - ex * l2) * den;
  if (opt_.steiner == SteinerRule::Circumcenter || !ev.skinny) return {P.x + ux, P.y + uy};
  // Off-centre: along the bisector of PQ from its midpoint towards the circumcentre.
  const double mx = ux - 0.5 * dx, my = uy - 0.5 * dy;
  const double dc2 = mx * mx + my * my;
  const double h = off_factor_ * std::sqrt(l2);
  if (dc2 <= h * h) return {P.x + ux, P.y + uy};
  offcenter = true;
  const double s = h / std::sqrt(dc2);
  return {P.x + 0.5 * dx + mx * s, P.y + 0.5 * dy + my * s};
}

}  // namespace deltamesh::refinement
