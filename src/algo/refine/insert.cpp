// Mesh updates of Delaunay refinement: a point inserted into its cavity
// (cavity.cpp) as a fan of triangles, and a subsegment split in two with the
// fans on both of its sides. The cavity's triangle slots are rewritten and
// new ones appended; every new triangle is considered for the queue and its
// subsegments for encroachment.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "algo/refine/refiner.hpp"

namespace deltamesh::refinement {

// The arrays a fan writes (mesh/cavity.hpp): flags always, markers when the
// mesh has them.
constexpr unsigned kFanCarry = detail::kCarryFlags | detail::kCarryMarkers;

VertexId Refiner::new_vertex(const Point& p, std::uint32_t seg, int marker) {
  const auto v = static_cast<VertexId>(pts_.size());
  pts_.push_back(p);
  ve_.push_back(kNone);
  seg_of_.push_back(seg);
  if (!m_.vertex_markers().empty()) m_.vertex_markers().push_back(marker);
  const std::size_t na = m_.num_vertex_attributes();
  if (na > 0) m_.vertex_attributes().resize(m_.vertex_attributes().size() + na, 0.0);
  ++st_.steiner_points;
  return v;
}

// A new triangle slot (vertices v, v, v until written), for a fan larger
// than its cavity.
TriId Refiner::new_slot(VertexId v) {
  if (!carry_bounds_ && m_.num_triangle_attributes() == 0) {
    // The arrays this refinement touches, grown by hand (Mesh::add_triangle
    // also handles bounds and attributes, at a cost per call).
    const auto t = static_cast<TriId>(tv_.size() / 3);
    tv_.resize(tv_.size() + 3, v);
    tw_.resize(tw_.size() + 3, kNone);
    fl_.resize(fl_.size() + 3, 0);
    if (has_markers_) mk_.resize(mk_.size() + 3, 0);
    ++appended_;
    return t;
  }
  return m_.add_triangle(v, v, v);  // resizes every per-triangle array
}

// Triangle attributes of the fan fan_[0..n): each new triangle takes those
// of the cavity triangle on its boundary edge, as area bounds do. A segment
// split's cavity spans both sides of the segment, so slots (and the
// attributes they held) pass from one region to the other; regional
// attributes (-A) must not leak across it.
void Refiner::carry_attributes() {
  const std::size_t na = m_.num_triangle_attributes();
  if (na == 0) return;
  std::vector<double>& at = m_.triangle_attributes();
  const std::size_t n = bnd_.size();
  attr_scratch_.resize(n * na);
  for (std::size_t i = 0; i < n; ++i)  // read every source before writing any slot
    for (std::size_t k = 0; k < na; ++k) attr_scratch_[i * na + k] = at[tri_of(bnd_[i].inner) * na + k];
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < na; ++k) at[fan_[i] * na + k] = attr_scratch_[i * na + k];
}

// Interpolated attributes for a new vertex: barycentric in the seed triangle.
static void interpolate_attributes(Mesh& m, VertexId v, const VertexId (&tri)[3], const Point& p) {
  const std::size_t na = m.num_vertex_attributes();
  if (na == 0) return;
  const Point& a = m.point(tri[0]);
  const Point& b = m.point(tri[1]);
  const Point& c = m.point(tri[2]);
  const double det = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  double wb = det != 0 ? ((p.x - a.x) * (c.y - a.y) - (p.y - a.y) * (c.x - a.x)) / det : 0.0;
  double wc = det != 0 ? ((b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x)) / det : 0.0;
  double wa = 1.0 - wb - wc;
  std::vector<double>& at = m.vertex_attributes();
  for (std::size_t k = 0; k < na; ++k)
    at[v * na + k] = wa * at[tri[0] * na + k] + wb * at[tri[1] * na + k] + wc * at[tri[2] * na + k];
}

// Inserts c, whose cavity is in cav_/bnd_, as a fan of triangles.
void Refiner::insert_interior(const Point& c, TriId seed) {
  const VertexId seed_v[3] = {tv_[3 * seed], tv_[3 * seed + 1], tv_[3 * seed + 2]};
  const VertexId v = new_vertex(c, kNone, 0);
  interpolate_attributes(m_, v, seed_v, c);
  ++st_.interior_points;
  const std::size_t n = bnd_.size();
  fan_.resize(n);
  for (std::size_t i = 0; i < n; ++i) fan_[i] = i < cav_.size() ? cav_[i] : new_slot(v);
  // The fan in slot order from the cavity's lowest-numbered boundary
  // vertex: the result depends on the cavity only, not on the triangle its
  // search started from. A point on an edge (a right triangle's
  // circumcentre) is found on either side by rounding, and a copy of the
  // input scaled by 10^k must still get the same queue order and numbering.
  // (The test hook's 2 keeps the search's order: another order, same work.)
  if (perturb_ != 2) [[likely]] {
    std::sort(fan_.begin(), fan_.begin() + static_cast<std::ptrdiff_t>(std::min(n, cav_.size())));
    const auto lowest = std::min_element(bnd_.begin(), bnd_.end(), [](const BoundaryEdge& x, const BoundaryEdge& y) { return x.a < y.a; });
    std::rotate(bnd_.begin(), lowest, bnd_.end());
  }
  // Vertices whose out-edge lies in the cavity get the fan's outer edge.
  for (std::size_t i = 0; i < n; ++i) {
    const HalfEdgeId oe = ve_[bnd_[i].a];
    if (oe == kNone || in_cavity(tri_of(oe))) ve_[bnd_[i].a] = 3 * fan_[i] + 1;
  }
  const detail::MeshArrays arrays = this->arrays();  // (after new_slot)
  for (std::size_t i = 0; i < n; ++i) {  // a closed fan: v is inside the cavity
    const BoundaryEdge& b = bnd_[i];
    detail::write_fan_triangle<kFanCarry>(arrays, fan_[i], v, b.a, b.b, b.outer, b.flags, b.marker);
    detail::link_spoke(arrays.tw, fan_[i], fan_[i + 1 == n ? 0 : i + 1]);
    if (carry_bounds_) m_.set_triangle_area_bound(fan_[i], b.area_bound);
  }
  ve_[v] = 3 * fan_[0];
  carry_attributes();
  if (trace_) [[unlikely]] trace_fan(TraceKind::SplitTriangle, v, kNone, kNone);
  if (!first_bad_.empty()) [[unlikely]] look_again_at_fan(n);
  for (std::size_t i = 0; i < n; ++i) {
    consider(fan_[i]);
    if (bnd_[i].flags & kConstrained) push_if_encroached(3 * fan_[i] + 1, v);
  }
}

// Splits the constrained edge e = (a -> b) at its split point (or at `at`,
// for a mirrored split; depth counts the mirrors that led here).
bool Refiner::split_segment(HalfEdgeId e, const Point* at, int depth) {
  const VertexId a = tv_[e], b = tv_[next_edge(e)];
  Point mp = at ? *at : segment_split_point(a, b);
  const int marker = has_markers_ ? mk_[e] : 0;
  const std::uint8_t flags = fl_[e];
  const bool boundary = tw_[e] == kNone;
  if ((boundary && !keep_split_inside(e, mp)) || !split_cavity(e, mp)) {
    // The split point is off the segment's line by rounding and some
    // neighbouring triangle is too flat to take it: leave this segment.
    ++st_.failed_splits;
    return false;
  }
  const std::uint32_t seg = segment_of(a, b);
  int vmarker = marker != 0 ? marker : (boundary ? 1 : 0);
  const VertexId v = new_vertex(mp, seg, vmarker);
  {
    const std::size_t na = m_.num_vertex_attributes();
    if (na > 0) {
      std::vector<double>& at = m_.vertex_attributes();
      const double la = std::sqrt(dist2(mp, pts_[a])), lb = std::sqrt(dist2(mp, pts_[b]));
      const double wa = la + lb > 0 ? lb / (la + lb) : 0.5;
      for (std::size_t k = 0; k < na; ++k) at[v * na + k] = wa * at[a * na + k] + (1 - wa) * at[b * na + k];
    }
  }
  ++st_.segment_splits;
  const std::size_t n = bnd_.size();
  const std::size_t n1 = side_split_;  // side one: boundary edges [0, n1), b ... a
  fan_.resize(n);
  // Slots: side one uses its cavity slots first; new slots fill up as needed.
  // Any assignment works as long as every cavity slot is reused.
  for (std::size_t i = 0; i < n; ++i) fan_[i] = i < cav_.size() ? cav_[i] : new_slot(v);
  for (std::size_t i = 0; i < n; ++i) {
    const HalfEdgeId oe = ve_[bnd_[i].a];
    if (oe == kNone || in_cavity(tri_of(oe))) ve_[bnd_[i].a] = 3 * fan_[i] + 1;
  }
  if (boundary) {
    const HalfEdgeId oe = ve_[a];
    if (oe == kNone || in_cavity(tri_of(oe))) ve_[a] = 3 * fan_[n1 - 1] + 2;
  }
  const detail::MeshArrays arrays = this->arrays();  // (after new_slot)
  for (std::size_t i = 0; i < n; ++i) {
    const BoundaryEdge& bd = bnd_[i];
    detail::write_fan_triangle<kFanCarry>(arrays, fan_[i], v, bd.a, bd.b, bd.outer, bd.flags, bd.marker);
    if (carry_bounds_) m_.set_triangle_area_bound(fan_[i], bd.area_bound);
  }
  // Two open fans, one per side of the segment, joined along it below.
  detail::link_spokes(arrays.tw, fan_.data(), 0, n1, /*closed=*/false);
  detail::link_spokes(arrays.tw, fan_.data(), n1, n, /*closed=*/false);
  auto seg_edge = [&](HalfEdgeId h) {
    fl_[h] = flags;
    if (has_markers_) mk_[h] = marker;
  };
  const HalfEdgeId mb1 = 3 * fan_[0], am1 = 3 * fan_[n1 - 1] + 2;  // m->b, a->m on side one
  seg_edge(mb1);
  seg_edge(am1);
  if (boundary) {
    tw_[mb1] = kNone;
    tw_[am1] = kNone;
  } else {
    const HalfEdgeId ma2 = 3 * fan_[n1], bm2 = 3 * fan_[n - 1] + 2;  // m->a, b->m on side two
    seg_edge(ma2);
    seg_edge(bm2);
    tw_[am1] = ma2;
    tw_[ma2] = am1;
    tw_[mb1] = bm2;
    tw_[bm2] = mb1;
  }
  ve_[v] = mb1;
  carry_attributes();
  if (trace_) [[unlikely]] trace_fan(TraceKind::SplitSegment, v, a, b);
  if (!first_bad_.empty()) [[unlikely]] look_again_at_fan(n);
  for (std::size_t i = 0; i < n; ++i) {
    consider(fan_[i]);
    if (bnd_[i].flags & kConstrained) push_if_encroached(3 * fan_[i] + 1, v);
  }
  // The two new subsegments against the apexes next to them.
  push_if_encroached(mb1, tv_[prev_edge(mb1)]);
  push_if_encroached(am1, tv_[prev_edge(am1)]);
  if (!boundary) {
    const HalfEdgeId ma2 = tw_[am1], bm2 = tw_[mb1];
    push_if_encroached(ma2, tv_[prev_edge(ma2)]);
    push_if_encroached(bm2, tv_[prev_edge(bm2)]);
  }
  // Segments that bound a small angle with this one get a vertex at the
  // same distance from the apex: vertices at equal radii never encroach
  // the partner's subsegments, where unequal ones would start a cascade of
  // splits down to the width of the wedge.
  if (opt_.small_angle_protection && seg != kNone && seg_small_[seg] && depth < 4) {
    for (int end = 0; end < 2; ++end) {
      if (!(seg_small_[seg] & (1 << end))) continue;
      const VertexId apex = segs_[seg][end];
      const double radius = std::sqrt(dist2(mp, pts_[apex]));
      const double piece2 = std::min(dist2(mp, pts_[a]), dist2(mp, pts_[b]));
      for (std::uint32_t partner : partners_[2 * seg + end]) {
        if (partner == kNone) continue;
        // Pieces shorter than the gap to the partner there do not encroach
        // it: mirroring them would carry fine splits made for some other
        // feature (a crossing further out) to where the partner needs none.
        if (piece2 < gap2(seg, partner, apex, radius)) continue;
        mirror_split(partner, apex, radius, depth + 1);
      }
    }
  }
  return true;
}

// ---- the trace --------------------------------------------------------------

// R1 for subsegment e: the apex that encroaches it is the cause.
void Refiner::trace_r1(HalfEdgeId e) {
  cause_ = detail::trace_event(TraceKind::SplitSegment, TraceReason::Encroached);
  const Point& a = pts_[tv_[e]];
  const Point& b = pts_[tv_[next_edge(e)]];
  const VertexId c = tv_[prev_edge(e)];
  const HalfEdgeId f = tw_[e];
  cause_.other = encroaches(a, b, pts_[c]) || f == kNone ? c : tv_[prev_edge(f)];
}

// R2 for bad triangle t at decision_.c: inserted, rejected, or the cause
// of a subsegment split.
void Refiner::trace_r2(TriId t, TraceKind kind, TraceReason why) {
  TraceEvent ev = detail::trace_event(kind, why);
  ev.tri = {tv_[3 * t], tv_[3 * t + 1], tv_[3 * t + 2]};
  if (kind != TraceKind::SplitTriangle) {
    ev.at = decision_.c;
    ev.has_at = true;
  }
  if (kind == TraceKind::Reject)
    detail::TraceAccess::plain(*trace_, ev);
  else
    cause_ = ev;
}

// The fan of new vertex v written into fan_ (every cavity slot among them);
// a-b: the subsegment split. The cause set before, else none given.
void Refiner::trace_fan(TraceKind kind, VertexId v, VertexId a, VertexId b) {
  TraceEvent ev = cause_.kind == kind ? cause_ : detail::trace_event(kind, TraceReason::None);
  cause_ = TraceEvent{};
  ev.vertex = v;
  ev.point = pts_[v];
  if (kind == TraceKind::SplitSegment) {
    ev.edge = {a, b, kNone, kNone};
    ev.tri = {kNone, kNone, kNone};
  }
  detail::TraceAccess::slots(*trace_, ev, tv_.data(), fan_);
}

}  // namespace deltamesh::refinement
