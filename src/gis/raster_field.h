// A single-band GDAL raster held in memory and sampled bilinearly at points given in
// another CRS (the meshing CRS). Used for size, angle and depth rasters.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/geometry.h"
#include "gis/crs.h"

namespace isoquad {

class RasterField {
 public:
  // Reads band 1 of `path`. `what` names the option in messages (e.g. "--size-raster").
  // `query_crs` is the CRS of the points passed to sample(). A raster without a CRS is
  // taken to be in `query_crs`. Throws Error(input) or Error(crs).
  RasterField(const std::string& path, const std::string& what, const CrsInfo& query_crs);
  ~RasterField();
  RasterField(const RasterField&) = delete;
  RasterField& operator=(const RasterField&) = delete;

  // Bilinear value at p (query CRS); NaN outside the raster or where a neighbouring
  // pixel is nodata.
  double sample(const Point2& p) const;

  const std::string& path() const { return path_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  std::string path_;
  int width_ = 0, height_ = 0;
  double inverse_[6] = {};  // georeferenced -> pixel/line
  std::vector<float> values_;
  bool has_nodata_ = false;
  double nodata_ = 0.0;
  std::unique_ptr<CrsTransform> to_raster_;
};

}  // namespace isoquad
