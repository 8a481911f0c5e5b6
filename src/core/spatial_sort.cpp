#include "core/spatial_sort.hpp"

#include <algorithm>
#include <cmath>

namespace deltamesh::detail {

std::uint32_t hilbert_index(std::uint32_t x, std::uint32_t y) {
  // Quadrant by quadrant from the top bit, rotating/reflecting the frame.
  constexpr std::uint32_t n = 1u << 16;
  std::uint32_t d = 0;
  for (std::uint32_t s = n / 2; s > 0; s /= 2) {
    const std::uint32_t rx = (x & s) ? 1 : 0;
    const std::uint32_t ry = (y & s) ? 1 : 0;
    d += s * s * ((3 * rx) ^ ry);
    if (ry == 0) {
      if (rx == 1) {
        x = n - 1 - x;
        y = n - 1 - y;
      }
      std::swap(x, y);
    }
  }
  return d;
}

std::vector<VertexId> hilbert_order(std::span<const Point> points) {
  const std::size_t n = points.size();
  std::vector<VertexId> order(n);
  if (n == 0) return order;
  double minx = points[0].x, maxx = minx, miny = points[0].y, maxy = miny;
  for (const Point& p : points) {
    minx = std::min(minx, p.x);
    maxx = std::max(maxx, p.x);
    miny = std::min(miny, p.y);
    maxy = std::max(maxy, p.y);
  }
  // One scale for both axes keeps the curve's cells square.
  const double extent = std::max(maxx - minx, maxy - miny);
  const double scale = extent > 0 ? 65535.0 / extent : 0.0;
  std::vector<std::uint64_t> keys(n), tmp(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto qx = static_cast<std::uint32_t>(std::clamp((points[i].x - minx) * scale, 0.0, 65535.0));
    const auto qy = static_cast<std::uint32_t>(std::clamp((points[i].y - miny) * scale, 0.0, 65535.0));
    keys[i] = (std::uint64_t{hilbert_index(qx, qy)} << 32) | i;
  }
  // LSD radix sort on the 32-bit curve index, 11 bits per pass (3 passes).
  for (int shift = 32; shift < 64; shift += 11) {
    std::size_t count[2049] = {};
    for (std::uint64_t k : keys) ++count[((k >> shift) & 2047) + 1];
    for (int b = 0; b < 2048; ++b) count[b + 1] += count[b];
    for (std::uint64_t k : keys) tmp[count[(k >> shift) & 2047]++] = k;
    keys.swap(tmp);
  }
  for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<VertexId>(keys[i] & 0xffffffffu);
  return order;
}

}  // namespace deltamesh::detail
