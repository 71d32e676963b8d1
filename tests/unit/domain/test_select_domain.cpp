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
