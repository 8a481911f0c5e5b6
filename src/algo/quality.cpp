// Mesh quality report: see include/deltamesh/quality.hpp.
#include "deltamesh/quality.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/angles.hpp"

namespace deltamesh {

namespace {

// As the refinement's dist2 (same expression, same rounding).
double squared_distance(const Point& a, const Point& b) {
  const double dx = a.x - b.x, dy = a.y - b.y;
  return dx * dx + dy * dy;
}

std::string fmt(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace

QualityReport quality_report(const Mesh& mesh, const QualityOptions& opt, const RefineStats* rs) {
  QualityReport r;
  r.angle_bound_deg = opt.min_angle_deg;
  if (rs) r.refine = *rs;
  const std::size_t nv = mesh.num_vertices();
  std::vector<char> used(nv, 0);
  bool first = true;
  for (TriId t = 0; t < mesh.num_triangle_slots(); ++t) {
    if (!mesh.is_real(t)) continue;
    const auto v = mesh.triangle(t);
    const Point& a = mesh.point(v[0]);
    const Point& b = mesh.point(v[1]);
    const Point& c = mesh.point(v[2]);
    for (VertexId x : v) used[x] = 1;
    for (int i = 0; i < 3; ++i) {
      const HalfEdgeId e = 3 * t + i;
      if (mesh.is_constrained(e) && (mesh.twin(e) == kNone || mesh.twin(e) > e)) ++r.segments;
    }
    ++r.triangles;
    // Measured on the triangle scaled by a power of two (exact), so nothing
    // overflows or underflows at any scale; the counts below use exactly the
    // refinement's expressions on exactly scaled coordinates, so they agree
    // with it bit for bit. Lengths and areas are scaled back at the end.
    Point s[3];
    int e = 0;
    scale_triangle(a, b, c, s, e);
    const double angles[3] = {angle_at_deg(s[0], s[1], s[2]), angle_at_deg(s[1], s[2], s[0]),
                              angle_at_deg(s[2], s[0], s[1])};
    const double lo = std::min({angles[0], angles[1], angles[2]});
    const double hi = std::max({angles[0], angles[1], angles[2]});
    for (double ang : angles) r.angle_histogram[std::min<std::size_t>(17, static_cast<std::size_t>(ang / 10.0))]++;
    const double l2[3] = {squared_distance(s[0], s[1]), squared_distance(s[1], s[2]), squared_distance(s[2], s[0])};
    // Twice the area from an end of the shortest edge, with the shortest
    // edge chosen as the refinement chooses it (see its eval()).
    const int sh = shortest_edge_index(l2);
    const double o1 = l2[(sh + 1) % 3], o2 = l2[(sh + 2) % 3];
    const Point &P = s[sh], &Q = s[(sh + 1) % 3], &R = s[(sh + 2) % 3];
    const double cross = (Q.x - P.x) * (R.y - P.y) - (Q.y - P.y) * (R.x - P.x);
    const double shortest_s = std::sqrt(std::min({l2[0], l2[1], l2[2]}));
    const double longest_s = std::sqrt(std::max({l2[0], l2[1], l2[2]}));
    const double area_s = 0.5 * std::fabs(cross);
    // Shortest altitude = 2 area / longest edge.
    const double aspect = area_s > 0 ? longest_s * longest_s / (2 * area_s) : INFINITY;
    // Circumradius = abc / (4 area).
    const double radius_s = area_s > 0 ? std::sqrt(l2[0] * l2[1] * l2[2]) / (4 * area_s) : INFINITY;
    const double re = shortest_s > 0 ? radius_s / shortest_s : INFINITY;
    const double shortest = std::ldexp(shortest_s, e), longest = std::ldexp(longest_s, e);
    const double area = std::ldexp(area_s, 2 * e);
    std::size_t bin = 0;
    while (bin < QualityReport::kAspectLimits.size() && aspect > QualityReport::kAspectLimits[bin]) ++bin;
    r.aspect_histogram[bin]++;
    if (first) {
      r.min_angle_deg = lo, r.max_angle_deg = hi;
      r.min_aspect_ratio = r.max_aspect_ratio = aspect;
      r.min_radius_edge = r.max_radius_edge = re;
      r.min_area = r.max_area = area;
      r.shortest_edge = shortest, r.longest_edge = longest;
      first = false;
    } else {
      r.min_angle_deg = std::min(r.min_angle_deg, lo), r.max_angle_deg = std::max(r.max_angle_deg, hi);
      r.min_aspect_ratio = std::min(r.min_aspect_ratio, aspect);
      r.max_aspect_ratio = std::max(r.max_aspect_ratio, aspect);
      r.min_radius_edge = std::min(r.min_radius_edge, re), r.max_radius_edge = std::max(r.max_radius_edge, re);
      r.min_area = std::min(r.min_area, area), r.max_area = std::max(r.max_area, area);
      r.shortest_edge = std::min(r.shortest_edge, shortest), r.longest_edge = std::max(r.longest_edge, longest);
    }
    // Below the bound by the test refinement uses (sine of the smallest
    // angle, from the cross product and the two longer edges), so both count alike.
    if (opt.min_angle_deg > 0) {
      const double rad = opt.min_angle_deg * std::numbers::pi / 180.0;
      const double sin2 = std::sin(rad) * std::sin(rad);
      // o1, o2: the two edges beside the shortest, as the refinement takes them.
      if (cross * cross < sin2 * (o1 * o2)) ++r.below_angle;
    }
    double bound = opt.max_area;
    const double tb = mesh.triangle_area_bound(t);
    if (tb > 0 && (bound <= 0 || tb < bound)) bound = tb;
    if (bound > 0 && area > bound) ++r.above_area;
  }
  const std::size_t ninput = std::min(opt.input_vertices, nv);
  for (std::size_t v = 0; v < nv; ++v) {
    if (!used[v]) continue;
    ++r.vertices;
    if (v < ninput) ++r.input_vertices;
    else ++r.steiner_vertices;
  }
  return r;
}

std::string QualityReport::text() const {
  std::ostringstream o;
  o << "Mesh quality statistics:\n";
  o << "  triangles: " << triangles << ", vertices: " << vertices << " (" << input_vertices << " input, "
    << steiner_vertices << " Steiner), segments: " << segments << "\n";
  o << "  smallest area: " << fmt(min_area) << "   largest area: " << fmt(max_area) << "\n";
  o << "  shortest edge: " << fmt(shortest_edge) << "   longest edge: " << fmt(longest_edge) << "\n";
  o << "  smallest angle: " << fmt(min_angle_deg) << "°   largest angle: " << fmt(max_angle_deg) << "°\n";
  o << "  aspect ratio (longest edge / shortest altitude): " << fmt(min_aspect_ratio) << " .. "
    << fmt(max_aspect_ratio) << "\n";
  o << "  radius-edge ratio (circumradius / shortest edge): " << fmt(min_radius_edge) << " .. "
    << fmt(max_radius_edge) << "\n";
  o << "  aspect ratio histogram:\n";
  double lo = 2 / std::sqrt(3.0);
  for (std::size_t i = 0; i < aspect_histogram.size(); ++i) {
    const double hi = i < kAspectLimits.size() ? kAspectLimits[i] : INFINITY;
    char buf[96];
    std::snprintf(buf, sizeof buf, "    %8.4g - %-8.4g : %zu\n", lo, hi, aspect_histogram[i]);
    o << buf;
    lo = hi;
  }
  o << "  angle histogram (every angle of every triangle):\n";
  for (std::size_t i = 0; i < 9; ++i) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "    %3zu - %3zu degrees: %10zu    %3zu - %3zu degrees: %10zu\n", 10 * i,
                  10 * i + 10, angle_histogram[i], 10 * i + 90, 10 * i + 100, angle_histogram[i + 9]);
    o << buf;
  }
  if (angle_bound_deg > 0) {
    o << "  triangles with an angle below " << fmt(angle_bound_deg) << "°: " << below_angle << "\n";
    if (refine && below_angle > 0) {
      o << "    at input angles < 60° (expected): " << refine->below_small_input_angle << "\n";
      if (refine->below_segment_protected) o << "    needing a segment split -Y/-YY forbids: " << refine->below_segment_protected << "\n";
      if (refine->below_budget) o << "    left when a budget stopped refinement: " << refine->below_budget << "\n";
      if (refine->below_out_of_reach)
        o << "    where the bound is out of reach (best there " << fmt(refine->reached_angle_deg)
          << "°): " << refine->below_out_of_reach << "\n";
      if (refine->below_precision) o << "    at the precision of doubles: " << refine->below_precision << "\n";
    }
  }
  if (above_area > 0) o << "  triangles above their area bound: " << above_area << "\n";
  if (refine && refine->too_large > 0) {
    o << "  triangles left above their size bound by refinement: " << refine->too_large << "\n";
    if (refine->too_large_precision)
      o << "    at the precision of doubles: " << refine->too_large_precision << "\n";
  }
  if (refine) o << "  " << refine->summary() << "\n";
  if (metric) o << "  in the metric: " << metric->summary() << "\n";
  return o.str();
}

// The schema is docs/stats-schema.md (version kStatsSchemaVersion); Python's
// quality() returns the same object as a dict. Infinite values are null.
std::string QualityReport::json() const {
  using json = nlohmann::ordered_json;  // keys in the order written (the table's)
  auto num = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  json o;
  o["schema"] = "deltamesh-stats";
  o["schema_version"] = kStatsSchemaVersion;
  o["triangles"] = triangles;
  o["vertices"] = vertices;
  o["input_vertices"] = input_vertices;
  o["steiner_vertices"] = steiner_vertices;
  o["segments"] = segments;
  o["min_angle_deg"] = num(min_angle_deg);
  o["max_angle_deg"] = num(max_angle_deg);
  o["min_aspect_ratio"] = num(min_aspect_ratio);
  o["max_aspect_ratio"] = num(max_aspect_ratio);
  o["min_radius_edge"] = num(min_radius_edge);
  o["max_radius_edge"] = num(max_radius_edge);
  o["min_area"] = num(min_area);
  o["max_area"] = num(max_area);
  o["shortest_edge"] = num(shortest_edge);
  o["longest_edge"] = num(longest_edge);
  o["angle_histogram_deg10"] = angle_histogram;
  o["aspect_histogram"] = {{"limits", kAspectLimits}, {"counts", aspect_histogram}};
  o["angle_bound_deg"] = num(angle_bound_deg);
  o["below_angle"] = below_angle;
  o["above_area"] = above_area;
  if (refine) {
    const RefineStats& s = *refine;
    o["refine"] = {
        {"complete", s.complete},
        {"budget_exhausted", s.budget_exhausted},
        {"time_exhausted", s.time_exhausted},
        {"input_vertices", s.input_vertices},
        {"steiner_points", s.steiner_points},
        {"segment_splits", s.segment_splits},
        {"interior_points", s.interior_points},
        {"offcenters", s.offcenters},
        {"rejected_points", s.rejected_points},
        {"small_angle_skips", s.small_angle_skips},
        {"below_bound", s.below_bound},
        {"below_reasons",
         {{"small_input_angle", s.below_small_input_angle},
          {"segment_protected", s.below_segment_protected},
          {"budget", s.below_budget},
          {"out_of_reach", s.below_out_of_reach},
          {"precision", s.below_precision}}},
        {"reached_angle", num(s.reached_angle_deg)},
        {"stalled", s.stalled},
        {"too_large", s.too_large},
        {"too_large_precision", s.too_large_precision},
        {"seconds", num(s.seconds)},
    };
  }
  if (metric) {
    const MetricFit& f = *metric;
    o["metric"] = {{"edges", f.edges},
                   {"within_sqrt2", num(f.within)},
                   {"min_length", num(f.min_length)},
                   {"mean_length", num(f.mean_length)},
                   {"max_length", num(f.max_length)},
                   {"min_quality", num(f.min_quality)},
                   {"mean_quality", num(f.mean_quality)}};
  }
  return o.dump();
}

}  // namespace deltamesh
