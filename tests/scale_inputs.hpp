// Inputs of the scale tests (test_scale.cpp, test_scale_long.cpp): the
// bundled plate, a holed square with scattered points, and a sample of the
// shared corpus (all of its .poly files in the long test; skipped when the
// corpus is missing).
#pragma once
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "deltamesh/deltamesh.hpp"

namespace deltamesh::test {

struct ScaleInput {
  std::string name;
  Pslg pslg;
  double area = 0;           // an area bound: 1/200 of the bounding box
};

inline Pslg scaled_pslg(Pslg p, double s) {
  for (Point& q : p.points) q = {q.x * s, q.y * s};
  for (Point& q : p.holes) q = {q.x * s, q.y * s};
  for (RegionSeed& r : p.regions) {
    r.p = {r.p.x * s, r.p.y * s};
    if (r.max_area > 0) r.max_area = r.max_area * s * s;  // exact for powers of two in range
  }
  return p;
}

// The unit square with a square hole and 20 scattered points (the issue's
// shape; points from a fixed linear congruential sequence).
inline Pslg holed_square() {
  Pslg p;
  p.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.3, 0.3}, {0.6, 0.3}, {0.6, 0.55}, {0.3, 0.55}};
  unsigned long long s = 12345;
  auto next = [&s] {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    return double(s >> 11) * 0x1p-53;
  };
  while (p.points.size() < 28) {
    const double x = 0.02 + 0.96 * next(), y = 0.02 + 0.96 * next();
    if (x > 0.27 && x < 0.63 && y > 0.27 && y < 0.58) continue;
    p.points.push_back({x, y});
  }
  for (VertexId i = 0; i < 4; ++i) p.segments.push_back({i, (i + 1) % 4, 1});
  for (VertexId i = 0; i < 4; ++i) p.segments.push_back({4 + i, 4 + (i + 1) % 4, 2});
  p.holes = {{0.45, 0.42}};
  return p;
}

// [-1, 1]^2 with a square of side 1e-12 at (1e-12, 1e-12) inside.
inline Pslg tiny_square_in_box() {
  Pslg p;
  p.points = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {1e-12, 1e-12}, {2e-12, 1e-12}, {2e-12, 2e-12}, {1e-12, 2e-12}};
  for (VertexId i = 0; i < 4; ++i) p.segments.push_back({i, (i + 1) % 4, 1});
  for (VertexId i = 0; i < 4; ++i) p.segments.push_back({4 + i, 4 + (i + 1) % 4, 2});
  return p;
}

inline ScaleInput scale_input(std::string name, Pslg p) {
  double lox = INFINITY, hix = -INFINITY, loy = INFINITY, hiy = -INFINITY;
  for (const Point& q : p.points)
    lox = std::min(lox, q.x), hix = std::max(hix, q.x), loy = std::min(loy, q.y), hiy = std::max(hiy, q.y);
  ScaleInput in;
  in.name = std::move(name);
  in.pslg = std::move(p);
  in.area = (hix - lox) * (hiy - loy) / 200;
  return in;
}

inline std::filesystem::path corpus_dir() {
  return std::filesystem::path(DELTAMESH_SOURCE_DIR) / ".." / "shared" / "corpus";
}

// all_corpus: every corpus .poly (the long test); else a sample of four.
inline std::vector<ScaleInput> scale_inputs(bool all_corpus) {
  std::vector<ScaleInput> v;
  v.push_back(scale_input("plate", read_poly(std::string(DELTAMESH_SOURCE_DIR) + "/examples/plate.poly")));
  v.push_back(scale_input("holed square", holed_square()));
  std::vector<std::string> names;
  std::error_code ec;
  if (all_corpus) {
    for (const auto& e : std::filesystem::directory_iterator(corpus_dir(), ec))
      if (e.path().extension() == ".poly") names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
  } else {
    names = {"cdt_kidney.poly", "cdt_island.poly", "airfoil_channel_naca0012.poly", "earcut_dude.poly"};
  }
  for (const std::string& n : names) {
    const auto path = corpus_dir() / n;
    if (!std::filesystem::exists(path, ec)) continue;
    v.push_back(scale_input(n, read_poly(path.string())));
  }
  return v;
}

}  // namespace deltamesh::test
