// Scattered samples as a depth source: a survey's soundings (SMS's scatter sets, D-Flow
// FM's .xyz samples) given as --bathymetry or --elevation beside grids and meshes.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry.h"
#include "gis/crs.h"
#include "gis/raster_field.h"

namespace isoquad {

class MeshNodeField;

// Whether `path` holds samples rather than a grid: a text file of x y z lines (.xyz) that
// GDAL cannot read as a grid, or a vector data set with a layer of points (and no raster).
bool is_sample_file(const std::string& path);

// The samples' values, linear over their Delaunay triangles (duplicate points averaged);
// NaN off their convex hull (beyond about a triangle's size, as MeshNodeField), so that
// the next source in the priority list gives the depth there.
//
// An .xyz holds a sample a line: x, y and the value, separated by spaces, tabs, commas
// or semicolons (more columns are ignored); blank lines, lines starting with #, *, %, !
// or //, and a header line before the first sample are skipped. A vector layer (the
// first with points) gives each point's Z, or with `field` that attribute (points where
// it is not set are skipped); a CSV's points are its columns named x, lon, longitude,
// easting or east and y, lat, latitude, northing or north (any case). Points are read in
// the file's CRS, else `crs_if_none`.
class SampleField : public PointField {
 public:
  // `what` names the option in messages (e.g. "--bathymetry"). Throws Error(input) for a
  // file that cannot be read, a malformed line, points without values or fewer than three
  // samples not in one line; Error(usage) for a missing `field`; Error(crs) without a CRS
  // or for samples that cannot be transformed into `query_crs`.
  // With `extent` ({xmin, ymin, xmax, ymax} in the query CRS), only the samples within a
  // quarter of its larger side of it are kept (a national survey, a bay meshed): the
  // triangles over the extent are those of the samples round it. None there: NaN
  // everywhere, for the next source.
  SampleField(const std::string& path, const std::string& what, const CrsInfo& query_crs,
              const std::string& crs_if_none, const std::string& field,
              const std::optional<std::array<double, 4>>& extent = std::nullopt);
  ~SampleField() override;
  SampleField(const SampleField&) = delete;
  SampleField& operator=(const SampleField&) = delete;

  double sample(const Point2& p) const override;
  // MeshNodeField::mean_over on the samples.
  double mean_over(const Point2& p, double half_width) const override;
  std::string kept_text() const override;
  std::size_t size() const { return size_; }          // distinct samples kept
  std::size_t num_read() const { return num_read_; }  // samples read

 private:
  std::size_t size_ = 0, num_read_ = 0;
  bool dropped_ = false;                      // samples far from the extent left out
  std::unique_ptr<MeshNodeField> triangles_;  // in the query CRS; null: no sample near
};

// Opens the samples as SampleField would (the file, its points and `field`, its CRS)
// without reading them all: the errors before a long job rather than after it.
void check_sample_file(const std::string& path, const std::string& what,
                       const std::string& crs_if_none, const std::string& field);

}  // namespace isoquad
