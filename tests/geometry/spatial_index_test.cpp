// StaticSpatialIndex against brute force, early exit, empty and degenerate boxes.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include <cutroute/core/random.hpp>
#include <cutroute/geometry/spatial_index.hpp>

namespace cutroute::geometry {
namespace {

Box random_box(Rng& rng, double extent, double max_size) {
  const double x = rng.uniform01() * extent, y = rng.uniform01() * extent;
  return {x, y, x + rng.uniform01() * max_size, y + rng.uniform01() * max_size};
}

TEST(StaticSpatialIndex, MatchesBruteForce) {
  for (std::size_t n : {0u, 1u, 15u, 16u, 17u, 255u, 256u, 257u, 5000u}) {
    SCOPED_TRACE(n);
    Rng rng(n + 1);
    std::vector<Box> boxes;
    for (std::size_t i = 0; i < n; ++i) boxes.push_back(random_box(rng, 1000, 50));
    const StaticSpatialIndex index(boxes);
    EXPECT_EQ(index.size(), n);
    std::vector<std::uint32_t> got;  // reused scratch buffer
    for (int q = 0; q < 200; ++q) {
      const Box query = random_box(rng, 1000, 200);
      index.query(query, got);
      std::sort(got.begin(), got.end());
      std::vector<std::uint32_t> want;
      for (std::uint32_t i = 0; i < n; ++i) if (boxes[i].intersects(query)) want.push_back(i);
      ASSERT_EQ(got, want);
    }
  }
}

TEST(StaticSpatialIndex, VisitorStopsEarly) {
  std::vector<Box> boxes(1000, Box{0, 0, 1, 1});
  const StaticSpatialIndex index(boxes);
  int calls = 0;
  index.query(Box{0, 0, 1, 1}, [&](std::uint32_t) { return ++calls < 7; });
  EXPECT_EQ(calls, 7);
  std::vector<std::uint32_t> all;
  index.query(Box{0.5, 0.5, 0.6, 0.6}, all);
  EXPECT_EQ(all.size(), 1000u);
}

TEST(StaticSpatialIndex, EmptyAndNonFiniteBoxesAreNeverReported) {
  std::vector<Box> boxes{Box{}, Box{0, 0, 1, 1}, Box{std::nan(""), 0, 1, 1}, Box{2, 2, 3, 3}};
  const StaticSpatialIndex index(boxes);
  std::vector<std::uint32_t> got;
  index.query(Box{-10, -10, 10, 10}, got);
  std::sort(got.begin(), got.end());
  EXPECT_EQ(got, (std::vector<std::uint32_t>{1, 3}));
  index.query(Box{}, got);
  EXPECT_TRUE(got.empty());
  const StaticSpatialIndex none;
  none.query(Box{0, 0, 1, 1}, got);
  EXPECT_TRUE(got.empty());
}

}  // namespace
}  // namespace cutroute::geometry
