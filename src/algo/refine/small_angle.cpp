// The small-angle rules of Delaunay refinement: without them, Ruppert's
// algorithm need not terminate when segments meet at angles under 60°.
//  - Skinny triangles in a small input angle are left alone, after G. L.
//    Miller, S. E. Pav, N. J. Walkington, "When and why Ruppert's algorithm
//    works", IMR 2003: one whose shortest edge joins two segments meeting at
//    a small angle (wedges under kWedgeAngle), or that holds an input angle
//    under the bound.
//  - Segment splits that would cascade into a small angle are refused
//    (J. R. Shewchuk, "Delaunay refinement algorithms for triangular mesh
//    generation", CGTA 2002), and splits in a narrow wedge are mirrored on
//    its other side at the same radius (with the concentric shells of
//    encroachment.cpp); at a hub's apex, no split below a fraction of
//    the apex's local feature size for a triangle inside the small angle
//    (refuse_split_near_apex: the shells are copies of each other, so a
//    cascade down them would not end).
//  - Thin channels between the two sides of a spike (a wedge under
//    kWedgeAngle whose sides run on, nearly antiparallel, through gentle
//    bends) are treated like the wedge itself: refining there cascades down
//    the spike (a star polygon with 1e-4 rad spikes needs ~L/gap triangles
//    per spike).
//  - R1 yields (exempt_from_r1) where splitting would only make triangles
//    these rules leave alone.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "algo/refine/refiner.hpp"

namespace deltamesh::refinement {

// Concentric shells only around input vertices with a domain angle under
// this (midpoints elsewhere). Measured on the corpus.
constexpr double kShellApexAngle = 60.0;
// A subsegment at such an apex with three or more segments (a hub) is not
// split below this fraction of the hub's local feature size for a triangle
// in a small input angle there (refuse_split_near_apex).
constexpr double kApexGuard = 1.0 / 16;
// Thin channels: the sides of a wedge under kWedgeAngle, continued through
// input vertices that bend less than kChannelBend, bound a channel where two
// of them run within kChannelParallel of each other, closer than
// 1/kChannelGap of their lengths.
constexpr double kChannelBend = 30.0;
constexpr double kChannelParallel = 10.0;
constexpr double kChannelGap = 64.0;

// Small-angle apexes: two segments at an input vertex that bound a sector
// of the domain narrower than 60° (the angle inside a hole or outside the
// domain does not count), the thresholds of the rules, and the spikes.
void Refiner::find_small_angles() {
  perturb_ = order_perturbation_for_tests;
  if (perturb_ == 1) key_scale_ *= 1 + 0x1p-40;  // the test hook (queue.hpp): bucket bounds moved
  shell_cos_ = std::cos(kShellApexAngle * std::numbers::pi / 180);
  small_cos2_ = std::cos(kWedgeAngle * std::numbers::pi / 180) * std::cos(kWedgeAngle * std::numbers::pi / 180);
  // A sector runs counter-clockwise from a constrained out-edge through
  // unconstrained edges to the next constrained edge; its angle is the sum
  // of the triangle corners in it.
  seg_small_.assign(segs_.size(), 0);
  partners_.assign(2 * segs_.size(), {kNone, kNone});
  apex_cos_.assign(n_input_, -2.0f);
  if (scan_threads_ > 1) {  // setup_scan.cpp: the same sectors, in the same order
    std::vector<Sector> sectors;
    sectors_in_parallel(sectors);
    for (const Sector& s : sectors) note_sector(s);
  } else {
    for (HalfEdgeId e0 = 0; e0 < tv_.size(); ++e0) {
      Sector s{e0, kNone, 0};
      if (sector_at(s)) note_sector(s);
    }
  }
  mark_spikes();
  measure_apex_feature_sizes();
}

// The local feature size of the input at each hub with shells (Ruppert
// 1995: here the distance to the nearest input vertex or segment that does
// not touch it), from the triangulation refinement starts from: the nearest
// vertex is a neighbour, and a segment nearer than every neighbour bounds a
// triangle of the vertex's fan.
void Refiner::measure_apex_feature_sizes() {
  apex_lfs2_.assign(n_input_, 0.0);
  has_hubs_ = false;
  if (scan_threads_ > 1) return apex_feature_sizes_in_parallel();  // setup_scan.cpp: the same, in the same order
  double d2;
  for (HalfEdgeId e = 0; e < tv_.size(); ++e)
    if (shelled_hub(tv_[e]) && apex_distance(e, d2)) note_apex_distance(tv_[e], d2);
}

// The squared distance from hub tv_[e] to what triangle tri_of(e) shows of
// the input (its neighbour, and the opposite edge when it is a segment);
// false when tv_[e] is no hub with shells, or for a ghost.
bool Refiner::apex_distance(HalfEdgeId e, double& d2) const {
  const VertexId v = tv_[e];
  if (!shelled_hub(v)) return false;
  const VertexId w = tv_[next_edge(e)], x = tv_[prev_edge(e)];
  if (w >= pts_.size() || x >= pts_.size()) return false;  // a ghost
  const Point& V = pts_[v];
  d2 = dist2(V, pts_[w]);
  if (fl_[next_edge(e)] & kConstrained) {  // the opposite edge w -> x
    const Point& W = pts_[w];
    const Point& X = pts_[x];
    const double ux = X.x - W.x, uy = X.y - W.y, l2 = ux * ux + uy * uy;
    const double f = l2 > 0 ? std::clamp(((V.x - W.x) * ux + (V.y - W.y) * uy) / l2, 0.0, 1.0) : 0.0;
    d2 = std::min(d2, dist2(V, {W.x + f * ux, W.y + f * uy}));
  }
  return true;
}

// The sector from constrained out-edge s.e0 of an input vertex: its angle
// and its closing edge s.g; false when s.e0 is no such edge or the sector
// does not close (the hull).
bool Refiner::sector_at(Sector& s) const {
  const HalfEdgeId e0 = s.e0;
  const VertexId v = tv_[e0];
  if (v >= n_input_ || !(fl_[e0] & kConstrained)) return false;
  const Point& A = pts_[v];
  double angle = 0;
  HalfEdgeId g = e0;
  bool closed = false;
  for (std::size_t guard = 0; guard < 1u << 20; ++guard) {
    const HalfEdgeId p = prev_edge(g);  // y -> v, the corner's other edge
    const Point& X = pts_[tv_[next_edge(g)]];
    const Point& Y = pts_[tv_[p]];
    const double ux = X.x - A.x, uy = X.y - A.y, wx = Y.x - A.x, wy = Y.y - A.y;
    angle += std::atan2(std::fabs(ux * wy - uy * wx), ux * wx + uy * wy);
    if (fl_[p] & kConstrained) {
      closed = true;
      g = p;
      break;
    }
    g = tw_[p];
    if (g == kNone || g == e0) break;
  }
  s.g = g;
  s.angle = angle;
  return closed;
}

// What a closed sector tells: its apex's smallest angle, and for angles
// below 60 degrees the small-angle marks of its two segments.
void Refiner::note_sector(const Sector& s) {
  const HalfEdgeId e0 = s.e0, g = s.g;
  const VertexId v = tv_[e0];
  const double angle = s.angle;
  const float c = static_cast<float>(std::cos(std::min(angle, std::numbers::pi)));
  apex_cos_[v] = std::max(apex_cos_[v], c);
  if (angle < std::numbers::pi / 3) {
    const std::uint32_t s1 = input_segment(v, tv_[next_edge(e0)]);
    const std::uint32_t s2 = input_segment(v, tv_[g]);
    for (std::uint32_t sg : {s1, s2})
      if (sg != kNone) seg_small_[sg] |= segs_[sg][0] == v ? 1 : 2;
    // Mirrored splits only in the narrow wedges where cascades happen.
    if (s1 != kNone && s2 != kNone && s1 != s2 && angle < kWedgeAngle * std::numbers::pi / 180) {
      auto add = [&](std::uint32_t x, std::uint32_t y) {
        auto& slot = partners_[2 * x + (segs_[x][0] == v ? 0 : 1)];
        if (slot[0] == kNone) slot[0] = y;
        else if (slot[1] == kNone && slot[0] != y) slot[1] = y;
      };
      add(s1, s2);
      add(s2, s1);
      seg_spike_[s1] |= kSpikeSeg;
      seg_spike_[s2] |= kSpikeSeg;
    }
  }
}

// Spike sides: from the sides of the narrow wedges, along chains of
// segments through input vertices of two segments that bend less than
// kChannelBend (linear: every segment is marked once).
void Refiner::mark_spikes() {
  channel_sin2_ = std::sin(kChannelParallel * std::numbers::pi / 180);
  channel_sin2_ *= channel_sin2_;
  const double bend_cos = std::cos((180.0 - kChannelBend) * std::numbers::pi / 180);  // < 0
  std::vector<std::uint32_t> work;
  for (std::uint32_t s = 0; s < segs_.size(); ++s) {
    if (!(seg_spike_[s] & kBoundarySeg)) seg_spike_[s] = 0;  // channels between boundary sides only
    if (seg_spike_[s] & kSpikeSeg) work.push_back(s);
  }
  has_spikes_ = !work.empty();
  while (!work.empty()) {
    const std::uint32_t s = work.back();
    work.pop_back();
    for (const VertexId w : segs_[s]) {
      if (adj_start_[w + 1] - adj_start_[w] != 2) continue;
      const auto [x0, s0] = adj_[adj_start_[w]];
      const auto [x1, s1] = adj_[adj_start_[w] + 1];
      const std::uint32_t next = s0 == s ? s1 : s0;
      if (next == s || seg_spike_[next] != kBoundarySeg) continue;
      const Point& W = pts_[w];
      const double ux = pts_[x0].x - W.x, uy = pts_[x0].y - W.y, vx = pts_[x1].x - W.x, vy = pts_[x1].y - W.y;
      const double dot = ux * vx + uy * vy;
      // The angle at w is over 180° - kChannelBend: cos below bend_cos.
      if (!(dot < 0 && dot * dot > bend_cos * bend_cos * (ux * ux + uy * uy) * (vx * vx + vy * vy))) continue;
      seg_spike_[next] |= kSpikeSeg;
      work.push_back(next);
    }
  }
}

// Triangle t as the small-angle rules see it.
TriView Refiner::view(TriId t) const {
  TriView tv;
  tv.t = t;
  for (int i = 0; i < 3; ++i) {
    const HalfEdgeId f = 3 * t + i;
    tv.v[i] = tv_[f];
    tv.p[i] = pts_[tv_[f]];
    tv.seg[i] = tv_[f] >= n_input_ ? seg_of_[tv_[f]] : kNone;
    tv.constrained[i] = (fl_[f] & kConstrained) != 0;
  }
  return tv;
}

// The segments an apex candidate list holds for vertex v: (apex, segment)
// pairs such that v lies on the segment and the apex is its other end.
void Refiner::apexes(VertexId v, std::uint32_t seg, std::array<std::pair<VertexId, std::uint32_t>, 2>& two,
                     int& n, std::vector<std::pair<VertexId, std::uint32_t>>& many) const {
  n = 0;
  many.clear();
  if (v >= n_input_) {
    const std::uint32_t s = seg;
    if (s == kNone || !seg_small_[s]) return;
    if (seg_small_[s] & 1) two[n++] = {segs_[s][0], s};
    if (seg_small_[s] & 2) two[n++] = {segs_[s][1], s};
    return;
  }
  for (std::uint32_t i = adj_start_[v]; i < adj_start_[v + 1]; ++i) {
    const auto [w, s] = adj_[i];
    // v is an endpoint of s; the apex is the other endpoint w.
    const std::uint8_t bit = segs_[s][0] == w ? 1 : 2;
    if (seg_small_[s] & bit) many.push_back({w, s});
  }
}

// A skinny triangle the small-angle rules leave alone: it lies in a small
// input angle, or in a thin channel.
// holding: also a triangle that holds an input angle under the bound.
bool Refiner::faces_small_angle(const TriView& tv, const Eval& ev, bool holding) const {
  if (in_small_input_angle(tv, ev, holding)) return true;
  return has_spikes_ && in_channel(tv);
}

// After Miller, Pav and Walkington: the triangle's shortest edge joins two
// different segments that meet at an apex at an angle below kWedgeAngle, and
// the triangle lies in the wedge between them; or (holding) the triangle
// holds an input angle below the bound between two segments.
bool Refiner::in_small_input_angle(const TriView& tv, const Eval& ev, bool holding) const {
  // The triangle holds an input angle below the bound between two segments:
  // no split can remove that angle.
  for (int i = 0; i < 3 && holding; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    if (tv.v[i] >= n_input_ || !tv.constrained[i] || !tv.constrained[k]) continue;
    const Point& A = tv.p[i];
    const Point& B = tv.p[j];
    const Point& C = tv.p[k];
    const double ux = B.x - A.x, uy = B.y - A.y, wx = C.x - A.x, wy = C.y - A.y;
    const double cross = ux * wy - uy * wx, l = (ux * ux + uy * uy) * (wx * wx + wy * wy);
    if (ux * wx + uy * wy > 0 && cross * cross < sin2_bound_ * l) return true;
  }
  const int ip = ev.shortest, iq = (ev.shortest + 1) % 3, ir = (ev.shortest + 2) % 3;
  const VertexId p = tv.v[ip], q = tv.v[iq];
  std::array<std::pair<VertexId, std::uint32_t>, 2> tp, tq;
  int np = 0, nq = 0;
  thread_local std::vector<std::pair<VertexId, std::uint32_t>> mp, mq;
  apexes(p, tv.seg[ip], tp, np, mp);
  if (np == 0 && mp.empty()) return false;
  apexes(q, tv.seg[iq], tq, nq, mq);
  if (nq == 0 && mq.empty()) return false;
  for (int i = 0; i < np; ++i) mp.push_back(tp[i]);
  for (int i = 0; i < nq; ++i) mq.push_back(tq[i]);
  for (const auto& [ap, sp] : mp)
    for (const auto& [aq, sq] : mq) {
      if (ap != aq || sp == sq) continue;
      const Point& A = pts_[ap];
      const VertexId op = segs_[sp][0] == ap ? segs_[sp][1] : segs_[sp][0];
      const VertexId oq = segs_[sq][0] == aq ? segs_[sq][1] : segs_[sq][0];
      const double ux = pts_[op].x - A.x, uy = pts_[op].y - A.y;
      const double wx = pts_[oq].x - A.x, wy = pts_[oq].y - A.y;
      const double dot = ux * wx + uy * wy;
      if (!(dot > 0 && dot * dot > small_cos2_ * (ux * ux + uy * uy) * (wx * wx + wy * wy))) continue;
      // ... and the triangle lies in the wedge between them: its third
      // vertex is inside the (convex, < 60°) cone at the apex. A triangle
      // beyond the wedge's mouth is skinny for other reasons and is split.
      const VertexId r = tv.v[ir];
      // On one of the two segments (split points are off their line by rounding).
      if (r == op || r == oq || (r >= n_input_ && (tv.seg[ir] == sp || tv.seg[ir] == sq))) return true;
      const Point& R = tv.p[ir];
      const double rx = R.x - A.x, ry = R.y - A.y;
      const double side = ux * wy - uy * wx;  // orientation of the cone u -> w
      const double s1 = ux * ry - uy * rx, s2 = rx * wy - ry * wx;
      if (side > 0 ? (s1 >= 0 && s2 >= 0) : (s1 <= 0 && s2 <= 0)) return true;
    }
  return false;
}

// The spike sides vertex v lies on (a Steiner vertex: its segment).
template <class F>
void Refiner::spike_segments(VertexId v, std::uint32_t seg, F&& f) const {
  if (v >= n_input_) {
    const std::uint32_t s = seg;
    if (s != kNone && (seg_spike_[s] & kSpikeSeg)) f(s);
    return;
  }
  for (std::uint32_t i = adj_start_[v]; i < adj_start_[v + 1]; ++i)
    if (seg_spike_[adj_[i].second] & kSpikeSeg) f(adj_[i].second);
}

// Two spike sides that can bound a channel: boundary segments facing each
// other, antiparallel within kChannelParallel (two pieces of one chain run
// parallel; the sides of a notch face away, which near_channel rejects).
// gap2: the squared width allowed, 1/kChannelGap of the shorter one.
bool Refiner::channel_pair(std::uint32_t sa, std::uint32_t sb, double& gap2) const {
  if (sa == sb) return false;
  const auto [a0, a1] = segs_[sa];
  const auto [b0, b1] = segs_[sb];
  const double ux = pts_[a1].x - pts_[a0].x, uy = pts_[a1].y - pts_[a0].y;
  const double wx = pts_[b1].x - pts_[b0].x, wy = pts_[b1].y - pts_[b0].y;
  const double la2 = ux * ux + uy * uy, lb2 = wx * wx + wy * wy;
  const double cross = ux * wy - uy * wx;
  if (!(ux * wx + uy * wy < 0 && cross * cross < channel_sin2_ * la2 * lb2)) return false;
  gap2 = std::min(la2, lb2) / (kChannelGap * kChannelGap);
  return true;
}

// p lies in the strip between the two sides: on the domain side of both
// lines (up to rounding) and closer than the allowed width to each.
bool Refiner::near_channel(const Point& p, std::uint32_t sa, std::uint32_t sb, double gap2) const {
  for (const std::uint32_t s : {sa, sb}) {
    const Point& A = pts_[segs_[s][0]];
    const Point& B = pts_[segs_[s][1]];
    const double ux = B.x - A.x, uy = B.y - A.y;
    const double l2 = ux * ux + uy * uy;
    const double cross = ux * (p.y - A.y) - uy * (p.x - A.x);  // |u| times the signed distance
    const double gap_l = std::sqrt(gap2 * l2);
    if (cross < -1e-3 * gap_l || cross > gap_l) return false;
  }
  return true;
}

// A triangle in a thin channel between two spike sides (every vertex in
// the channel, some vertex on each side): it cannot be made good without
// refining the whole spike down to the channel's width, so it is left as
// an input angle's triangle is.
bool Refiner::in_channel(const TriView& tv) const {
  std::array<std::uint32_t, 4> segs[3];
  int n[3] = {0, 0, 0};
  for (int i = 0; i < 3; ++i)
    spike_segments(tv.v[i], tv.seg[i], [&](std::uint32_t s) {
      if (n[i] < 4) segs[i][n[i]++] = s;
    });
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j)
      for (int x = 0; x < n[i]; ++x)
        for (int y = 0; y < n[j]; ++y) {
          double gap2;
          const std::uint32_t sa = segs[i][x], sb = segs[j][y];
          if (!channel_pair(sa, sb, gap2)) continue;
          if (near_channel(tv.p[0], sa, sb, gap2) && near_channel(tv.p[1], sa, sb, gap2) &&
              near_channel(tv.p[2], sa, sb, gap2))
            return true;
        }
  return false;
}

// A bad triangle the small-angle rules leave as it is.
bool Refiner::left_alone(const TriView& tv, bool holding) const {
  const Eval ev = eval(tv.t, tv.p[0], tv.p[1], tv.p[2]);
  return ev.skinny && !ev.large && faces_small_angle(tv, ev, holding);
}


// Shewchuk's rule against cascades at small angles (Shewchuk 2002): a
// segment next to a small-angle apex is not split on behalf of a skinny
// triangle when the split would make a subsegment shorter than the
// triangle's shortest edge.
// And a guard at a hub (an apex with shells and three or more segments): a
// subsegment from the hub is not split into pieces shorter than kApexGuard
// times the hub's local feature size for a skinny triangle that lies inside
// an input angle under 60° there. Near the apex everything is a power-of-two copy of itself one
// shell further out, so once a skinny triangle beside the innermost shell
// asks for a split that makes the next shell, the same triangle comes back
// one shell further in, forever (a hub of 16 random spokes ran down to
// 2^-169 of its size when the queue's order moved by 2^-40). What is left
// lies in the small angle: the input angle explains it, the feature size
// bounds the work.
bool Refiner::refuse_split_near_apex(HalfEdgeId e, const Eval& ev, TriId t) const {
  if (!opt_.small_angle_protection) return false;
  const VertexId a = tv_[e], b = tv_[next_edge(e)];
  const std::uint32_t s = segment_of(a, b);
  if (s == kNone || !seg_small_[s]) return false;
  const Point m = segment_split_point(a, b);
  const double part = std::min(dist2(m, pts_[a]), dist2(m, pts_[b]));
  const Point& p0 = pts_[tv_[3 * t]];
  const Point& p1 = pts_[tv_[3 * t + 1]];
  const Point& p2 = pts_[tv_[3 * t + 2]];
  const Point g{(p0.x + p1.x + p2.x) / 3, (p0.y + p1.y + p2.y) / 3};
  if (part < ev.shortest2)  // Shewchuk's rule, for a triangle in the small angle it protects
    return ((seg_small_[s] & 1) && in_small_sector(segs_[s][0], g)) ||
           ((seg_small_[s] & 2) && in_small_sector(segs_[s][1], g));
  const bool ain = a < n_input_, bin = b < n_input_;
  if (ain == bin) return false;
  const VertexId apex = ain ? a : b;
  if (!(part < kApexGuard * kApexGuard * apex_lfs2_[apex])) return false;
  return in_small_sector(apex, g);
}

// A hub's wedge between the bound and twice the bound can keep every
// angle at the bound only without an edge from the apex into it: any such
// edge cuts it into two angles one of which stays below the bound forever
// (a best point in the annulus of a 61° wedge cut it into 30.1° + 30.9°).
// Wedges under 60° are small input angles, whose triangles the rules above
// leave anyway: this is about wedges from 60° to twice a bound over 30°.
// For a Steiner point c whose cavity (bnd_) reaches a hub's apex inside
// such a wedge: the subsegment from the apex along the wedge's side nearer
// to c in angle, which decide() splits instead (as if c encroached it),
// and the far side (far_seg) to split at the same radius, so that the
// apex's triangle in the wedge stays isosceles (unequal radii make it skinny,
// and the next point cuts the wedge one shell further in). kNone when c
// makes no such edge.
HalfEdgeId Refiner::hub_wedge_side(const Point& c, std::uint32_t& far_seg, VertexId& apex) const {
  constexpr double kTwoPi = 2 * std::numbers::pi;
  for (const BoundaryEdge& b : bnd_) {
    const VertexId v = b.a;
    if (v >= n_input_ || !(apex_lfs2_[v] > 0)) continue;  // hubs only (measure_apex_feature_sizes)
    const Point& A = pts_[v];
    const double dc = std::atan2(c.y - A.y, c.x - A.x);
    double ccw = INFINITY, cw = INFINITY;
    std::uint32_t s_ccw = kNone, s_cw = kNone;
    for (std::uint32_t i = adj_start_[v]; i < adj_start_[v + 1]; ++i) {
      const Point& O = pts_[adj_[i].first];
      double d = std::atan2(O.y - A.y, O.x - A.x) - dc;
      while (d < 0) d += kTwoPi;
      while (d >= kTwoPi) d -= kTwoPi;
      if (d < ccw) ccw = d, s_ccw = adj_[i].second;
      if (kTwoPi - d < cw) cw = kTwoPi - d, s_cw = adj_[i].second;
    }
    const double wedge = ccw + cw;
    if (!(wedge >= std::max(bound_rad_, std::numbers::pi / 3) && wedge < 2 * bound_rad_)) continue;
    const std::uint32_t s = ccw < cw ? s_ccw : s_cw;
    far_seg = ccw < cw ? s_cw : s_ccw;
    apex = v;
    const VertexId other = segs_[s][0] == v ? segs_[s][1] : segs_[s][0];
    HalfEdgeId side = kNone;
    m_.for_each_out_edge(v, [&](HalfEdgeId h) {
      const VertexId w = tv_[next_edge(h)];
      if ((fl_[h] & kConstrained) && (w == other || (w >= n_input_ && seg_of_[w] == s))) {
        side = h;
        return false;
      }
      const HalfEdgeId p = prev_edge(h);
      const VertexId x = tv_[p];
      if ((fl_[p] & kConstrained) && (x == other || (x >= n_input_ && seg_of_[x] == s))) {
        side = p;
        return false;
      }
      return true;
    });
    if (side != kNone) return side;
  }
  return kNone;
}

// A hub's narrow wedge (two neighbouring spokes under kWedgeAngle apart)
// is w = r·angle wide at radius r, and that width is its local feature
// size: a quality mesh of the cells between its sides costs 1/angle
// triangles per halving of r (a million for two spokes 1e-6 rad apart).
// The mid-wedge rule spares the cells whose crossing edge is their
// shortest; a point inserted inside a cell is not spared: its skinny
// triangles send their own points into the next cell, and so on down the
// wedge (bunches of spokes 1e-15..1e-6 rad apart, 2^26 long, at -q33:
// 236,000 Steiner points, most in one wedge 2^19 in from the tips). So a skinny
// triangle in a small input angle at the hub whose Steiner point c would
// sit in such a cell (strictly inside the wedge, nearer the apex than
// either tip, its cavity reaching both sides) is left alone, as the small
// angle explains it.
bool Refiner::leave_for_narrow_wedge(TriId t, const Point& c) const {
  auto on_cavity = [&](std::uint32_t s) {
    return std::any_of(bnd_.begin(), bnd_.end(), [&](const BoundaryEdge& o) {
      return (o.flags & kConstrained) && segment_of(o.a, o.b) == s;
    });
  };
  for (const BoundaryEdge& b : bnd_) {
    if (!(b.flags & kConstrained)) continue;
    const std::uint32_t s = segment_of(b.a, b.b);
    if (s == kNone) continue;
    for (int end = 0; end < 2; ++end) {
      const VertexId apex = segs_[s][end];
      if (!(apex_lfs2_[apex] > 0)) continue;  // hubs only
      const Point& A = pts_[apex];
      const Point& S = pts_[segs_[s][1 - end]];
      const double rc2 = dist2(c, A);
      for (const std::uint32_t p : partners_[2 * s + end]) {
        if (p == kNone) continue;
        const Point& P = pts_[segs_[p][0] == apex ? segs_[p][1] : segs_[p][0]];
        if (!(rc2 < dist2(S, A) && rc2 < dist2(P, A))) continue;
        // Strictly inside the cone A, S -> P (convex: under kWedgeAngle).
        const double side = orient2d(A, S, P);
        const double s1 = orient2d(A, S, c), s2 = orient2d(A, c, P);
        if (!(side > 0 ? (s1 > 0 && s2 > 0) : side < 0 && (s1 < 0 && s2 < 0))) continue;
        if (!on_cavity(p)) continue;
        const Point& p0 = pts_[tv_[3 * t]];
        const Point& p1 = pts_[tv_[3 * t + 1]];
        const Point& p2 = pts_[tv_[3 * t + 2]];
        if (in_small_sector(apex, {(p0.x + p1.x + p2.x) / 3, (p0.y + p1.y + p2.y) / 3})) return true;
      }
    }
  }
  return false;
}

// Whether g lies in an input angle under 60° at `apex`: between two
// segments there that are next to each other around it, at most as far
// from the apex as the longer of the two reaches.
bool Refiner::in_small_sector(VertexId apex, const Point& g) const {
  const Point& A = pts_[apex];
  const double gx = g.x - A.x, gy = g.y - A.y;
  const double dg = std::atan2(gy, gx);
  constexpr double kTwoPi = 2 * std::numbers::pi;
  double ccw = INFINITY, cw = INFINITY, reach_ccw = 0, reach_cw = 0;
  for (std::uint32_t i = adj_start_[apex]; i < adj_start_[apex + 1]; ++i) {
    const Point& O = pts_[adj_[i].first];
    const double ox = O.x - A.x, oy = O.y - A.y;
    double d = std::atan2(oy, ox) - dg;
    while (d < 0) d += kTwoPi;
    while (d >= kTwoPi) d -= kTwoPi;
    const double len2 = ox * ox + oy * oy;
    if (d < ccw) ccw = d, reach_ccw = len2;
    if (kTwoPi - d < cw) cw = kTwoPi - d, reach_cw = len2;
  }
  return ccw + cw < std::numbers::pi / 3 && gx * gx + gy * gy <= std::max(reach_ccw, reach_cw);
}

// Rule R1 yields when splitting the subsegment would only make triangles
// the small-angle rules leave alone anyway: on each side where a vertex
// encroaches, both halves of its triangle, by the mid-wedge rule (wedges
// under kWedgeAngle) or the channel rule. Splitting would start the cascade
// those rules avoid (in a thin channel, every subsegment of a side is
// encroached from across; a narrow wedge's side by the other side's end).
// Not with conforming Delaunay, which needs every split.
bool Refiner::exempt_from_r1(HalfEdgeId e) const {
  if (!opt_.small_angle_protection || opt_.conforming_delaunay) return false;
  const VertexId a = tv_[e], b = tv_[next_edge(e)];
  const Point& A = pts_[a];
  const Point& B = pts_[b];
  const std::uint32_t seg = segment_of(a, b);
  const Point m = segment_split_point(a, b);
  const auto mv = static_cast<VertexId>(pts_.size());  // the vertex the split would add
  bool any = false;
  for (const HalfEdgeId f : {e, tw_[e]}) {
    if (f == kNone || !encroaches(A, B, pts_[tv_[prev_edge(f)]])) continue;
    const VertexId w = tv_[prev_edge(f)];
    // Not where that vertex is itself an apex of angles under 60°: the
    // shells around it refine there anyway, and the unsplit subsegment
    // then drives a cascade into the apex (seen on ne110m_land at -q33).
    if (w < n_input_ && apex_cos_[w] > shell_cos_) return false;
    // f = x -> y with apex w becomes x -> m -> w and m -> y -> w.
    const TriView whole = view(tri_of(f));
    const int i = static_cast<int>(f % 3), j = (i + 1) % 3, k = (i + 2) % 3;
    TriView h1 = whole, h2 = whole;
    h1.v[j] = mv, h1.p[j] = m, h1.seg[j] = seg;
    h1.constrained[j] = false;  // m -> w
    h2.v[i] = mv, h2.p[i] = m, h2.seg[i] = seg;
    h2.constrained[k] = false;  // w -> m
    if (!left_alone(h1, false) || !left_alone(h2, false)) return false;
    any = true;
  }
  return any;
}

// Squared distance between segments s and t (both ending at apex) at
// distance `radius` from the apex.
double Refiner::gap2(std::uint32_t s, std::uint32_t t, VertexId apex, double radius) const {
  const Point& A = pts_[apex];
  const Point& S = pts_[segs_[s][0] == apex ? segs_[s][1] : segs_[s][0]];
  const Point& T = pts_[segs_[t][0] == apex ? segs_[t][1] : segs_[t][0]];
  const double ux = S.x - A.x, uy = S.y - A.y, wx = T.x - A.x, wy = T.y - A.y;
  const double cross = ux * wy - uy * wx;
  return radius * radius * cross * cross / ((ux * ux + uy * uy) * (wx * wx + wy * wy));
}

// Mirrored splits in a narrow wedge: segment `seg` (one end at `apex`) is
// split at distance `radius` from the apex, where its partner was just
// split, unless a vertex of it is already about that far. Vertices at equal
// radii never encroach the partner's subsegments (the idea of Shewchuk
// 2002's concentric shells, applied to every split near the apex).
void Refiner::mirror_split(std::uint32_t seg, VertexId apex, double radius, int depth) {
  const VertexId other = segs_[seg][0] == apex ? segs_[seg][1] : segs_[seg][0];
  const Point A = pts_[apex], O = pts_[other];
  const double len = std::sqrt(dist2(A, O));
  if (!(radius > 0) || radius >= len) return;
  auto on_seg = [&](VertexId w) { return w == other || (w >= n_input_ && seg_of_[w] == seg); };
  VertexId u = apex;
  double ru = 0;
  for (std::size_t steps = 0; steps < 100000; ++steps) {
    // The next vertex of the segment beyond u.
    VertexId next = kNone;
    double rn = INFINITY;
    HalfEdgeId hint = kNone;
    auto consider_w = [&](VertexId w, HalfEdgeId h) {
      if (!on_seg(w)) return;
      const double r = std::sqrt(dist2(pts_[w], A));
      if (r > ru && r < rn) rn = r, next = w, hint = h;
    };
    m_.for_each_out_edge(u, [&](HalfEdgeId h) {
      if (fl_[h] & kConstrained) consider_w(tv_[next_edge(h)], h);
      const HalfEdgeId p = prev_edge(h);
      if (fl_[p] & kConstrained) consider_w(tv_[p], p);
      return true;
    });
    if (next == kNone) return;
    if (rn < radius) {
      u = next;
      ru = rn;
      continue;
    }
    const double piece = rn - ru;
    if (radius - ru < 0.05 * piece || rn - radius < 0.05 * piece) return;  // already (nearly) there
    HalfEdgeId e = tv_[hint] == u ? hint : tw_[hint];
    if (e == kNone || tv_[e] != u) e = edge(u, next, kNone);
    if (e == kNone || !splittable(e) || !budget_left()) return;
    const Point p{A.x + (O.x - A.x) * (radius / len), A.y + (O.y - A.y) * (radius / len)};
    split_segment(e, &p, depth);
    return;
  }
}

}  // namespace deltamesh::refinement
