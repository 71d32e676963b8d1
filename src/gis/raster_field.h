// A single-band GDAL raster held in memory and sampled bilinearly at points given in
// another CRS (the meshing CRS). Used for size, angle and depth rasters.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/geometry.h"
#include "gis/crs.h"

namespace isoquad {

// Values at points of a query CRS, NaN where there is none: a raster (RasterField) or a
// mesh's node values (MeshNodeField).
class PointField {
 public:
  virtual ~PointField() = default;
  virtual double sample(const Point2& p) const = 0;
  // The mean value over the square of half-width `half_width` round p (query CRS
  // units), where the field is finer than that square; else sample(p). NaN: none.
  virtual double mean_over(const Point2& p, double /*half_width*/) const { return sample(p); }
  // Why no point may have found a value, when the field can tell (a raster without a
  // CRS whose extent looks like longitudes and latitudes); empty otherwise.
  virtual std::string crs_hint() const { return ""; }
  // How much of the source was kept round the extent it was read for, where some was
  // left out ("412 of its 3000 samples"); empty otherwise.
  virtual std::string kept_text() const { return ""; }
};

class RasterField : public PointField {
 public:
  // Reads band 1 of `path`. `what` names the option in messages (e.g. "--size-raster").
  // `query_crs` is the CRS of the points passed to sample(). A raster without a CRS is
  // taken to be in `query_crs`. With `extent` ({xmin, ymin, xmax, ymax} in the query
  // CRS), only the pixels under it are read (with a margin): a continental or
  // global grid costs the domain's part of it; sample() gives NaN off that part. Throws
  // Error(input) or Error(crs).
  RasterField(const std::string& path, const std::string& what, const CrsInfo& query_crs,
              const std::optional<std::array<double, 4>>& extent = std::nullopt);
  ~RasterField() override;
  RasterField(const RasterField&) = delete;
  RasterField& operator=(const RasterField&) = delete;

  // Bilinear value at p (query CRS); NaN outside the raster or where a neighbouring
  // pixel is nodata.
  double sample(const Point2& p) const override;
  // The mean of the cells with a value whose centres lie in the square (in the raster's
  // pixels, the bounding box of its corners), where sample(p) is not NaN; sample(p)
  // when the square spans fewer than two cells' centres either way.
  double mean_over(const Point2& p, double half_width) const override;
  std::string crs_hint() const override;

  const std::string& path() const { return path_; }
  int width() const { return width_; }
  int height() const { return height_; }
  // The pixels read: {first column, first row, columns, rows}; on a grid round the
  // globe the columns may run past its last into its first.
  const std::array<int, 4>& window() const { return window_; }

 private:
  std::string path_;
  int width_ = 0, height_ = 0;
  std::array<int, 4> window_{0, 0, 0, 0};
  double inverse_[6] = {};  // georeferenced -> pixel/line
  std::vector<float> values_;
  bool has_nodata_ = false;
  double nodata_ = 0.0;
  std::unique_ptr<CrsTransform> to_raster_;
  std::array<double, 4> extent_{};  // xmin, ymin, xmax, ymax of the whole raster, its units
  // A geographic raster's 360 degrees of longitude in pixels (signed; 0 otherwise), and
  // whether its columns go round the globe.
  double lon_turn_px_ = 0.0;
  bool global_ = false;
  // `px` moved by whole turns of longitude to the nearest `reference` (pixel columns).
  double nearest_turn(double px, double reference) const;
  // p (query CRS) in pixels, cell centres at integers; false when it cannot be
  // transformed.
  bool to_pixel(const Point2& p, double& px, double& py) const;
  // The value of cell (i, j) (a global grid's columns taken round its seam); NaN where
  // it has none or was not read.
  double cell(int i, int j) const;
};

// A raster of depths (metres, positive down: --bathymetry) or of elevations (positive
// up, as GEBCO, EMODnet and SRTM15+ give them: --elevation), read as depths.
struct DepthRaster {
  DepthRaster() = default;
  DepthRaster(std::string path_, bool elevation_ = false)
      : path(std::move(path_)), elevation(elevation_) {}
  std::string path;
  bool elevation = false;
  // The CRS of a file that does not say its own (--depth-crs, else --src-crs): a mesh (a
  // .gr3, .14, .2dm; empty: the query CRS, as for a raster without one) or samples (an
  // .xyz; empty: an error).
  std::string crs_if_none;
  // The attribute of a vector layer of samples that holds their values (--depth-field;
  // empty: the points' Z); grids and meshes ignore it.
  std::string field;
  const char* option() const { return elevation ? "--elevation" : "--bathymetry"; }
};

// Depth rasters in priority order (a harbour survey, then a regional grid, then a global
// one): at a point, the first with a value there gives it. A mesh file among them
// (is_mesh_file: a model's hgrid.gr3) gives its nodes' values (MeshNodeField), scattered
// samples (is_sample_file: soundings) their triangles' (SampleField). Throws as
// RasterField, MeshNodeField and SampleField.
class RasterStack {
 public:
  // With `share`, each source of scattered samples or mesh that `share` has too (the same
  // file, options and query CRS) takes its field from it rather than reading (and
  // triangulating) it again: the sizes' depths, then the outputs'. Grids are read again,
  // a window each.
  RasterStack(const std::vector<DepthRaster>& rasters, const CrsInfo& query_crs,
              const std::optional<std::array<double, 4>>& extent = std::nullopt,
              const RasterStack* share = nullptr);
  ~RasterStack();
  RasterStack(const RasterStack&) = delete;
  RasterStack& operator=(const RasterStack&) = delete;

  // The first raster's depth at p that is not NaN; NaN where none has one.
  double sample(const Point2& p) const;
  // The same with each raster's mean over the square of half-width `half_width` round p
  // (PointField::mean_over); 0: sample(p).
  double mean_over(const Point2& p, double half_width) const;

  std::size_t size() const { return rasters_.size(); }
  // Whether a source is scattered samples (is_sample_file, a triangulation) or a mesh
  // (is_mesh_file, a whole file read): those `share` takes.
  bool has_shareable() const;
  // The field of source i.
  const PointField& field(std::size_t i) const { return *rasters_[i]; }
  // --bathymetry 'a.tif', --elevation 'b.tif' (for messages).
  std::string paths_text() const;
  // The rasters' crs_hint()s, for a message that none gave a value.
  std::string crs_hints() const;
  // The sources' kept_text()s, each after its file's name; empty when all were kept.
  std::string kept_text() const;

 private:
  std::vector<std::shared_ptr<const PointField>> rasters_;
  std::vector<DepthRaster> sources_;
  std::string query_wkt_;
};

// Opens `path` as RasterField would, without reading its values (a mesh file: reads it
// as MeshNodeField would): the errors (Error input) before a long job rather than after
// it.
void check_raster(const std::string& path, const std::string& what);
// The same for a depth source of RasterStack, samples included (check_sample_file).
void check_depth_source(const DepthRaster& source);

}  // namespace isoquad
