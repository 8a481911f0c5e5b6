// Seeded input generators shared by deltamesh-gen, the tests and the
// benchmarks. Every draw goes through Rng below, whose distributions are
// written out here: std::uniform_real_distribution and friends are not
// specified bit for bit, so the same seed would give different inputs on
// another standard library. std::mt19937_64 is fully specified, so uniform,
// grid, collinear and duplicates are bit-identical everywhere; gaussian,
// cocircular, star and smooth also call libm (log, cos, sin), whose last bit
// may differ between C libraries.
#pragma once
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <optional>
#include <random>
#include <string_view>
#include <utility>
#include <vector>

#include "deltamesh/geometry.hpp"
#include "deltamesh/pslg.hpp"

namespace deltamesh::gen {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(seed) {}

  std::uint64_t bits() { return engine_(); }
  // Uniform in [0, 1): the top 53 bits of one draw.
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Uniform integer in [0, n), n > 0, without modulo bias (rejection).
  std::uint64_t below(std::uint64_t n) {
    const std::uint64_t limit = -n % n;  // 2^64 mod n: draws under it are rejected
    for (;;) {
      const std::uint64_t r = engine_();
      if (r >= limit) return r % n;
    }
  }
  // Standard normal by the Marsaglia polar method.
  double normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u, v, s;
    do {
      u = 2.0 * uniform() - 1.0;
      v = 2.0 * uniform() - 1.0;
      s = u * u + v * v;
    } while (s >= 1.0 || s == 0.0);
    const double f = std::sqrt(-2.0 * std::log(s) / s);
    spare_ = v * f;
    has_spare_ = true;
    return u * f;
  }

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

enum class Kind { Uniform, Gaussian, Grid, Collinear, Cocircular, Duplicates, Star, SquareHole, Smooth };

struct KindInfo {
  Kind kind;
  std::string_view name;
  std::string_view help;
};

inline constexpr KindInfo kKinds[] = {
    {Kind::Uniform, "uniform", "N points uniform in the unit square"},
    {Kind::Gaussian, "gaussian", "N points in 10 gaussian clusters in about the unit square"},
    {Kind::Grid, "grid", "k*k points on the integer grid, k = round(sqrt(N)) (all cocircular)"},
    {Kind::Collinear, "collinear", "N points on the line y = 2x, x uniform in [0,1)"},
    {Kind::Cocircular, "cocircular", "N points on the unit circle, coordinates rounded to double"},
    {Kind::Duplicates, "duplicates", "N points, about half of them copies of the others"},
    {Kind::Star, "star", "star-shaped polygon, N vertices, radii uniform in [0.5,1] (.poly)"},
    {Kind::SquareHole, "square-hole", "unit square with the hole [0.4,0.6]^2, ~N boundary vertices (.poly)"},
    {Kind::Smooth, "smooth", "polygon r(t) = 0.7 + 0.2 sin 7t + 0.05 sin 53t, N vertices (.poly, from 1)"},
};

inline std::optional<Kind> parse_kind(std::string_view name) {
  for (const KindInfo& k : kKinds)
    if (k.name == name) return k.kind;
  return std::nullopt;
}

// Kinds whose output is a PSLG with segments (always written as .poly).
inline bool is_polygon_kind(Kind kind) {
  return kind == Kind::Star || kind == Kind::SquareHole || kind == Kind::Smooth;
}

// Fisher-Yates with our own integer draws.
template <class T>
void shuffle(std::vector<T>& v, Rng& rng) {
  for (std::size_t i = v.size(); i > 1; --i) std::swap(v[i - 1], v[rng.below(i)]);
}

inline std::vector<Point> uniform_points(std::size_t n, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<Point> p(n);
  for (Point& q : p) {
    q.x = rng.uniform();
    q.y = rng.uniform();
  }
  return p;
}

inline std::vector<Point> gaussian_points(std::size_t n, std::uint64_t seed) {
  constexpr int kClusters = 10;
  Rng rng(seed);
  Point center[kClusters];
  double sigma[kClusters];
  for (int c = 0; c < kClusters; ++c) {
    center[c] = {rng.uniform(0.1, 0.9), rng.uniform(0.1, 0.9)};
    sigma[c] = rng.uniform(0.01, 0.06);
  }
  std::vector<Point> p(n);
  for (Point& q : p) {
    const auto c = rng.below(kClusters);
    q.x = center[c].x + sigma[c] * rng.normal();
    q.y = center[c].y + sigma[c] * rng.normal();
  }
  return p;
}

// k*k points (i, j), row by row; k = round(sqrt(n)).
inline std::vector<Point> grid_points(std::size_t n) {
  const auto k = static_cast<std::size_t>(std::llround(std::sqrt(static_cast<double>(n))));
  std::vector<Point> p;
  p.reserve(k * k);
  for (std::size_t j = 0; j < k; ++j)
    for (std::size_t i = 0; i < k; ++i) p.push_back({static_cast<double>(i), static_cast<double>(j)});
  return p;
}

// (t, 2t) is exactly collinear: doubling is exact.
inline std::vector<Point> collinear_points(std::size_t n, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<Point> p(n);
  for (Point& q : p) {
    const double t = rng.uniform();
    q = {t, 2.0 * t};
  }
  return p;
}

// On the unit circle up to the rounding of cos and sin: a near-degenerate case.
inline std::vector<Point> cocircular_points(std::size_t n, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<Point> p(n);
  for (Point& q : p) {
    const double a = 2.0 * std::numbers::pi * rng.uniform();
    q = {std::cos(a), std::sin(a)};
  }
  return p;
}

// ceil(n/2) distinct uniform points, then copies of random ones, shuffled.
inline std::vector<Point> duplicate_points(std::size_t n, std::uint64_t seed) {
  Rng rng(seed);
  const std::size_t distinct = (n + 1) / 2;
  std::vector<Point> p(distinct);
  for (Point& q : p) {
    q.x = rng.uniform();
    q.y = rng.uniform();
  }
  p.reserve(n);
  for (std::size_t i = distinct; i < n; ++i) p.push_back(p[rng.below(distinct)]);
  shuffle(p, rng);
  return p;
}

// Vertex i at angle 2*pi*i/n (increasing, so the ring is simple), radius
// uniform in [0.5, 1]; segments close the ring. Needs n >= 3.
inline Pslg star_polygon(std::size_t n, std::uint64_t seed) {
  Rng rng(seed);
  Pslg g;
  g.points.resize(n);
  g.segments.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double a = 2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(n);
    const double r = rng.uniform(0.5, 1.0);
    g.points[i] = {r * std::cos(a), r * std::sin(a)};
    g.segments[i] = {static_cast<VertexId>(i), static_cast<VertexId>((i + 1) % n), 0};
  }
  return g;
}

// The smooth polygon of the benchmarks: vertex i at t = 2 pi i / n on
// r(t) = 0.7 + 0.2 sin 7t + 0.05 sin 53t (r > 0 and t increasing, so the
// ring is simple), segment i joining vertices i and i+1, the last one back
// to vertex 0. Numbered from 1 in files (first_index). Needs n >= 3.
inline Pslg smooth_polygon(std::size_t n) {
  Pslg g;
  g.first_index = 1;
  g.points.resize(n);
  g.segments.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = 2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(n);
    const double r = 0.7 + 0.2 * std::sin(7.0 * t) + 0.05 * std::sin(53.0 * t);
    g.points[i] = {r * std::cos(t), r * std::sin(t)};
    g.segments[i] = {static_cast<VertexId>(i), static_cast<VertexId>((i + 1) % n), 0};
  }
  return g;
}

// The unit square with the hole [0.4,0.6]^2: each of the 8 sides is split
// into m = max(1, n/8) segments, and a hole point marks the hole.
inline Pslg square_with_hole(std::size_t n) {
  const std::size_t m = n / 8 > 0 ? n / 8 : 1;
  Pslg g;
  auto ring = [&](double lo, double hi) {
    const auto first = static_cast<VertexId>(g.points.size());
    const Point corner[4] = {{lo, lo}, {hi, lo}, {hi, hi}, {lo, hi}};
    for (int s = 0; s < 4; ++s) {
      const Point a = corner[s], b = corner[(s + 1) % 4];
      for (std::size_t i = 0; i < m; ++i) {
        const double t = static_cast<double>(i) / static_cast<double>(m);
        // Corners exactly, and the moving coordinate as lo + (hi-lo)*t.
        g.points.push_back({a.x == b.x ? a.x : a.x + (b.x - a.x) * t, a.y == b.y ? a.y : a.y + (b.y - a.y) * t});
      }
    }
    const auto count = static_cast<VertexId>(g.points.size()) - first;
    for (VertexId i = 0; i < count; ++i) g.segments.push_back({first + i, first + (i + 1) % count, 0});
  };
  ring(0.0, 1.0);
  ring(0.4, 0.6);
  g.holes.push_back({0.5, 0.5});
  return g;
}

// The input of `kind` with about n vertices, coordinates multiplied by scale.
inline Pslg generate(Kind kind, std::size_t n, std::uint64_t seed, double scale = 1.0) {
  Pslg g;
  switch (kind) {
    case Kind::Uniform: g.points = uniform_points(n, seed); break;
    case Kind::Gaussian: g.points = gaussian_points(n, seed); break;
    case Kind::Grid: g.points = grid_points(n); break;
    case Kind::Collinear: g.points = collinear_points(n, seed); break;
    case Kind::Cocircular: g.points = cocircular_points(n, seed); break;
    case Kind::Duplicates: g.points = duplicate_points(n, seed); break;
    case Kind::Star: g = star_polygon(n, seed); break;
    case Kind::SquareHole: g = square_with_hole(n); break;
    case Kind::Smooth: g = smooth_polygon(n); break;
  }
  if (scale != 1.0) {
    for (Point& p : g.points) p = {p.x * scale, p.y * scale};
    for (Point& p : g.holes) p = {p.x * scale, p.y * scale};
  }
  return g;
}

}  // namespace deltamesh::gen
