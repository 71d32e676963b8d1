// Areas removed from a domain (--exclude): holes, notches, pieces cut apart, overlaps
// counted once, invalid polygons refused or repaired, nothing left refused.
#include "domain/exclude_areas.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"

using namespace isoquad;

namespace {

Domain square_domain(double side) {
  Domain d;
  d.polygons.push_back({{{0, 0}, {side, 0}, {side, side}, {0, side}}, {}});
  return d;
}

SourcePolygon box(double x0, double y0, double x1, double y1, long long fid = 0) {
  SourcePolygon p;
  p.fid = fid;
  p.rings = {{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}};
  return p;
}

}  // namespace

TEST(ExcludeAreas, APolygonInsideBecomesAHoleAndOneOutsideIsNotCounted) {
  Domain d = square_domain(10000);
  const ExcludeResult r =
      exclude_areas(d, {box(2000, 3000, 4000, 5000), box(20000, 0, 21000, 1000)}, {});
  ASSERT_EQ(d.polygons.size(), 1u);
  ASSERT_EQ(d.polygons[0].holes.size(), 1u);
  EXPECT_EQ(r.num_polygons, 1u);
  EXPECT_NEAR(r.area_removed_m2, 4e6, 1e-3);
  EXPECT_NEAR(area(d), 96e6, 1e-3);
  EXPECT_GT(signed_area(d.polygons[0].outer), 0);
  EXPECT_LT(signed_area(d.polygons[0].holes[0]), 0);
}

TEST(ExcludeAreas, OverlapsCountOnceAndAcrossTheEdgeANotch) {
  Domain d = square_domain(10000);
  // Two overlapping boxes (a 3 x 2 km union), and one half outside the domain.
  const ExcludeResult r = exclude_areas(
      d, {box(2000, 2000, 4000, 4000), box(3000, 2000, 5000, 4000), box(9000, 5000, 11000, 6000)},
      {});
  EXPECT_EQ(r.num_polygons, 3u);
  EXPECT_NEAR(r.area_removed_m2, 6e6 + 1e6, 1e-3);
  ASSERT_EQ(d.polygons.size(), 1u);
  EXPECT_EQ(d.polygons[0].holes.size(), 1u);
  EXPECT_EQ(d.polygons[0].outer.size(), 8u);  // the notch's four corners more
}

TEST(ExcludeAreas, AStripAcrossCutsTheDomainInTwoSortedByArea) {
  Domain d = square_domain(10000);
  exclude_areas(d, {box(-1000, 6000, 11000, 7000)}, {});
  ASSERT_EQ(d.polygons.size(), 2u);
  EXPECT_NEAR(area(d.polygons[0]), 60e6, 1e-3);
  EXPECT_NEAR(area(d.polygons[1]), 30e6, 1e-3);
}

TEST(ExcludeAreas, InvalidPolygonsAreRefusedWhereTheFileDrewThemOrRepaired) {
  SourcePolygon bowtie;
  bowtie.fid = 7;
  bowtie.rings = {{{2000, 2000}, {4000, 4000}, {4000, 2000}, {2000, 4000}}};
  ExcludeParams p;
  p.what = "--exclude 'walls.gpkg'";
  p.to_file = [](const Point2& q) { return Point2{q.x / 1000, q.y / 1000}; };
  Domain d = square_domain(10000);
  try {
    exclude_areas(d, {bowtie}, p);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), ErrorClass::input);
    EXPECT_NE(e.message().find("--exclude 'walls.gpkg': feature 7 is invalid"), std::string::npos)
        << e.message();
    EXPECT_NE(e.message().find("at or near (3, 3)"), std::string::npos) << e.message();
  }
  EXPECT_NEAR(area(d), 100e6, 1e-3);  // unchanged
  p.repair = true;
  const ExcludeResult r = exclude_areas(d, {bowtie}, p);
  EXPECT_EQ(r.num_repaired, 1u);
  EXPECT_NEAR(r.area_removed_m2, 2e6, 1e-3);  // the bow tie's two triangles
}

TEST(ExcludeAreas, NothingLeftIsAnInputError) {
  Domain d = square_domain(10000);
  ExcludeParams p;
  p.what = "--exclude 'all.gpkg'";
  try {
    exclude_areas(d, {box(-1, -1, 10001, 10001)}, p);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), ErrorClass::input);
    EXPECT_NE(e.message().find("nothing is left to mesh"), std::string::npos) << e.message();
  }
}

TEST(ExcludeAreas, WhatTheDomainHoldsAgainIsMeasured) {
  Domain d = square_domain(10000);
  const ExcludeResult r =
      exclude_areas(d, {box(2000, 2000, 4000, 4000), box(6000, 6000, 6100, 6100)}, {});
  ASSERT_EQ(r.removed.size(), 2u);
  ExcludedMeshed m = excluded_area_meshed(d, r.removed);
  EXPECT_EQ(m.num_areas, 2u);
  EXPECT_EQ(m.num_mostly, 0u);
  EXPECT_NEAR(m.area_m2, 0.0, 1e-3);
  // The small hole dropped (as the cleaning drops holes under the least area): that
  // area lies in the domain again.
  Domain filled = d;
  auto& holes = filled.polygons[0].holes;
  holes.erase(std::remove_if(holes.begin(), holes.end(),
                             [](const Ring& h) { return std::abs(signed_area(h)) < 1e5; }),
              holes.end());
  ASSERT_EQ(holes.size(), 1u);
  m = excluded_area_meshed(filled, r.removed);
  EXPECT_EQ(m.num_mostly, 1u);
  EXPECT_NEAR(m.area_m2, 1e4, 1e-3);
}
