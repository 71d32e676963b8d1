#include "gis/crs.h"
#include "gis/map_scale.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "support/geodesic.h"

using namespace isoquad;

TEST(Crs, ParsesEpsgWktProjStringsAndProjJson) {
  const CrsInfo l93 = parse_crs("EPSG:2154", "--dst-crs");
  EXPECT_TRUE(l93.projected);
  EXPECT_NE(l93.name.find("Lambert-93"), std::string::npos);
  EXPECT_TRUE(parse_crs(l93.wkt, "wkt").projected);
  const CrsInfo utm = parse_crs("+proj=utm +zone=30 +datum=WGS84 +units=m", "proj");
  EXPECT_TRUE(utm.projected);
  const CrsInfo wgs = parse_crs(
      R"({"type":"GeographicCRS","name":"WGS 84","datum":{"type":"GeodeticReferenceFrame",)"
      R"("name":"World Geodetic System 1984","ellipsoid":{"name":"WGS 84",)"
      R"("semi_major_axis":6378137,"inverse_flattening":298.257223563}},)"
      R"("coordinate_system":{"subtype":"ellipsoidal","axis":[{"name":"Latitude",)"
      R"("abbreviation":"lat","direction":"north","unit":"degree"},{"name":"Longitude",)"
      R"("abbreviation":"lon","direction":"east","unit":"degree"}]}})",
      "projjson");
  EXPECT_TRUE(wgs.geographic);
}

TEST(Crs, UnknownCrsIsACrsErrorNamingTheOption) {
  try {
    parse_crs("EPSG:99999999", "--dst-crs");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), ErrorClass::crs);
    EXPECT_NE(std::string(e.what()).find("--dst-crs"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("EPSG:99999999"), std::string::npos);
  }
}

TEST(Crs, TransformUsesLonLatOrderAndReportsFailures) {
  const CrsInfo wgs = parse_crs("EPSG:4326", "src");
  const CrsInfo l93 = parse_crs("EPSG:2154", "dst");
  CrsTransform t(wgs, l93);
  Point2 p{3.0, 46.5};  // the projection origin of Lambert-93
  ASSERT_TRUE(t.transform(p));
  EXPECT_NEAR(p.x, 700000.0, 1e-3);
  EXPECT_NEAR(p.y, 6600000.0, 1e-3);
  // Lambert conformal conic cannot map the opposite pole.
  std::vector<Point2> bad{{3.0, 46.5}, {3.0, -90.0}};
  EXPECT_EQ(t.transform(bad), 1);
}

// The automatic projection must keep areas close to the ellipsoid's: it is conformal,
// with the scale balanced between centre and edge.
TEST(Crs, LocalProjectionPreservesAreaOfADomainTheSizeOfFrance) {
  const CrsInfo wgs = parse_crs("EPSG:4326", "src");
  Ring lonlat;
  for (int i = 0; i < 40; ++i) lonlat.push_back({-4.0 + 12.0 * i / 40, 42.5});
  for (int i = 0; i < 40; ++i) lonlat.push_back({8.0, 42.5 + 8.5 * i / 40});
  for (int i = 0; i < 40; ++i) lonlat.push_back({8.0 - 12.0 * i / 40, 51.0});
  for (int i = 0; i < 40; ++i) lonlat.push_back({-4.0, 51.0 - 8.5 * i / 40});
  const LocalProjection lp = choose_local_projection(wgs, lonlat);
  EXPECT_TRUE(lp.crs.projected);
  EXPECT_NEAR(lp.lon0_deg, 2.0, 1e-9);
  EXPECT_NEAR(lp.lat0_deg, 46.75, 1e-9);
  // Named with its centre, to tell it from another region's in a GIS.
  EXPECT_EQ(lp.crs.name, "isoquad local oblique stereographic 46.7500N 2.0000E");
  EXPECT_LT(lp.scale_factor, 1.0);
  EXPECT_GT(lp.max_distance_km, 600.0);
  Ring projected = lonlat;
  // The straight lon/lat edges are densified above, so the planar area is meaningful.
  ASSERT_EQ(CrsTransform(wgs, lp.crs).transform(projected), -1);
  const double reference = test::geodesic_area_m2(lonlat);
  EXPECT_NEAR(std::abs(signed_area(projected)) / reference, 1.0, 0.005);
}

TEST(Crs, LocalProjectionHandlesTheAntimeridian) {
  const CrsInfo wgs = parse_crs("EPSG:4326", "src");
  Ring fiji{{177.0, -19.0}, {179.5, -19.0}, {-179.5, -16.0}, {177.0, -16.0}};
  const LocalProjection lp = choose_local_projection(wgs, fiji);
  EXPECT_NEAR(lp.lon0_deg, 178.75, 1e-9);
  EXPECT_EQ(lp.crs.name, "isoquad local oblique stereographic 17.5000S 178.7500E");
  EXPECT_LT(lp.max_distance_km, 300.0);
}

TEST(Crs, LocalProjectionOfADomainRoundAPoleIsCentredOnThePole) {
  const CrsInfo wgs = parse_crs("EPSG:4326", "src");
  // A cap south of 65 S (every longitude, to the pole, as a lon/lat box draws it): the
  // middle of the box would be 77.5 S on the antimeridian, 1400 km from the pole.
  Ring cap;
  for (int i = 0; i <= 72; ++i) cap.push_back({-180.0 + 5.0 * i, -65.0});
  cap.push_back({180.0, -90.0});
  cap.push_back({-180.0, -90.0});
  LocalProjection lp = choose_local_projection(wgs, cap);
  EXPECT_EQ(lp.lat0_deg, -90.0);
  EXPECT_NEAR(lp.max_distance_km, 2800.0, 30.0);  // 25 degrees of meridian
  // A band from 60 to 75 N round the globe: the north pole.
  Ring band;
  for (int i = 0; i <= 72; ++i) band.push_back({-180.0 + 5.0 * i, 60.0});
  for (int i = 0; i <= 72; ++i) band.push_back({180.0 - 5.0 * i, 75.0});
  lp = choose_local_projection(wgs, band);
  EXPECT_EQ(lp.lat0_deg, 90.0);
  EXPECT_NEAR(lp.max_distance_km, 3350.0, 30.0);
  // A wedge from the pole to 60 S between 120 and 150 E: the mean direction of its
  // points (three at 60 S, two at the pole: 72.3 S), on its middle meridian.
  Ring wedge{{120.0, -60.0}, {135.0, -60.0}, {150.0, -60.0}, {150.0, -90.0}, {120.0, -90.0}};
  lp = choose_local_projection(wgs, wedge);
  EXPECT_NEAR(lp.lon0_deg, 135.0, 1e-6);
  EXPECT_NEAR(lp.lat0_deg, -72.3, 0.05);
}

// A PROJ string names no CRS: the summaries show the PROJ string, not "unknown", also
// for the WKT made from it.
TEST(Crs, ACrsWithoutANameIsShownByItsProjString) {
  const CrsInfo utm = parse_crs("+proj=utm +zone=31 +datum=WGS84 +units=m +no_defs", "test");
  EXPECT_EQ(utm.name.rfind("+proj=utm +zone=31", 0), 0u) << utm.name;
  EXPECT_EQ(parse_crs(utm.wkt, "test").name, utm.name);
  EXPECT_EQ(parse_crs("EPSG:32631", "test").name, "WGS 84 / UTM zone 31N");
}

// The scale of World Mercator (EPSG:3395, conformal on the ellipsoid) is known in closed
// form: sqrt(1 - e^2 sin^2 lat) / cos lat. MapScale measures it by geodesics.
TEST(MapScale, MercatorsScaleGrowsAsTheSecantOfTheLatitude) {
  const CrsInfo wgs = parse_crs("EPSG:4326", "src"), mercator = parse_crs("EPSG:3395", "dst");
  std::vector<Point2> corners{{0, 0}, {20, 70}};
  ASSERT_EQ(CrsTransform(wgs, mercator).transform(corners), -1);
  const MapScale scale(mercator, {corners[0].x, corners[0].y, corners[1].x, corners[1].y});
  const double e2 = 0.00669437999014;  // WGS 84
  for (const double lat : {0.0, 30.0, 60.0, 69.0}) {
    Point2 p{7.5, lat};
    ASSERT_TRUE(CrsTransform(wgs, mercator).transform(p));
    const double phi = lat * M_PI / 180;
    const double expected = std::sqrt(1 - e2 * std::sin(phi) * std::sin(phi)) / std::cos(phi);
    // Bilinear between nodes 0.27 degrees of latitude apart at 60 N.
    EXPECT_NEAR(scale.at(p) / expected, 1.0, 2e-4) << lat;
  }
  EXPECT_NEAR(scale.min(), 1.0, 1e-6);
  EXPECT_NEAR(scale.max() * std::cos(70 * M_PI / 180), std::sqrt(1 - e2 * 0.883), 1e-4);
  EXPECT_GT(scale.max_error(), 1.9);
}

// UTM is 0.9996 on its central meridian and grows away from it; the automatic projection
// is its own scale factor at its centre.
TEST(MapScale, UtmAndTheLocalProjectionHaveTheirScaleFactorAtTheirCentre) {
  const CrsInfo wgs = parse_crs("EPSG:4326", "src"), utm = parse_crs("EPSG:32631", "dst");
  const MapScale u(utm, {400000, 4800000, 600000, 5200000}, 8);
  EXPECT_NEAR(u.at({500000, 5000000}), 0.9996, 1e-6);
  EXPECT_GT(u.at({600000, 5000000}), u.at({500000, 5000000}));
  EXPECT_LT(u.max_error(), 0.0005);

  Ring lonlat{{-4, 42.5}, {8, 42.5}, {8, 51}, {-4, 51}};
  const LocalProjection lp = choose_local_projection(wgs, lonlat);
  const MapScale s(lp.crs, {-600000, -600000, 600000, 600000});
  EXPECT_NEAR(s.at({0, 0}), lp.scale_factor, 1e-6);
  // Balanced: the centre under 1, the domain's farthest points as much over it, and the
  // box's corners (850 km out, the farthest 750 km) about twice that.
  EXPECT_LT(s.min(), 1.0);
  EXPECT_GT(s.max() - 1.0, 1.0 - s.min());
  EXPECT_LT(s.max() - 1.0, 3 * (1.0 - s.min()));
}

// What crs_distortion measures, on CRSs whose distortion is known: UTM conformal and
// within 0.1% of the ground in its zone; World Mercator conformal, its scale the secant
// of the latitude (1.5 at 48 N); Europe's equal-area CRS (EPSG:3035) about true to
// scale at its centre (52 N, 10 E) but not conformal 1,000 km from it.
TEST(CrsDistortion, ConformalOrNotAndHowFarFromTheGroundsScale) {
  const CrsInfo wgs = parse_crs("EPSG:4326", "src");
  auto measured = [&wgs](const char* code, std::vector<Point2> lonlat) {
    const CrsInfo crs = parse_crs(code, "dst");
    EXPECT_EQ(CrsTransform(wgs, crs).transform(lonlat), -1) << code;
    return crs_distortion(crs, lonlat);
  };
  CrsDistortion d = measured("EPSG:32631", {{0.5, 43}, {3, 45}, {5.5, 50}});
  EXPECT_TRUE(d.measured);
  EXPECT_LT(d.max_scale_error, 0.001);
  EXPECT_LT(d.max_anisotropy, 1e-5);
  EXPECT_LT(d.max_skew_deg, 1e-3);
  d = measured("EPSG:3395", {{-4, 48}, {0, 48}});
  EXPECT_NEAR(d.max_scale_error, 0.49, 0.01);
  EXPECT_LT(d.max_anisotropy, 1e-5);
  EXPECT_LT(d.max_skew_deg, 1e-3);
  d = measured("EPSG:3035", {{10, 52}});
  EXPECT_LT(d.max_anisotropy, 1e-3);  // on the ellipsoid, 0.03% at its very centre
  EXPECT_LT(d.max_scale_error, 1e-3);
  d = measured("EPSG:3035", {{-5, 45}, {25, 60}});
  EXPECT_GT(d.max_anisotropy + d.max_skew_deg / 57.3, 0.005);
  EXPECT_FALSE(crs_distortion(parse_crs("EPSG:32631", "dst"), {}).measured);
}
