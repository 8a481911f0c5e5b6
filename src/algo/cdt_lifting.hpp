// Flip ordering through the lifting map (seed §2.3) for inserting segment ab
// into a constrained Delaunay triangulation.
//
// 1. The seed's event time, equation (1). Lowering the heights of a and b by
//    t, a crossing edge cd has its event when a', b', c', d' become coplanar:
//
//      det | ax ay ax²+ay²-t 1 |
//          | bx by bx²+by²-t 1 |  =  D - t K = 0,   t(c,d) = D / K,
//          | cx cy cx²+cy²   1 |
//          | dx dy dx²+dy²   1 |
//
//    D = incircle determinant of a, b, c, d; K = (by-ay)(dx-cx) - (bx-ax)(dy-cy).
//    t is the vertical gap, above the point where cd crosses ab, between the
//    lifted segment a'b' and the lifted edge c'd'. Flipping the crossing edges
//    in this order does NOT always give the CDT (lowering a and b changes
//    which triangles are regular on both sides of ab; test_cdt.cpp has a
//    two-edge counterexample), so the method uses the motion below; these
//    functions remain for that demonstration.
//
// 2. The motion the Lifting method simulates. Every vertex v on the right of
//    ab rises by t |orient2d(a, b, v)| (proportional to its distance from the
//    line ab); a, b and the left side stay. On each side the heights differ
//    from the paraboloid by an affine function, which changes no regular
//    triangulation, so the final triangulation of each side is its
//    constrained Delaunay one; and as t grows, the crease along ab makes ab
//    an edge. Restricted to the cavity (the triangles crossing ab, boundary
//    fixed), the triangulation changes by flips, each when the four lifted
//    points of an edge's quadrilateral become coplanar:
//
//      Delta(t) = det | x-q  |x-q|² + t (s(x)-s(q)) |
//                     | y-q  |y-q|² + t (s(y)-s(q)) |  =  R0 + t R1,
//                     | p-q  |p-q|² + t (s(p)-s(q)) |
//
//    for edge xy with apex p (triangle x y p counter-clockwise) and opposite
//    apex q, s(v) = -orient2d(a, b, v) on the right of ab and 0 elsewhere.
//    Delta > 0 means q is inside the (lifted) circle of xyp: the edge is to be
//    flipped at t = -R0 / R1 when R1 > 0 (never when R1 <= 0). The added
//    height is a convex function of the position (|distance| up to an affine
//    term), so a vertex inside the triangle of the other three never reaches
//    their plane: every event is at a strictly convex quadrilateral. Quads
//    wholly on one side have R1 = 0 exactly.
//
// Times are compared exactly: floating-point intervals first, and when two
// overlap, the sign of a cross-multiplied difference in expansion arithmetic.
#pragma once
#include <cstdint>

#include "deltamesh/geometry.hpp"

namespace deltamesh::detail {

struct EventTime {
  double t = 0.0;   // approximation of the exact time
  double lo = 0.0;  // the exact time lies in [lo, hi] (infinite when unknown)
  double hi = 0.0;
};

// ---- 1. the seed's equation (1) ----

// The interval of t(c,d) = D / K for segment ab.
EventTime seed_event_time(const Point& a, const Point& b, const Point& c, const Point& d);
// Exact sign of t(c1,d1) - t(c2,d2) for segment ab (both K nonzero).
int compare_seed_event_times(const Point& a, const Point& b, const Point& c1, const Point& d1, const Point& c2,
                             const Point& d2);

// ---- 2. the kinetic flips ----

// The four vertices of an edge's quadrilateral (x->y with apex p, opposite
// apex q) and, per vertex, whether it lies strictly right of ab (exact).
struct Quad {
  Point x, y, p, q;
  bool rx, ry, rp, rq;
};

struct KineticEvent {
  bool happens = false;  // R1 > 0 (exactly)
  EventTime time;        // of -R0 / R1, when it happens
};

KineticEvent kinetic_event(const Point& a, const Point& b, const Quad& quad);
// Exact sign of time(q1) - time(q2) (both events happen).
int compare_kinetic_times(const Point& a, const Point& b, const Quad& q1, const Quad& q2);

inline int compare_times(const EventTime& e1, const EventTime& e2) {
  if (e1.hi < e2.lo) return -1;
  if (e2.hi < e1.lo) return 1;
  return 0;  // undecided: compare exactly
}

}  // namespace deltamesh::detail
