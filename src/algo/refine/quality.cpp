// Quality criteria of Delaunay refinement: a triangle is bad when it is
// skinny (its smallest angle below the bound: equivalently, its
// circumradius-to-shortest-edge ratio above 1 / (2 sin bound), the measure of
// Ruppert 1995 and Shewchuk 2002) or too large (area above the global,
// regional or per-triangle bound or the max_area_at callback, or longest edge
// above max_edge_at). Bad triangles go to the queue.
#include <algorithm>
#include <cmath>

#include "algo/refine/refiner.hpp"
#include "core/angles.hpp"
#include "core/parallel.hpp"

namespace deltamesh::refinement {

// The smallest area bound that applies to triangle t = abc (<= 0: none).
double Refiner::area_bound(TriId t, const Point& a, const Point& b, const Point& c) const {
  double bound = opt_.max_area;
  if (has_area_bounds_) {
    const double tb = m_.triangle_area_bound(t);
    if (tb > 0 && (bound <= 0 || tb < bound)) bound = tb;
  }
  if (opt_.max_area_at) {
    const double cb = opt_.max_area_at((a.x + b.x + c.x) / 3.0, (a.y + b.y + c.y) / 3.0);
    if (cb > 0 && (bound <= 0 || cb < bound)) bound = cb;
  }
  return bound;
}

// Quality of triangle abc (counter-clockwise) under t's size bound.
Eval Refiner::eval(TriId t, const Point& a, const Point& b, const Point& c) const {
  Eval ev;
  const ShortestEdgeShape sh = shortest_edge_shape(a, b, c);
  const double* l2s = sh.l2;
  const double cross = sh.cross, den = sh.den;
  ev.shortest = sh.shortest;
  ev.shortest2 = l2s[sh.shortest];
  ev.skinny = cross * cross < sin2_bound_ * den;
  if (ev.skinny) ev.sin2 = den > 0 ? cross * cross / den : 0.0;
  const double bound = area_bound(t, a, b, c);
  if (bound > 0 && 0.5 * cross > bound) ev.large = true;
  if (opt_.max_edge_at) {
    const double eb = opt_.max_edge_at((a.x + b.x + c.x) / 3.0, (a.y + b.y + c.y) / 3.0);
    if (eb > 0 && std::max({l2s[0], l2s[1], l2s[2]}) > eb * eb) ev.large = true;
  }
  return ev;
}

// Queues triangle t when it is bad (skinny ones by the queue's order, the
// others as too large); a rewritten slot forgets why it was left alone.
void Refiner::consider(TriId t) {
  if (t < why_.size()) why_[t] = Reason::None;
  const Eval ev = eval(t);
  if (!ev.skinny && !ev.large) return;
  const QueueEntry q{t, tv_[3 * t], tv_[3 * t + 1], tv_[3 * t + 2]};
  if (ev.skinny)
    queue_.push_skinny(shortest_first_ ? shortest_edge_key(ev.shortest2 * key_scale_) : worst_quality_key(ev.sin2, sin2_bound_), q);
  else
    queue_.push_large(q);
}

std::vector<std::uint8_t> Refiner::bad_slots() const {
  std::vector<std::uint8_t> bad;
  if (scan_threads_ < 2 || opt_.max_area_at || opt_.max_edge_at) return bad;
  const std::size_t nt = tv_.size() / 3, chunks = 4 * std::size_t{scan_threads_};
  const std::size_t before = first_bad_.size();  // slots as the first look saw them (run())
  bad.resize(nt);
  detail::run_tasks(chunks, scan_threads_, [&](std::size_t i) {
    for (std::size_t t = nt * i / chunks; t < nt * (i + 1) / chunks; ++t) {
      if (tv_[3 * t] >= pts_.size()) continue;  // a dead or ghost slot: never bad
      if (t < before && first_bad_[t] != detail::kLookAgain) {  // the same triangle (no size callbacks or per-triangle bounds)
        bad[t] = first_bad_[t];
        continue;
      }
      const Eval ev = eval(static_cast<TriId>(t));
      bad[t] = ev.skinny || ev.large;
    }
  });
  return bad;
}

// The first look of refine_in_parts' last pass: the parts' final verdicts
// (the same triangles, evaluated the same way), and eval() for the slots the
// stitch's flips rewrote.
std::vector<std::uint8_t> Refiner::first_look() const {
  std::vector<std::uint8_t> bad = std::move(stage_->first_look);
  for (std::size_t t = 0; t < bad.size(); ++t)
    if (bad[t] == detail::kLookAgain) {
      const Eval ev = eval(static_cast<TriId>(t));
      bad[t] = ev.skinny || ev.large;
    }
  return bad;
}

}  // namespace deltamesh::refinement
