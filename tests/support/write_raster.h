// Test rasters: a GeoTIFF of values given by a function of the pixel centres.
#pragma once

#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "gis/gdal_env.h"

namespace isoquad::test {

// nx x ny square pixels `pixel` wide from (x0, y1) right and down, in EPSG `epsg` (0: no
// CRS, so read in the query CRS), value(x, y) at each pixel centre; NaN values are
// written as the band's nodata, -9999. Returns `path`.
inline std::string write_geotiff(const std::string& path, double x0, double y1, double pixel,
                                 int nx, int ny, int epsg,
                                 const std::function<double(double, double)>& value) {
  ensure_gdal_registered();
  GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GTiff");
  GDALDataset* ds = drv->Create(path.c_str(), nx, ny, 1, GDT_Float32, nullptr);
  double gt[6] = {x0, pixel, 0, y1, 0, -pixel};
  ds->SetGeoTransform(gt);
  if (epsg != 0) {
    OGRSpatialReference srs;
    srs.importFromEPSG(epsg);
    ds->SetSpatialRef(&srs);
  }
  std::vector<float> v(static_cast<std::size_t>(nx) * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double d = value(x0 + (i + 0.5) * pixel, y1 - (j + 0.5) * pixel);
      v[static_cast<std::size_t>(j) * nx + i] = std::isnan(d) ? -9999.0f : static_cast<float>(d);
    }
  GDALRasterBand* band = ds->GetRasterBand(1);
  band->SetNoDataValue(-9999);
  EXPECT_EQ(band->RasterIO(GF_Write, 0, 0, nx, ny, v.data(), nx, ny, GDT_Float32, 0, 0), CE_None);
  GDALClose(ds);
  return path;
}

// nx x ny Int16 pixels `pixel` wide from (x0, y1) in UTM 31N, packed as netCDF packs
// values: value = raw * 0.1 - 100 (GDAL's band scale and offset), -32768 the nodata.
// `raw` holds the rows from the north. Returns `path`.
inline std::string write_packed_geotiff(const std::string& path, double x0, double y1, double pixel,
                                        int nx, int ny, std::vector<std::int16_t> raw) {
  ensure_gdal_registered();
  GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GTiff");
  GDALDataset* ds = drv->Create(path.c_str(), nx, ny, 1, GDT_Int16, nullptr);
  double gt[6] = {x0, pixel, 0, y1, 0, -pixel};
  ds->SetGeoTransform(gt);
  OGRSpatialReference srs;
  srs.importFromEPSG(32631);
  ds->SetSpatialRef(&srs);
  GDALRasterBand* band = ds->GetRasterBand(1);
  band->SetScale(0.1);
  band->SetOffset(-100.0);
  band->SetNoDataValue(-32768);
  EXPECT_EQ(band->RasterIO(GF_Write, 0, 0, nx, ny, raw.data(), nx, ny, GDT_Int16, 0, 0), CE_None);
  GDALClose(ds);
  return path;
}

}  // namespace isoquad::test
