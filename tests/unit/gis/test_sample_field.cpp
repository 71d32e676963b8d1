// SampleField: scattered samples (soundings) as a depth source. A linear function is
// reproduced between the samples and NaN far off their outline; an .xyz's separators,
// comments and header; duplicates averaged; GeoJSON points with Z or an attribute,
// transformed from lon/lat, and a CSV's columns; the mean over a square where the samples are
// dense; the errors (no CRS, a bad line, collinear samples, no values); RasterStack's order with a
// raster, and a gridded .xyz left to GDAL as a raster.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/error.h"
#include "gis/crs.h"
#include "gis/sample_field.h"
#include "support/test_support.h"
#include "support/write_raster.h"

using namespace isoquad;
using namespace isoquad::test;

namespace {

double linear(double x, double y) {
  return 0.03 * x - 0.02 * y + 40;
}

// `n` points scattered over [0, size]^2 (a fixed sequence), one "x y value" line each,
// after a comment and a header.
std::string scattered_xyz(int n, double size) {
  std::string text = "# soundings\nx y z\n";
  unsigned state = 12345;
  auto next = [&state] {
    state = state * 1103515245u + 12345u;
    return static_cast<double>((state >> 8) & 0xffff) / 65535.0;
  };
  for (int i = 0; i < n; ++i) {
    const double x = size * next(), y = size * next();
    text += std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(linear(x, y)) + "\n";
  }
  // The corners, so that the outline is the square.
  for (const auto& [x, y] : {std::pair{0.0, 0.0}, {size, 0.0}, {size, size}, {0.0, size}})
    text += std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(linear(x, y)) + "\n";
  return text;
}

std::string error_of(const std::function<void()>& f, ErrorClass expected) {
  try {
    f();
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), expected) << e.what();
    return e.what();
  }
  ADD_FAILURE() << "no error";
  return "";
}

const CrsInfo& utm() {
  static const CrsInfo crs = parse_crs("EPSG:32631", "test");
  return crs;
}

// A survey of 54 soundings over [0, 1000]^2 (survey.xyz, in UTM 31N) and a grid of 7 m
// everywhere over a larger square (grid.tif), as depth sources.
std::pair<DepthRaster, DepthRaster> survey_and_grid(const TempDir& dir) {
  write_file(dir.file("survey.xyz"), scattered_xyz(50, 1000));
  write_geotiff(dir.file("grid.tif"), -5000, 5000, 100, 100, 100, 32631,
                [](double, double) { return 7.0; });
  DepthRaster survey{dir.file("survey.xyz")};
  survey.crs_if_none = "EPSG:32631";
  return {survey, DepthRaster{dir.file("grid.tif")}};
}

}  // namespace

TEST(SampleField, LinearBetweenSamplesNanFarOffTheirOutline) {
  TempDir dir;
  write_file(dir.file("s.xyz"), scattered_xyz(300, 1000));
  ASSERT_TRUE(is_sample_file(dir.file("s.xyz")));
  const SampleField f(dir.file("s.xyz"), "--bathymetry", utm(), "EPSG:32631", "");
  EXPECT_EQ(f.size(), 304u);
  for (const Point2 p : {Point2{10, 10}, Point2{500, 500}, Point2{999, 3}, Point2{250, 760}})
    EXPECT_NEAR(f.sample(p), linear(p.x, p.y), 1e-4) << p.x << " " << p.y;
  EXPECT_TRUE(std::isnan(f.sample({5000, 500})));
  EXPECT_TRUE(std::isnan(f.sample({500, -3000})));
}

TEST(SampleField, XyzSeparatorsCommentsAndHeader) {
  TempDir dir;
  write_file(dir.file("s.xyz"),
             "* D-Flow FM samples\n"
             "easting,northing,depth\n"
             "0,0,10\n"
             "100;0;+12.5\n"
             "\n"
             "// a note\n"
             "0\t100\t14 extra columns\r\n"
             "  100  100  16.5\n"
             "% the end\n");
  const SampleField f(dir.file("s.xyz"), "--bathymetry", utm(), "EPSG:32631", "");
  EXPECT_EQ(f.size(), 4u);
  EXPECT_NEAR(f.sample({0, 0}), 10, 1e-9);
  EXPECT_NEAR(f.sample({100, 0}), 12.5, 1e-9);
  EXPECT_NEAR(f.sample({0, 100}), 14, 1e-9);
  EXPECT_NEAR(f.sample({100, 100}), 16.5, 1e-9);

  write_file(dir.file("bad.xyz"), "x y z\n0 0 1\n1 0 2\n0 1 3\n1 1 four\n");
  const std::string e =
      error_of([&] { SampleField(dir.file("bad.xyz"), "--bathymetry", utm(), "EPSG:32631", ""); },
               ErrorClass::input);
  EXPECT_NE(e.find("line 5 is not a sample"), std::string::npos) << e;
  // The check before a long job reads the start of the file and its CRS.
  error_of([&] { check_sample_file(dir.file("bad.xyz"), "--bathymetry", "EPSG:32631", ""); },
           ErrorClass::input);
}

TEST(SampleField, RepeatedSoundingsAreAveraged) {
  TempDir dir;
  write_file(dir.file("s.xyz"), "0 0 1\n100 0 1\n0 100 1\n0 0 3\n100 100 5\n");
  const SampleField f(dir.file("s.xyz"), "--bathymetry", utm(), "EPSG:32631", "");
  EXPECT_EQ(f.size(), 4u);
  EXPECT_NEAR(f.sample({0, 0}), 2, 1e-12);
}

TEST(SampleField, PointsWithZOrAnAttributeFromLonLat) {
  TempDir dir;
  const CrsTransform to_utm(parse_crs("EPSG:4326", "test"), utm());
  // Four soundings round 3.05 E 45.05 N; their values linear in UTM metres.
  std::string with_z = R"({"type":"FeatureCollection","features":[)";
  std::string with_attribute = with_z;
  const double lonlat[4][2] = {{3.0, 45.0}, {3.1, 45.0}, {3.1, 45.1}, {3.0, 45.1}};
  Point2 centre{0, 0};
  for (int i = 0; i < 4; ++i) {
    Point2 p{lonlat[i][0], lonlat[i][1]};
    ASSERT_TRUE(to_utm.transform(p));
    centre.x += p.x / 4, centre.y += p.y / 4;
    const std::string lon = std::to_string(lonlat[i][0]), lat = std::to_string(lonlat[i][1]);
    const std::string value = std::to_string(linear(p.x - 500000, p.y - 4980000));
    const std::string sep = i ? "," : "";
    with_z += sep + R"({"type":"Feature","properties":{"id":)" + std::to_string(i) +
              R"(},"geometry":{"type":"Point","coordinates":[)" + lon + "," + lat + "," + value +
              "]}}";
    with_attribute += sep + R"({"type":"Feature","properties":{"depth":)" + value +
                      R"(},"geometry":{"type":"Point","coordinates":[)" + lon + "," + lat + "]}}";
  }
  write_file(dir.file("z.geojson"), with_z + "]}");
  write_file(dir.file("a.geojson"), with_attribute + "]}");
  ASSERT_TRUE(is_sample_file(dir.file("z.geojson")));
  // Linear in UTM over the four corners: exact on the triangles' shared nodes, and
  // between them (a quadrilateral's two triangles, each a plane through its nodes).
  const double expected = linear(centre.x - 500000, centre.y - 4980000);
  const SampleField z(dir.file("z.geojson"), "--bathymetry", utm(), "", "");
  EXPECT_NEAR(z.sample(centre), expected, 1e-3);
  const SampleField a(dir.file("a.geojson"), "--bathymetry", utm(), "", "depth");
  EXPECT_NEAR(a.sample(centre), expected, 1e-3);

  std::string e = error_of(
      [&] { check_sample_file(dir.file("a.geojson"), "--bathymetry", "", ""); }, ErrorClass::usage);
  EXPECT_NE(e.find("points without Z"), std::string::npos) << e;
  EXPECT_NE(e.find("--depth-field (attributes: depth)"), std::string::npos) << e;
  e = error_of([&] { check_sample_file(dir.file("a.geojson"), "--bathymetry", "", "elev"); },
               ErrorClass::usage);
  EXPECT_NE(e.find("no attribute 'elev'"), std::string::npos) << e;
  // Polygons are no samples: left to the raster reader and its message.
  write_file(dir.file("p.geojson"), geojson_polygons({"[[[0,0],[1,0],[1,1],[0,0]]]"}));
  EXPECT_FALSE(is_sample_file(dir.file("p.geojson")));
}

// A CSV's columns named as coordinates (any case) give the points, --depth-field their
// values; the CSV has no CRS.
TEST(SampleField, ACsvsCoordinateColumns) {
  TempDir dir;
  write_file(dir.file("s.csv"),
             "Easting,Northing,Depth,Date\n0,0,5,2020\n1000,0,6,2020\n0,1000,7,2021\n"
             "1000,1000,8,2021\n200,700,6.6,2021\n");  // on a plane, not a grid
  ASSERT_TRUE(is_sample_file(dir.file("s.csv")));
  const std::string e =
      error_of([&] { check_sample_file(dir.file("s.csv"), "--bathymetry", "EPSG:32631", ""); },
               ErrorClass::usage);
  EXPECT_NE(e.find("(attributes: Easting, Northing, Depth, Date)"), std::string::npos) << e;
  error_of([&] { check_sample_file(dir.file("s.csv"), "--bathymetry", "", "Depth"); },
           ErrorClass::crs);
  const SampleField f(dir.file("s.csv"), "--bathymetry", utm(), "EPSG:32631", "Depth");
  EXPECT_NEAR(f.sample({1000, 0}), 6, 1e-9);
  EXPECT_NEAR(f.sample({500, 500}), 6.5, 1e-9);
}

TEST(SampleField, MeanOverTheSquareWhereTheSamplesAreDense) {
  TempDir dir;
  // A 10 m lattice, 5 + 1 and 5 - 1 in a checkerboard (a noisy survey of 5 m).
  std::string text;
  for (int j = 0; j <= 40; ++j)
    for (int i = 0; i <= 40; ++i)
      text += std::to_string(10 * i) + " " + std::to_string(10 * j) + " " +
              std::to_string((i + j) % 2 ? 4 : 6) + "\n";
  write_file(dir.file("s.xyz"), text);
  const SampleField f(dir.file("s.xyz"), "--bathymetry", utm(), "EPSG:32631", "");
  EXPECT_NEAR(f.sample({200, 200}), 6, 1e-9);
  EXPECT_NEAR(f.mean_over({200, 200}, 50), 5.0, 0.01);  // 121 samples, 61 of 6
  // Under four samples in the square (one, of 6): the value between them.
  EXPECT_NEAR(f.mean_over({202, 200}, 6), 5.6, 1e-9);
  EXPECT_TRUE(std::isnan(f.mean_over({-500, 200}, 50)));
}

TEST(SampleField, ErrorsNameTheFileAndTheFix) {
  TempDir dir;
  write_file(dir.file("s.xyz"), scattered_xyz(10, 100));
  std::string e = error_of([&] { check_sample_file(dir.file("s.xyz"), "--elevation", "", ""); },
                           ErrorClass::crs);
  EXPECT_NE(e.find("--elevation '"), std::string::npos) << e;
  EXPECT_NE(e.find("give it with --depth-crs"), std::string::npos) << e;
  // On one line, unevenly (GDAL reads evenly spaced ones as a grid).
  write_file(dir.file("line.xyz"), "0 0 1\n10 10 2\n35 35 3\n36 36 4\n");
  ASSERT_TRUE(is_sample_file(dir.file("line.xyz")));
  e = error_of([&] { SampleField(dir.file("line.xyz"), "--bathymetry", utm(), "EPSG:32631", ""); },
               ErrorClass::input);
  EXPECT_NE(e.find("not all on one line"), std::string::npos) << e;
  // --depth-field names the points' attribute of other files: an .xyz keeps its third
  // column.
  const SampleField named(dir.file("s.xyz"), "--bathymetry", utm(), "EPSG:32631", "depth");
  EXPECT_NEAR(named.sample({50, 50}), linear(50, 50), 1e-4);
}

TEST(SampleField, RasterStackTakesSamplesBeforeAGridAndGriddedXyzIsAGrid) {
  TempDir dir;
  const auto [survey, grid] = survey_and_grid(dir);
  check_depth_source(survey);
  const RasterStack stack({survey, grid}, utm());
  EXPECT_NEAR(stack.sample({400, 600}), linear(400, 600), 1e-4);
  EXPECT_NEAR(stack.sample({3000, 600}), 7.0, 1e-9);
  // Evenly spaced rows and columns: GDAL's XYZ grid, read as a raster.
  std::string rows;
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i)
      rows += std::to_string(100 * i) + " " + std::to_string(100 * j) + " 3\n";
  write_file(dir.file("grid.xyz"), rows);
  EXPECT_FALSE(is_sample_file(dir.file("grid.xyz")));
}

// With an extent, the samples farther than a quarter of its larger side from it are not
// kept (a national survey, a bay meshed): the values over it stay; an extent far from
// every sample gives NaN everywhere rather than an error.
TEST(SampleField, OnlyTheSamplesNearTheExtentAreKept) {
  TempDir dir;
  std::string text = scattered_xyz(50, 1000);
  for (int i = 0; i < 20; ++i)  // far to the east
    text += std::to_string(100000 + 500 * i) + " " + std::to_string(300 * (i % 4)) + " 5\n";
  write_file(dir.file("survey.xyz"), text);
  const SampleField all(dir.file("survey.xyz"), "--bathymetry", utm(), "EPSG:32631", "");
  const SampleField near(dir.file("survey.xyz"), "--bathymetry", utm(), "EPSG:32631", "",
                         std::array<double, 4>{0, 0, 1000, 1000});
  EXPECT_EQ(all.num_read(), 74u);
  EXPECT_EQ(all.size(), 74u);
  EXPECT_EQ(near.num_read(), 74u);
  EXPECT_EQ(near.size(), 54u);
  for (const Point2& p : {Point2{400, 600}, Point2{50, 950}, Point2{990, 10}})
    EXPECT_NEAR(near.sample(p), linear(p.x, p.y), 1e-4) << p.x << " " << p.y;
  const SampleField none(dir.file("survey.xyz"), "--bathymetry", utm(), "EPSG:32631", "",
                         std::array<double, 4>{-50000, 40000, -49000, 41000});
  EXPECT_EQ(none.size(), 0u);
  EXPECT_TRUE(std::isnan(none.sample({-49500, 40500})));
  EXPECT_TRUE(std::isnan(none.mean_over({-49500, 40500}, 100)));
}

// A stack built with `share` takes the samples' and the meshes' fields of the other (one
// triangulation, one read, for the sizes and the outputs), not its grids; with another
// query CRS, or the samples given with another option, it builds its own.
TEST(SampleField, RasterStackSharesTheSamplesOfAnother) {
  TempDir dir;
  const auto [survey, grid] = survey_and_grid(dir);
  // A model's grid of two triangles over the survey (a .gr3 in the same CRS), shared too.
  write_file(dir.file("hgrid.gr3"),
             "grid\n2 4\n1 0 0 5\n2 1000 0 5\n3 1000 1000 5\n4 0 1000 5\n1 3 1 2 3\n2 3 1 3 4\n");
  DepthRaster model{dir.file("hgrid.gr3")};
  model.crs_if_none = "EPSG:32631";
  const RasterStack first({survey, grid, model}, utm());
  EXPECT_TRUE(first.has_shareable());
  EXPECT_FALSE(RasterStack({grid}, utm()).has_shareable());
  const RasterStack second({survey, grid, model}, utm(), std::nullopt, &first);
  EXPECT_EQ(&second.field(0), &first.field(0));
  EXPECT_NE(&second.field(1), &first.field(1));
  EXPECT_EQ(&second.field(2), &first.field(2));
  EXPECT_EQ(second.field(2).sample({500, 200}), 5.0);
  EXPECT_EQ(second.sample({400, 600}), first.sample({400, 600}));
  const CrsInfo other = parse_crs("EPSG:32630", "test");
  EXPECT_NE(&RasterStack({survey}, other, std::nullopt, &first).field(0), &first.field(0));
  DepthRaster heights = survey;
  heights.elevation = true;
  const RasterStack third({heights}, utm(), std::nullopt, &first);
  EXPECT_NE(&third.field(0), &first.field(0));
  EXPECT_EQ(third.sample({400, 600}), -first.sample({400, 600}));
}
