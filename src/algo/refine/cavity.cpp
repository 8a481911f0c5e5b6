// Point location and Bowyer-Watson cavities of Delaunay refinement. The
// cavity kernel (find and commit) is mesh/cavity.hpp; here are the parts
// refinement adds: what a boundary edge records (its marker and the area
// bound of the triangle inside), the cavities of segment splits (both sides
// of the segment), and the visibility check. The cavity is found read-only,
// so the same search tells whether the point encroaches a segment (R2's
// rejection) before anything changes; insert.cpp commits it.
#include <cmath>

#include "algo/refine/refiner.hpp"
#include "deltamesh/predicates.hpp"
#include "mesh/locate.hpp"

namespace deltamesh::refinement {

// Point location for a Steiner point c near triangle t: the straight walk
// (mesh kernel walk_line) along the ray from a point inside t to c. Stops in
// the triangle holding c, or at the first segment (or boundary edge) the ray
// crosses. A vertex exactly on the ray counts as left of it (PointTarget).
Refiner::Walk Refiner::walk(TriId t, const Point& c) const {
  Walk w;
  const HalfEdgeId b0 = 3 * t;
  const Point& A = pts_[tv_[b0]];
  const Point& B = pts_[tv_[b0 + 1]];
  const Point& C = pts_[tv_[b0 + 2]];
  {
    const double o0 = orient2d(A, B, c), o1 = orient2d(B, C, c), o2 = orient2d(C, A, c);
    if (o0 >= 0 && o1 >= 0 && o2 >= 0) {
      w.tri = t;
      if (c == A || c == B || c == C) {
        w.kind = Walk::OnVertex;
        return w;
      }
      w.kind = Walk::Found;
      if (o0 == 0) w.edge = b0;
      else if (o1 == 0) w.edge = b0 + 1;
      else if (o2 == 0) w.edge = b0 + 2;
      return w;
    }
  }
  Point o{(A.x + B.x + C.x) / 3.0, (A.y + B.y + C.y) / 3.0};
  auto inside = [&](const Point& p) { return orient2d(A, B, p) > 0 && orient2d(B, C, p) > 0 && orient2d(C, A, p) > 0; };
  if (!inside(o)) {
    // A sliver whose centroid rounds out of it (a tiny edge seen from a far
    // corner: inside, only points near that edge have the precision to be
    // strictly inside): start a quarter of the edge's length in from it.
    const Point* v[3] = {&A, &B, &C};
    int s = 0;
    double lo = dist2(A, B);
    if (dist2(B, C) < lo) lo = dist2(B, C), s = 1;
    if (dist2(C, A) < lo) lo = dist2(C, A), s = 2;
    const Point &P = *v[s], &Q = *v[(s + 1) % 3], &R = *v[(s + 2) % 3];
    const Point m{P.x + 0.5 * (Q.x - P.x), P.y + 0.5 * (Q.y - P.y)};
    const double f = 0.25 * std::sqrt(lo / dist2(m, R));
    o = {m.x + (R.x - m.x) * f, m.y + (R.y - m.y) * f};
    if (!inside(o)) {
      w.kind = Walk::Failed;
      return w;
    }
  }
  const HalfEdgeId exit = detail::line_exit(tv_.data(), pts_.data(), t, o, c);
  if (exit == kNone) {
    w.kind = Walk::Failed;
    return w;
  }
  detail::PointTarget target{c};
  const detail::SegmentWalk r = detail::walk_line(
      tv_.data(), tw_.data(), pts_.data(), o, c, target, exit,
      [this](HalfEdgeId h) { return tw_[h] != kNone && !(fl_[h] & kConstrained); }, tv_.size());
  switch (r.kind) {
    case detail::SegmentWalk::Kind::Stopped:
      w.kind = Walk::Blocked;
      w.tri = tri_of(r.edge);
      w.edge = r.edge;
      return w;
    case detail::SegmentWalk::Kind::Reached: {
      // c is in the triangle the walk ended in, on its exit edge when side == 0.
      const HalfEdgeId e = r.edge;
      w.tri = tri_of(e);
      if (c == pts_[tv_[e]] || c == pts_[tv_[next_edge(e)]] || c == pts_[tv_[prev_edge(e)]]) {
        w.kind = Walk::OnVertex;
        return w;
      }
      w.kind = Walk::Found;
      if (target.side == 0) w.edge = e;
      return w;
    }
    default:  // LeftHull cannot happen (a compacted mesh has no ghosts); Overrun: a broken mesh
      w.kind = Walk::Failed;
      return w;
  }
}

inline void Refiner::record_boundary(HalfEdgeId e) {
  BoundaryEdge b;
  b.a = tv_[e];
  b.b = tv_[next_edge(e)];
  b.inner = e;
  b.outer = tw_[e];
  b.flags = fl_[e];
  b.marker = has_markers_ ? mk_[e] : 0;
  b.area_bound = carry_bounds_ ? m_.triangle_area_bound(tri_of(e)) : -1.0;
  bnd_.push_back(b);
}

// Growth of the cavity from the half-edges on stack_ (the mesh kernel);
// boundary edges are recorded in counter-clockwise order.
bool Refiner::grow(const Point& c) {
  return detail::grow_cavity(arrays(), c, cav_, stack_, [this](HalfEdgeId e) { record_boundary(e); });
}

bool Refiner::boundary_visible(const Point& c, std::size_t from, std::size_t to) const {
  for (std::size_t i = from; i < to; ++i)
    if (!(orient2d(pts_[bnd_[i].a], pts_[bnd_[i].b], c) > 0)) return false;
  return true;
}

bool Refiner::in_circumcircle(TriId t, const Point& p) const {
  return incircle(pts_[tv_[3 * t]], pts_[tv_[3 * t + 1]], pts_[tv_[3 * t + 2]], p) > 0;
}


// Cavity of point m splitting the constrained edge e = (a -> b): side one
// (e's triangle) then side two (its twin's), each boundary running b ... a
// and a ... b respectively. Both triangles of e join only when m lies
// strictly inside their circumcircles (exact incircle), like every other
// triangle: m is rounded and may lie off the segment's line, and a
// far-side triangle whose circle misses it would keep an edge that is not
// locally Delaunay against m. Then the split fails.
bool Refiner::split_cavity(HalfEdgeId e, const Point& m) {
  begin_cavity();
  if (!in_circumcircle(tri_of(e), m)) return false;
  add_to_cavity(tri_of(e));
  stack_.push_back(prev_edge(e));
  stack_.push_back(next_edge(e));
  if (!grow(m)) return false;
  side_split_ = bnd_.size();
  const HalfEdgeId f = tw_[e];
  if (f != kNone) {
    if (!in_circumcircle(tri_of(f), m)) return false;
    add_to_cavity(tri_of(f));
    stack_.push_back(prev_edge(f));
    stack_.push_back(next_edge(f));
    if (!grow(m)) return false;
  }
  return boundary_visible(m, 0, bnd_.size());
}

}  // namespace deltamesh::refinement
