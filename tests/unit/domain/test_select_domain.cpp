#include "domain/select_domain.h"

#include <gtest/gtest.h>

#include <algorithm>

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

// Where a source draws its rings from, and in which direction, does not change the
// domain: each ring starts at its lowest vertex, the outer ones counter-clockwise.
TEST(SelectDomain, TheDomainDoesNotDependOnWhereTheRingsStart) {
  const Ring outer = {{0, 0}, {10, -1}, {12, 6}, {4, 9}, {-3, 5}};
  const Ring hole = {{3, 2}, {5, 2}, {6, 4}, {4, 5}};
  const SelectResult a = select_domain(source({{outer, hole}}), params(DomainKind::land));
  for (std::size_t shift = 0; shift < 4; ++shift) {
    Ring o = outer, h = hole;
    std::rotate(o.begin(), o.begin() + static_cast<std::ptrdiff_t>(shift), o.end());
    std::rotate(h.begin(), h.begin() + static_cast<std::ptrdiff_t>(shift), h.end());
    if (shift % 2) std::reverse(o.begin(), o.end());
    if (shift >= 2) std::reverse(h.begin(), h.end());
    const SelectResult b = select_domain(source({{o, h}}), params(DomainKind::land));
    ASSERT_EQ(b.polygons.size(), 1u);
    ASSERT_EQ(b.polygons[0].holes.size(), 1u);
    EXPECT_TRUE(b.polygons[0].outer == a.polygons[0].outer) << shift;
    EXPECT_TRUE(b.polygons[0].holes[0] == a.polygons[0].holes[0]) << shift;
  }
  EXPECT_TRUE(a.polygons[0].outer[0] == (Point2{10, -1}));
  EXPECT_GT(signed_area(a.polygons[0].outer), 0.0);
  EXPECT_TRUE(a.polygons[0].holes[0][0] == (Point2{3, 2}));
  EXPECT_LT(signed_area(a.polygons[0].holes[0]), 0.0);
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

// A sea polygon (the water above a coast, islands as holes) cut to a bbox is the same
// domain as the bbox minus the land: --domain sea only reads the polygons the other way.
TEST(SelectDomain, TheSeaInABboxIsTheBboxMinusTheLand) {
  const Ring coast = {{-10, -10}, {110, -10}, {110, 10}, {-10, 10}};
  SourceData land = source({{coast}, {square(20, 40, 10)}, {square(60, 60, 5)}});
  land.bbox_ring = square(0, 0, 100);
  const SelectResult water = select_domain(land, params(DomainKind::water));
  auto hole = [](Ring r) {
    std::reverse(r.begin(), r.end());
    return r;
  };
  SourceData sea = source({{{{-20, 10}, {120, 10}, {120, 120}, {-20, 120}},
                            hole(square(20, 40, 10)),
                            hole(square(60, 60, 5))}});
  sea.bbox_ring = land.bbox_ring;
  const SelectResult r = select_domain(sea, params(DomainKind::sea));
  ASSERT_EQ(r.polygons.size(), 1u);
  ASSERT_EQ(water.polygons.size(), 1u);
  EXPECT_TRUE(r.polygons[0].outer == water.polygons[0].outer);
  ASSERT_EQ(r.polygons[0].holes.size(), 2u);
  EXPECT_TRUE(r.polygons[0].holes == water.polygons[0].holes);
  EXPECT_DOUBLE_EQ(area(r.polygons[0]), 100.0 * 90.0 - 100.0 - 25.0);

  // Without a bbox the sea is the polygons themselves, as land would be; a bbox that
  // misses them leaves nothing, said so.
  sea.bbox_ring.reset();
  EXPECT_DOUBLE_EQ(area(select_domain(sea, params(DomainKind::sea)).polygons[0]),
                   140.0 * 110.0 - 125.0);
  sea.bbox_ring = square(0, -8, 5);
  try {
    select_domain(sea, params(DomainKind::sea));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), ErrorClass::input);
    EXPECT_NE(std::string(e.what()).find("the sea domain is empty"), std::string::npos) << e.what();
  }
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

namespace {

// A landmass around the globe as Natural Earth draws Eurasia: one ring from -180 to
// 180 (through Greenwich) whose south coast runs along latitude 30, with a bay 5 degrees
// deep between longitudes 20 and 30; and an island in that bay.
SourceData world_with_bay() {
  SourceData d;
  d.crs = parse_crs("EPSG:4326", "test");
  SourcePolygon land;
  land.fid = 0;
  land.rings = {{{-180, 30}, {-90, 30}, {-10, 30}, {10, 30}, {20, 30}, {20, 35}, {30, 35},
                 {30, 30}, {90, 30}, {180, 30}, {180, 70}, {90, 70}, {10, 70}, {-10, 70},
                 {-90, 70}, {-180, 70}}};
  SourcePolygon island;
  island.fid = 0;
  island.part = 1;
  island.rings = {square(24, 32, 1)};
  d.polygons = {land, island};
  return d;
}

Ring box_ring(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

}  // namespace

TEST(SelectDomain, ALandmassAroundTheGlobeIsNotUnwrapped) {
  // Shifting its negative longitudes by 360 would wrap the ring back across Greenwich
  // and cut seams through the water at every latitude where the coast crosses it.
  SourceData d = world_with_bay();
  d.bbox_ring = box_ring(18, 28, 32, 40);
  const SelectResult r = select_domain(d, params(DomainKind::water));
  ASSERT_EQ(r.polygons.size(), 1u);
  // The bbox (14 x 12) minus the land in it: 14 x 2 below 30, the bay 10 x 5 with the
  // island (1 x 1) as a hole.
  EXPECT_NEAR(area(r.polygons[0]), 14 * 2 + 10 * 5 - 1, 1e-6);
  EXPECT_EQ(r.polygons[0].holes.size(), 1u);
  for (const Point2& q : r.polygons[0].outer) {
    EXPECT_GE(q.x, 18 - 1e-9);
    EXPECT_LE(q.x, 32 + 1e-9);
  }
}

TEST(SelectDomain, WithABboxOnlyWhatLiesNearItIsChecked) {
  // The landmass is invalid far from the bbox (a bow-tie in its north coast near
  // longitude 100): the bbox's water is still read without --repair.
  SourceData d = world_with_bay();
  Ring& ring = d.polygons[0].rings[0];
  ring = {{-180, 30}, {-90, 30}, {-10, 30}, {10, 30}, {20, 30}, {20, 35}, {30, 35},
          {30, 30}, {90, 30}, {180, 30}, {180, 70}, {101, 70}, {100, 60}, {99, 70},
          {101, 65}, {10, 70}, {-10, 70}, {-90, 70}, {-180, 70}};
  d.bbox_ring = box_ring(18, 28, 32, 40);
  const SelectResult r = select_domain(d, params(DomainKind::water));
  EXPECT_EQ(r.num_repaired, 0u);
  ASSERT_EQ(r.polygons.size(), 1u);
  EXPECT_NEAR(area(r.polygons[0]), 14 * 2 + 10 * 5 - 1, 1e-6);
  // Where the bbox covers the invalid place, it is reported there.
  d.bbox_ring = box_ring(95, 50, 105, 75);
  try {
    select_domain(d, params(DomainKind::water));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), ErrorClass::input);
    EXPECT_NE(std::string(e.what()).find("feature 0"), std::string::npos) << e.what();
  }
}

TEST(SelectDomain, WaterWithNoLandInTheBboxIsTheBbox) {
  SourceData d = world_with_bay();
  d.bbox_ring = box_ring(0, -10, 10, 0);  // open sea
  const SelectResult r = select_domain(d, params(DomainKind::water));
  ASSERT_EQ(r.polygons.size(), 1u);
  EXPECT_NEAR(area(r.polygons[0]), 100.0, 1e-9);
}

TEST(SelectDomain, AnIslandAcrossTheAntimeridianInAWorldFileIsCutThere) {
  // The world stays in [-180, 180] (its Eurasia cannot move); an island whose ring
  // crosses the antimeridian as written (179.5 -> -179.5, 1 degree high) would run
  // around the globe: it is cut at 180 instead, half on each side.
  SourceData d = world_with_bay();
  SourcePolygon island;
  island.fid = 1;
  island.rings = {{{179.5, -17.0}, {-179.5, -17.0}, {-179.5, -16.0}, {179.5, -16.0}}};
  d.polygons.push_back(island);
  d.bbox_ring = box_ring(178, -19, 180, -15);
  SelectResult r = select_domain(d, params(DomainKind::water));
  ASSERT_EQ(r.polygons.size(), 1u);
  EXPECT_NEAR(area(r.polygons[0]), 2 * 4 - 0.5, 1e-9);
  d.bbox_ring = box_ring(-180, -19, -178, -15);
  r = select_domain(d, params(DomainKind::water));
  ASSERT_EQ(r.polygons.size(), 1u);
  EXPECT_NEAR(area(r.polygons[0]), 2 * 4 - 0.5, 1e-9);
  // Elsewhere in the bbox's latitudes, no band of land.
  d.bbox_ring = box_ring(10, -19, 12, -15);
  r = select_domain(d, params(DomainKind::water));
  ASSERT_EQ(r.polygons.size(), 1u);
  EXPECT_NEAR(area(r.polygons[0]), 8.0, 1e-9);
}

TEST(SelectDomain, ALandmassAcrossBothMeridiansIsCutAtTheAntimeridian) {
  // As Natural Earth's Eurasia: from -10 (west of Greenwich) to its tip 10 degrees past
  // the antimeridian, drawn at -180..-170 and joined by two edges across the antimeridian
  // (at latitudes 48..66 and 69..69.5 as drawn). Read as drawn, those edges run around
  // the globe and make a band of land between them.
  SourceData d;
  d.crs = parse_crs("EPSG:4326", "test");
  SourcePolygon land;
  land.fid = 0;
  land.rings = {{{-10, 30}, {80, 30}, {170, 30}, {-170, 66}, {-170, 69}, {170, 70}, {80, 70},
                 {-10, 70}}};
  d.polygons = {land};
  // The tip, cut at the antimeridian: (-180, 48), (-170, 66), (-170, 69), (-180, 69.5).
  d.bbox_ring = box_ring(-180, 40, -160, 75);
  SelectResult r = select_domain(d, params(DomainKind::land));
  ASSERT_EQ(r.polygons.size(), 1u);
  const double tip = 0.5 * (10 * (66 - 48) + 10 * (69.5 - 69)) + 10 * (69 - 66);  // 122.5
  EXPECT_NEAR(area(r.polygons[0]), tip, 1e-6);
  // The Atlantic at those latitudes is water: no band.
  d.bbox_ring = box_ring(-40, 60, -20, 68);
  r = select_domain(d, params(DomainKind::water));
  ASSERT_EQ(r.polygons.size(), 1u);
  EXPECT_NEAR(area(r.polygons[0]), 160.0, 1e-9);
}

TEST(SelectDomain, ABboxAcrossTheAntimeridianReadsBothSides) {
  // A world file (which stays in [-180, 180]) with an island across the antimeridian
  // (1 x 1 degree) and one drawn east of it at -179.5..-179 (0.5 x 1): a bbox from 178 to
  // 182 holds both whole.
  SourceData d = world_with_bay();
  SourcePolygon across, east;
  across.fid = 1;
  across.rings = {{{179.5, -17.0}, {-179.5, -17.0}, {-179.5, -16.0}, {179.5, -16.0}}};
  east.fid = 2;
  east.rings = {{{-179.5, -19.0}, {-179.0, -19.0}, {-179.0, -18.0}, {-179.5, -18.0}}};
  d.polygons.push_back(across);
  d.polygons.push_back(east);
  d.bbox_ring = box_ring(178, -20, 182, -15);
  const SelectResult r = select_domain(d, params(DomainKind::water));
  ASSERT_EQ(r.polygons.size(), 1u);
  EXPECT_EQ(r.polygons[0].holes.size(), 2u);
  EXPECT_NEAR(area(r.polygons[0]), 4 * 5 - 1.0 - 0.5, 1e-9);
}

TEST(SelectDomain, ALandmassRoundAPoleIsClosedThroughThePole) {
  // As world-atlas's Antarctica at 1:50m (a spherical polygon from d3's TopoJSON): a
  // coast round the south pole drawn from -180 to 179 at 70 S (with a bay of 10 by 5
  // degrees), closed by the short edge back across the antimeridian, and a hole that is
  // a ring round the pole itself at 89.999 S. Read as drawn, the coast encloses the thin
  // strip between itself and its closing edge; meant is everything south of it.
  SourceData d;
  d.crs = parse_crs("EPSG:4326", "test");
  SourcePolygon land;
  land.fid = 0;
  Ring coast;
  for (int lon = -180; lon < 0; lon += 10) coast.push_back({double(lon), -70.0});
  coast.push_back({0.0, -70.0});
  coast.push_back({0.0, -75.0});
  coast.push_back({10.0, -75.0});
  coast.push_back({10.0, -70.0});
  for (int lon = 20; lon <= 170; lon += 10) coast.push_back({double(lon), -70.0});
  coast.push_back({179.0, -70.0});
  Ring pole;
  for (int lon = -180; lon < 180; lon += 30) pole.push_back({double(lon), -89.999});
  std::reverse(pole.begin(), pole.end());
  land.rings = {coast, pole};
  d.polygons = {land};
  d.bbox_ring = box_ring(-180, -90, 180, -60);
  SelectResult r = select_domain(d, params(DomainKind::land));
  ASSERT_EQ(r.polygons.size(), 1u);
  EXPECT_TRUE(r.polygons[0].holes.empty());
  EXPECT_NEAR(area(r.polygons[0]), 360.0 * 20.0 - 10.0 * 5.0, 1e-6);
  // The water between 60 and 70 S is the bbox's band above it, with the bay.
  r = select_domain(d, params(DomainKind::water));
  double water = 0.0;
  for (const Polygon& p : r.polygons) water += area(p);
  EXPECT_NEAR(water, 360.0 * 10.0 + 10.0 * 5.0, 1e-6);
}

// A polygon of sea drawn as a map's lon/lat rectangle up to the top of the map (as
// geo-maps' earth-seas is): its edge along 90 N from 180 back to -180 is the pole, not a
// crossing of the antimeridian. Read as drawn, with or without a bbox; an island in it
// stays a hole.
TEST(SelectDomain, AnEdgeAlongThePoleCrossesNoAntimeridian) {
  SourceData d;
  d.crs = parse_crs("EPSG:4326", "test");
  SourcePolygon sea;
  sea.fid = 0;
  Ring island = box_ring(10, 40, 20, 50);
  std::reverse(island.begin(), island.end());
  sea.rings = {{{-180, 0}, {-90, 0}, {0, 0}, {90, 0}, {180, 0}, {180, 90}, {-180, 90}}, island};
  d.polygons = {sea};
  SelectResult r = select_domain(d, params(DomainKind::sea));
  ASSERT_EQ(r.polygons.size(), 1u);
  EXPECT_EQ(r.polygons[0].holes.size(), 1u);
  EXPECT_NEAR(area(r.polygons[0]), 360.0 * 90.0 - 100.0, 1e-6);
  d.bbox_ring = box_ring(-180, -90, 180, 90);
  r = select_domain(d, params(DomainKind::sea));
  double total = 0.0;
  for (const Polygon& p : r.polygons) total += area(p);
  EXPECT_NEAR(total, 360.0 * 90.0 - 100.0, 1e-6);
}
