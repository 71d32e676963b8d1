// Rings touching at a point: detected, and opened apart so that the background mesh can
// triangulate the domain.
#include "domain/separate_rings.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"

using namespace isoquad;

namespace {

Polygon square_with_holes(std::vector<Ring> holes) {
  Polygon p;
  p.outer = {{0, 0}, {1000, 0}, {1000, 1000}, {0, 1000}};
  p.holes = std::move(holes);
  orient_polygon(p);
  return p;
}

}  // namespace

TEST(SeparateRings, TwoHolesTouchingAtAVertexBecomeOneHole) {
  Domain d;
  d.polygons.push_back(square_with_holes({{{300, 300}, {500, 500}, {300, 500}},
                                          {{500, 500}, {700, 500}, {700, 700}}}));
  const double before = area(d);
  EXPECT_EQ(pinch_points(d).size(), 1u);
  separate_rings(d, 5.0);
  EXPECT_EQ(pinch_points(d).size(), 0u);
  ASSERT_EQ(d.polygons.size(), 1u);
  EXPECT_EQ(d.polygons[0].holes.size(), 1u);
  // Only a little area around the pinch changes.
  EXPECT_NEAR(area(d), before, 0.002 * before);
}

TEST(SeparateRings, HoleTouchingTheShellBecomesABay) {
  Domain d;
  d.polygons.push_back(square_with_holes({{{0, 0}, {300, 300}, {300, 100}}}));
  EXPECT_EQ(pinch_points(d).size(), 1u);
  separate_rings(d, 5.0);
  EXPECT_EQ(pinch_points(d).size(), 0u);
  ASSERT_EQ(d.polygons.size(), 1u);
  EXPECT_TRUE(d.polygons[0].holes.empty());
}

TEST(SeparateRings, SeparateRingsAreLeftAlone) {
  Domain d;
  d.polygons.push_back(square_with_holes({{{300, 300}, {500, 300}, {500, 500}}}));
  EXPECT_EQ(pinch_points(d).size(), 0u);
}

TEST(SeparateRings, OnlyTheNeighbourhoodOfThePinchChanges) {
  Domain d;
  d.polygons.push_back(square_with_holes({{{0, 0}, {300, 300}, {300, 100}}}));
  const double before = area(d);
  separate_rings(d, 5.0);
  // At most the octagon of radius 5 m (area < pi 25) is cut out.
  EXPECT_LT(before - area(d), M_PI * 25.0);
  EXPECT_GT(before - area(d), 0.0);
}

TEST(SeparateRings, NearTouchesCountAsTouches) {
  // A hole whose vertex is a nanometre from the shell's bottom edge (GEOS output is
  // often off by rounding like this), and two holes whose vertices are a nanometre apart.
  Domain d;
  d.polygons.push_back(square_with_holes({{{500, 1e-9}, {600, 300}, {400, 300}},
                                          {{300, 500}, {500, 600}, {300, 600}},
                                          {{500 + 1e-9, 600}, {700, 500}, {700, 600}}}));
  EXPECT_EQ(pinch_points(d).size(), 2u);
  separate_rings(d, 5.0);
  EXPECT_EQ(pinch_points(d).size(), 0u);
  ASSERT_EQ(d.polygons.size(), 1u);
  EXPECT_EQ(d.polygons[0].holes.size(), 1u);  // the first is a bay, the others one hole
  // A vertex 1 m from another ring is left alone.
  Domain far;
  far.polygons.push_back(square_with_holes({{{500, 1}, {600, 300}, {400, 300}}}));
  EXPECT_EQ(pinch_points(far).size(), 0u);
}

TEST(SeparateRings, SliversTheCutLeavesAreDropped) {
  // A needle 400 m long and 10 micrometres wide at its base, its tip on the square's side
  // (Kiribati at 1:10m had such a sliver island): the octagon cuts the tip off, and what
  // is left of the needle ends in two vertices far closer than rounding (a new pinch at
  // every cut). It is far smaller than the octagon: dropped.
  Domain d;
  d.polygons.push_back(square_with_holes({}));
  Polygon needle;
  needle.outer = {{1000, 500}, {1400, 500}, {1400, 500.00001}};
  d.polygons.push_back(needle);
  EXPECT_EQ(pinch_points(d).size(), 1u);
  separate_rings(d, 5.0);
  EXPECT_EQ(pinch_points(d).size(), 0u);
  ASSERT_EQ(d.polygons.size(), 1u);
  EXPECT_NEAR(area(d), 1.0e6, M_PI * 25.0);
}

namespace {

Polygon rectangle(double x0, double y0, double x1, double y1) {
  Polygon p;
  p.outer = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  orient_polygon(p);
  return p;
}

}  // namespace

TEST(MergeSharedBoundaries, PiecesSharingAnEdgeWithinRoundingBecomeOne) {
  // Two halves of an island, as a source cut at the antimeridian leaves them, projected
  // separately: the shared edge off by a nanometre (a gap GEOS sees, too narrow to mesh).
  Domain d;
  d.polygons.push_back(rectangle(0, 0, 1000, 1000));
  d.polygons.push_back(rectangle(1000 + 1e-9, 0, 2000, 1000));
  d.polygons.push_back(rectangle(5000, 0, 6000, 1000));  // far away: stays apart
  EXPECT_FALSE(pinch_points(d).empty());
  EXPECT_TRUE(merge_shared_boundaries(d));
  ASSERT_EQ(d.polygons.size(), 2u);
  EXPECT_NEAR(area(d), 3.0e6, 1.0);
  EXPECT_TRUE(pinch_points(d).empty());
  EXPECT_NEAR(area(d.polygons[0]), 2.0e6, 1.0);  // the largest first
}

TEST(MergeSharedBoundaries, OverlappingPolygonsBecomeTheirUnion) {
  Domain d;
  d.polygons.push_back(rectangle(0, 0, 1000, 1000));
  d.polygons.push_back(rectangle(500, 500, 1500, 1500));
  EXPECT_TRUE(merge_shared_boundaries(d));
  ASSERT_EQ(d.polygons.size(), 1u);
  EXPECT_NEAR(area(d), 1.75e6, 1.0);
}

TEST(MergeSharedBoundaries, PolygonsTouchingAtAPointStayAsTheyAre) {
  // Corner to corner, and a hole touching its shell: separate_rings' business.
  Domain d;
  d.polygons.push_back(rectangle(0, 0, 1000, 1000));
  d.polygons.push_back(rectangle(1000, 1000, 2000, 2000));
  d.polygons.push_back(square_with_holes({{{0, 0}, {300, 300}, {300, 100}}}));
  for (Point2& p : d.polygons.back().outer) p.x += 5000;
  for (Point2& p : d.polygons.back().holes[0]) p.x += 5000;
  const Domain before = d;
  EXPECT_FALSE(pinch_points(d).empty());
  EXPECT_FALSE(merge_shared_boundaries(d));
  ASSERT_EQ(d.polygons.size(), before.polygons.size());
  for (std::size_t i = 0; i < d.polygons.size(); ++i) {
    EXPECT_EQ(d.polygons[i].outer, before.polygons[i].outer);
    EXPECT_EQ(d.polygons[i].holes, before.polygons[i].holes);
  }
}

TEST(MergeSharedBoundaries, ARingRunningBackAlongItselfLosesTheSlit) {
  // A bbox round every longitude, projected: its sides at -180 and 180 become one
  // meridian, a slit from the bbox edge to the pole whose two sides are a nanometre apart.
  Domain d;
  Polygon p;
  p.outer = {{0, 0},         {500, 0},     {500, 300},    {500, 600}, {500 + 1e-9, 300},
             {500 + 1e-9, 0}, {1000, 0},   {1000, 1000},  {0, 1000}};
  d.polygons.push_back(p);
  EXPECT_FALSE(pinch_points(d).empty());
  EXPECT_TRUE(merge_shared_boundaries(d));
  ASSERT_EQ(d.polygons.size(), 1u);
  EXPECT_TRUE(pinch_points(d).empty());
  EXPECT_TRUE(d.polygons[0].holes.empty());
  EXPECT_NEAR(area(d), 1.0e6, 1e-3);
  for (const Point2& q : d.polygons[0].outer) EXPECT_FALSE(q.y > 1.0 && q.y < 999.0 && std::abs(q.x - 500) < 1.0);
}
