// Adaptation to a size field: coarsen, refine, smooth; and the refinement
// owed after smoothing a refined mesh.
#include "deltamesh/adapt.hpp"
#include "core/plural.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "algo/adapt/common.hpp"

namespace deltamesh {

using adaptation::Clock;
using adaptation::seconds_since;

std::string AdaptStats::summary() const {
  char buf[64];
  std::snprintf(buf, sizeof buf, ", %.3f s", seconds);
  return count_of(removed, "vertex", "vertices") + " removed, " + std::to_string(inserted) + " inserted, " +
         count_of(triangles, "triangle", "triangles") + (complete ? "" : " (incomplete: see the refinement report)") +
         buf;
}

SmoothStats smooth_refined(Mesh& mesh, const SmoothOptions& options, const RefineOptions& refine_options,
                           RefineStats& refined, std::size_t* resplit) {
  const SmoothStats s = smooth(mesh, options);
  if (resplit) *resplit = 0;
  if (refined.budget_exhausted || refined.time_exhausted) return s;  // a budget stopped it: nothing is owed
  // The budgets are the whole run's (the second refinement could otherwise
  // add max_steiner points again, and take the time limit again).
  RefineOptions r = refine_options;
  if (r.max_steiner != kUnlimited && r.max_steiner != kAutomaticBudget)
    r.max_steiner -= std::min(r.max_steiner, refined.steiner_points);
  if (r.time_limit_seconds > 0)
    r.time_limit_seconds = std::max(1e-9, r.time_limit_seconds - refined.seconds);  // (<= 0 is none)
  const RefineStats again = refine(mesh, r);
  if (resplit) *resplit = again.steiner_points;
  refined.steiner_points += again.steiner_points;
  refined.segment_splits += again.segment_splits;
  refined.interior_points += again.interior_points;
  refined.offcenters += again.offcenters;
  refined.complete = again.complete;
  refined.budget_exhausted = again.budget_exhausted;
  refined.time_exhausted = again.time_exhausted;
  // What is left below the bound is the final mesh's, as the second
  // refinement classified it.
  refined.below_bound = again.below_bound;
  refined.below_small_input_angle = again.below_small_input_angle;
  refined.below_segment_protected = again.below_segment_protected;
  refined.below_budget = again.below_budget;
  refined.below_precision = again.below_precision;
  refined.too_large = again.too_large;
  refined.too_large_precision = again.too_large_precision;
  refined.seconds += again.seconds;
  return s;
}

AdaptStats adapt(Mesh& mesh, const SizeField& h, const AdaptOptions& options) {
  const auto t0 = Clock::now();
  AdaptStats st;
  st.coarsen = coarsen(mesh, h, options.coarsen);
  RefineOptions r = options.refine;
  if (h) {
    const SizeField user = r.max_edge_at;
    r.max_edge_at = [h, user](double x, double y) {
      double v = h(x, y);
      if (!(v > 0) || !std::isfinite(v)) v = -1.0;
      if (user) {
        const double u = user(x, y);
        if (u > 0 && (v <= 0 || u < v)) v = u;
      }
      return v;
    };
  }
  st.refine = refine(mesh, r);
  // A moved vertex may encroach a segment: no smoothing of conforming meshes.
  if (options.smooth_passes > 0 && mesh.num_triangles() > 0 && !options.refine.conforming_delaunay) {
    SmoothOptions so;
    so.passes = options.smooth_passes;
    so.h = h;
    so.max_area = options.refine.max_area;
    so.protect_first = options.coarsen.protect_first;
    st.smooth = smooth_refined(mesh, so, r, st.refine, &st.resplit);
  }
  st.removed = st.coarsen.removed;
  st.inserted = st.refine.steiner_points;
  st.triangles = mesh.num_triangles();
  st.complete = st.refine.complete;
  st.seconds = seconds_since(t0);
  return st;
}

}  // namespace deltamesh
