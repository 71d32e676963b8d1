#include "gis/rings_from_lines.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

using namespace isoquad;

namespace {

SourceLine line(long long fid, std::vector<Point2> points) {
  SourceLine l;
  l.fid = fid;
  l.points = std::move(points);
  return l;
}

// A closed square of side s with its lower left corner at (x, y), counter-clockwise.
SourceLine square(long long fid, double x, double y, double s) {
  return line(fid, {{x, y}, {x + s, y}, {x + s, y + s}, {x, y + s}, {x, y}});
}

std::string error_of(const std::vector<SourceLine>& lines) {
  try {
    rings_from_lines(lines, "m");
  } catch (const LinesError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error";
  return "";
}

std::vector<double> ring_areas(const SourcePolygon& p) {
  std::vector<double> a;
  for (const Ring& r : p.rings) a.push_back(std::abs(signed_area(r)));
  return a;
}

}  // namespace

TEST(RingsFromLines, ClosedLinesNestByContainment) {
  // Land (10 x 10) with a lake (6 x 6) holding an island (2 x 2), and a separate islet;
  // given smallest first, so that the order of the input does not decide the nesting.
  const LineRings r = rings_from_lines(
      {square(1, 4, 4, 2), square(2, 2, 2, 6), square(3, 0, 0, 10), square(4, 20, 0, 1)}, "m");
  EXPECT_EQ(r.num_rings, 4u);
  EXPECT_EQ(r.num_joined_rings, 0u);
  ASSERT_EQ(r.polygons.size(), 3u);
  // In the order of the outer rings' lines: the island, the land with the lake, the islet.
  EXPECT_EQ(r.polygons[0].fid, 1);
  EXPECT_EQ(ring_areas(r.polygons[0]), (std::vector<double>{4}));
  EXPECT_EQ(r.polygons[1].fid, 3);
  EXPECT_EQ(ring_areas(r.polygons[1]), (std::vector<double>{100, 36}));
  EXPECT_EQ(r.polygons[2].fid, 4);
  EXPECT_EQ(ring_areas(r.polygons[2]), (std::vector<double>{1}));
}

TEST(RingsFromLines, OpenLinesJoinEndToEndInEitherDirection) {
  // A 4 x 2 rectangle drawn as three lines, one reversed, out of order, one of them
  // with a repeated point; and a closed triangle of its own.
  const LineRings r = rings_from_lines(
      {line(7, {{4, 2}, {0, 2}, {0, 0}}), line(8, {{0, 0}, {2, 0}, {2, 0}, {4, 0}}),
       line(9, {{4, 2}, {4, 0}}), line(10, {{10, 0}, {11, 0}, {10, 1}, {10, 0}})},
      "m");
  EXPECT_EQ(r.num_rings, 2u);
  EXPECT_EQ(r.num_joined_rings, 1u);
  EXPECT_EQ(r.num_lines_joined, 3u);
  ASSERT_EQ(r.polygons.size(), 2u);
  ASSERT_EQ(r.polygons[0].rings.size(), 1u);
  EXPECT_EQ(r.polygons[0].fid, 7);
  EXPECT_EQ(r.polygons[0].rings[0].size(), 5u);  // 4 corners and a midpoint, stored open
  EXPECT_DOUBLE_EQ(std::abs(signed_area(r.polygons[0].rings[0])), 8.0);
  EXPECT_DOUBLE_EQ(std::abs(signed_area(r.polygons[1].rings[0])), 0.5);
}

TEST(RingsFromLines, RingsThatTouchAtAPointAreCutApartThere) {
  // Two unit squares meeting at (1, 1), drawn as four lines whose ends all meet there:
  // two rings that touch, not one that crosses itself.
  const LineRings joined =
      rings_from_lines({line(1, {{1, 1}, {1, 0}, {0, 0}, {0, 1}}), line(2, {{0, 1}, {1, 1}}),
                        line(3, {{1, 1}, {2, 1}, {2, 2}}), line(4, {{2, 2}, {1, 2}, {1, 1}})},
                       "m");
  ASSERT_EQ(joined.polygons.size(), 2u);
  for (const SourcePolygon& p : joined.polygons) {
    ASSERT_EQ(p.rings.size(), 1u);
    EXPECT_EQ(p.rings[0].size(), 4u);
    EXPECT_DOUBLE_EQ(std::abs(signed_area(p.rings[0])), 1.0);
  }
  // The same figure eight as one closed line.
  const LineRings closed = rings_from_lines(
      {line(5, {{1, 1}, {1, 0}, {0, 0}, {0, 1}, {1, 1}, {2, 1}, {2, 2}, {1, 2}, {1, 1}})}, "m");
  ASSERT_EQ(closed.polygons.size(), 2u);
  EXPECT_DOUBLE_EQ(std::abs(signed_area(closed.polygons[0].rings[0])), 1.0);
  EXPECT_DOUBLE_EQ(std::abs(signed_area(closed.polygons[1].rings[0])), 1.0);
  // A lake that touches its shore at one point stays a hole of the land.
  const LineRings lake = rings_from_lines(
      {square(6, 0, 0, 4), line(7, {{0, 2}, {1, 1}, {2, 2}, {1, 3}, {0, 2}})}, "m");
  ASSERT_EQ(lake.polygons.size(), 1u);
  EXPECT_EQ(ring_areas(lake.polygons[0]), (std::vector<double>{16, 2}));
}

TEST(RingsFromLines, LooseAndOddEndsAreNamed) {
  // A square with one side missing: two loose ends, at (1, 0) and (0, 0).
  std::string e = error_of({line(3, {{0, 0}, {0, 1}, {1, 1}}), line(4, {{1, 1}, {1, 0}})});
  EXPECT_NE(e.find("feature 3 ends at (0, 0), where no other line ends"), std::string::npos) << e;
  EXPECT_NE(e.find("feature 4's at (1, 0), 1 m away"), std::string::npos) << e;
  EXPECT_NE(e.find("2 loose end(s)"), std::string::npos) << e;
  // A third line from a corner of a closed square to its middle.
  e = error_of({line(1, {{0, 0}, {1, 0}}), line(2, {{1, 0}, {1, 1}, {0, 1}, {0, 0}}),
                line(3, {{0, 0}, {0.5, 0.5}})});
  EXPECT_NE(e.find("3 line ends meet at (0, 0)"), std::string::npos) << e;
  EXPECT_NE(e.find("feature 1, feature 2, feature 3"), std::string::npos) << e;
}

TEST(RingsFromLines, TheResultDoesNotDependOnTheLinesDirections) {
  std::vector<SourceLine> lines = {line(1, {{0, 0}, {3, 0}, {3, 1}}), line(2, {{3, 1}, {3, 3}}),
                                   line(3, {{3, 3}, {0, 3}, {0, 0}}), square(4, 1, 1, 1)};
  const LineRings a = rings_from_lines(lines, "m");
  for (SourceLine& l : lines) std::reverse(l.points.begin(), l.points.end());
  const LineRings b = rings_from_lines(lines, "m");
  ASSERT_EQ(a.polygons.size(), 1u);
  ASSERT_EQ(b.polygons.size(), 1u);
  EXPECT_EQ(ring_areas(a.polygons[0]), (std::vector<double>{9, 1}));
  EXPECT_EQ(ring_areas(b.polygons[0]), (std::vector<double>{9, 1}));
}
