#include "core/spatial_sort.hpp"

#include <algorithm>
#include <cmath>
#include <compare>
#include <cstddef>
#include <iterator>
#include <memory>

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

// Four levels per step: (frame, 4 bits of x, 4 bits of y) -> 8 curve bits
// and the next frame, packed as digit | frame << 8. Three lookups for 12
// levels instead of twelve dependent ones.
struct HilbertTable4 {
  std::uint16_t entry[4][256];
};

constexpr HilbertTable4 make_hilbert_table4() {
  HilbertTable4 t{};
  for (unsigned frame = 0; frame < 4; ++frame)
    for (unsigned xy = 0; xy < 256; ++xy) {
      const unsigned x = xy >> 4, y = xy & 15;
      unsigned f = frame, d = 0;
      for (int level = 3; level >= 0; --level) {
        const unsigned q = (((x >> level) & 1) << 1) | ((y >> level) & 1);
        d = (d << 2) | kHilbert.digit[f][q];
        f = kHilbert.next[f][q];
      }
      t.entry[frame][xy] = static_cast<std::uint16_t>(d | (f << 8));
    }
  return t;
}

constexpr HilbertTable4 kHilbert4 = make_hilbert_table4();

static_assert(kHilbert.digit[1][0] == 0 && kHilbert.next[1][0] == 0);

}  // namespace

std::uint32_t hilbert_index(std::uint32_t x, std::uint32_t y, int levels) {
  std::uint32_t d = 0;
  unsigned frame = 0;
  for (int level = levels - 1; level >= 0; --level) {
    const unsigned q = (((x >> level) & 1) << 1) | ((y >> level) & 1);
    d = (d << 2) | kHilbert.digit[frame][q];
    frame = kHilbert.next[frame][q];
  }
  return d;
}

// Three steps of four levels cover 12: a 12th, zero, top level read in
// frame 1 gives digit 0 and leaves frame 0 (static_assert above), so
// starting in frame 1 gives the 11-level index.
std::uint32_t hilbert_index_11(std::uint32_t x, std::uint32_t y) {
  std::uint32_t d = 0;
  unsigned frame = 1;
  for (int shift = 8; shift >= 0; shift -= 4) {
    const unsigned e = kHilbert4.entry[frame][(((x >> shift) & 15) << 4) | ((y >> shift) & 15)];
    d = (d << 8) | (e & 0xFF);
    frame = e >> 8;
  }
  return d;
}
namespace {

// at(order[0]), at(order[1]), ... as a random-access range, so that a
// vector is filled from it in one copy (no zero-fill, no per-element
// capacity check).
template <class At>
class Gather {
 public:
  using iterator_category = std::random_access_iterator_tag;
  using value_type = Point;
  using difference_type = std::ptrdiff_t;
  using pointer = const Point*;
  using reference = const Point&;

  Gather(const At* at, const VertexId* k) : at_(at), k_(k) {}
  reference operator*() const { return (*at_)(*k_); }
  reference operator[](difference_type i) const { return (*at_)(k_[i]); }
  Gather& operator++() {
    ++k_;
    return *this;
  }
  Gather operator++(int) { return Gather(at_, k_++); }
  Gather& operator--() {
    --k_;
    return *this;
  }
  Gather operator--(int) { return Gather(at_, k_--); }
  Gather& operator+=(difference_type d) {
    k_ += d;
    return *this;
  }
  Gather& operator-=(difference_type d) {
    k_ -= d;
    return *this;
  }
  Gather operator+(difference_type d) const { return Gather(at_, k_ + d); }
  friend Gather operator+(difference_type d, const Gather& g) { return g + d; }
  Gather operator-(difference_type d) const { return Gather(at_, k_ - d); }
  difference_type operator-(const Gather& o) const { return k_ - o.k_; }
  bool operator==(const Gather& o) const { return k_ == o.k_; }
  auto operator<=>(const Gather& o) const { return k_ <=> o.k_; }

 private:
  const At* at_;
  const VertexId* k_;
};

// The order for n points, point i being at(i): the input itself, or a
// subset read through its indices (no copy of the subset's points).
template <class At>
std::vector<VertexId> hilbert_order_of(std::size_t n, const At& at, std::vector<Point>* sorted) {
  std::vector<VertexId> order;
  if (sorted) sorted->clear();
  if (n == 0) return order;
  double minx = at(0).x, maxx = minx, miny = at(0).y, maxy = miny;
  for (std::size_t i = 0; i < n; ++i) {
    const Point& p = at(i);
    minx = std::min(minx, p.x);
    maxx = std::max(maxx, p.x);
    miny = std::min(miny, p.y);
    maxy = std::max(maxy, p.y);
  }
  // One scale for both axes keeps the curve's cells square.
  const double extent = std::max(maxx - minx, maxy - miny);
  constexpr int kLevels = 11;  // 2^22 cells: finer than locality needs
  constexpr double kCells = (1 << kLevels) - 1;
  const double scale = extent > 0 ? kCells / extent : 0.0;
  // Biased randomized insertion order (BRIO): each point falls in a round by
  // a hash of its index, rounds growing 8-fold, the last holding ~7/8 of the
  // points; within a round, Hilbert order. Random rounds keep the number of
  // flips per insertion near its randomized expectation, Hilbert order keeps
  // the walks short. Sort key: round (3 bits) above the top 22 bits of the
  // curve index; two counting-sort passes of 13 bits.
  constexpr int kBits = 13, kBuckets = 1 << kBits;
  constexpr std::uint32_t kLastRound = 7;
  auto round_of = [](std::size_t i) {
    std::uint64_t z = (i + 1) * 0x9E3779B97F4A7C15ull;  // splitmix64 finaliser
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    std::uint32_t level = 0;
    while (level < kLastRound && (z & 7) == 0) {
      ++level;
      z >>= 3;
    }
    return kLastRound - level;
  };
  // Written before read: default-initialised (no zero-fill of 16n bytes).
  std::unique_ptr<std::uint64_t[]> keys(new std::uint64_t[n]), tmp(new std::uint64_t[n]);
  std::vector<std::size_t> low(kBuckets + 1, 0), high(kBuckets + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const Point& p = at(i);
    const auto qx = static_cast<std::uint32_t>(std::clamp((p.x - minx) * scale, 0.0, kCells));
    const auto qy = static_cast<std::uint32_t>(std::clamp((p.y - miny) * scale, 0.0, kCells));
    static_assert(kLevels == 11);
    const std::uint32_t k = (round_of(i) << (2 * kLevels)) | hilbert_index_11(qx, qy);
    keys[i] = (std::uint64_t{k} << 32) | i;
    ++low[(k & (kBuckets - 1)) + 1];
    ++high[(k >> kBits) + 1];
  }
  for (int b = 0; b < kBuckets; ++b) {
    low[b + 1] += low[b];
    high[b + 1] += high[b];
  }
  for (std::size_t i = 0; i < n; ++i) tmp[low[(keys[i] >> 32) & (kBuckets - 1)]++] = keys[i];
  for (std::size_t i = 0; i < n; ++i) keys[high[tmp[i] >> (32 + kBits)]++] = tmp[i];
  tmp.reset();
  // Copied in, not resized first: a resize would zero-fill (and fault in)
  // the order and the points only for these copies to overwrite them. The
  // order is each key's low 32 bits (the index).
  order.assign(keys.get(), keys.get() + n);
  if (sorted) sorted->assign(Gather<At>(&at, order.data()), Gather<At>(&at, order.data() + n));
  return order;
}

}  // namespace

std::vector<VertexId> hilbert_order(std::span<const Point> points, std::vector<Point>* sorted) {
  return hilbert_order_of(points.size(), [points](std::size_t i) -> const Point& { return points[i]; }, sorted);
}

std::vector<VertexId> hilbert_order(std::span<const Point> points, std::span<const VertexId> subset,
                                    std::vector<Point>* sorted) {
  return hilbert_order_of(
      subset.size(), [points, subset](std::size_t i) -> const Point& { return points[subset[i]]; }, sorted);
}

}  // namespace deltamesh::detail
