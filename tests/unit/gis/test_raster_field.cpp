// Rasters sampled at points of another CRS (gis/raster_field.h), read whole or only
// under an extent.
#include "gis/raster_field.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "core/error.h"
#include "gis/crs.h"
#include "gis/gdal_env.h"
#include "support/test_support.h"
#include "support/write_archive.h"
#include "support/write_raster.h"

using namespace isoquad;
using namespace isoquad::test;

namespace {

// A world grid in lon/lat, 0.5-degree pixels, value lon + 1000 lat at the pixel centres
// (bilinear sampling is exact between them).
std::string world(const TempDir& dir) {
  return write_geotiff(dir.file("world.tif"), -180, 90, 0.5, 720, 360, 4326,
                       [](double lon, double lat) { return lon + 1000 * lat; });
}

// Under `extent` (query CRS), the window's samples are the whole raster's, on a lattice
// of points; returns the share of the raster's pixels read.
double compare_under(const std::string& path, const CrsInfo& crs,
                     const std::array<double, 4>& extent) {
  const RasterField whole(path, "--bathymetry", crs);
  const RasterField part(path, "--bathymetry", crs, extent);
  int compared = 0;
  for (int a = 0; a <= 100; ++a)
    for (int b = 0; b <= 100; ++b) {
      const Point2 p{extent[0] + (extent[2] - extent[0]) * a / 100.0,
                     extent[1] + (extent[3] - extent[1]) * b / 100.0};
      const double w = whole.sample(p), s = part.sample(p);
      if (std::isnan(w)) {
        EXPECT_TRUE(std::isnan(s));
        continue;
      }
      EXPECT_EQ(s, w) << p.x << " " << p.y;
      ++compared;
    }
  EXPECT_GT(compared, 5000);
  const auto& win = part.window();
  EXPECT_EQ(whole.window(), (std::array<int, 4>{0, 0, 720, 360}));
  return static_cast<double>(win[2]) * win[3] / (720.0 * 360.0);
}

}  // namespace

TEST(RasterField, UnderAnExtentOnlyThatPartIsRead) {
  TempDir dir;
  const std::string path = world(dir);
  // Brittany in a local oblique stereographic, 400 x 300 km.
  const CrsInfo brittany =
      parse_crs("+proj=sterea +lat_0=48.1 +lon_0=-3.6 +datum=WGS84 +units=m", "t");
  EXPECT_LT(compare_under(path, brittany, {-200000, -150000, 200000, 150000}), 0.01);
  // Round the North Pole (polar stereographic), 3,000 km across: every longitude, and
  // the rows up to the pole, whose lattice point may miss it.
  const CrsInfo arctic = parse_crs("EPSG:3413", "t");
  EXPECT_LT(compare_under(path, arctic, {-1490000, -1510000, 1510000, 1490000}), 0.2);
  // Across the antimeridian (Fiji): both ends of the grid.
  const CrsInfo fiji = parse_crs("+proj=sterea +lat_0=-17.5 +lon_0=179 +datum=WGS84 +units=m", "t");
  EXPECT_LT(compare_under(path, fiji, {-300000, -300000, 300000, 300000}), 0.01);
}

// Round the antimeridian, a world grid drawn from -180 to 180 and the same drawn from 0 to
// 360 give the same values, and so does a regional grid from 170 to 190 degrees east;
// between a global grid's last column and its first, values are interpolated across
// its seam.
TEST(RasterField, LongitudesGoRoundTheAntimeridian) {
  TempDir dir;
  auto value = [](double lon, double lat) { return 100 * std::sin(lon * M_PI / 180) + 1000 * lat; };
  const std::string west = write_geotiff(dir.file("w.tif"), -180, 90, 0.5, 720, 360, 4326, value);
  const std::string east = write_geotiff(dir.file("e.tif"), 0, 90, 0.5, 720, 360, 4326, value);
  const std::string fiji_grid = write_geotiff(dir.file("f.tif"), 170, -5, 0.5, 40, 50, 4326, value);
  const CrsInfo fiji = parse_crs("+proj=sterea +lat_0=-17.5 +lon_0=179 +datum=WGS84 +units=m", "t");
  const std::array<double, 4> extent{-300000, -300000, 300000, 300000};
  const RasterField a(west, "--bathymetry", fiji, extent), b(east, "--bathymetry", fiji, extent),
      c(fiji_grid, "--bathymetry", fiji);
  int compared = 0;
  for (int i = 0; i <= 60; ++i)
    for (int j = 0; j <= 60; ++j) {
      const Point2 p{extent[0] + 10000.0 * i, extent[1] + 10000.0 * j};
      const double va = a.sample(p);
      ASSERT_FALSE(std::isnan(va)) << p.x << " " << p.y;
      EXPECT_NEAR(b.sample(p), va, 1e-6) << p.x << " " << p.y;
      EXPECT_NEAR(c.sample(p), va, 1e-6) << p.x << " " << p.y;
      ++compared;
    }
  EXPECT_EQ(compared, 61 * 61);
  // Each global grid's window is a few hundred columns of 720, past the seam for the
  // grid drawn from -180.
  for (const RasterField* f : {&a, &b}) {
    EXPECT_LT(f->window()[2], 100);
    EXPECT_LT(f->window()[3], 100);
  }
  EXPECT_GT(a.window()[0] + a.window()[2], 720);
  // On the antimeridian at a row of pixel centres (latitude -17.25): halfway between the
  // columns centred at 179.75 and -179.75.
  const CrsInfo lonlat = parse_crs("EPSG:4326", "t");
  const RasterField whole(west, "--bathymetry", lonlat);
  const double seam = 0.5 * (value(179.75, -17.25) + value(-179.75, -17.25));
  EXPECT_NEAR(whole.sample({180.0, -17.25}), seam, 1e-3);
  EXPECT_NEAR(whole.sample({-180.0, -17.25}), seam, 1e-3);
  EXPECT_NEAR(whole.sample({539.875, -17.25}),
              0.75 * value(179.75, -17.25) + 0.25 * value(-179.75, -17.25), 1e-3);
}

// The mean over a square: the cells with a value whose centres lie in it, where the point
// has a value; the bilinear value when the square spans fewer than two cells' centres.
TEST(RasterField, TheMeanOverASquareCountsTheCellsWithAValue) {
  TempDir dir;
  // 10 x 10 cells of 100 m in UTM 31N, value the column (0 to 9); the cells of columns
  // 0 and 1 in rows 0 to 4 without a value.
  const std::string path =
      write_geotiff(dir.file("g.tif"), 500000, 5001000, 100, 10, 10, 32631, [](double x, double y) {
        const double column = std::floor((x - 500000) / 100);
        return column < 2 && y > 5000500 ? std::nan("") : column;
      });
  const RasterField f(path, "--bathymetry", parse_crs("EPSG:32631", "t"));
  // Columns 4 to 7, rows 5 to 8 (centres 450 to 750 m east, 150 to 450 m north).
  EXPECT_NEAR(f.mean_over({500600, 5000300}, 160), 5.5, 1e-9);
  // Columns 1 to 3 over rows 4 to 6: the cell without a value (column 1, row 4) left out.
  EXPECT_NEAR(f.mean_over({500250, 5000450}, 160), (2 + 3 + 2 * (1 + 2 + 3)) / 8.0, 1e-9);
  // A point without a value (next to cells without one, as sample() gives it): none.
  EXPECT_TRUE(std::isnan(f.mean_over({500200, 5000500}, 160)));
  EXPECT_TRUE(std::isnan(f.mean_over({500100, 5000800}, 60)));
  // Fewer than two centres either way: the bilinear value.
  EXPECT_DOUBLE_EQ(f.mean_over({500520, 5000300}, 40), f.sample({500520, 5000300}));
  EXPECT_DOUBLE_EQ(f.mean_over({500520, 5000300}, 0), f.sample({500520, 5000300}));
}

// GEBCO's and EMODnet's grids come zipped, beside their licence texts: read as they are.
TEST(RasterField, ReadsAZippedGridAsDownloaded) {
  TempDir dir;
  const std::string tif = world(dir);
  const CrsInfo lonlat = parse_crs("EPSG:4326", "t");
  const RasterField plain(tif, "--bathymetry", lonlat);
  const std::string zip =
      write_zip(dir.file("gebco_2024.zip"),
                {{"GEBCO_2024_TID.pdf", "terms"}, {"gebco_2024/world.tif", read_file(tif)}});
  const RasterField zipped(zip, "--bathymetry", lonlat);
  for (const Point2 p : {Point2{-3.25, 48.25}, Point2{179.9, -17.6}, Point2{12.3, 45.6}})
    EXPECT_EQ(zipped.sample(p), plain.sample(p)) << p.x << " " << p.y;
  EXPECT_EQ(zipped.sample({-3.25, 48.25}), -3.25 + 1000 * 48.25);
  // Two grids: the message names them and how to pick one.
  const std::string two =
      write_zip(dir.file("two.zip"), {{"a.tif", read_file(tif)}, {"b.tif", read_file(tif)}});
  try {
    check_raster(two, "--bathymetry");
    ADD_FAILURE() << "no error for " << two;
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), ErrorClass::input);
    EXPECT_NE(std::string(e.what()).find(
                  "--bathymetry '" + two +
                  "': the archive holds 2 raster files (a.tif, b.tif): name one, e.g. /vsizip/" +
                  two + "/a.tif"),
              std::string::npos)
        << e.what();
  }
}

// A grid GDAL opens by a name that is not a file (a driver's prefix here; a WCS, a
// PostGIS raster, a URL alike) is read as the file is.
TEST(RasterField, AGridNamedForGdalIsRead) {
  TempDir dir;
  const std::string tif = world(dir);
  const CrsInfo lonlat = parse_crs("EPSG:4326", "t");
  const RasterField plain(tif, "--bathymetry", lonlat);
  const RasterField named("GTIFF_DIR:1:" + tif, "--bathymetry", lonlat);
  EXPECT_EQ(named.sample({-3.25, 48.25}), plain.sample({-3.25, 48.25}));
  try {
    check_raster("GTIFF_DIR:1:" + dir.file("none.tif"), "--bathymetry");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no such file, nor a raster GDAL opens by this name"),
              std::string::npos)
        << e.what();
  }
}

// A point on the raster's edge, come back from another CRS a little off it, takes the
// edge's value; beyond half a pixel, none.
TEST(RasterField, TheEdgeHoldsWithinHalfAPixel) {
  TempDir dir;
  // 10 x 10 pixels of 100 m in UTM 31N, value x / 100 at the pixel centres.
  const std::string path = write_geotiff(dir.file("g.tif"), 500000, 5001000, 100, 10, 10, 32631,
                                         [](double x, double) { return x / 100; });
  const CrsInfo utm = parse_crs("EPSG:32631", "t");
  const RasterField f(path, "--bathymetry", utm);
  EXPECT_DOUBLE_EQ(f.sample({500000.0, 5000500.0}), 5000.5);        // on the west edge
  EXPECT_DOUBLE_EQ(f.sample({499999.5, 5000500.0}), 5000.5);        // 0.005 pixel off it
  EXPECT_DOUBLE_EQ(f.sample({499960.0, 5000500.0}), 5000.5);        // 0.4 pixel off
  EXPECT_TRUE(std::isnan(f.sample({499940.0, 5000500.0})));         // 0.6 pixel off
  EXPECT_DOUBLE_EQ(f.sample({501040.0, 5000000.0 - 40}), 5009.5);   // the south-east corner
  EXPECT_TRUE(std::isnan(f.sample({501060.0, 5000500.0})));
}

// A raster without a CRS is read in the query CRS; when its extent looks like longitudes
// and latitudes, the hint for "no vertex has a depth" says so.
TEST(RasterField, AGridWithoutACrsInLongitudesIsNamed) {
  TempDir dir;
  const CrsInfo local = parse_crs("+proj=sterea +lat_0=40.5 +lon_0=3.6 +datum=WGS84 +units=m", "t");
  const std::string lonlat = write_geotiff(dir.file("ll.tif"), 3.0, 41.0, 0.02, 60, 50, 0,
                                           [](double, double) { return 10.0; });
  const RasterField no_crs(lonlat, "--bathymetry", local);
  EXPECT_NE(no_crs.crs_hint().find("looks like longitudes and latitudes"), std::string::npos)
      << no_crs.crs_hint();
  const std::string metres = write_geotiff(dir.file("m.tif"), 500000, 5001000, 100, 10, 10, 0,
                                           [](double, double) { return 10.0; });
  const RasterField in_metres(metres, "--bathymetry", local);
  EXPECT_NE(in_metres.crs_hint().find("has no CRS"), std::string::npos);
  EXPECT_EQ(in_metres.crs_hint().find("longitudes"), std::string::npos);
  const std::string with_crs = write_geotiff(dir.file("w.tif"), 3.0, 41.0, 0.02, 60, 50, 4326,
                                             [](double, double) { return 10.0; });
  EXPECT_EQ(RasterField(with_crs, "--bathymetry", local).crs_hint(), "");
}

// Packed values (a netCDF variable's scale_factor and add_offset, GDAL's band scale and
// offset) are read in their units, nodata left out.
TEST(RasterField, PackedValuesAreUnpacked) {
  TempDir dir;
  std::vector<std::int16_t> raw(16, 500);  // -50 m
  raw[0] = -32768;
  const std::string path =
      write_packed_geotiff(dir.file("packed.tif"), 500000, 5000400, 100, 4, 4, raw);
  const RasterField f(path, "--elevation", parse_crs("EPSG:32631", "t"));
  EXPECT_NEAR(f.sample({500250.0, 5000150.0}), -50.0, 1e-4);
  EXPECT_TRUE(std::isnan(f.sample({500050.0, 5000350.0})));  // next to the cell without a value
}
