// Delaunay refinement to bounds above kAutomaticBudgetAngle, where it need
// not terminate (Shewchuk 2002 reports termination in practice up to about
// 33.8°): a second stage from the mesh refined to kAutomaticBudgetAngle,
// watched for progress, that gives the better of the two meshes back.
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "algo/refine/refiner.hpp"

namespace deltamesh::refinement {

// sin^2 of the smallest angle of the mesh; outside_small_angles: of the
// triangles not left alone at small input angles.
double Refiner::smallest_sin2(bool outside_small_angles) const {
  double low = 1.0;
  const std::size_t nt = tv_.size() / 3;
  for (TriId t = 0; t < nt; ++t) {
    if (outside_small_angles && t < why_.size() && why_[t] == Reason::SmallAngle) continue;
    const Point& a = pts_[tv_[3 * t]];
    const Point& b = pts_[tv_[3 * t + 1]];
    const Point& c = pts_[tv_[3 * t + 2]];
    const double l0 = dist2(a, b), l1 = dist2(b, c), l2 = dist2(c, a);
    const double cross = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    const double den = std::max({l0 * l1, l1 * l2, l2 * l0});  // the two longer edges
    if (den > 0) low = std::min(low, cross * cross / den);
  }
  return low;
}

// Above kAutomaticBudgetAngle: the mesh refined to kAutomaticBudgetAngle is
// kept aside, and refinement goes on to the requested bound, worst
// triangles first (shortest-edge-first lets the smallest angle collapse
// where points spiral into a corner), watched by checkpoint(). If it stops
// short, the mesh with the larger smallest angle (overall and outside small
// input angles) is returned.
void Refiner::go_beyond(ProgressReporter& progress) {
  count_appended();
  const double kept_all = smallest_sin2(false), kept_outside = smallest_sin2(true);
  Mesh kept = m_;
  const std::vector<Reason> kept_why = why_;
  const RefineStats kept_st = st_;
  set_bound(std::clamp(opt_.min_angle_deg, 0.0, 60.0));
  shortest_first_ = false;
  skipped_.clear();
  requeues_ = 0;
  requeue_mark_ = SIZE_MAX;
  queue_encroached();
  const std::size_t nt = tv_.size() / 3;
  for (TriId t = 0; t < nt; ++t) consider(t);
  watch_ = true;
  watch_cap_ = st_.steiner_points + 4 * pts_.size() + 10000;
  refine_loop(progress);
  count_appended();
  if (!(stalled_ || st_.budget_exhausted || st_.time_exhausted)) return;
  if (smallest_sin2(false) >= kept_all && smallest_sin2(true) >= kept_outside) return;
  const RefineStats later = st_;
  const std::size_t vertices_later = pts_.size();
  m_ = std::move(kept);  // the references to its arrays stay valid
  m_.set_trace(trace_);  // (the copy had none)
  if (trace_) [[unlikely]] detail::TraceAccess::rewind(*trace_, tv_, pts_.size(), vertices_later);
  why_ = kept_why;
  st_ = kept_st;
  st_.min_angle_deg = later.min_angle_deg;
  st_.stalled = later.stalled;
  st_.stall_x = later.stall_x, st_.stall_y = later.stall_y, st_.stall_radius = later.stall_radius;
  st_.budget_exhausted = later.budget_exhausted;
  st_.time_exhausted = later.time_exhausted;
  st_.peak_queue = later.peak_queue;
  st_.discarded_steiner = later.steiner_points - kept_st.steiner_points;
  st_.kept_angle_deg = kAutomaticBudgetAngle;
}

// Progress above the guaranteed range: every check_interval_ Steiner points,
// the triangles still below the bound (outside small input angles) and the
// smallest angle among them. Refinement that neither cuts their number by a
// quarter nor raises that angle by about half a degree over two intervals
// is not converging: its points pile up in one neighbourhood (off-centres
// spiralling into a corner) while the smallest angle there stays put, as
// Delaunay refinement does beyond the bounds it is known to reach
// (Shewchuk 2002: ~33.8° in practice). The last interval's points name the
// place.
void Refiner::checkpoint() {
  next_check_ = st_.steiner_points + check_interval_;
  std::size_t bad = 0;
  double low = 1.0;
  const std::size_t nt = tv_.size() / 3;
  for (TriId t = 0; t < nt; ++t) {
    const Eval ev = eval(t);
    if (!ev.skinny || (t < why_.size() && why_[t] == Reason::SmallAngle)) continue;
    ++bad;
    low = std::min(low, ev.sin2);
  }
  const bool fewer = bad < best_bad_ - best_bad_ / 4 || best_bad_ == SIZE_MAX;
  const bool higher = low > best_sin2_ * 1.02;  // about half a degree near 35°
  best_bad_ = std::min(best_bad_, bad);
  best_sin2_ = std::max(best_sin2_, low);
  const bool capped = st_.steiner_points >= watch_cap_;
  if (!capped && (fewer || higher)) {
    stale_checks_ = 0;
  } else if (capped || ++stale_checks_ >= 2) {
    // Where the last interval's points went: their coordinate-wise median,
    // and the median distance from it.
    std::vector<double> xs, ys, ds;
    for (std::size_t v = window_start_; v < pts_.size(); ++v) xs.push_back(pts_[v].x), ys.push_back(pts_[v].y);
    if (!xs.empty()) {
      auto median = [](std::vector<double>& a) {
        std::nth_element(a.begin(), a.begin() + a.size() / 2, a.end());
        return a[a.size() / 2];
      };
      const Point c{median(xs), median(ys)};
      for (std::size_t v = window_start_; v < pts_.size(); ++v) ds.push_back(std::sqrt(dist2(pts_[v], c)));
      st_.stall_x = c.x, st_.stall_y = c.y, st_.stall_radius = median(ds);
    }
    stalled_ = true;
    stopped_ = true;
    st_.stalled = true;
  }
  window_start_ = pts_.size();
}

}  // namespace deltamesh::refinement
