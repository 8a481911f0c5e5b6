// The spatial sort's table-driven curve index must equal the level-by-level
// one: the insertion order, and so every output, depends on it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include "core/spatial_sort.hpp"

namespace {

using namespace deltamesh;

TEST(SpatialSort, FourLevelTableMatchesLevelByLevel) {
  for (std::uint32_t x = 0; x < 2048; x += 7)
    for (std::uint32_t y = 0; y < 2048; ++y)
      ASSERT_EQ(detail::hilbert_index_11(x, y), detail::hilbert_index(x, y, 11)) << x << " " << y;
  for (std::uint32_t x : {0u, 1u, 1023u, 1024u, 2046u, 2047u})
    for (std::uint32_t y = 0; y < 2048; ++y) ASSERT_EQ(detail::hilbert_index_11(x, y), detail::hilbert_index(x, y, 11));
}

TEST(SpatialSort, IndexIsABijectionOfTheGrid) {
  // 2^11 x 2^11 cells onto 0 .. 2^22 - 1, neighbours on the curve adjacent.
  std::vector<std::uint32_t> cell(std::size_t{1} << 22, ~0u);
  for (std::uint32_t x = 0; x < 2048; ++x)
    for (std::uint32_t y = 0; y < 2048; ++y) {
      const std::uint32_t d = detail::hilbert_index_11(x, y);
      ASSERT_LT(d, cell.size());
      ASSERT_EQ(cell[d], ~0u);
      cell[d] = x << 11 | y;
    }
  for (std::size_t d = 1; d < cell.size(); ++d) {
    const int dx = static_cast<int>(cell[d] >> 11) - static_cast<int>(cell[d - 1] >> 11);
    const int dy = static_cast<int>(cell[d] & 2047) - static_cast<int>(cell[d - 1] & 2047);
    ASSERT_EQ(std::abs(dx) + std::abs(dy), 1) << d;
  }
}

// n points uniform in [-5, 5]^2 from a seeded generator.
std::vector<Point> random_points(std::uint64_t seed, std::size_t n) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-5.0, 5.0);
  std::vector<Point> pts(n);
  for (Point& p : pts) p = {u(rng), u(rng)};
  return pts;
}

TEST(SpatialSort, OrderIsAPermutationAndSortedCopyFollowsIt) {
  const std::vector<Point> pts = random_points(3, 50000);
  std::vector<Point> sorted;
  const std::vector<VertexId> order = detail::hilbert_order(pts, &sorted);
  ASSERT_EQ(order.size(), pts.size());
  std::vector<VertexId> seen(order);
  std::sort(seen.begin(), seen.end());
  for (std::size_t i = 0; i < seen.size(); ++i) ASSERT_EQ(seen[i], i);
  for (std::size_t k = 0; k < order.size(); ++k) ASSERT_EQ(sorted[k], pts[order[k]]);
}

TEST(SpatialSort, SubsetReadInPlaceOrdersAsItsCopy) {
  // The slabs of the parallel build sort their points through their input
  // indices; the order must be the one of the same points copied out.
  const std::vector<Point> pts = random_points(5, 60000);
  std::vector<VertexId> subset;
  std::vector<Point> copy;
  for (VertexId i = 0; i < pts.size(); ++i)
    if (pts[i].x < 1.0 && i % 3 != 0) {
      subset.push_back(i);
      copy.push_back(pts[i]);
    }
  std::vector<Point> sorted_copy, sorted_subset;
  const std::vector<VertexId> want = detail::hilbert_order(copy, &sorted_copy);
  const std::vector<VertexId> got = detail::hilbert_order(pts, subset, &sorted_subset);
  ASSERT_GT(got.size(), 20000u);
  EXPECT_EQ(got, want);
  EXPECT_EQ(sorted_subset, sorted_copy);
  for (std::size_t k = 0; k < got.size(); ++k) ASSERT_EQ(sorted_subset[k], pts[subset[got[k]]]);
}

}  // namespace
