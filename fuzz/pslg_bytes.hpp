// Shared by the targets that build a small PSLG from fuzzer bytes
// (fuzz_insert_segments, fuzz_adapt): coordinates from bytes, a polygon ring
// plus random segments, and the PSLG as a .poly for crash reports.
#pragma once
#include <fuzzer/FuzzedDataProvider.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <string>

#include "deltamesh/errors.hpp"
#include "deltamesh/pslg.hpp"
#include "deltamesh/triangulate.hpp"
#include "fuzz_util.hpp"

namespace deltamesh::fuzz {

// Coordinates: a small integer grid (exact collinearities and cocircular
// points), the grid scaled and offset, or the grid with each coordinate
// moved by a few ulps (nearly collinear points, near-misses of vertices).
struct Coords {
  int mode = 0;
  int grid = 8;
  double scale = 1.0, ox = 0.0, oy = 0.0;

  void init(FuzzedDataProvider& in) {
    mode = in.ConsumeIntegralInRange<int>(0, 2);
    grid = in.ConsumeIntegralInRange<int>(1, 16);
    if (mode != 0) {
      scale = std::ldexp(1.0, in.ConsumeIntegralInRange<int>(-60, 60));
      const int shift = in.ConsumeIntegralInRange<int>(0, 40);
      ox = in.ConsumeBool() ? std::ldexp(scale, shift) : 0.0;
      oy = in.ConsumeBool() ? -std::ldexp(scale, shift / 2) : 0.0;
    }
  }
  double coord(FuzzedDataProvider& in, double offset) const {
    double v = in.ConsumeIntegralInRange<int>(0, grid);
    if (mode == 0) return v;
    v = offset + scale * v;
    if (mode == 2) {
      const int ulps = in.ConsumeIntegralInRange<int>(-3, 3);
      for (int k = 0; k < std::abs(ulps); ++k) v = std::nextafter(v, ulps > 0 ? INFINITY : -INFINITY);
    }
    return v;
  }
  Point point(FuzzedDataProvider& in) const {
    const double x = coord(in, ox);
    return {x, coord(in, oy)};
  }
};

// n points, then m segments: the first min(n, m) close the polygon
// 0-1-...-(ring-1) when `ring` (so that carving keeps something), the rest
// join random vertices; markers 0..3. Then a hole point when `hole`.
inline void read_pslg(FuzzedDataProvider& in, const Coords& cm, std::size_t n, std::size_t m, bool ring, bool hole,
                      Pslg& g) {
  for (std::size_t i = 0; i < n; ++i) g.points.push_back(cm.point(in));
  const std::size_t closed = ring ? std::min(n, m) : 0;
  for (std::size_t i = 0; i < m; ++i) {
    Segment s;
    if (i < closed) {
      s.a = static_cast<VertexId>(i);
      s.b = static_cast<VertexId>((i + 1) % closed);
    } else {
      s.a = in.ConsumeIntegralInRange<VertexId>(0, static_cast<VertexId>(n - 1));
      s.b = in.ConsumeIntegralInRange<VertexId>(0, static_cast<VertexId>(n - 1));
    }
    s.marker = in.ConsumeIntegralInRange<int>(0, 3);
    g.segments.push_back(s);
  }
  if (hole) g.holes.push_back(cm.point(in));
}

// The PSLG as a .poly file (shortest round-trip decimals), printed with
// DELTAMESH_FUZZ_VERBOSE: a crash becomes a regression input by copying it.
inline std::string to_poly(const Pslg& g) {
  char buf[64];
  auto num = [&](double v) {
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
  };
  std::string s = std::to_string(g.points.size()) + " 2 " + std::to_string(g.num_point_attributes) + " " +
                  (g.point_markers.empty() ? "0" : "1") + "\n";
  for (std::size_t i = 0; i < g.points.size(); ++i) {
    s += std::to_string(i) + " " + num(g.points[i].x) + " " + num(g.points[i].y);
    for (std::size_t k = 0; k < g.num_point_attributes; ++k)
      s += " " + num(g.point_attributes[i * g.num_point_attributes + k]);
    if (!g.point_markers.empty()) s += " " + std::to_string(g.point_markers[i]);
    s += "\n";
  }
  s += std::to_string(g.segments.size()) + " 1\n";
  for (std::size_t i = 0; i < g.segments.size(); ++i)
    s += std::to_string(i) + " " + std::to_string(g.segments[i].a) + " " + std::to_string(g.segments[i].b) + " " +
         std::to_string(g.segments[i].marker) + "\n";
  s += std::to_string(g.holes.size()) + "\n";
  for (std::size_t i = 0; i < g.holes.size(); ++i)
    s += std::to_string(i) + " " + num(g.holes[i].x) + " " + num(g.holes[i].y) + "\n";
  s += std::to_string(g.regions.size()) + "\n";
  for (std::size_t i = 0; i < g.regions.size(); ++i)
    s += std::to_string(i) + " " + num(g.regions[i].p.x) + " " + num(g.regions[i].p.y) + " " +
         num(g.regions[i].attribute) + " " + num(g.regions[i].max_area) + "\n";
  return s;
}

// triangulate() under the targets' rules: an InputError (bad input) ends
// the run quietly; any other exception (InternalError among them) is a bug.
// False: nothing to go on with (an error, or no triangle left).
inline bool triangulate_or_stop(const Pslg& g, const TriangulateOptions& options, Mesh& out) {
  try {
    out = triangulate(g, options);
  } catch (const InputError&) {
    return false;
  } catch (...) {
    unexpected_exception("triangulate");
  }
  return out.num_triangles() > 0;
}

}  // namespace deltamesh::fuzz
