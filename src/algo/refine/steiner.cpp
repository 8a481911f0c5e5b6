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
#include <array>
#include <cstdint>
#include <cmath>
#include <limits>
#include <span>

#include "algo/refine/refiner.hpp"
#include "deltamesh/predicates.hpp"

namespace deltamesh::refinement {

namespace {

// Candidate (bad, r2) beats the best so far: fewer skinny triangles left, or
// as many and farther from every vertex by more than a relative 2^-24.
// Symmetric candidates tie in exact arithmetic (equidistant from two
// vertices); without the margin their rounding noise would pick one, and an
// input scaled by a factor other than a power of two (rounded) would pick
// another and refine differently from there on.
constexpr double kTieMargin = 1.0 + 0x1p-24;
// Relative distance within which a candidate counts as on a circle or a line.
constexpr double kNear = 0x1p-26;
bool beats(int bad, double r2, int best_bad, double best_r2) {
  return bad < best_bad || (bad == best_bad && r2 > best_r2 * kTieMargin);
}

// The coarse grid of the search, in units of |PQ| from PQ's midpoint: heights
// towards the bad triangle, shifts along PQ. Without size bounds the two
// lowest rows (0.87, 1.0) are left out: points that low leave fewer skinny
// triangles but small ones, and the refinement then needs more points
// (measured on the reference set of docs/benchmarks.md and the corpus: 1.6%
// fewer triangles than from 1.0, 11% fewer candidates scored). With size
// bounds the search runs only away from too-large triangles and the full
// grid stays (without the 0.87 row, parallel refinement in parts no longer
// agreed with the sequential count within 3%).
constexpr double kHeights[] = {0.87, 1.0, 1.15, 1.3, 1.5, 1.75, 2.0};
constexpr double kShifts[] = {0.0, -0.25, 0.25, -0.5, 0.5, -0.75, 0.75, -1.0, 1.0};
constexpr std::size_t kFirstRowUnsized = 2;
// best_point()'s seeds without size bounds: the apex height over a skinny
// edge AB in units of |AB|, and the fractions of the way to it from the
// primary. Measured on the reference set (docs/benchmarks.md): fractions
// 0.4, 0.7, 1 gave 1% more triangles (most such seeds leave the petal),
// 0.2, 0.4 0.5% more; heights 0.866 (the equilateral apex) and 0.45 more.
constexpr double kSeedHeight = 0.6;
constexpr double kSeedSteps[] = {0.15, 0.3, 0.5};

}  // namespace

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

// SteinerRule::Grid (the default before the petal-local search): a search over the petal of t's shortest edge PQ (the
// points from which PQ makes a triangle within the angle bound: above the
// lines at the bound's angle from P and Q, inside the circle through P and Q
// on which PQ subtends the bound). A coarse grid, then a pattern search at
// three step sizes around the best point so far, pick the point whose
// insertion leaves the fewest skinny triangles, then the one farthest from
// every vertex. On the corpus this gives 14% (q30) to 19% (q33) fewer
// triangles than the off-centre alone (docs/benchmarks.md); the off-centre is
// kept when it leaves none. Finer coarse grids and wider shifts were measured:
// the width (shifts up to ±|PQ|) and the local search matter most.
Point Refiner::grid_point(TriId t, const Eval& ev, const Point& primary) {
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
    if (y >= ymax * (1 - kNear) || y <= 0) return;
    // Angles at P and Q, then at the new vertex (sine rule), at least the bound.
    if (y < tan_a * (0.5 + s) || y < tan_a * (0.5 - s)) return;
    const double a2 = (0.5 + s) * (0.5 + s) + y * y, b2 = (0.5 - s) * (0.5 - s) + y * y;
    if (y * y * std::min({1.0, a2, b2}) < sin2_bound_ * a2 * b2) return;
    const Point c{M.x + l * (s * ux + y * nx), M.y + l * (s * uy + y * ny)};
    int bad;
    double r2;
    if (!score(t, c, min2, bad, r2)) return;
    if (beats(bad, r2, best_bad, best_r2)) {
      best_bad = bad, best_r2 = r2, best = c;
      best_y = y, best_s = s;
    }
  };
  for (const double y : std::span(kHeights).subspan(sized_ ? 0 : kFirstRowUnsized))
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


// The petal's neighbourhood for best_point(): the triangles connected to t
// through unconstrained edges whose circumcircle meets the disc (centre,
// radius). Every candidate of the petal lies in that disc, so its
// Bowyer-Watson cavity is made of these triangles only. False when there are
// too many (then the off-centre is kept). The circles are in floating point:
// the chosen point is checked against the mesh afterwards.
bool Refiner::gather_petal(TriId t, const Point& centre, double radius) {
  petal_.clear();
  petal_.reserve(kMaxPetal);
  begin_cavity();  // the cavity stamp marks gathered triangles
  const std::size_t slots = tv_.size() / 3;
  cav_.reserve_slots(slots);
  if (petal_index_.size() < slots) petal_index_.resize(slots);
  const auto circle = [&](TriId u, PetalTri& pt) {
    const Point& A = pts_[tv_[3 * u]];
    const Point& B = pts_[tv_[3 * u + 1]];
    const Point& C = pts_[tv_[3 * u + 2]];
    const double bx = B.x - A.x, by = B.y - A.y, cx = C.x - A.x, cy = C.y - A.y;
    const double d = 2 * (bx * cy - by * cx);
    const double b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
    const double ux = (cy * b2 - by * c2) / d, uy = (bx * c2 - cx * b2) / d;
    pt.cx = A.x + ux;
    pt.cy = A.y + uy;
    pt.r2 = ux * ux + uy * uy;
    if (!(d > 0) || !std::isfinite(pt.r2)) pt.cx = A.x, pt.cy = A.y, pt.r2 = INFINITY;
    pt.r2_in = pt.r2 * (1 - kNear);
    pt.r2_out = pt.r2 * (1 + kNear);
  };
  const auto meets = [&](const PetalTri& pt) {
    const double dx = pt.cx - centre.x, dy = pt.cy - centre.y;
    const double s = std::sqrt(pt.r2) + radius;
    return dx * dx + dy * dy < s * s;
  };
  const auto add = [&](TriId u, const PetalTri& pt) {
    cav_.add_reserved(u);
    petal_index_[u] = static_cast<std::uint32_t>(petal_.size());
    PetalTri& q = petal_.emplace_back(pt);
    for (int k = 0; k < 3; ++k) q.p[k] = pts_[tv_[3 * u + k]];
    for (int k = 0; k < 3; ++k) q.e2[k] = dist2(q.p[k], q.p[k == 2 ? 0 : k + 1]);
  };
  PetalTri pt{};
  circle(t, pt);
  add(t, pt);
  for (std::size_t i = 0; i < petal_.size(); ++i) {
    const TriId u = cav_[i];
    for (int k = 0; k < 3; ++k) {
      const HalfEdgeId e = 3 * u + k;
      const HalfEdgeId f = tw_[e];
      std::int32_t nb = kOut;
      if (fl_[e] & kConstrained) nb = kWall;
      else if (f != kNone) {
        const TriId w = tri_of(f);
        if (in_cavity(w)) nb = static_cast<std::int32_t>(petal_index_[w]);
        else {
          circle(w, pt);
          if (meets(pt)) {
            if (petal_.size() >= kMaxPetal) return false;
            nb = static_cast<std::int32_t>(petal_.size());
            add(w, pt);
          }
        }
      }
      petal_[i].nb[k] = nb;
    }
  }
  return true;
}

// Whether c lies within a relative kNear of the boundary of segment ab's
// encroachment region (its diametral circle, or lens): a degenerate place,
// refused like the other near cases of score_local().
bool Refiner::near_encroachment(const Point& a, const Point& b, const Point& c) const {
  const double ax = a.x - c.x, ay = a.y - c.y, bx = b.x - c.x, by = b.y - c.y;
  const double dot = ax * bx + ay * by, ab2 = (ax * ax + ay * ay) * (bx * bx + by * by);
  if (dot * dot <= kNear * kNear * ab2) return true;
  return lens_ && dot < 0 && std::fabs(dot * dot - lens_cos2_ * ab2) <= kNear * ab2;
}

// score() on the gathered neighbourhood: the cavity of c grown by its
// triangles' circles, with the same tests on its boundary edges. Only a
// point that beats (best_bad, best_r2) matters: scoring stops (false) as
// soon as c cannot, since `bad` only grows and `radius2` only shrinks.
// radius2 starts at the distance to the corners of the bad triangle (the
// first petal triangle), which are on every cavity's boundary, so that a
// point too close to them is dropped before its cavity is grown.
bool Refiner::score_local(const Point& c, double min2, int best_bad, double best_r2, int& bad, double& radius2,
                          std::vector<std::array<Point, 2>>* skinny) {
  // A candidate within a relative kNear of a circumcircle, or of the line
  // of a cavity edge, is degenerate there: rounding (an input scaled by
  // 10^k) decides its side, so it is refused rather than scored.
  bool near = false;
  const auto inside = [&](const PetalTri& pt) {
    const double dx = c.x - pt.cx, dy = c.y - pt.cy;
    const double d2 = dx * dx + dy * dy;
    if (d2 < pt.r2_in) return true;
    near = d2 <= pt.r2_out;
    return false;
  };
  const PetalTri& t0 = petal_[0];
  if (!inside(t0)) return false;
  const double beat_r2 = best_r2 * kTieMargin;
  radius2 = std::min({dist2(t0.p[0], c), dist2(t0.p[1], c), dist2(t0.p[2], c)});
  if (radius2 < min2 || (best_bad == 0 && radius2 <= beat_r2)) return false;
  if (++petal_stamp_ == 0) {
    petal_in_.fill(0);
    petal_stamp_ = 1;
  }
  const std::uint32_t stamp = petal_stamp_;
  bad = 0;
  std::size_t top = 0;
  petal_stack_[top++] = 0;
  petal_in_[0] = stamp;
  while (top > 0) {
    const PetalTri& pt = petal_[static_cast<std::size_t>(petal_stack_[--top])];
    for (int k = 0; k < 3; ++k) {
      const std::int32_t j = pt.nb[k];
      if (j >= 0) {
        const auto ju = static_cast<std::size_t>(j);
        if (petal_in_[ju] == stamp) continue;
        if (inside(petal_[ju])) {
          petal_in_[ju] = stamp;
          petal_stack_[top++] = j;
          continue;
        }
        if (near) return false;
      }
      const Point& A = pt.p[k];
      const Point& B = pt.p[k == 2 ? 0 : k + 1];
      const double cross = (B.x - A.x) * (c.y - A.y) - (B.y - A.y) * (c.x - A.x);
      if (!(cross > 0)) return false;
      if (j == kWall && (encroaches(A, B, c) || near_encroachment(A, B, c))) return false;
      const double la = dist2(A, c), lb = dist2(B, c), lab = pt.e2[k];
      radius2 = std::min({radius2, la, lb});
      if (radius2 < min2) return false;
      const double lo = std::min({la, lb, lab});
      if (cross * cross * lo < sin2_bound_ * la * lb * lab) {
        // Skinny, and maybe c on the line of AB (then degenerate).
        if (cross * cross <= kNear * kNear * lab * std::max(la, lb)) return false;
        ++bad;
        if (skinny) skinny->push_back({A, B});
      }
      if (bad > best_bad || (bad == best_bad && radius2 <= beat_r2)) return false;
    }
  }
  return true;
}

// Whether the point at height y and shift s (units of |PQ|, from PQ's
// midpoint) makes a triangle with PQ within the bound: the angles at P and Q,
// then at the new vertex (sine rule). tan_a: tan of the bound.
static bool in_petal(double tan_a, double sin2_bound, double y, double s) {
  // Nearer to P or Q than |PQ|: refused by score_local() (a new edge shorter
  // than PQ) whatever the mesh, so not scored at all.
  if (y * y + (0.5 + s) * (0.5 + s) < 0.999 || y * y + (0.5 - s) * (0.5 - s) < 0.999) return false;
  if (y < tan_a * (0.5 + s) || y < tan_a * (0.5 - s)) return false;
  const double a2 = (0.5 + s) * (0.5 + s) + y * y, b2 = (0.5 - s) * (0.5 - s) + y * y;
  return !(y * y * std::min({1.0, a2, b2}) < sin2_bound * a2 * b2);
}

// What best_point() needs of the bound, computed once per bound: the petal's
// disc and a coarse grid, its cells inside the petal in grid_point()'s order.
// The order matters: exact ties in the distance to the nearest vertex are
// common (mirror-image candidates), and the first of equal candidates wins.
// Scoring the cells most likely to win first (measured) saved 3% of the
// instructions but changed 0.05% of the triangles.
void Refiner::prepare_grid() {
  grid_tan_ = std::tan(bound_rad_);
  grid_half_cot_ = 0.5 / std::tan(bound_rad_);
  grid_disc_ = 0.5 / std::sin(bound_rad_);
  grid_cells_.clear();
  for (const double y : std::span(kHeights).subspan(sized_ ? 0 : kFirstRowUnsized))
    for (const double s : kShifts)
      if (in_petal(grid_tan_, sin2_bound_, y, s)) grid_cells_.push_back({y, s});
  grid_rad_ = bound_rad_;
}

// SteinerRule::Best: grid_point()'s search with every candidate scored on
// the triangles whose circumcircle meets the petal's disc, gathered once
// (gather_petal, score_local), instead of by a cavity grown in the mesh, and
// no candidate of the pattern search scored twice. Most skinny triangles
// need the search (the off-centre leaves a skinny triangle for about 19 in
// 20 on the corpus), so the search's cost is the rule's cost. The winner is
// scored on the mesh again (exact incircle) and kept only if it still beats
// the off-centre.
Point Refiner::best_point(TriId t, const Eval& ev, const Point& primary) {
  const HalfEdgeId e = 3 * t + ev.shortest;
  const Point P = pts_[tv_[e]];
  const Point Q = pts_[tv_[next_edge(e)]];
  const double l = std::sqrt(ev.shortest2);
  const double ux = (Q.x - P.x) / l, uy = (Q.y - P.y) / l;
  const double nx = -uy, ny = ux;  // towards the triangle's third vertex (counter-clockwise)
  const Point M{0.5 * (P.x + Q.x), 0.5 * (P.y + Q.y)};
  const double ymax = ((primary.x - M.x) * nx + (primary.y - M.y) * ny) / l;
  const double min2 = ev.shortest2 * 0.999;  // no new edge shorter than PQ
  constexpr int kFails = std::numeric_limits<int>::max();
  int primary_bad = 0;
  double primary_r2 = 0;
  // With size bounds the primary's cavity is needed (its neighbours'
  // sizes), so it is scored on the mesh first, as in grid_point().
  if (sized_) {
    if (!score(t, primary, min2, primary_bad, primary_r2)) primary_bad = kFails, primary_r2 = 0;
    if (primary_bad == 0) return primary;
    if (primary_bad != kFails)
      for (const BoundaryEdge& b : bnd_)
        if (b.outer != kNone && eval(tri_of(b.outer)).large) return primary;
  }
  // The petal lies in the disc from whose circle PQ subtends the bound. The
  // primary (an off-centre 2% below the disc's top, or a circumcentre lower
  // on the same bisector) lies in it too, so without size bounds it is
  // scored on the petal like the other candidates.
  if (grid_rad_ != bound_rad_) prepare_grid();
  const double half_cot = grid_half_cot_, rad = grid_disc_;
  if (!gather_petal(t, {M.x + l * half_cot * nx, M.y + l * half_cot * ny}, l * rad)) return primary;
  if (!sized_) {
    skinny_edges_.clear();
    if (!score_local(primary, min2, kFails, 0, primary_bad, primary_r2, &skinny_edges_)) primary_bad = kFails;
    // A primary refused (it encroaches a segment, its cavity is not
    // star-shaped, or it comes too close to a vertex) is kept: decide()
    // splits the segment or skips. Searching on gave a better point for
    // one such triangle in five, and more triangles in the end (measured).
    if (primary_bad == 0 || primary_bad == kFails) return primary;
  }
  int best_bad = primary_bad;
  double best_r2 = primary_r2;
  Point best = primary;
  double best_y = ymax, best_s = 0;
  const auto within_petal = [&](double y, double s) { return in_petal(grid_tan_, sin2_bound_, y, s); };
  const double y_top = ymax * (1 - kNear);  // up to the primary (not at it: degenerate)
  const auto try_point = [&](double y, double s) {
    const Point c{M.x + l * (s * ux + y * nx), M.y + l * (s * uy + y * ny)};
    int bad;
    double r2;
    if (!score_local(c, min2, best_bad, best_r2, bad, r2)) return false;
    if (!beats(bad, r2, best_bad, best_r2)) return false;
    best_bad = bad, best_r2 = r2, best = c;
    best_y = y, best_s = s;
    return true;
  };
  const auto consider = [&](double y, double s) {
    if (y >= y_top || y <= 0 || !within_petal(y, s)) return false;
    return try_point(y, s);
  };
  if (sized_) {
    for (const auto& [y, s] : grid_cells_)
      if (y < y_top) try_point(y, s);
  } else {
    // Seeds instead of the grid: for each cavity edge AB that the primary
    // leaves skinny, points from the primary towards the apex of a good
    // triangle on AB (0.6 |AB| from AB's midpoint, on the primary's side),
    // the direction in which that triangle stops being skinny (after
    // Erten and Üngör's search of the regions where each new triangle is
    // good). With the wider pattern search below this scores ~2.5x fewer
    // candidates than the grid on the corpus, for fewer triangles
    // (docs/benchmarks.md).
    for (const auto& [A, B] : skinny_edges_) {
      const Point X{0.5 * (A.x + B.x) - kSeedHeight * (B.y - A.y), 0.5 * (A.y + B.y) + kSeedHeight * (B.x - A.x)};
      for (const double a : kSeedSteps) {
        const double cx = primary.x + a * (X.x - primary.x) - M.x, cy = primary.y + a * (X.y - primary.y) - M.y;
        consider((cx * nx + cy * ny) / l, (cx * ux + cy * uy) / l);
      }
    }
  }
  // The pattern search of grid_point() on a lattice of its finest steps
  // around the best point so far, each lattice point scored at most once (a
  // move's neighbourhood overlaps the last one's): steps of 4, 2 and 1 units
  // of (0.01875, 0.03125) |PQ| after the grid, 8, 4 and 2 after the seeds
  // (wider, since the seeds are few), at most 3 moves each, so offsets stay
  // within 42 units.
  constexpr double kUnitY = 0.01875, kUnitS = 0.03125;
  constexpr int kSide = 128, kMid = 64;
  std::array<std::uint64_t, 2 * kSide> seen{};  // row iy + kMid: two words, bit is + kMid
  const auto first_visit = [&](int ky, int ks) {
    const int b = ks + kMid;
    std::uint64_t& word = seen[static_cast<std::size_t>(2 * (ky + kMid) + (b >> 6))];
    const std::uint64_t bit = std::uint64_t{1} << (b & 63);
    if (word & bit) return false;
    word |= bit;
    return true;
  };
  const double y0 = best_y, s0 = best_s;
  int cy = 0, cs = 0;
  first_visit(0, 0);
  const int first_step = sized_ ? 4 : 8, last_step = sized_ ? 1 : 2;
  for (int step = first_step; step >= last_step && best_bad > 0; step /= 2) {
    for (int move = 0; move < 3 && best_bad > 0; ++move) {
      const int py = cy, ps = cs;
      for (int i = -1; i <= 1; ++i)
        for (int j = -1; j <= 1; ++j) {
          const int ky = py + i * step, ks = ps + j * step;
          if (first_visit(ky, ks) && consider(y0 + ky * kUnitY, s0 + ks * kUnitS)) cy = ky, cs = ks;
        }
      if (cy == py && cs == ps) break;
    }
  }
  if (best.x == primary.x && best.y == primary.y) return primary;
  int bad;
  double r2;
  if (!score(t, best, min2, bad, r2)) return primary;
  if (beats(bad, r2, primary_bad, primary_r2)) return best;
  return primary;
}

}  // namespace deltamesh::refinement
