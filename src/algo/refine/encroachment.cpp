// Encroachment of segments in Delaunay refinement (Ruppert's R1), and where
// an encroached subsegment is split. The test itself, Refiner::encroaches,
// is inline in refiner.hpp: the best-point search calls it in its inner loop.
//  - Diametral circle (J. Ruppert, "A Delaunay refinement algorithm for
//    quality 2-dimensional mesh generation", J. Algorithms 1995): a vertex
//    strictly inside the circle with the subsegment as diameter encroaches.
//  - Diametral lens (J. R. Shewchuk, "Delaunay refinement algorithms for
//    triangular mesh generation", CGTA 2002): only a vertex from which the
//    subsegment subtends more than max(90°, 180° - 2·bound), i.e. one that
//    would make a triangle below the bound with it.
//  - Concentric shells (Shewchuk 2002): a subsegment with one input-vertex
//    end is split at a power-of-two distance from that vertex (in the
//    input's unit, Refiner::unit_), so that the splits of segments meeting
//    at a small angle stay at equal radii.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "algo/refine/refiner.hpp"
#include "algo/refine_parallel.hpp"
#include "core/expansion.hpp"
#include "deltamesh/predicates.hpp"

namespace deltamesh::refinement {

// Exact sign of (a - p)·(b - p): negative iff p lies strictly inside the
// circle with diameter ab. The magnitude is an approximation.
double diametral_dot(const Point& a, const Point& b, const Point& p) {
  const double ax = a.x - p.x, bx = b.x - p.x, ay = a.y - p.y, by = b.y - p.y;
  const double t1 = ax * bx, t2 = ay * by;
  const double det = t1 + t2;
  const double bound = 8.0 * detail::kEpsilon * (std::fabs(t1) + std::fabs(t2));
  if (det > bound || -det > bound) return det;
  double dax[2], dbx[2], day[2], dby[2];
  detail::two_diff(a.x, p.x, dax[1], dax[0]);
  detail::two_diff(b.x, p.x, dbx[1], dbx[0]);
  detail::two_diff(a.y, p.y, day[1], day[0]);
  detail::two_diff(b.y, p.y, dby[1], dby[0]);
  double px[8], py[8], work[12], sum[16];
  const int nx = detail::expansion_product(2, dax, 2, dbx, px, work);
  const int ny = detail::expansion_product(2, day, 2, dby, py, work);
  const int n = detail::fast_expansion_sum_zeroelim(nx, px, ny, py, sum);
  return detail::signed_estimate(n, sum);
}

namespace {

// The coarsest multiple of a power-of-two multiple of `unit` (the input's
// unit length) in the middle of [lo, hi], at least 1 - 1/sqrt2 of the way
// from either end (for lo = 0, the concentric shell). Splits of the segments
// around one apex then all fall on one nested set of radii: vertices of
// neighbouring segments sit at equal radii or as far apart as the
// subsegments they split. Midpoints of subsegments of unequal segments drift
// into pairs of radii far closer than the local feature size; the short
// edges between them make skinny triangles whose splits, mirrored around the
// apex, cascade (hubs of many spokes of random lengths ran to the budget).
double grid_radius(double lo, double hi, double unit) {
  const double margin = (1.0 - 0.5 * std::numbers::sqrt2) * (hi - lo);
  const double l = lo + margin, h = hi - margin;
  int ex;
  std::frexp(hi / unit, &ex);  // hi < unit 2^ex, up to rounding
  for (double step = std::ldexp(unit, ex + 1); step > 0; step *= 0.5) {
    // A radius already on the grid (m step, rounded) must give m again:
    // h / step is rounded too, so the floor allows a relative 2^-40.
    const double r = std::floor(h / step * (1 + 0x1p-40)) * step;
    if (r >= l) return r;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

// Subsegment e is encroached by the vertex opposite it on either side.
bool Refiner::encroached(HalfEdgeId e) const {
  const Point& a = pts_[tv_[e]];
  const Point& b = pts_[tv_[next_edge(e)]];
  if (encroaches(a, b, pts_[tv_[prev_edge(e)]])) return true;
  const HalfEdgeId f = tw_[e];
  return f != kNone && encroaches(a, b, pts_[tv_[prev_edge(f)]]);
}

// Subsegment e may be split when -Y/-YY allow it (Protected otherwise)
// and its split point is a new point (Precision: it rounds onto an end).
Reason Refiner::split_refusal(HalfEdgeId e) const {
  if (fl_[e] & detail::kFrozenEdge) return Reason::Protected;  // a cut of refine_in_parts
  switch (opt_.segment_splitting) {
    case SegmentSplitting::All: break;
    case SegmentSplitting::InteriorOnly:
      if (tw_[e] == kNone) return Reason::Protected;
      break;
    case SegmentSplitting::None: return Reason::Protected;
  }
  const Point& a = pts_[tv_[e]];
  const Point& b = pts_[tv_[next_edge(e)]];
  const Point m = segment_split_point(tv_[e], tv_[next_edge(e)]);
  return m == a || m == b ? Reason::Precision : Reason::None;
}

// R1's trigger after an insertion: subsegment e (if it is one) is pushed on
// the encroached stack when `apex` encroaches it and it may be split.
void Refiner::push_if_encroached(HalfEdgeId e, VertexId apex) {
  if (!(fl_[e] & kConstrained)) return;
  const VertexId a = tv_[e], b = tv_[next_edge(e)];
  if (!encroaches(pts_[a], pts_[b], pts_[apex])) return;
  if (!splittable(e)) return;
  encroached_.push_back({a, b, e});
}

// Where subsegment ab is split: on a concentric shell (a power-of-two
// distance) around its input-vertex end when exactly one end is an input
// vertex with a small domain angle, so that the splits of segments meeting at
// that apex stay at equal distances from it and never encroach each other;
// otherwise the midpoint.
Point Refiner::segment_split_point(VertexId a, VertexId b) const {
  const Point& A = pts_[a];
  const Point& B = pts_[b];
  const bool ain = a < n_input_, bin = b < n_input_;
  if (opt_.small_angle_protection && ain != bin && apex_cos_[ain ? a : b] > shell_cos_) {
    const Point& apex = ain ? A : B;
    const Point& other = ain ? B : A;
    const double len = std::sqrt(dist2(apex, other));
    const double half = 0.5 * len;
    // The shells' radii are unit_ times powers of two (a scale of the input
    // scales them with it): the one nearest half, up to sqrt2.
    int ex;
    std::frexp(half / unit_, &ex);  // half / unit_ = f 2^ex, f in [0.5, 1)
    double shell = std::ldexp(unit_, ex - 1);
    while (shell > half) shell *= 0.5;  // shell <= half < 2 shell, whatever the rounding
    while (shell > 0 && 2 * shell <= half) shell *= 2;
    if (half > shell * std::numbers::sqrt2) shell *= 2;
    const double f = shell / len;
    return within_predicate_range({apex.x + (other.x - apex.x) * f, apex.y + (other.y - apex.y) * f});
  }
  // Subsegments further out, on a segment in a narrow wedge (one with
  // mirrored partners) at an apex of three or more segments (a hub): on the
  // grid of radii around that apex. At a spike's tip (two segments) the
  // channel rule copes and midpoints grade better.
  if (opt_.small_angle_protection && !(ain && bin)) {
    const std::uint32_t s = seg_of_[ain ? b : a];
    if (s != kNone) {
      VertexId apex = kNone;
      double nearest = INFINITY;
      for (int end = 0; end < 2; ++end) {
        const VertexId w = segs_[s][end];
        if (w == a || w == b || partners_[2 * s + end][0] == kNone ||
            adj_start_[w + 1] - adj_start_[w] < 3)
          continue;
        const double d = std::min(dist2(pts_[w], A), dist2(pts_[w], B));
        if (d < nearest) nearest = d, apex = w;
      }
      if (apex != kNone) {
        const Point& P = pts_[apex];
        const Point& O = pts_[segs_[s][0] == apex ? segs_[s][1] : segs_[s][0]];
        const double ra = std::sqrt(dist2(P, A)), rb = std::sqrt(dist2(P, B));
        const double f = grid_radius(std::min(ra, rb), std::max(ra, rb), unit_) / std::sqrt(dist2(P, O));
        return within_predicate_range({P.x + (O.x - P.x) * f, P.y + (O.y - P.y) * f});
      }
    }
  }
  return within_predicate_range({0.5 * (A.x + B.x), 0.5 * (A.y + B.y)});
}

// A boundary segment's rounded split point may fall outside the domain,
// and where pieces of the domain touch (a vertex shared by separate fans, a
// nearly collinear boundary edge of another piece) inside a neighbouring
// piece: the new triangles would overlap it. Keeps m on the segment or
// inside, strictly between a and b (exact tests): m itself or the nearest
// double at most two ulps away per coordinate; false when none is.
bool Refiner::keep_split_inside(HalfEdgeId e, Point& m) const {
  const Point& a = pts_[tv_[e]];
  const Point& b = pts_[tv_[next_edge(e)]];
  const Point& apex = pts_[tv_[prev_edge(e)]];
  auto inside = [&](const Point& c) {
    return orient2d(a, b, c) >= 0 && orient2d(b, apex, c) > 0 && orient2d(apex, a, c) > 0 && diametral_dot(a, b, c) < 0;
  };
  if (inside(m)) return true;
  auto step = [](double v, int k) {
    for (; k > 0; --k) v = std::nextafter(v, INFINITY);
    for (; k < 0; ++k) v = std::nextafter(v, -INFINITY);
    return v;
  };
  for (int r = 1; r <= 2; ++r)
    for (int d = 1; d <= 2 * r; ++d)  // nearest first: axis steps, then diagonals
      for (int dx = -r; dx <= r; ++dx)
        for (int dy = -r; dy <= r; ++dy) {
          if (std::max(std::abs(dx), std::abs(dy)) != r || std::abs(dx) + std::abs(dy) != d) continue;
          const Point c{step(m.x, dx), step(m.y, dy)};
          if (inside(c)) {
            m = c;
            return true;
          }
        }
  return false;
}

}  // namespace deltamesh::refinement
