// Exact power-of-two normalisation (see normalize.hpp).
#include "algo/normalize.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "core/parallel.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/predicates.hpp"
#include "mesh/editor.hpp"

namespace deltamesh::detail {

namespace {

double scale_positive(double v, int e) {
  if (!(v > 0)) return v;
  const double s = std::ldexp(v, e);
  return s > 0 ? s : std::numeric_limits<double>::denorm_min();
}

double largest(std::span<const Point> points) {
  double m = 0;
  for (const Point& p : points) m = std::max({m, std::fabs(p.x), std::fabs(p.y)});
  return m;
}

// Parts of [0, n) for up to `threads` threads (0 = every hardware one):
// one part below kMinChunk elements per part.
constexpr std::size_t kMinChunk = std::size_t{1} << 17;
std::size_t chunks_for(std::size_t n, unsigned threads) {
  return std::max<std::size_t>(1, std::min<std::size_t>(resolve_threads(threads), n / kMinChunk));
}
std::span<const Point> chunk(std::span<const Point> points, std::size_t j, std::size_t chunks) {
  const std::size_t b = points.size() * j / chunks, e = points.size() * (j + 1) / chunks;
  return points.subspan(b, e - b);
}

std::string show(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace

double Frame::area_to(double a) const { return scale_positive(a, 2 * k); }
double Frame::length_to(double h) const { return scale_positive(h, k); }
double Frame::area_from(double a) const { return scale_positive(a, -2 * k); }

std::function<double(double, double)> Frame::area_field_to(std::function<double(double, double)> f) const {
  if (!f || identity()) return f;
  return [f = std::move(f), k = k, self = *this](double x, double y) {
    return self.area_to(f(std::ldexp(x, -k), std::ldexp(y, -k)));
  };
}

std::function<double(double, double)> Frame::length_field_to(std::function<double(double, double)> f) const {
  if (!f || identity()) return f;
  return [f = std::move(f), k = k, self = *this](double x, double y) {
    return self.length_to(f(std::ldexp(x, -k), std::ldexp(y, -k)));
  };
}

Frame frame_for(std::span<const Point> points, unsigned threads) {
  // One pass in parts (the whole input, on the serial path). A NaN or an
  // infinity only sets a flag; the loop below then names the first.
  struct Extent {
    double m = 0, lo = INFINITY;  // largest, and smallest nonzero, magnitude
    bool bad = false;
  };
  const auto extent = [](std::span<const Point> part) {
    Extent x;
    for (const Point& p : part) {
      const double ax = std::fabs(p.x), ay = std::fabs(p.y);
      x.bad |= !(ax <= std::numeric_limits<double>::max() && ay <= std::numeric_limits<double>::max());
      const double big = ax < ay ? ay : ax;
      x.m = x.m < big ? big : x.m;
      const double sx = ax > 0 ? ax : INFINITY, sy = ay > 0 ? ay : INFINITY;
      const double small = sx < sy ? sx : sy;
      x.lo = small < x.lo ? small : x.lo;
    }
    return x;
  };
  const std::size_t chunks = chunks_for(points.size(), threads);
  std::vector<Extent> parts(chunks);
  if (chunks == 1)
    parts[0] = extent(points);
  else
    run_tasks(chunks, resolve_threads(threads), [&](std::size_t j) { parts[j] = extent(chunk(points, j, chunks)); });
  double m = 0, lo = INFINITY;
  bool bad = false;
  for (const Extent& x : parts) {  // max and min: the same whatever the parts
    m = std::max(m, x.m);
    lo = std::min(lo, x.lo);
    bad |= x.bad;
  }
  for (std::size_t i = 0; bad && i < points.size(); ++i) {
    const Point& p = points[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) {
      const bool bad_x = !std::isfinite(p.x);
      const double v = bad_x ? p.x : p.y;
      throw InputError(std::string("coordinate ") + (bad_x ? "x" : "y") + " of point " + std::to_string(i) + " is " +
                           (std::isnan(v) ? "NaN" : "infinite"),
                       i);
    }
  }
  Frame f;
  if (m == 0) return f;
  int e = 0, elo = 0;
  std::frexp(m, &e);  // m = g 2^e, g in [1/2, 1)
  std::frexp(lo, &elo);
  // The largest magnitude in [1/2, 1), where every measure is safe. When the
  // smallest nonzero one would then fall below the predicates' 2^-200, the
  // input goes in the middle of their range instead: raised only until it
  // reached 2^-200, a refinement's midpoints and circumcentres near zero
  // (finer than the input's own coordinates) were rounded to 0 there, far
  // off their segments (tests/regress/refine_segment_chain_beside_far_hull_vertex.poly).
  int highest = 200 - e;  // m 2^highest < 2^200; one more when m is a power of two
  if (std::ldexp(m, highest + 1) <= kMaxCoordinate) ++highest;
  const int lowest = -199 - elo;  // lo 2^lowest >= 2^-200
  if (-e >= lowest)
    f.k = -e;
  else if (lowest >= highest)
    f.k = highest;  // no room to spare (if too little, scale_vertices names the coordinate)
  else
    f.k = lowest + (highest - lowest) / 2;
  return f;
}

namespace {

// x 2^k: a product with a power of two is exact, and rounds as ldexp does
// when the result is subnormal, at a fraction of ldexp's cost (millions of
// coordinates on the serial path); ldexp where 2^k is not a double.
double times_power_of_two(double v, int k, double p) { return p > 0 ? v * p : std::ldexp(v, k); }

double power_of_two(int k) { return k >= -1022 && k <= 1023 ? std::ldexp(1.0, k) : 0.0; }

}  // namespace

void scale_vertices(const Frame& f, std::vector<Point>& points, unsigned threads) {
  const double pk = power_of_two(f.k);
  if (pk > 0) {
    // Branch-free passes over the whole input (the serial path), in parts:
    // is any nonzero coordinate too small once scaled? If not, scale
    // (nothing to do in the identity frame). Else the loop below names the
    // first.
    const double small = kMinCoordinate;
    const std::size_t chunks = chunks_for(points.size(), threads);
    std::vector<std::uint8_t> tiny(chunks, 0);
    run_tasks(chunks, resolve_threads(threads), [&](std::size_t j) {
      bool t = false;
      for (const Point& p : chunk(points, j, chunks)) {
        const double sx = std::fabs(p.x * pk), sy = std::fabs(p.y * pk);
        t |= ((sx < small) & (p.x != 0)) | ((sy < small) & (p.y != 0));
      }
      tiny[j] = t;
    });
    if (std::find(tiny.begin(), tiny.end(), 1) == tiny.end()) {
      if (!f.identity())
        run_tasks(chunks, resolve_threads(threads), [&](std::size_t j) {
          const std::size_t b = points.size() * j / chunks, e = points.size() * (j + 1) / chunks;
          for (std::size_t i = b; i < e; ++i) points[i] = {points[i].x * pk, points[i].y * pk};
        });
      return;
    }
  }
  const double big = largest(points);  // before the loop scales points in place
  for (std::size_t i = 0; i < points.size(); ++i) {
    Point& p = points[i];
    const Point q{times_power_of_two(p.x, f.k, pk), times_power_of_two(p.y, f.k, pk)};
    for (int c = 0; c < 2; ++c) {
      const double v = c ? p.y : p.x, s = c ? q.y : q.x;
      if (v != 0 && std::fabs(s) < kMinCoordinate) {
        const std::string problem = std::string("coordinate ") + (c ? "y" : "x") + " (" + show(v) +
                                    ") is nonzero but too small beside the largest coordinate magnitude (" +
                                    show(big) +
                                    "): the exact predicates resolve nonzero coordinates within a ratio of about "
                                    "2^400 (1e120) of the largest";
        throw VertexError("point " + std::to_string(i) + ": " + problem, i, problem);
      }
    }
    p = q;
  }
}

void scale_seeds(const Frame& f, std::vector<Point>& points) {
  const double big = 0x1p100;
  for (Point& p : points)
    for (double* v : {&p.x, &p.y}) {
      if (!std::isfinite(*v)) continue;  // refused where seeds are read
      double s = std::ldexp(*v, f.k);
      if (std::fabs(s) > big) s = std::copysign(big, s);
      if (std::fabs(s) < kMinCoordinate) s = 0.0;
      *v = s;
    }
}

bool needs_frame(std::span<const Point> points) {
  const double hi = kMaxCoordinate, lo = kMinCoordinate;
  // One branch-free pass (NaN fails every comparison); an infinity also
  // flags it, so a flagged input is looked at again for a finite culprit.
  bool out = false;
  for (const Point& p : points) {
    const double ax = std::fabs(p.x), ay = std::fabs(p.y);
    out |= (ax > hi) | (ay > hi) | ((ax < lo) & (ax != 0)) | ((ay < lo) & (ay != 0));
  }
  if (!out) return false;
  for (const Point& p : points)
    for (const double v : {std::fabs(p.x), std::fabs(p.y)})
      if (std::isfinite(v) && (v > hi || (v < lo && v != 0))) return true;
  return false;
}

bool in_predicate_range(std::span<const Point> points, unsigned threads) {
  const double hi = kMaxCoordinate, lo = kMinCoordinate;
  const auto scan = [hi, lo](std::span<const Point> part) {
    bool out = false;  // NaN fails every comparison
    for (const Point& p : part) {
      const double ax = std::fabs(p.x), ay = std::fabs(p.y);
      out |= !(ax <= hi) | !(ay <= hi) | ((ax < lo) & (ax != 0)) | ((ay < lo) & (ay != 0));
    }
    return !out;
  };
  const std::size_t chunks = chunks_for(points.size(), threads);
  if (chunks == 1) return scan(points);
  std::vector<std::uint8_t> ok(chunks, 0);
  run_tasks(chunks, resolve_threads(threads), [&](std::size_t j) { ok[j] = scan(chunk(points, j, chunks)); });
  return std::all_of(ok.begin(), ok.end(), [](std::uint8_t b) { return b != 0; });
}

Pslg scaled_pslg(const Frame& f, Pslg pslg) {
  scale_vertices(f, pslg.points);
  scale_seeds(f, pslg.holes);
  std::vector<Point> seeds;
  for (const RegionSeed& r : pslg.regions) seeds.push_back(r.p);
  scale_seeds(f, seeds);
  for (std::size_t i = 0; i < seeds.size(); ++i) {
    pslg.regions[i].p = seeds[i];
    pslg.regions[i].max_area = f.area_to(pslg.regions[i].max_area);
  }
  return pslg;
}

void scale_options(const Frame& f, RefineOptions& options) {
  options.max_area = f.area_to(options.max_area);
  options.max_area_at = f.area_field_to(std::move(options.max_area_at));
  options.max_edge_at = f.length_field_to(std::move(options.max_edge_at));
}

void scale_mesh(const Frame& f, Mesh& mesh) {
  std::vector<Point>& points = detail::MeshEditor(mesh).points();
  std::vector<Point> framed = points;
  scale_vertices(f, framed);  // may throw: the mesh is left as it was
  points.swap(framed);
  if (mesh.has_triangle_area_bounds())
    for (TriId t = 0; t < mesh.num_triangle_slots(); ++t) {
      const double a = mesh.triangle_area_bound(t);
      if (a > 0) mesh.set_triangle_area_bound(t, f.area_to(a));
    }
}

void restore(const Frame& f, Mesh& mesh) {
  if (f.identity()) return;  // every vertex and bound as it is
  const double pk = power_of_two(-f.k);
  for (Point& p : detail::MeshEditor(mesh).points())
    p = {times_power_of_two(p.x, -f.k, pk), times_power_of_two(p.y, -f.k, pk)};
  if (mesh.has_triangle_area_bounds())
    for (TriId t = 0; t < mesh.num_triangle_slots(); ++t) {
      const double a = mesh.triangle_area_bound(t);
      if (a > 0) mesh.set_triangle_area_bound(t, f.area_from(a));
    }
}

void restore(const Frame& f, RefineStats& st) {
  const int k = -f.k;
  st.stall_x = std::ldexp(st.stall_x, k);
  st.stall_y = std::ldexp(st.stall_y, k);
  st.stall_radius = std::ldexp(st.stall_radius, k);
  st.precision_x = std::ldexp(st.precision_x, k);
  st.precision_y = std::ldexp(st.precision_y, k);
  st.precision_edge = std::ldexp(st.precision_edge, k);
  st.precision_magnitude = std::ldexp(st.precision_magnitude, k);
}

}  // namespace deltamesh::detail
