// The bad-triangle queue of Delaunay refinement: O(1) push and pop, with
// entries that keep their three vertices so that a stale one (its slot
// rewritten since) is recognised on pop instead of searched for.
#pragma once
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "deltamesh/mesh.hpp"

namespace deltamesh::refinement {

constexpr int kBuckets = 2048;

// Test hook (tests/test_refine_hubs.cpp), 0 everywhere else: another order
// of the same work, to check that the small-angle rules do not depend on
// luck of order. 1: the bucket bounds move by a relative 2^-40 (keys just
// below a bound change bucket); 2: each new fan is written in the cavity
// search's order, not from the lowest slot and vertex id (insert.cpp). Read
// once per refinement.
inline int order_perturbation_for_tests = 0;

// Bucket of a skinny triangle, shortest edge first (RefineOrder::
// ShortestEdgeFirst): three buckets per octave of the squared shortest edge
// relative to the input's unit (Refiner::unit_; the exponent from frexp: no
// logarithm). Refining from small features outwards grades better than
// worst first.
inline int shortest_edge_key(double shortest2) {
  int ex;
  // A length exactly on a bucket bound (round input coordinates make such
  // ties common) is, in a copy of the input scaled by 10^k, a few ulps to
  // either side of it: the 2^-40 nudge up sends both to the upper bucket,
  // where the exact value goes, so the order does not depend on the scale.
  const double f = std::frexp(shortest2 * (1 + 0x1p-40), &ex);  // = f 2^ex, f in [0.5, 1)
  return std::clamp(3 * (ex + 340) + (f < 0.63 ? 0 : (f < 0.794 ? 1 : 2)), 0, kBuckets - 1);
}

// Bucket of a skinny triangle, worst first (RefineOrder::WorstFirst): by the
// squared sine of its smallest angle relative to the bound's.
inline int worst_quality_key(double sin2, double sin2_bound) {
  return std::clamp(static_cast<int>(sin2 / sin2_bound * kBuckets), 0, kBuckets - 1);
}

struct QueueEntry {
  TriId t;
  VertexId a, b, c;
};

// Skinny triangles wait in buckets (lowest key first, found through a
// bitmap); triangles that are only too large wait on a LIFO stack and go
// after every skinny one (depth first, which keeps the working set in cache).
class BadQueue {
 public:
  BadQueue() {
    for (auto& b : buckets_) b.reserve(4);
  }
  void push_skinny(int key, const QueueEntry& e) {
    buckets_[key].push_back(e);
    bits_[key >> 6] |= std::uint64_t{1} << (key & 63);
    ++size_;
    ++skinny_;
  }
  void push_large(const QueueEntry& e) {
    large_.push_back(e);
    ++size_;
  }
  bool empty() const { return size_ == 0; }
  std::size_t size() const { return size_; }
  QueueEntry pop() {
    --size_;
    if (skinny_ == 0) {
      const QueueEntry e = large_.back();
      large_.pop_back();
      return e;
    }
    --skinny_;
    for (int w = 0; w < kBuckets / 64; ++w) {
      if (bits_[w] == 0) continue;
      const int key = 64 * w + std::countr_zero(bits_[w]);
      std::vector<QueueEntry>& b = buckets_[key];
      const QueueEntry e = b.back();
      b.pop_back();
      if (b.empty()) bits_[w] &= ~(std::uint64_t{1} << (key & 63));
      return e;
    }
    const QueueEntry e = large_.back();
    large_.pop_back();
    return e;
  }

 private:
  std::array<std::vector<QueueEntry>, kBuckets> buckets_;
  std::array<std::uint64_t, kBuckets / 64> bits_{};
  std::vector<QueueEntry> large_;
  std::size_t size_ = 0;
  std::size_t skinny_ = 0;
};

}  // namespace deltamesh::refinement
