// Delaunay refinement: the driver. Ruppert's algorithm (J. Ruppert, "A
// Delaunay refinement algorithm for quality 2-dimensional mesh generation",
// J. Algorithms 1995) as refined by J. R. Shewchuk, "Delaunay refinement
// algorithms for triangular mesh generation", CGTA 2002:
//  - R1 (split_encroached_segment): a subsegment encroached by a vertex is
//    split; encroached subsegments always go first, from a stack.
//  - R2 (split_bad_triangle): a bad triangle (quality.cpp) gets a Steiner
//    point (steiner.hpp, steiner.cpp); when that point would encroach subsegments
//    (encroachment.cpp) it is rejected and they are split instead.
//  - The small-angle rules (small_angle.cpp) leave alone what cannot be
//    improved, so that refinement terminates on every input; budgets and
//    the time limit bound the rest.
// The public interface is include/deltamesh/refine.hpp; docs/internals.md
// maps the rules to the functions. No code is taken from any implementation.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include "algo/normalize.hpp"
#include "algo/refine/cavity.hpp"
#include "algo/refine_parallel.hpp"
#include "algo/refine/refiner.hpp"
#include "algo/refine/steiner.hpp"
#include "deltamesh/progress.hpp"
#include "mesh/canonical.hpp"

namespace deltamesh::refinement {

// Off-centres this much nearer than the bound's petal tip (see setup()).
constexpr double kOffcentreShrink = 0.98;
// Triangles skipped for reasons that depend on their neighbours (a refused
// or impossible segment split) get this many more looks once the queue runs dry.
constexpr int kRequeueRounds = 4;

void Refiner::run() {
  start_ = Clock::now();
  // When a sizing callback throws, the exception leaves run() between two
  // insertions: the triangles are whole, only their count lags behind.
  struct CountAppended {
    Refiner& r;
    ~CountAppended() { r.count_appended(); }
  } count_on_exit{*this};
  setup();
  queue_encroached();
  const std::size_t nt = tv_.size() / 3;
  std::vector<std::uint8_t> bad =
      stage_ && stage_->first_look.size() == nt ? first_look() : bad_slots();  // consider() queues only bad ones
  for (TriId t = 0; t < nt; ++t)
    if (bad.empty() || bad[t]) consider(t);
  if (!bad.empty() && !has_area_bounds_) first_bad_ = std::move(bad);  // finish() re-evaluates only rewritten slots
  ProgressReporter progress(opt_.progress, "refine", "Steiner points");
  refine_loop(progress);
  if (beyond_ && !stopped_) go_beyond(progress);  // beyond.cpp
  else if (beyond_) set_bound(std::clamp(opt_.min_angle_deg, 0.0, 60.0));  // report against the bound asked for
  finish();
}

// Parameters from the options, the input segments and their small angles.
void Refiner::setup() {
  n_input_ = pts_.size();
  st_.input_vertices = n_input_;
  set_unit();
  const double theta = std::clamp(opt_.min_angle_deg, 0.0, 60.0);
  shortest_first_ = opt_.order == RefineOrder::ShortestEdgeFirst;
  best_ = (opt_.steiner == SteinerRule::Best || opt_.steiner == SteinerRule::Grid) && theta > 0;
  lens_ = opt_.encroachment == EncroachmentRule::DiametralLens && !opt_.conforming_delaunay;
  // Beyond the bounds refinement reaches in practice, first refine to
  // kAutomaticBudgetAngle, which terminates, then go on (go_beyond()).
  beyond_ = theta > kAutomaticBudgetAngle;
  set_bound(beyond_ ? kAutomaticBudgetAngle : theta);
  carry_bounds_ = m_.has_triangle_area_bounds();
  has_area_bounds_ = opt_.use_triangle_area_bounds && carry_bounds_;
  sized_ = opt_.max_area > 0 || has_area_bounds_ || opt_.max_area_at || opt_.max_edge_at;
  budget_ = opt_.max_steiner;
  if (budget_ == kAutomaticBudget) budget_ = kAutomaticBudgetBase + kAutomaticBudgetPerVertex * n_input_;


  // Every boundary edge is a segment; the input segments and their incidence
  // at input vertices (on scan_threads_ threads: setup_scan.cpp).
  const std::size_t ne = tv_.size();
  if (scan_threads_ > 1) {
    scan_edges_in_parallel();
  } else {
    for (HalfEdgeId e = 0; e < ne; ++e)
      if (tw_[e] == kNone && !m_.is_constrained(e)) m_.set_edge_flags(e, m_.edge_flags(e) | kConstrained);
    has_markers_ = m_.has_edge_markers();
    adj_start_.assign(n_input_ + 1, 0);
    for (HalfEdgeId e = 0; e < ne; ++e) {
      if (!(fl_[e] & kConstrained) || (tw_[e] != kNone && tw_[e] < e)) continue;
      const VertexId a = tv_[e], b = tv_[next_edge(e)];
      segs_.push_back({a, b});
      seg_spike_.push_back(tw_[e] == kNone ? kBoundarySeg : 0);  // a boundary one runs with the domain on its left
      ++adj_start_[a + 1];
      ++adj_start_[b + 1];
    }
  }
  for (std::size_t v = 0; v < n_input_; ++v) adj_start_[v + 1] += adj_start_[v];
  adj_.resize(adj_start_[n_input_]);
  {
    std::vector<std::uint32_t> fill(adj_start_.begin(), adj_start_.end() - 1);
    for (std::uint32_t s = 0; s < segs_.size(); ++s) {
      const auto [a, b] = segs_[s];
      adj_[fill[a]++] = {b, s};
      adj_[fill[b]++] = {a, s};
    }
  }
  find_small_angles();
  // Out-edges from scratch: any out-edge for an interior vertex, the
  // boundary one (most clockwise) for a boundary vertex, as compact() sets
  // them (scan_edges_in_parallel() set them already).
  if (scan_threads_ < 2) {
    std::fill(ve_.begin(), ve_.end(), kNone);
    for (HalfEdgeId e = 0; e < ne; ++e)
      if (ve_[tv_[e]] == kNone || tw_[e] == kNone) ve_[tv_[e]] = e;
  }
  seg_of_.assign(n_input_, kNone);
  if (!m_.vertex_markers().empty()) m_.vertex_markers().resize(n_input_, 0);
  reserve_for_area_bounds();
}

// The input's unit length: the larger side of the bounding box of the
// vertices (1 when that is not a positive finite length).
void Refiner::set_unit() {
  double lox = INFINITY, hix = -INFINITY, loy = INFINITY, hiy = -INFINITY;
  for (const Point& p : pts_) {
    lox = std::min(lox, p.x), hix = std::max(hix, p.x);
    loy = std::min(loy, p.y), hiy = std::max(hiy, p.y);
  }
  const double u = std::max(hix - lox, hiy - loy);
  unit_ = u > 0 && std::isfinite(u) ? u : 1.0;
  key_scale_ = 1.0 / (unit_ * unit_);
}

// The angle criterion and what depends on it.
void Refiner::set_bound(double theta) {
  st_.min_angle_deg = theta;
  const double rad = theta * std::numbers::pi / 180.0;
  sin2_bound_ = angle_bound_sin2(theta);
  // The off-centre sits where the shortest edge pq subtends the bound
  // angle, i.e. at distance |pq|/2 · cot(theta/2) from pq's midpoint; a
  // little nearer, so that the new triangle clears the bound after rounding.
  off_factor_ = theta > 0 ? 0.5 * kOffcentreShrink / std::tan(rad / 2) : 0.0;
  bound_rad_ = rad;
  if (lens_) lens_cos2_ = lens_angle_cos2(theta);
}

// Triangle t's area over its area bound (0 without one, or for a ghost).
double Refiner::area_ratio(TriId t, bool global) const {
  if (tv_[3 * t] >= pts_.size()) return 0;
  const Point& a = pts_[tv_[3 * t]];
  const Point& b = pts_[tv_[3 * t + 1]];
  const Point& c = pts_[tv_[3 * t + 2]];
  const double area = 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
  double bound = global ? opt_.max_area : -1;
  if (has_area_bounds_) {
    const double tb = m_.triangle_area_bound(t);
    if (tb > 0 && (bound <= 0 || tb < bound)) bound = tb;
  }
  return bound > 0 ? area / bound : 0;
}

// With area bounds the final size is predictable: reserve it, so the arrays
// do not double (and briefly triple) at the end.
void Refiner::reserve_for_area_bounds() {
  const bool global = opt_.max_area > 0;
  if (!global && !has_area_bounds_) return;
  // refine_in_parts' last pass: the stitch reserved room, and the estimate
  // (a pass over every triangle) would only raise a budget of 50 per vertex.
  if (stage_ && !stage_->reserve) return;
  double estimate = 0;
  const std::size_t nt = tv_.size() / 3;
  if (scan_threads_ > 1) estimate = area_estimate_in_parallel(global);  // setup_scan.cpp
  else
    for (TriId t = 0; t < nt; ++t) estimate += area_ratio(t, global);
  // Refinement to an area bound A ends with triangles of mean area ~0.6 A.
  const double tris = 1.75 * estimate + static_cast<double>(nt);
  if (tris > 1e10) return;
  auto want_t = static_cast<std::size_t>(tris);
  // Size bounds ask for about want_t / 2 vertices: the automatic budget
  // leaves room for four times that.
  if (opt_.max_steiner == kAutomaticBudget) budget_ = std::max(budget_, 2 * want_t);
  // Reserve no more than the Steiner budget can fill (a point adds at most
  // two triangles) and no more than kMaxReserve triangles: a tiny area bound
  // with a small budget asked for gigabytes up front (found by fuzz_mesh).
  constexpr std::size_t kMaxReserve = std::size_t{1} << 23;
  want_t = std::min({want_t, nt + 2 * std::min(budget_, kMaxReserve), kMaxReserve});
  if (want_t > nt) {
    m_.reserve(pts_.size() + want_t / 2 + 16, want_t + 16);
    fl_.reserve(3 * (want_t + 16));
    if (has_markers_) mk_.reserve(3 * (want_t + 16));
    seg_of_.reserve(pts_.size() + want_t / 2 + 16);
  }
}

// Encroached subsegments, for rule R1 before anything else.
void Refiner::queue_encroached() {
  if (scan_threads_ > 1) return queue_encroached_in_parallel();  // setup_scan.cpp: the same, in the same order
  for (HalfEdgeId e = 0; e < tv_.size(); ++e)
    if ((fl_[e] & kConstrained) && (tw_[e] == kNone || tw_[e] > e) && encroached(e) && splittable(e))
      encroached_.push_back({tv_[e], tv_[next_edge(e)], e});
}

// The refinement loop: with the encroached subsegments and bad triangles
// queued, R1 goes before R2, one step at a time, until nothing is left to do
// or a budget, the time limit or the progress watch (beyond.cpp) stops it.
void Refiner::refine_loop(ProgressReporter& progress) {
  if (watch_) {
    check_interval_ = std::max<std::size_t>(256, pts_.size() / 8);
    next_check_ = st_.steiner_points + check_interval_;
    window_start_ = pts_.size();
  }
  while (!stopped_) {
    if (progress.active()) progress.set(st_.steiner_points);
    if (watch_ && st_.steiner_points >= next_check_) {
      checkpoint();
      if (stopped_) break;
    }
    if (!tick()) break;
    if (!encroached_.empty()) split_encroached_segment();  // R1
    else if (!queue_.empty()) split_bad_triangle();        // R2
    else if (!look_again_at_skipped()) break;
  }
}

// False when the time limit has passed (looked at every 256 steps).
bool Refiner::tick() {
  if (opt_.time_limit_seconds > 0 && (++iterations_ & 255) == 0 &&
      std::chrono::duration<double>(Clock::now() - start_).count() > opt_.time_limit_seconds) {
    st_.time_exhausted = true;
    return false;
  }
  return true;
}

// Ruppert's R1: splits the subsegment on top of the encroached stack, if it
// still exists and is still encroached, unless the small-angle rules exempt
// it.
void Refiner::split_encroached_segment() {
  const SubsegmentRef r = encroached_.back();
  encroached_.pop_back();
  const HalfEdgeId e = edge(r.a, r.b, r.hint);
  if (e == kNone || !(fl_[e] & kConstrained) || !encroached(e) || !splittable(e)) return;
  if (exempt_from_r1(e)) return;
  if (!budget_left()) return;
  if (trace_) [[unlikely]] trace_r1(e);
  split_segment(e);
}

// Ruppert's R2 for the bad triangle at the head of the queue: skips it (and
// remembers why), inserts its Steiner point, or splits the subsegments that
// point encroaches.
void Refiner::split_bad_triangle() {
  st_.peak_queue = std::max(st_.peak_queue, queue_.size());
  const QueueEntry q = queue_.pop();
  if (!alive(q)) return;
  decide(q.t, decision_);
  switch (decision_.kind) {
    case Decision::Skip:
      if (decision_.reason == Reason::SmallAngle) ++st_.small_angle_skips;
      if (decision_.transient) skipped_.push_back(q);
      if (decision_.reason != Reason::None) remember_skip(q.t, decision_.reason);
      break;
    case Decision::Insert:
      if (!budget_left()) break;
      if (decision_.offcenter) ++st_.offcenters;
      if (trace_) [[unlikely]] trace_r2(q.t, TraceKind::SplitTriangle, decision_.rule);
      insert_interior(decision_.c, cav_[0]);
      break;
    case Decision::Split: {
      ++st_.rejected_points;
      if (trace_) [[unlikely]] trace_r2(q.t, TraceKind::Reject, TraceReason::Encroaches);
      bool split = false;
      for (const SubsegmentRef& r : decision_.segments) {
        const HalfEdgeId e = edge(r.a, r.b, r.hint);
        if (e == kNone) continue;
        if (!budget_left()) break;
        if (trace_) [[unlikely]] trace_r2(q.t, TraceKind::SplitSegment, TraceReason::RejectedPoint);
        split |= split_segment(e);
      }
      if (split && decision_.mirror_seg != kNone && budget_left())
        mirror_split(decision_.mirror_seg, decision_.mirror_apex, decision_.mirror_radius, 1);
      // Requeue the triangle for another look, unless no split could be
      // made (then the same decision would come back forever).
      if (split && alive(q)) consider(q.t);
      else if (!split && !stopped_) remember_skip(q.t, Reason::Precision);
      break;
    }
  }
}

// Once the queue runs dry: another look at the transient skips, a bounded
// number of times, and only while the last round changed the mesh (else the
// same skips come back). False when there is nothing more to do.
bool Refiner::look_again_at_skipped() {
  if (skipped_.empty() || requeues_ >= kRequeueRounds || st_.steiner_points == requeue_mark_) return false;
  requeue_mark_ = st_.steiner_points;
  ++requeues_;
  std::vector<QueueEntry> again;
  again.swap(skipped_);
  for (const QueueEntry& s : again)
    if (alive(s)) consider(s.t);
  return true;
}

// What to do with bad triangle t: skip it (and why), split the subsegments
// its Steiner point encroaches or lies beyond, or insert that point (its
// cavity left in cav_/bnd_).
void Refiner::decide(TriId t, Decision& d) {
  d.kind = Decision::Skip;
  d.reason = Reason::None;
  d.transient = false;
  d.segments.clear();
  d.mirror_seg = kNone;
  const Eval ev = eval(t);
  if (!ev.skinny && !ev.large) return;
  if (ev.skinny && !ev.large && opt_.small_angle_protection && faces_small_angle(t, ev)) {
    d.reason = Reason::SmallAngle;
    return;
  }
  d.c = steiner_point(t, ev, d.offcenter);
  if (!std::isfinite(d.c.x) || !std::isfinite(d.c.y)) {
    d.reason = Reason::Precision;
    return;
  }
  if (ev.skinny && !ev.large && best_)
    d.c = opt_.steiner == SteinerRule::Grid ? grid_point(t, ev, d.c) : best_point(t, ev, d.c);
  d.c = within_predicate_range(d.c);
  d.rule = ev.skinny && !ev.large && best_ ? TraceReason::BestPoint
           : d.offcenter                   ? TraceReason::OffCentre
           : ev.skinny                     ? TraceReason::Circumcentre
                                           : TraceReason::Area;
  // Precision is measured by what rounding does, where the work is: a point
  // that rounds onto a vertex (or out of its cavity, below) is not inserted.
  const Walk w = walk(t, d.c);
  enc_scratch_.clear();
  switch (w.kind) {
    case Walk::Failed:
    case Walk::OnVertex:
      d.reason = Reason::Precision;
      return;
    case Walk::Blocked:
      enc_scratch_.push_back(w.edge);
      decide_segments(t, enc_scratch_, ev, d);
      return;
    case Walk::Found:
      break;
  }
  if (w.edge != kNone && (fl_[w.edge] & kConstrained)) {  // on a segment
    enc_scratch_.push_back(w.edge);
    decide_segments(t, enc_scratch_, ev, d);
    return;
  }
  if (!cavity(d.c, w.tri)) {
    d.reason = Reason::Precision;
    return;
  }
  // A point that would cut a hub's wedge into an angle below the bound for
  // good splits the apex subsegment instead (small_angle.cpp), unless the
  // piece would be shorter than t's shortest edge (then it goes in).
  if (ev.skinny && !ev.large && opt_.small_angle_protection && has_hubs_) {
    std::uint32_t far_seg = kNone;
    VertexId apex = kNone;
    const HalfEdgeId h = hub_wedge_side(d.c, far_seg, apex);
    if (h != kNone && splittable(h)) {
      const Point m = segment_split_point(tv_[h], tv_[next_edge(h)]);
      if (std::min(dist2(m, pts_[tv_[h]]), dist2(m, pts_[tv_[next_edge(h)]])) >= ev.shortest2) {
        enc_scratch_.push_back(h);
        d.mirror_seg = far_seg, d.mirror_apex = apex, d.mirror_radius = std::sqrt(dist2(m, pts_[apex]));
      }
    }
    // A point in a cell across a hub's narrow wedge for a triangle in that
    // small angle: left alone, as the angle explains it (small_angle.cpp).
    if (enc_scratch_.empty() && leave_for_narrow_wedge(t, d.c)) {
      d.reason = Reason::SmallAngle;
      d.transient = true;
      return;
    }
  }
  // R2's rejection: a point that encroaches subsegments is not inserted;
  // they are split instead. One that encroaches only subsegments that may
  // not be split is inserted anyway.
  for (const BoundaryEdge& b : bnd_) {
    if (!(b.flags & kConstrained) || !encroaches(pts_[b.a], pts_[b.b], d.c)) continue;
    const HalfEdgeId e = b.inner;  // the cavity is still intact
    if (splittable(e) && std::find(enc_scratch_.begin(), enc_scratch_.end(), e) == enc_scratch_.end() &&
        (enc_scratch_.empty() || tw_[e] != enc_scratch_[0]))
      enc_scratch_.push_back(e);
  }
  if (!enc_scratch_.empty()) {
    decide_segments(t, enc_scratch_, ev, d);
    return;
  }
  d.kind = Decision::Insert;
}

// The subsegments in `enc` that may be split for triangle t, evaluated as
// `ev`; none: a transient skip, with the reason.
void Refiner::decide_segments(TriId t, const std::vector<HalfEdgeId>& enc, const Eval& ev, Decision& d) {
  Reason why = Reason::None;
  for (HalfEdgeId e : enc) {
    if (const Reason r = split_refusal(e); r != Reason::None) {
      if (why != Reason::Protected) why = r;  // -Y's refusal is the one to name
      continue;
    }
    // The rule against cascades is for skinny triangles (as the small-angle
    // skip in decide()): a triangle above its size bound gets its split, and
    // size bounds end those splits.
    if (!ev.large && refuse_split_near_apex(e, ev, t)) {
      if (why == Reason::None) why = Reason::SmallAngle;
      continue;
    }
    d.segments.push_back({tv_[e], tv_[next_edge(e)], e});
  }
  if (d.segments.empty()) {
    d.kind = Decision::Skip;
    d.reason = why == Reason::None ? Reason::Precision : why;
    d.transient = true;
  } else {
    d.kind = Decision::Split;
  }
}

// The half-edge a -> b: the hint if it still is one, else a rotation around
// a, else the twin of b -> a (a vertex where holes touch has two fans and
// the rotation from its out-edge sees only one).
HalfEdgeId Refiner::edge(VertexId a, VertexId b, HalfEdgeId hint) const {
  if (hint < tv_.size() && tv_[hint] == a && tv_[next_edge(hint)] == b) return hint;
  HalfEdgeId e = m_.find_edge(a, b);
  if (e != kNone) return e;
  e = m_.find_edge(b, a);
  return e != kNone ? tw_[e] : kNone;
}

bool Refiner::budget_left() {
  if (st_.steiner_points >= budget_) {
    st_.budget_exhausted = true;
    stopped_ = true;
    return false;
  }
  return true;
}

// The input segment between input vertices a and b, or kNone.
std::uint32_t Refiner::input_segment(VertexId a, VertexId b) const {
  if (a < n_input_) {
    for (std::uint32_t i = adj_start_[a]; i < adj_start_[a + 1]; ++i)
      if (adj_[i].first == b) return adj_[i].second;
  }
  return kNone;
}

// The input segment subsegment ab lies on (kNone when ab is no subsegment).
std::uint32_t Refiner::segment_of(VertexId a, VertexId b) const {
  return a >= n_input_ ? seg_of_[a] : (b >= n_input_ ? seg_of_[b] : input_segment(a, b));
}

}  // namespace deltamesh::refinement

namespace deltamesh {

using refinement::Refiner;

namespace detail {

RefineStats refine_scanning(Mesh& mesh, const RefineOptions& options, unsigned scan_threads, RefineStage* stage) {
  RefineStats stats;
  if (!mesh.compacted()) mesh.compact();
  stats.input_vertices = mesh.num_vertices();
  stats.min_angle_deg = options.min_angle_deg;
  if (mesh.num_triangles() == 0) return stats;
  Refiner r(mesh, options, stats);
  r.set_scan_threads(scan_threads);
  r.set_stage(stage);
  r.run();
  // Mesh::add_triangle (used when triangles carry bounds or attributes)
  // clears the compacted flag; the mesh has no dead or ghost slots.
  if (!mesh.compacted()) {
    mesh.compact();
    if (stage) stage->final_bad.clear();  // (in case it moved a slot)
  }
  return stats;
}

}  // namespace detail

RefineStats refine(Mesh& mesh, const RefineOptions& options) {
  if (detail::needs_frame(mesh.points())) {  // beyond the predicates' range: in an exact power-of-two frame
    const detail::Frame f = detail::frame_for(mesh.points());
    RefineOptions framed = options;
    detail::scale_options(f, framed);
    detail::scale_mesh(f, mesh);
    struct Restore {  // also when refinement throws (a sizing callback)
      const detail::Frame& f;
      Mesh& m;
      ~Restore() { detail::restore(f, m); }
    } restore_on_exit{f, mesh};
    const detail::TraceFrameScope in_frame(mesh.trace(), f.k);
    RefineStats stats = refine(mesh, framed);
    detail::restore(f, stats);
    return stats;
  }
  if (std::optional<RefineStats> in_parts = detail::refine_in_parts(mesh, options)) return *in_parts;
  if (!mesh.compacted()) mesh.compact();
  // Slots in an order of the triangulation's own (not of how it was built):
  // the queue, the walks and the new slots follow it.
  detail::canonical_triangle_order(mesh);
  return detail::refine_scanning(mesh, options, 1);
}

std::string_view to_string(SteinerRule r) {
  switch (r) {
    case SteinerRule::Best: return "best";
    case SteinerRule::Grid: return "grid";
    case SteinerRule::Offcenter: return "offcenter";
    case SteinerRule::Circumcenter: break;
  }
  return "circumcenter";
}

std::optional<SteinerRule> parse_steiner_rule(std::string_view name) {
  if (name == "offcenter" || name == "off-center" || name == "offcentre") return SteinerRule::Offcenter;
  if (name == "circumcenter" || name == "circumcentre") return SteinerRule::Circumcenter;
  if (name == "best") return SteinerRule::Best;
  if (name == "grid") return SteinerRule::Grid;
  return std::nullopt;
}

std::string_view to_string(EncroachmentRule r) {
  return r == EncroachmentRule::DiametralCircle ? "circle" : "lens";
}

std::optional<EncroachmentRule> parse_encroachment_rule(std::string_view name) {
  if (name == "circle") return EncroachmentRule::DiametralCircle;
  if (name == "lens") return EncroachmentRule::DiametralLens;
  return std::nullopt;
}

}  // namespace deltamesh
