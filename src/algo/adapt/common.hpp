// Helpers shared by coarsening, smoothing and the adaptation pipelines.
#pragma once
#include <chrono>
#include <cmath>
#include <cstddef>

#include "deltamesh/geometry.hpp"

namespace deltamesh::adaptation {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

inline double dist(const Point& a, const Point& b) { return std::hypot(a.x - b.x, a.y - b.y); }

// Vertices of higher degree are never removed nor moved (reducing one costs
// O(degree^2)).
constexpr std::size_t kMaxDegree = 4096;

}  // namespace deltamesh::adaptation
