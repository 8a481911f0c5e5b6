// Statistics of a Delaunay refinement: the triangles left bad when it ends,
// classified by why they were left (RefineStats), and the report.
#include <chrono>
#include <cmath>
#include <numbers>
#include <sstream>

#include "algo/refine/refiner.hpp"
#include "mesh/editor.hpp"

namespace deltamesh::refinement {

// Triangles appended by hand (insert.cpp's new_slot) join the mesh's count.
void Refiner::count_appended() {
  detail::MeshEditor(m_).set_live_real(detail::MeshEditor(m_).live_real() + appended_);
  appended_ = 0;
}

// Counts what is left bad and why, and whether refinement is complete.
void Refiner::finish() {
  count_appended();
  const bool stopped = st_.budget_exhausted || st_.time_exhausted || stalled_;
  // Classify what is left by the reason recorded when each triangle was
  // last left alone (linear: no decision is repeated here). A bad triangle
  // without one was still waiting when a budget stopped refinement.
  const std::size_t nt = tv_.size() / 3;
  double low_outside = 2.0;
  for (TriId t = 0; t < nt; ++t) {
    const Eval ev = eval(t);
    if (!ev.skinny && !ev.large) continue;
    Reason why = t < why_.size() ? why_[t] : Reason::None;
    if (why == Reason::None) why = stalled_ ? Reason::OutOfReach : (stopped ? Reason::Budget : Reason::Precision);
    if (ev.large) {
      ++st_.too_large;
      if (why == Reason::Precision) ++st_.too_large_precision;
    }
    if (!ev.skinny) continue;
    ++st_.below_bound;
    if (why != Reason::SmallAngle) low_outside = std::min(low_outside, ev.sin2);
    switch (why) {
      case Reason::SmallAngle: ++st_.below_small_input_angle; break;
      case Reason::Protected: ++st_.below_segment_protected; break;
      case Reason::Budget: ++st_.below_budget; break;
      case Reason::OutOfReach: ++st_.below_out_of_reach; break;
      default: ++st_.below_precision; break;
    }
  }
  // Complete: no budget stopped it and every triangle is within its size
  // bound (skinny triangles may remain for the reasons counted above).
  st_.reached_angle_deg =
      low_outside > 1.0 ? st_.min_angle_deg : std::asin(std::sqrt(low_outside)) * 180.0 / std::numbers::pi;
  st_.complete = !stopped && st_.too_large == 0;
  if (stalled_) st_.budget_exhausted = true;  // the progress watch is a budget: the mesh is as good as it got
  st_.seconds = std::chrono::duration<double>(Clock::now() - start_).count();
}

}  // namespace deltamesh::refinement

namespace deltamesh {

std::string RefineStats::summary() const {
  std::ostringstream out;
  const bool stopped = budget_exhausted || time_exhausted;
  out << "refinement " << (complete ? "complete" : (stopped ? "stopped early" : "incomplete"));
  if (stalled) {
    out << " (" << min_angle_deg << "° out of reach: no progress while half the last Steiner points went within "
        << stall_radius << " of (" << stall_x << ", " << stall_y << "); " << reached_angle_deg
        << "° reached outside small input angles";
    if (discarded_steiner)
      out << ", the mesh refined to " << kept_angle_deg << "° kept, " << discarded_steiner << " later Steiner points dropped";
    out << ")";
  } else if (budget_exhausted) {
    out << " (Steiner budget reached)";
  }
  if (time_exhausted) out << " (time limit reached)";
  out << ": " << steiner_points << " Steiner points (" << segment_splits << " on segments, " << interior_points
      << " inside, " << offcenters << " off-centres), " << rejected_points << " encroaching points rejected";
  if (below_bound > 0) {
    out << "; " << below_bound << " triangles below " << min_angle_deg << "°:";
    if (below_small_input_angle) out << " " << below_small_input_angle << " at input angles < 60°";
    if (below_segment_protected) out << " " << below_segment_protected << " need a split -Y forbids";
    if (below_budget) out << " " << below_budget << " left by the budget";
    if (below_out_of_reach) out << " " << below_out_of_reach << " where the bound is out of reach";
    if (below_precision) out << " " << below_precision << " at the precision of doubles";
  }
  if (too_large > 0) {
    out << "; " << too_large << " triangles above their size bound";
    if (too_large_precision) out << " (" << too_large_precision << " at the precision of doubles)";
  }
  return out.str();
}

}  // namespace deltamesh
