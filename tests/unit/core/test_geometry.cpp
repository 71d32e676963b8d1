#include "core/geometry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace isoquad;

TEST(Geometry, SignedAreaAndPerimeterOfUnitSquare) {
  Ring ccw{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  EXPECT_DOUBLE_EQ(signed_area(ccw), 1.0);
  EXPECT_DOUBLE_EQ(perimeter(ccw), 4.0);
  Ring cw(ccw.rbegin(), ccw.rend());
  EXPECT_DOUBLE_EQ(signed_area(cw), -1.0);
}

TEST(Geometry, AreaIsPreciseFarFromTheOrigin) {
  const double o = 6.6e6;  // Lambert-93 northings are this large
  Ring r{{o, o}, {o + 1, o}, {o + 1, o + 1}, {o, o + 1}};
  EXPECT_NEAR(signed_area(r), 1.0, 1e-9);
}

TEST(Geometry, OrientPolygonMakesOuterCcwAndHolesCw) {
  Polygon p;
  p.outer = {{0, 0}, {0, 4}, {4, 4}, {4, 0}};  // clockwise
  p.holes = {{{1, 1}, {2, 1}, {2, 2}, {1, 2}}};  // counter-clockwise
  orient_polygon(p);
  EXPECT_GT(signed_area(p.outer), 0);
  EXPECT_LT(signed_area(p.holes[0]), 0);
  EXPECT_DOUBLE_EQ(area(p), 15.0);
}

TEST(Geometry, RemovesDuplicatesClosingPointAndSpikes) {
  Ring r{{0, 0}, {1, 0}, {1, 0}, {2, 0}, {2, 2}, {3, 3}, {2, 2}, {0, 2}, {0, 0}};
  const std::size_t removed = remove_duplicates_and_spikes(r);
  // The duplicate (1,0), the closing copy, and the spike 2,2 -> 3,3 -> 2,2.
  EXPECT_EQ(removed, 4u);
  ASSERT_EQ(r.size(), 5u);
  EXPECT_DOUBLE_EQ(signed_area(r), 4.0);
  for (std::size_t i = 0; i < r.size(); ++i) EXPECT_NE(r[i], r[(i + 1) % r.size()]);
}

TEST(Geometry, SortByAreaPutsLargestFirst) {
  std::vector<Polygon> ps(3);
  ps[0].outer = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  ps[1].outer = {{0, 0}, {3, 0}, {3, 3}, {0, 3}};
  ps[2].outer = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  sort_by_area(ps);
  EXPECT_DOUBLE_EQ(area(ps[0]), 9.0);
  EXPECT_DOUBLE_EQ(area(ps[1]), 4.0);
  EXPECT_DOUBLE_EQ(area(ps[2]), 1.0);
}

TEST(Geometry, PolylineIndexFindsPointsNearAnySegment) {
  // A staircase of 100 segments (several runs of the index) and a short second line:
  // points at 0.4 from a segment are near at a tolerance of 0.5 and not at 0.3, wherever
  // the segment lies; a point beside the staircase's bounding box is near nothing.
  std::vector<Point2> stairs{{0, 0}};
  for (int i = 0; i < 50; ++i) {
    stairs.push_back({i + 1.0, static_cast<double>(i)});
    stairs.push_back({i + 1.0, i + 1.0});
  }
  const PolylineIndex index({stairs, {{-10, 0}, {-10, 5}}});
  for (int i : {0, 17, 33, 49}) {
    const Point2 p{i + 0.5, i - 0.4};  // below the horizontal step (i, i) -> (i + 1, i)
    EXPECT_TRUE(index.near(p, 0.5)) << i;
    EXPECT_FALSE(index.near(p, 0.3)) << i;
  }
  EXPECT_TRUE(index.near({-9.6, 2.5}, 0.5));
  EXPECT_FALSE(index.near({-9.6, 2.5}, 0.3));
  EXPECT_FALSE(index.near({60, 0}, 5.0));
  // Beyond the index's extent, within the tolerance of its last segment (x = 50).
  EXPECT_TRUE(index.near({50.3, 49.5}, 0.5));
  EXPECT_FALSE(index.near({50.3, 49.5}, 0.2));
  // Every cell of the grid answers as a plain search of every segment would.
  for (double x = -12; x <= 52; x += 0.7)
    for (double y = -2; y <= 52; y += 0.9) {
      double nearest = distance_to_segment({x, y}, {-10, 0}, {-10, 5});
      for (std::size_t i = 0; i + 1 < stairs.size(); ++i)
        nearest = std::min(nearest, distance_to_segment({x, y}, stairs[i], stairs[i + 1]));
      EXPECT_EQ(index.near({x, y}, 0.45), nearest <= 0.45) << x << " " << y;
      // The nearest segment within the tolerance is one at the plain search's distance.
      Point2 a, b;
      const bool found = index.nearest_segment({x, y}, 0.45, a, b);
      EXPECT_EQ(found, nearest <= 0.45) << x << " " << y;
      if (found) {
        EXPECT_EQ(distance_to_segment({x, y}, a, b), nearest) << x << " " << y;
      }
      // The segments near: exactly those within 1.3 of the point, in order, once each.
      std::vector<std::pair<int, int>> within;
      if (distance_to_segment({x, y}, {-10, 0}, {-10, 5}) <= 1.3) within.emplace_back(1, 0);
      for (std::size_t i = 0; i + 1 < stairs.size(); ++i)
        if (distance_to_segment({x, y}, stairs[i], stairs[i + 1]) <= 1.3)
          within.emplace_back(0, static_cast<int>(i));
      std::sort(within.begin(), within.end());
      EXPECT_EQ(index.segments_near({x, y}, 1.3), within) << x << " " << y;
    }
  EXPECT_FALSE(PolylineIndex().near({0, 0}, 1.0));
  EXPECT_DOUBLE_EQ(distance_to_segment({2, 1}, {0, 0}, {4, 0}), 1.0);
  EXPECT_DOUBLE_EQ(distance_to_segment({7, 4}, {0, 0}, {4, 0}), 5.0);
  EXPECT_DOUBLE_EQ(distance_to_segment({3, 4}, {0, 0}, {0, 0}), 5.0);
}

// A ring's sides in bands answer crosses_odd as the ring does, point for point: a star
// of 300 vertices (spikes and notches, horizontal sides, a repeated first point) and
// points on a grid through it, on its vertices and at their heights.
TEST(Geometry, EdgeBandsAnswerAsTheRing) {
  std::vector<Point2> star;
  for (int i = 0; i < 300; ++i) {
    const double t = 2 * M_PI * i / 300, r = i % 7 == 0 ? 5.0 : (i % 2 ? 10.0 : 8.0);
    star.push_back({std::round(r * std::cos(t) * 8) / 8, std::round(r * std::sin(t) * 8) / 8});
  }
  for (const bool closed : {false, true}) {
    std::vector<Point2> ring = star;
    if (closed) ring.push_back(ring.front());
    const EdgeBands bands(ring);
    for (double x = -11; x <= 11; x += 0.37)
      for (double y = -11; y <= 11; y += 0.29)
        ASSERT_EQ(bands.crosses_odd({x, y}), crosses_odd(ring, {x, y})) << x << " " << y;
    for (const Point2& v : ring) {
      ASSERT_EQ(bands.crosses_odd(v), crosses_odd(ring, v)) << v.x << " " << v.y;
      for (double dx : {-0.5, 0.5})
        ASSERT_EQ(bands.crosses_odd({v.x + dx, v.y}), crosses_odd(ring, {v.x + dx, v.y}));
    }
  }
  EXPECT_FALSE(EdgeBands({}).crosses_odd({0, 0}));
}
