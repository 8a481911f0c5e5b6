// Statistics of a Delaunay refinement: the triangles left bad when it ends,
// classified by why they were left (RefineStats), and the report.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <sstream>

#include "algo/refine/refiner.hpp"
#include "core/plural.hpp"
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
  double precision_sin2 = 2.0;
  const std::vector<std::uint8_t> bad = bad_slots();
  const bool keep = stage_ && stage_->keep_final_bad;
  if (keep) stage_->final_bad.assign(nt, 0);
  for (TriId t = 0; t < nt; ++t) {
    if (!bad.empty() && !bad[t]) continue;
    const Eval ev = eval(t);
    if (!ev.skinny && !ev.large) continue;
    if (keep) stage_->final_bad[t] = 1;
    Reason why = t < why_.size() ? why_[t] : Reason::None;
    if (why == Reason::None) why = stalled_ ? Reason::OutOfReach : (stopped ? Reason::Budget : Reason::Precision);
    if (why == Reason::Precision && (st_.precision_edge == 0.0 || (ev.skinny && ev.sin2 < precision_sin2))) {
      const Point& a = pts_[tv_[3 * t]];
      const Point& b = pts_[tv_[3 * t + 1]];
      const Point& c = pts_[tv_[3 * t + 2]];
      st_.precision_x = (a.x + b.x + c.x) / 3.0;
      st_.precision_y = (a.y + b.y + c.y) / 3.0;
      st_.precision_edge = std::sqrt(ev.shortest2);
      st_.precision_magnitude = std::max({std::fabs(a.x), std::fabs(a.y), std::fabs(b.x), std::fabs(b.y),
                                          std::fabs(c.x), std::fabs(c.y)});
      precision_sin2 = ev.skinny ? ev.sin2 : 2.0;
    }
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
  // Complete (the one rule for unmet bounds, docs/robustness.md "Exit
  // codes"): no budget stopped it, every triangle is within its size bound,
  // and every triangle below the angle bound sits in a small input angle.
  // Triangles left because -Y/-YY forbids a split or no distinct point fits
  // at the precision of doubles are unmet bounds too.
  st_.reached_angle_deg =
      low_outside > 1.0 ? st_.min_angle_deg : std::asin(std::sqrt(low_outside)) * 180.0 / std::numbers::pi;
  st_.complete = !stopped && st_.too_large == 0 && st_.below_segment_protected == 0 && st_.below_precision == 0;
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
      out << ", the mesh refined to " << kept_angle_deg << "° kept, "
          << count_of(discarded_steiner, "later Steiner point", "later Steiner points") << " dropped";
    out << ")";
  } else if (budget_exhausted) {
    out << " (Steiner budget reached)";
  }
  if (time_exhausted) out << " (time limit reached)";
  out << ": " << count_of(steiner_points, "Steiner point", "Steiner points") << " (" << segment_splits
      << " on segments, " << interior_points << " inside, " << count_of(offcenters, "off-centre", "off-centres")
      << "), " << count_of(rejected_points, "encroaching point", "encroaching points") << " rejected";
  if (below_bound > 0) {
    out << "; " << count_of(below_bound, "triangle", "triangles") << " below " << min_angle_deg << "°:";
    if (below_small_input_angle) out << " " << below_small_input_angle << " at input angles < 60°";
    if (below_segment_protected) out << " " << below_segment_protected << " need a split -Y forbids";
    if (below_budget) out << " " << below_budget << " left by the budget";
    if (below_out_of_reach) out << " " << below_out_of_reach << " where the bound is out of reach";
    if (below_precision) out << " " << below_precision << " at the precision of doubles";
  }
  if (too_large > 0) {
    out << "; " << count_of(too_large, "triangle", "triangles") << " above "
        << (too_large == 1 ? "its" : "their") << " size bound";
    if (too_large_precision) out << " (" << too_large_precision << " at the precision of doubles)";
  }
  return out.str();
}

std::string RefineStats::unmet() const {
  if (complete) return {};
  std::ostringstream out;
  const char* sep = "";
  if (stalled) {
    out << min_angle_deg << "° out of reach (" << reached_angle_deg << "° reached)";
    sep = "; ";
  } else if (budget_exhausted || time_exhausted) {
    out << (time_exhausted ? "the time limit" : "the Steiner budget") << " stopped refinement";
    sep = "; ";
  }
  const std::size_t left = below_bound - below_small_input_angle;
  if (left > 0) {
    out << sep << left << (left == 1 ? " triangle" : " triangles") << " below " << min_angle_deg << "°:";
    if (below_segment_protected) out << " " << below_segment_protected << " need a segment split -Y/-YY forbids";
    if (below_budget) out << " " << below_budget << " left by the budget";
    if (below_out_of_reach) out << " " << below_out_of_reach << " where the bound is out of reach";
    if (below_precision) out << " " << below_precision << " at the precision of doubles";
    sep = "; ";
  }
  if (too_large > 0) {
    out << sep << too_large << (too_large == 1 ? " triangle" : " triangles") << " above their size bound";
    if (too_large_precision) out << " (" << too_large_precision << " at the precision of doubles)";
    sep = "; ";
  }
  if (below_precision || too_large_precision)
    out << sep << "precision: the worst near (" << precision_x << ", " << precision_y << ") has a shortest edge of "
        << precision_edge << " at coordinates of magnitude " << precision_magnitude
        << ": a new vertex there would round onto its neighbours or out of its cavity";
  return out.str();
}

}  // namespace deltamesh
