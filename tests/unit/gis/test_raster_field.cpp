// Rasters sampled at points of another CRS (gis/raster_field.h), read whole or only
// under an extent.
#include "gis/raster_field.h"

#include <gtest/gtest.h>

#include <cmath>

#include "gis/crs.h"
#include "gis/gdal_env.h"
#include "support/test_support.h"
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
  EXPECT_LE(compare_under(path, fiji, {-300000, -300000, 300000, 300000}), 1.0);
}
