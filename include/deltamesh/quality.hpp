// Mesh quality report (seed §3.2, §3.4): angles, aspect ratio, radius-edge
// ratio, sizes, and the triangles below a bound with the reasons refinement
// gave. Printable text for -V and JSON for --stats=json.
#pragma once
#include <array>
#include <cstddef>
#include <optional>
#include <string>

#include "deltamesh/mesh.hpp"
#include "deltamesh/metric.hpp"
#include "deltamesh/refine.hpp"

namespace deltamesh {

struct QualityOptions {
  // Count triangles whose smallest angle is below this (0: none).
  double min_angle_deg = 0.0;
  // Count triangles above this area, or above their own per-triangle bound
  // when the mesh carries them (<= 0: only per-triangle bounds).
  double max_area = -1.0;
  // Vertices with ids below this were input vertices; the rest are Steiner
  // points. Default: every vertex is an input vertex.
  std::size_t input_vertices = static_cast<std::size_t>(-1);
};

// The version of the JSON object QualityReport::json() writes (--stats=json,
// Python's quality()); docs/stats-schema.md. Raised when a key changes
// meaning or goes; new keys may appear within a version.
inline constexpr int kStatsSchemaVersion = 1;

struct QualityReport {
  std::size_t triangles = 0;
  std::size_t vertices = 0;          // vertices used by a triangle
  std::size_t input_vertices = 0;    // ... of which input vertices
  std::size_t steiner_vertices = 0;  // ... and Steiner points
  std::size_t segments = 0;          // constrained edges (subsegments)

  double min_angle_deg = 0.0;
  double max_angle_deg = 0.0;
  // Every angle of every triangle, in 10° bins: [0,10), [10,20), ... [170,180].
  std::array<std::size_t, 18> angle_histogram{};
  // Aspect ratio (§3.2): longest edge / shortest altitude, >= 2/sqrt(3).
  double min_aspect_ratio = 0.0;
  double max_aspect_ratio = 0.0;
  // Bins with upper limits 1.5, 2, 2.5, 3, 4, 6, 10, 15, 25, 50, 100, 1000, inf.
  static constexpr std::array<double, 12> kAspectLimits{1.5, 2, 2.5, 3, 4, 6, 10, 15, 25, 50, 100, 1000};
  std::array<std::size_t, 13> aspect_histogram{};
  // Radius-edge ratio (§3.4): circumradius / shortest edge, >= 1/sqrt(3).
  double min_radius_edge = 0.0;
  double max_radius_edge = 0.0;
  double min_area = 0.0, max_area = 0.0;
  double shortest_edge = 0.0, longest_edge = 0.0;

  double angle_bound_deg = 0.0;      // the bound counted against
  std::size_t below_angle = 0;       // triangles whose smallest angle is below the bound
  std::size_t above_area = 0;        // triangles above their area bound
  std::optional<RefineStats> refine; // why triangles are below the bound, when refinement ran
  std::optional<MetricFit> metric;   // after adaptation to a metric: edge lengths and quality in it

  std::string text() const;
  std::string json() const;  // one line, docs/stats-schema.md
};

QualityReport quality_report(const Mesh& mesh, const QualityOptions& options = {},
                             const RefineStats* refine_stats = nullptr);

}  // namespace deltamesh
