// Invariants of a Pslg returned by a reader.
#pragma once
#include <cmath>
#include <string>

#include "deltamesh/pslg.hpp"
#include "fuzz_util.hpp"

namespace deltamesh::fuzz {

inline void check_finite(const Point& p, const char* what) {
  DELTAMESH_FUZZ_CHECK(std::isfinite(p.x) && std::isfinite(p.y), std::string(what) + " is not finite");
}

// strict_regions: a region's area bound is -1 or positive (the Triangle
// readers normalise it; GeoJSON passes the property through).
inline void check_pslg(const Pslg& g, bool strict_regions = true) {
  const std::size_t n = g.points.size();
  for (const Point& p : g.points) check_finite(p, "a vertex");
  DELTAMESH_FUZZ_CHECK(g.point_markers.empty() || g.point_markers.size() == n, "one marker per vertex");
  DELTAMESH_FUZZ_CHECK(g.point_attributes.size() == n * g.num_point_attributes, "attributes per vertex");
  for (const double a : g.point_attributes) DELTAMESH_FUZZ_CHECK(std::isfinite(a), "vertex attribute not finite");
  DELTAMESH_FUZZ_CHECK(g.first_index == 0 || g.first_index == 1, "first index " + std::to_string(g.first_index));
  for (const Segment& s : g.segments) {
    // (A segment with one vertex at both ends is read; meshing ignores it.)
    DELTAMESH_FUZZ_CHECK(s.a < n && s.b < n, "segment endpoint out of range");
  }
  for (const Point& h : g.holes) check_finite(h, "a hole");
  for (const RegionSeed& r : g.regions) {
    check_finite(r.p, "a region point");
    DELTAMESH_FUZZ_CHECK(std::isfinite(r.attribute), "region attribute not finite");
    DELTAMESH_FUZZ_CHECK(!strict_regions || r.max_area == -1.0 || (r.max_area > 0 && std::isfinite(r.max_area)),
                         "region area bound " + std::to_string(r.max_area));
  }
}

}  // namespace deltamesh::fuzz
