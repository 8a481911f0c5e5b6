// Steiner points of Delaunay refinement: where a bad triangle is split
// (Ruppert's R2 and the size bounds).
//  - The circumcentre (Ruppert 1995) and Üngör's off-centre (A. Üngör,
//    "Off-centers: a new type of Steiner points for computing size-optimal
//    quality-guaranteed Delaunay triangulations", LATIN 2004: on the
//    bisector of the shortest edge, no farther from it than the point where
//    it subtends the angle bound): steiner.hpp, inline on R2's hot path.
//  - The best point (here): the off-centre, or a point of the shortest
//    edge's petal that leaves fewer skinny triangles, in the spirit of
//    H. Erten and A. Üngör, "Quality triangulations with locally optimal
//    Steiner points", SIAM J. Sci. Comput. 2009.
#include <algorithm>
#include <cmath>
#include <limits>

#include "algo/refine/refiner.hpp"
#include "deltamesh/predicates.hpp"

namespace deltamesh::refinement {

// Scores candidate c for bad triangle t: its cavity must hold t (c inside
// t's circumcircle), be star-shaped from c, touch no segment c encroaches, and
// keep c at least sqrt(min2) away from every vertex (no edge shorter than
// t's). `bad` counts the new triangles that would still be skinny (size is
// left to the size bound's own splits); radius2 is the squared distance to
// the nearest vertex. The cavity is grown from t itself and checked in
// floating point: the chosen point is located and its cavity built exactly
// afterwards by decide().
bool Refiner::score(TriId t, const Point& c, double min2, int& bad, double& radius2) {
  const HalfEdgeId b0 = 3 * t;
  if (!(incircle(pts_[tv_[b0]], pts_[tv_[b0 + 1]], pts_[tv_[b0 + 2]], c) > 0)) return false;
  begin_cavity();
  add_to_cavity(t);
  stack_.push_back(b0 + 2);
  stack_.push_back(b0 + 1);
  stack_.push_back(b0);
  if (!grow(c)) return false;
  bad = 0;
  radius2 = INFINITY;
  for (const BoundaryEdge& b : bnd_) {
    const Point& A = pts_[b.a];
    const Point& B = pts_[b.b];
    const double cross = (B.x - A.x) * (c.y - A.y) - (B.y - A.y) * (c.x - A.x);
    if (!(cross > 0)) return false;
    if ((b.flags & kConstrained) && encroaches(A, B, c)) return false;
    const double la = dist2(A, c), lb = dist2(B, c), lab = dist2(A, B);
    radius2 = std::min({radius2, la, lb});
    if (radius2 < min2) return false;
    // sin of the smallest angle = cross / (product of the two longer edges).
    const double lo = std::min({la, lb, lab});
    const double den = la * lb * lab / lo;
    if (cross * cross < sin2_bound_ * den) ++bad;
  }
  return true;
}

// SteinerRule::Best: a search over the petal of t's shortest edge PQ (the
// points from which PQ makes a triangle within the angle bound: above the
// lines at the bound's angle from P and Q, inside the circle through P and Q
// on which PQ subtends the bound). A coarse grid, then a pattern search at
// three step sizes around the best point so far, pick the point whose
// insertion leaves the fewest skinny triangles, then the one farthest from
// every vertex. On the corpus this gives 14% (q30) to 19% (q33) fewer
// triangles than the off-centre alone (docs/benchmarks.md); the off-centre is
// kept when it leaves none. Finer coarse grids and wider shifts were measured:
// the width (shifts up to ±|PQ|) and the local search matter most.
Point Refiner::best_point(TriId t, const Eval& ev, const Point& primary) {
  const HalfEdgeId e = 3 * t + ev.shortest;
  const Point P = pts_[tv_[e]];
  const Point Q = pts_[tv_[next_edge(e)]];
  const double l = std::sqrt(ev.shortest2);
  const double ux = (Q.x - P.x) / l, uy = (Q.y - P.y) / l;
  const double nx = -uy, ny = ux;  // towards the triangle's third vertex (counter-clockwise)
  const Point M{0.5 * (P.x + Q.x), 0.5 * (P.y + Q.y)};
  // Heights and shifts below are in units of l; the primary is the highest.
  const double ymax = ((primary.x - M.x) * nx + (primary.y - M.y) * ny) / l;
  const double min2 = ev.shortest2 * 0.999;  // no new edge shorter than PQ
  int best_bad = 0;
  double best_r2 = 0;
  Point best = primary;
  double best_y = ymax, best_s = 0;
  if (!score(t, primary, min2, best_bad, best_r2)) best_bad = std::numeric_limits<int>::max(), best_r2 = 0;
  if (best_bad == 0) return primary;
  // Next to triangles that are too large the bad ones are split anyway by
  // the size bound's refinement: the search would cost time for nothing.
  if (sized_ && best_bad != std::numeric_limits<int>::max())
    for (const BoundaryEdge& b : bnd_)
      if (b.outer != kNone && eval(tri_of(b.outer)).large) return primary;
  const double tan_a = std::tan(bound_rad_);
  const auto consider = [&](double y, double s) {
    if (y >= ymax || y <= 0) return;
    // Angles at P and Q, then at the new vertex (sine rule), at least the bound.
    if (y < tan_a * (0.5 + s) || y < tan_a * (0.5 - s)) return;
    const double a2 = (0.5 + s) * (0.5 + s) + y * y, b2 = (0.5 - s) * (0.5 - s) + y * y;
    if (y * y * std::min({1.0, a2, b2}) < sin2_bound_ * a2 * b2) return;
    const Point c{M.x + l * (s * ux + y * nx), M.y + l * (s * uy + y * ny)};
    int bad;
    double r2;
    if (!score(t, c, min2, bad, r2)) return;
    if (bad < best_bad || (bad == best_bad && r2 > best_r2)) {
      best_bad = bad, best_r2 = r2, best = c;
      best_y = y, best_s = s;
    }
  };
  static constexpr double kHeights[] = {0.87, 1.0, 1.15, 1.3, 1.5, 1.75, 2.0};
  static constexpr double kShifts[] = {0.0, -0.25, 0.25, -0.5, 0.5, -0.75, 0.75, -1.0, 1.0};
  for (const double y : kHeights)
    for (const double s : kShifts) consider(y, s);
  // Pattern search: step to the best neighbour while that improves, then halve.
  for (double dy = 0.075, ds = 0.125; dy > 0.015 && best_bad > 0; dy *= 0.5, ds *= 0.5) {
    for (int move = 0; move < 3 && best_bad > 0; ++move) {
      const double y0 = best_y, s0 = best_s;
      for (int i = -1; i <= 1; ++i)
        for (int j = -1; j <= 1; ++j)
          if (i != 0 || j != 0) consider(y0 + i * dy, s0 + j * ds);
      if (best_y == y0 && best_s == s0) break;
    }
  }
  return best;
}

}  // namespace deltamesh::refinement
