// Statistics of a Delaunay refinement: the triangles left bad when it ends,
// classified by why they were left (RefineStats), and the report.
#include <chrono>
#include <sstream>

#include "algo/refine/refiner.hpp"

namespace deltamesh::refinement {

// Triangles appended by hand (insert.cpp's new_slot) join the mesh's count.
void Refiner::count_appended() {
  m_.set_live_real(m_.live_real() + appended_);
  appended_ = 0;
}

// Counts what is left bad and why, and whether refinement is complete.
void Refiner::finish() {
  count_appended();
  const bool stopped = st_.budget_exhausted || st_.time_exhausted;
  // Classify what is left by the reason recorded when each triangle was
  // last left alone (linear: no decision is repeated here). A bad triangle
  // without one was still waiting when a budget stopped refinement.
  const std::size_t nt = tv_.size() / 3;
  for (TriId t = 0; t < nt; ++t) {
    const Eval ev = eval(t);
    if (!ev.skinny && !ev.large) continue;
    Reason why = t < why_.size() ? why_[t] : Reason::None;
    if (why == Reason::None) why = stopped ? Reason::Budget : Reason::Precision;
    if (ev.large) {
      ++st_.too_large;
      if (why == Reason::Precision) ++st_.too_large_precision;
    }
    if (!ev.skinny) continue;
    ++st_.below_bound;
    switch (why) {
      case Reason::SmallAngle: ++st_.below_small_input_angle; break;
      case Reason::Protected: ++st_.below_segment_protected; break;
      case Reason::Budget: ++st_.below_budget; break;
      default: ++st_.below_precision; break;
    }
  }
  // Complete: no budget stopped it and every triangle is within its size
  // bound (skinny triangles may remain for the reasons counted above).
  st_.complete = !stopped && st_.too_large == 0;
  st_.seconds = std::chrono::duration<double>(Clock::now() - start_).count();
}

}  // namespace deltamesh::refinement

namespace deltamesh {

std::string RefineStats::summary() const {
  std::ostringstream out;
  const bool stopped = budget_exhausted || time_exhausted;
  out << "refinement " << (complete ? "complete" : (stopped ? "stopped early" : "incomplete"));
  if (budget_exhausted) out << " (Steiner budget reached)";
  if (time_exhausted) out << " (time limit reached)";
  out << ": " << steiner_points << " Steiner points (" << segment_splits << " on segments, " << interior_points
      << " inside, " << offcenters << " off-centres), " << rejected_points << " encroaching points rejected";
  if (below_bound > 0) {
    out << "; " << below_bound << " triangles below " << min_angle_deg << "°:";
    if (below_small_input_angle) out << " " << below_small_input_angle << " at input angles < 60°";
    if (below_segment_protected) out << " " << below_segment_protected << " need a split -Y forbids";
    if (below_budget) out << " " << below_budget << " left by the budget";
    if (below_precision) out << " " << below_precision << " at the precision of doubles";
  }
  if (too_large > 0) {
    out << "; " << too_large << " triangles above their size bound";
    if (too_large_precision) out << " (" << too_large_precision << " at the precision of doubles)";
  }
  return out.str();
}

}  // namespace deltamesh
