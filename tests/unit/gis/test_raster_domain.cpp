// A domain from a raster's cells in [zmin, zmax] (gis/raster_domain.h): the polygons
// out of the range, and the area read, checked against a DEM of known contours.
#include "gis/raster_domain.h"

#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <netcdf.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "app/front_end.h"
#include "core/error.h"
#include "domain/select_domain.h"
#include "gis/gdal_env.h"
#include "support/test_support.h"
#include "support/write_raster.h"

using namespace isoquad;
using namespace isoquad::test;

namespace {

constexpr double kPi = 3.14159265358979323846;

// 20 x 20 km in UTM 31N at 100 m: a cone-shaped island, the 0 m contour a circle of
// 6 km round (510000, 4990000), sea round it; `nodata_cells` x `nodata_cells` cells
// without a value in the north-west corner.
std::string island_dem(const TempDir& dir, int nodata_cells = 0, int epsg = 32631) {
  return write_geotiff(dir.file("dem.tif"), 500000, 5000000, 100, 200, 200, epsg,
                       [=](double x, double y) {
                         if (x < 500000 + 100 * nodata_cells && y > 5000000 - 100 * nodata_cells)
                           return std::nan("");
                         return 0.01 * (6000 - std::hypot(x - 510000, y - 4990000));
                       });
}

ReadParams dem_params(const std::string& path) {
  ReadParams p;
  p.path = path;
  p.zmax = 0.0;
  return p;
}

double domain_area(const SourceData& source) {
  SelectParams sp;
  sp.kind = DomainKind::water;
  double total = 0.0;
  for (const Polygon& p : select_domain(source, sp).polygons) total += area(p);
  return total;
}

// The error reading `p` gives: its class and message (internal, "no error" when none).
std::pair<ErrorClass, std::string> failure(const ReadParams& p) {
  try {
    read_raster_domain(p);
  } catch (const Error& e) {
    return {e.error_class(), e.message()};
  }
  return {ErrorClass::internal, "no error"};
}

ErrorClass error_of(const ReadParams& p) {
  return failure(p).first;
}

}  // namespace

TEST(RasterDomain, TheSeaBelowZeroIsTheAreaMinusTheIsland) {
  TempDir dir;
  const SourceData sea = read_raster_domain(dem_params(island_dem(dir)));
  ASSERT_TRUE(sea.raster.has_value());
  EXPECT_EQ(sea.raster->columns, 200);
  EXPECT_EQ(sea.raster->num_valid_cells, 40000u);
  EXPECT_EQ(sea.raster->averaged, 1);
  // The cells out of the island's circle, within a row of cells along it.
  const double sea_cells = 40000 - kPi * 60 * 60;
  EXPECT_NEAR(static_cast<double>(sea.raster->num_cells_in_range), sea_cells, 2 * kPi * 60);
  // One polygon out of the range, the island, whose edge is the circle.
  ASSERT_EQ(sea.polygons.size(), 1u);
  ASSERT_EQ(sea.polygons[0].rings.size(), 1u);
  EXPECT_NEAR(std::abs(signed_area(sea.polygons[0].rings[0])), kPi * 6000 * 6000,
              0.002 * kPi * 6000 * 6000);
  for (const Point2& p : sea.polygons[0].rings[0])
    EXPECT_NEAR(std::hypot(p.x - 510000, p.y - 4990000), 6000, 15);
  // The area read is the raster's extent, cells' outer edges included.
  ASSERT_TRUE(sea.bbox_ring.has_value());
  EXPECT_NEAR(std::abs(signed_area(*sea.bbox_ring)), 400e6, 1.0);
  EXPECT_NEAR(domain_area(sea), 400e6 - kPi * 36e6, 0.002 * kPi * 36e6);

  // Above zero: the island alone; the sea is the polygon out of the range, the island its
  // hole.
  ReadParams above = dem_params(dir.file("dem.tif"));
  above.zmax.reset();
  above.zmin = 0.0;
  const SourceData land = read_raster_domain(above);
  ASSERT_EQ(land.polygons.size(), 1u);
  ASSERT_EQ(land.polygons[0].rings.size(), 2u);
  EXPECT_NEAR(domain_area(land), kPi * 36e6, 0.002 * kPi * 36e6);
  // A band: the sea from -20 to 0 m, a ring round the island 2 km wide.
  ReadParams band = dem_params(dir.file("dem.tif"));
  band.zmin = -20.0;
  EXPECT_NEAR(domain_area(read_raster_domain(band)), kPi * (64e6 - 36e6), 0.004 * kPi * 28e6);
}

TEST(RasterDomain, CellsWithoutAValueAreOutside) {
  TempDir dir;
  const SourceData sea = read_raster_domain(dem_params(island_dem(dir, 20)));
  EXPECT_EQ(sea.raster->num_valid_cells, 40000u - 400u);
  ASSERT_EQ(sea.polygons.size(), 2u);
  // The wall runs through the centres of the first cells with a value: 2,050 m square.
  EXPECT_NEAR(domain_area(sea), 400e6 - kPi * 36e6 - 2050.0 * 2050.0, 0.002 * kPi * 36e6);
}

TEST(RasterDomain, ALargeWindowIsReadAveraged) {
  TempDir dir;
  ReadParams p = dem_params(island_dem(dir, 21));
  p.max_raster_cells = 2500;
  const SourceData sea = read_raster_domain(p);
  EXPECT_EQ(sea.raster->averaged, 4);
  EXPECT_EQ(sea.raster->read_columns, 50);
  EXPECT_EQ(sea.warnings.size(), 1u);
  // The average leaves the cells without a value out: no mean of -9999 and a depth.
  EXPECT_GT(sea.raster->value_min, -82.0);
  EXPECT_NEAR(domain_area(sea), 400e6 - kPi * 36e6 - 2100.0 * 2100.0, 0.03 * kPi * 36e6);
}

// A lon/lat grid round the globe, read under a bbox across its seam: the island on the
// antimeridian whole, in the bbox's longitudes, whether the grid runs from -180 or from
// 0, read cell by cell or averaged.
TEST(RasterDomain, AGlobalGridIsReadAcrossItsSeam) {
  TempDir dir;
  // 0.1-degree cells from 10 to 25 S; an island of radius 0.5 degrees round (180, -17).
  auto island = [](double lon, double lat) {
    const double dlon = std::remainder(lon - 180.0, 360.0);
    return 1000 * (0.5 - std::hypot(dlon, lat + 17));
  };
  const std::string west =
      write_geotiff(dir.file("w.tif"), -180, -10, 0.1, 3600, 150, 4326, island);
  const std::string east = write_geotiff(dir.file("e.tif"), 0, -10, 0.1, 3600, 150, 4326, island);
  auto read = [](const std::string& path, const std::array<double, 4>& bbox, std::size_t cells) {
    ReadParams p = dem_params(path);
    p.bbox = bbox;
    p.max_raster_cells = cells;
    return read_raster_domain(p);
  };
  const std::array<double, 4> across{178, -19, 182, -15};
  for (const auto& [path, cells] : {std::pair<std::string, std::size_t>{west, 1u << 20},
                                    {east, 1u << 20},
                                    {west, 1000},
                                    {east, 1000}}) {
    SCOPED_TRACE(path + " " + std::to_string(cells));
    const SourceData sea = read(path, across, cells);
    EXPECT_TRUE(sea.warnings.size() == (cells < 5000 ? 1u : 0u));
    ASSERT_TRUE(sea.bbox_ring.has_value());
    EXPECT_NEAR(std::abs(signed_area(*sea.bbox_ring)), 16.0, 1e-9);
    ASSERT_EQ(sea.polygons.size(), 1u);
    ASSERT_EQ(sea.polygons[0].rings.size(), 1u);
    const double tolerance = cells < 5000 ? 0.2 : 0.02;  // averaged: cells of 0.2 degrees
    EXPECT_NEAR(std::abs(signed_area(sea.polygons[0].rings[0])), kPi * 0.25, 10 * tolerance * 0.5);
    for (const Point2& q : sea.polygons[0].rings[0])
      EXPECT_NEAR(std::hypot(q.x - 180, q.y + 17), 0.5, tolerance);
  }
  // West of -180 on the grid from 0: the island in the bbox's longitudes.
  const SourceData sea = read(east, {-182, -19, -178, -15}, 1u << 20);
  ASSERT_EQ(sea.polygons.size(), 1u);
  for (const Point2& q : sea.polygons[0].rings[0])
    EXPECT_NEAR(std::hypot(q.x + 180, q.y + 17), 0.5, 0.02);
}

TEST(RasterDomain, UnderABboxInAnotherCrs) {
  TempDir dir;
  ReadParams p = dem_params(island_dem(dir));
  // The raster's west half and more, in lon/lat (about 2.95 to 3.127 E).
  p.bbox = std::array<double, 4>{2.9, 44.9, 3.127, 45.2};
  p.bbox_crs = "EPSG:4326";
  const SourceData half = read_raster_domain(p);
  ASSERT_TRUE(half.bbox_ring.has_value());
  const double box = std::abs(signed_area(*half.bbox_ring));
  EXPECT_GT(box, 180e6);
  EXPECT_LT(box, 220e6);
  EXPECT_LT(half.raster->num_valid_cells, 40000u * 6 / 10);
  EXPECT_NEAR(domain_area(half), box - kPi * 18e6, 0.05 * kPi * 18e6);
  ASSERT_EQ(half.warnings.size(), 1u);
  EXPECT_NE(half.warnings[0].find("% of --bbox 2.9,44.9,3.127,45.2: the domain is the part"),
            std::string::npos)
      << half.warnings[0];
  p.bbox = std::array<double, 4>{3.05, 45.0, 3.15, 45.1};  // inside: no warning
  EXPECT_TRUE(read_raster_domain(p).warnings.empty());
  p.bbox = std::array<double, 4>{10, 50, 11, 51};
  EXPECT_EQ(error_of(p), ErrorClass::input);
}

// Packed values (scale and offset) are contoured in their units.
TEST(RasterDomain, PackedValuesAreContouredUnpacked) {
  TempDir dir;
  std::vector<std::int16_t> raw(100, 500);              // -50 m: sea
  for (int j = 0; j < 10; ++j) raw[j * 10 + 9] = 1200;  // +20 m: the east column is land
  const std::string path =
      write_packed_geotiff(dir.file("packed.tif"), 500000, 5001000, 100, 10, 10, raw);
  const SourceData sea = read_raster_domain(dem_params(path));
  EXPECT_DOUBLE_EQ(sea.raster->value_min, -50.0);
  EXPECT_DOUBLE_EQ(sea.raster->value_max, 20.0);
  EXPECT_EQ(sea.raster->num_cells_in_range, 90u);
}

TEST(RasterDomain, ClearErrors) {
  TempDir dir;
  const std::string path = island_dem(dir);
  ReadParams p = dem_params(path);
  p.zmax.reset();
  EXPECT_EQ(error_of(p), ErrorClass::usage);
  p.zmin = 5.0;
  p.zmax = 1.0;
  EXPECT_EQ(error_of(p), ErrorClass::usage);
  p.zmin = 100.0;
  p.zmax = 200.0;
  {
    const auto [cls, message] = failure(p);
    EXPECT_EQ(cls, ErrorClass::input);
    EXPECT_NE(message.find("has no cell in [100, 200]"), std::string::npos) << message;
  }
  const std::string no_crs = write_geotiff(dir.file("nocrs.tif"), 0, 1000, 10, 10, 10, 0,
                                           [](double, double) { return 1.0; });
  EXPECT_EQ(error_of(dem_params(no_crs)), ErrorClass::crs);
  const std::string lonlat = write_geotiff(dir.file("ll.tif"), 3, 41, 0.02, 60, 50, 0,
                                           [](double, double) { return -1.0; });
  {
    const auto [cls, message] = failure(dem_params(lonlat));
    EXPECT_EQ(cls, ErrorClass::crs);
    EXPECT_NE(message.find("look like longitudes and latitudes: --src-crs EPSG:4326"),
              std::string::npos)
        << message;
  }
  ReadParams assigned = dem_params(no_crs);
  assigned.src_crs = "EPSG:32631";
  assigned.zmax = 2.0;
  EXPECT_EQ(read_raster_domain(assigned).polygons.size(), 0u);
  EXPECT_EQ(error_of(dem_params(dir.file("missing.tif"))), ErrorClass::input);
}

TEST(RasterDomain, WhichInputsAreRasters) {
  TempDir dir;
  EXPECT_TRUE(is_raster_input(island_dem(dir)));
  // The same grid as netCDF (GEBCO's format): a raster, not a mesh, with the same cells.
  {
    GdalDataset tif(static_cast<GDALDataset*>(GDALOpen(dir.file("dem.tif").c_str(), GA_ReadOnly)));
    GDALDriver* netcdf = GetGDALDriverManager()->GetDriverByName("netCDF");
    ASSERT_NE(netcdf, nullptr);
    GdalDataset nc(netcdf->CreateCopy(dir.file("dem.nc").c_str(), tif.get(), FALSE, nullptr,
                                      nullptr, nullptr));
    ASSERT_TRUE(nc);
  }
  EXPECT_TRUE(is_raster_input(dir.file("dem.nc")));
  const SourceData from_nc = read_raster_domain(dem_params(dir.file("dem.nc")));
  const SourceData from_tif = read_raster_domain(dem_params(dir.file("dem.tif")));
  EXPECT_EQ(from_nc.raster->num_cells_in_range, from_tif.raster->num_cells_in_range);
  EXPECT_NEAR(domain_area(from_nc), domain_area(from_tif), 1.0);
  // A netCDF file of two grids: the message names each as GDAL opens it.
  int nc = -1, dy = -1, dx = -1, v = -1;
  ASSERT_EQ(nc_create(dir.file("two.nc").c_str(), NC_CLOBBER, &nc), NC_NOERR);
  nc_def_dim(nc, "y", 4, &dy);
  nc_def_dim(nc, "x", 5, &dx);
  const int dims[2] = {dy, dx};
  nc_def_var(nc, "elevation", NC_FLOAT, 2, dims, &v);
  nc_def_var(nc, "tid", NC_FLOAT, 2, dims, &v);
  nc_close(nc);
  EXPECT_TRUE(is_raster_input(dir.file("two.nc")));
  {
    const auto [cls, message] = failure(dem_params(dir.file("two.nc")));
    EXPECT_EQ(cls, ErrorClass::input);
    EXPECT_NE(message.find("holds several grids: give one as INPUT, NETCDF:\""), std::string::npos)
        << message;
  }
  write_file(dir.file("p.geojson"),
             R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},)"
             R"("geometry":{"type":"Polygon","coordinates":[[[0,0],[1,0],[1,1],[0,0]]]}}]})");
  EXPECT_FALSE(is_raster_input(dir.file("p.geojson")));
  EXPECT_FALSE(is_raster_input(dir.file("missing.tif")));
  write_file(dir.file("m.gr3"), "m\n1 3\n1 0 0 1\n2 1 0 1\n3 0 1 1\n1 3 1 2 3\n");
  EXPECT_FALSE(is_raster_input(dir.file("m.gr3")));
}

// Through the front end: a band of depths that reaches the raster's edge only between its
// corners is one annulus, with no piece at the corners to merge, and its boundary is
// open nowhere (it stays inside the raster).
TEST(RasterDomain, ABandOfDepthsThroughTheFrontEnd) {
  TempDir dir;
  FrontEndOptions o;
  o.read = dem_params(island_dem(dir));
  o.read.zmin = -20.0;
  o.read.zmax = -5.0;
  const FrontEndResult r = build_planar_domain(o);
  EXPECT_TRUE(r.summary.warnings.empty()) << r.summary.warnings.front();
  ASSERT_EQ(r.domain.polygons.size(), 1u);
  EXPECT_EQ(r.domain.polygons[0].holes.size(), 1u);
  EXPECT_NEAR(area(r.domain), kPi * (64e6 - 42.25e6), 0.02 * kPi * 21.75e6);
  EXPECT_EQ(r.summary.num_open_parts, 0u);
}
