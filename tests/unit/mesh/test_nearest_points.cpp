#include "mesh/nearest_points.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace isoquad {
namespace {

// Against a brute-force scan: the k nearest of 2,000 random points, with their
// distances, nearest first; points on a lattice (many as near) come lower index first;
// asking for more than there are gives them all; an empty set gives nothing.
TEST(NearestPoints, AgreeWithAScanOfEveryPoint) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> coordinate(-5000.0, 5000.0);
  std::vector<Point2> points(2000);
  for (Point2& p : points) p = {coordinate(random), coordinate(random)};
  const NearestPoints index(points);
  ASSERT_EQ(index.size(), points.size());
  for (int trial = 0; trial < 50; ++trial) {
    const Point2 q{coordinate(random), coordinate(random)};
    std::vector<std::pair<double, int>> all;
    for (int i = 0; i < static_cast<int>(points.size()); ++i)
      all.emplace_back(distance(points[i], q), i);
    std::sort(all.begin(), all.end());
    for (std::size_t k : {1u, 7u, 40u}) {
      const auto found = index.nearest(q, k);
      ASSERT_EQ(found.size(), k);
      for (std::size_t j = 0; j < k; ++j) {
        EXPECT_EQ(found[j].second, all[j].second) << trial << " " << k << " " << j;
        EXPECT_DOUBLE_EQ(found[j].first, all[j].first);
      }
    }
  }
  const std::vector<Point2> lattice = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  const NearestPoints square(lattice);
  const auto four = square.nearest({0.5, 0.5}, 10);
  ASSERT_EQ(four.size(), 4u);
  for (int j = 0; j < 4; ++j) EXPECT_EQ(four[j].second, j);
  EXPECT_TRUE(NearestPoints({}).nearest({0, 0}, 3).empty());
}

}  // namespace
}  // namespace isoquad
