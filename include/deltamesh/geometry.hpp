// Basic geometric types shared by every layer.
#pragma once
#include <cstdint>
#include <limits>

namespace deltamesh {

struct Point {
  double x = 0.0;
  double y = 0.0;
  friend bool operator==(const Point&, const Point&) = default;
};

// Ids are plain 32-bit indices: the mesh stores them in flat arrays, and 4 bytes
// instead of 8 is what keeps a triangle under 48 bytes.
using VertexId = std::uint32_t;
using TriId = std::uint32_t;
using HalfEdgeId = std::uint32_t;  // half-edge e = 3*t + i, from tri_v[e] to tri_v[next(e)]

inline constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
// The vertex at infinity that ghost triangles share (never a real index).
inline constexpr VertexId kInfinite = kNone - 1;

inline constexpr HalfEdgeId next_edge(HalfEdgeId e) { return e % 3 == 2 ? e - 2 : e + 1; }
inline constexpr HalfEdgeId prev_edge(HalfEdgeId e) { return e % 3 == 0 ? e + 2 : e - 1; }
inline constexpr TriId tri_of(HalfEdgeId e) { return e / 3; }

}  // namespace deltamesh
