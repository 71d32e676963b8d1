#include "domain/select_domain.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "gis/crs.h"

using namespace isoquad;

namespace {

Ring square(double x0, double y0, double size) {
  return {{x0, y0}, {x0 + size, y0}, {x0 + size, y0 + size}, {x0, y0 + size}};
}

SourceData source(const std::vector<std::vector<Ring>>& polygons) {
  SourceData d;
  d.crs = parse_crs("EPSG:3857", "test");
  long long fid = 0;
  for (const auto& rings : polygons) {
    SourcePolygon sp;
    sp.fid = fid++;
    sp.rings = rings;
    d.polygons.push_back(sp);
  }
  return d;
}

SelectParams params(DomainKind kind, bool repair = false) {
  SelectParams p;
  p.kind = kind;
  p.repair = repair;
  p.source_name = "test.geojson";
  return p;
}

}  // namespace

TEST(SelectDomain, LandIsTheUnionOfOverlappingPolygons) {
  const SourceData d = source({{square(0, 0, 10)}, {square(5, 5, 10)}, {square(100, 0, 1)}});
  const SelectResult r = select_domain(d, params(DomainKind::land));
  ASSERT_EQ(r.polygons.size(), 2u);
  EXPECT_DOUBLE_EQ(area(r.polygons[0]), 175.0);  // 100 + 100 - 25
  EXPECT_DOUBLE_EQ(area(r.polygons[1]), 1.0);
  EXPECT_GT(signed_area(r.polygons[0].outer), 0.0);
}

TEST(SelectDomain, LandIsClippedToTheBbox) {
  SourceData d = source({{square(0, 0, 10)}});
  d.bbox_ring = square(5, -5, 20);
  const SelectResult r = select_domain(d, params(DomainKind::land));
  ASSERT_EQ(r.polygons.size(), 1u);
  EXPECT_DOUBLE_EQ(area(r.polygons[0]), 50.0);
}

TEST(SelectDomain, WaterIsTheBboxMinusTheLandWithIslandsAsHoles) {
  // A coast along the bottom edge (crossing the bbox) and two islands.
  SourceData d = source({{{{-10, -10}, {110, -10}, {110, 10}, {-10, 10}}},
                         {square(20, 40, 10)},
                         {square(60, 60, 5)}});
  d.bbox_ring = square(0, 0, 100);
  const SelectResult r = select_domain(d, params(DomainKind::water));
  ASSERT_EQ(r.polygons.size(), 1u);
  const Polygon& sea = r.polygons[0];
  EXPECT_EQ(sea.holes.size(), 2u);
  EXPECT_DOUBLE_EQ(area(sea), 100.0 * 90.0 - 100.0 - 25.0);
  EXPECT_GT(signed_area(sea.outer), 0.0);
  for (const Ring& h : sea.holes) EXPECT_LT(signed_area(h), 0.0);
}

TEST(SelectDomain, WaterWithoutBboxIsAUsageError) {
  const SourceData d = source({{square(0, 0, 10)}});
  try {
    select_domain(d, params(DomainKind::water));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), ErrorClass::usage);
    EXPECT_NE(std::string(e.what()).find("--bbox"), std::string::npos);
  }
}

TEST(SelectDomain, WaterCoveredByLandIsEmpty) {
  SourceData d = source({{square(-1, -1, 20)}});
  d.bbox_ring = square(0, 0, 10);
  try {
    select_domain(d, params(DomainKind::water));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), ErrorClass::input);
    EXPECT_NE(std::string(e.what()).find("empty"), std::string::npos);
  }
}

TEST(SelectDomain, SelfIntersectionIsReportedWithItsLocationOrRepaired) {
  const SourceData d = source({{{{0, 0}, {10, 10}, {10, 0}, {0, 10}}}});
  try {
    select_domain(d, params(DomainKind::land));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), ErrorClass::input);
    const std::string what = e.what();
    EXPECT_NE(what.find("test.geojson"), std::string::npos) << what;
    EXPECT_NE(what.find("feature 0"), std::string::npos) << what;
    EXPECT_NE(what.find("Self-intersection"), std::string::npos) << what;
    EXPECT_NE(what.find("(5, 5)"), std::string::npos) << what;
    EXPECT_NE(what.find("--repair"), std::string::npos) << what;
  }
  const SelectResult r = select_domain(d, params(DomainKind::land, true));
  EXPECT_EQ(r.num_repaired, 1u);
  ASSERT_EQ(r.polygons.size(), 2u);  // the bow-tie becomes two triangles
  EXPECT_DOUBLE_EQ(area(r.polygons[0]) + area(r.polygons[1]), 50.0);
}

TEST(SelectDomain, GeographicPolygonsAcrossTheAntimeridianAreUnwrapped) {
  // An island whose ring crosses the antimeridian (179.5 -> -179.5: invalid as written),
  // and one cut at +-180 into two parts (as Natural Earth cuts Fiji): valid, one
  // component each, in longitudes [0, 360).
  SourceData d;
  d.crs = parse_crs("EPSG:4326", "test");
  SourcePolygon crossing;
  crossing.fid = 0;
  crossing.rings = {{{179.5, -17.0}, {-179.5, -17.0}, {-179.5, -16.0}, {179.5, -16.0}}};
  SourcePolygon west, east;
  west.fid = east.fid = 1;
  east.part = 1;
  west.rings = {square(179.0, -20.0, 1.0)};   // 179 .. 180
  east.rings = {square(-180.0, -20.0, 0.5)};  // -180 .. -179.5, 0.5 high
  d.polygons = {crossing, west, east};
  const SelectResult r = select_domain(d, params(DomainKind::land));
  ASSERT_EQ(r.polygons.size(), 2u);
  EXPECT_NEAR(area(r.polygons[0]), 1.25, 1e-9);  // the cut island, joined
  EXPECT_NEAR(area(r.polygons[1]), 1.0, 1e-9);  // the crossing one, 1 x 1 degree
  for (const Polygon& p : r.polygons)
    for (const Point2& q : p.outer) {
      EXPECT_GE(q.x, 179.0);
      EXPECT_LE(q.x, 180.5);
    }
  // Without repair, nothing was invalid.
  EXPECT_EQ(r.num_repaired, 0u);
}
