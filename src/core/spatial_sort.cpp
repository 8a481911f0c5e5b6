#include "core/spatial_sort.hpp"

#include <algorithm>
#include <cmath>

namespace deltamesh::detail {

namespace {

// The curve's frame at each level is one of four: x/y swapped or not, both
// complemented or not (the two commute). A table maps (frame, quadrant bits)
// to (curve digit, next frame), so the loop has no data-dependent branches;
// branch mispredictions made the plain version the slowest part of sorting.
struct HilbertTable {
  std::uint8_t digit[4][4];
  std::uint8_t next[4][4];
};

constexpr HilbertTable make_hilbert_table() {
  HilbertTable t{};
  for (unsigned frame = 0; frame < 4; ++frame) {
    const unsigned swapped = frame & 1, complemented = frame >> 1;
    for (unsigned q = 0; q < 4; ++q) {
      unsigned bx = q >> 1, by = q & 1;
      if (swapped) {
        const unsigned tmp = bx;
        bx = by;
        by = tmp;
      }
      bx ^= complemented;
      by ^= complemented;
      t.digit[frame][q] = static_cast<std::uint8_t>((3 * bx) ^ by);
      unsigned s2 = swapped, c2 = complemented;
      if (by == 0) {
        c2 ^= bx;
        s2 ^= 1;
      }
      t.next[frame][q] = static_cast<std::uint8_t>(s2 | (c2 << 1));
    }
  }
  return t;
}

constexpr HilbertTable kHilbert = make_hilbert_table();

}  // namespace

std::uint32_t hilbert_index(std::uint32_t x, std::uint32_t y) {
  std::uint32_t d = 0;
  unsigned frame = 0;
  for (int level = 15; level >= 0; --level) {
    const unsigned q = (((x >> level) & 1) << 1) | ((y >> level) & 1);
    d = (d << 2) | kHilbert.digit[frame][q];
    frame = kHilbert.next[frame][q];
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
