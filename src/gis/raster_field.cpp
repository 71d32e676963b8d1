#include "gis/raster_field.h"

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <sys/stat.h>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>

#include "core/error.h"
#include "gis/gdal_env.h"
#include "gis/mesh_field.h"
#include "gis/read_mesh.h"
#include "gis/sample_field.h"

namespace isoquad {

namespace {

[[noreturn]] void raster_error(const std::string& what, const std::string& path,
                               const std::string& problem) {
  throw Error(ErrorClass::input, "raster", what + " '" + path + "': " + problem);
}

// The dataset of `path`, checked: a readable raster with a band and a usable
// geotransform. `inverse`: the geotransform's inverse. Throws Error(input).
std::unique_ptr<GDALDataset> open_raster(const std::string& path, const std::string& what,
                                         double inverse[6]) {
  ensure_gdal_registered();
  auto fail = [&](const std::string& problem) { raster_error(what, path, problem); };
  struct stat st {};
  const bool named_source = is_data_source_name(path);  // a WCS, a PostGIS raster, a URL
  if (path.rfind("/vsi", 0) != 0 && !named_source && stat(path.c_str(), &st) != 0)
    fail("no such file");
  std::string problem;
  const std::string open_path =
      named_source ? path : gdal_path(path, ArchiveContent::raster, problem);
  if (open_path.empty()) fail(problem);
  GdalErrorCapture capture;
  std::unique_ptr<GDALDataset> ds(static_cast<GDALDataset*>(
      GDALOpenEx(open_path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
  if (!ds) {
    const bool depths = what == "--bathymetry" || what == "--elevation";
    fail(std::string(named_source ? "no such file, nor a raster GDAL opens by this name"
                                  : "cannot read as a raster") +
         (capture.last_message().empty() ? std::string() : " (" + capture.last_message() + ")") +
         (depths ? "; nor as a mesh (.gr3, .ll, .14, .2dm, .mesh, .msh, .slf, .nc) or as samples "
                   "(an .xyz, or a layer of points)"
                 : ""));
  }
  if (ds->GetRasterCount() < 1) fail("has no raster band");
  double gt[6];
  if (ds->GetGeoTransform(gt) != CE_None) fail("has no georeferencing (geotransform)");
  if (!GDALInvGeoTransform(gt, inverse)) fail("has a singular geotransform");
  return ds;
}

}  // namespace

void check_raster(const std::string& path, const std::string& what) {
  if (is_mesh_file(path)) return check_mesh_field(path, what);
  const auto lock = gdal_raster_lock();
  double inverse[6];
  open_raster(path, what, inverse);
}

void check_depth_source(const DepthRaster& source) {
  if (!is_mesh_file(source.path) && is_sample_file(source.path))
    return check_sample_file(source.path, source.option(), source.crs_if_none, source.field);
  check_raster(source.path, source.option());
}

RasterField::RasterField(const std::string& path, const std::string& what, const CrsInfo& query_crs,
                         const std::optional<std::array<double, 4>>& extent)
    : path_(path) {
  const auto lock = gdal_raster_lock();  // until the data set is closed
  const std::unique_ptr<GDALDataset> ds = open_raster(path, what, inverse_);
  GdalErrorCapture capture;
  width_ = ds->GetRasterXSize();
  height_ = ds->GetRasterYSize();
  const OGRSpatialReference* srs = ds->GetSpatialRef();
  double gt[6];
  ds->GetGeoTransform(gt);
  if (srs) {
    const CrsInfo raster_crs = crs_from_srs(*srs);
    to_raster_ = std::make_unique<CrsTransform>(query_crs, raster_crs);
    // Longitudes: a point east of the antimeridian comes back from PROJ at -179, which a
    // grid drawn from 0 to 360 holds at 181; a grid round the whole globe holds its
    // columns' neighbours across its seam.
    if (raster_crs.geographic && gt[2] == 0 && gt[4] == 0) {
      lon_turn_px_ = 360.0 * inverse_[1];
      global_ = std::abs(std::abs(lon_turn_px_) - width_) <= 0.5;
    }
  }
  window_ = {0, 0, width_, height_};
  for (const auto& [i, j] :
       {std::pair<int, int>{0, 0}, {width_, 0}, {0, height_}, {width_, height_}}) {
    const double x = gt[0] + i * gt[1] + j * gt[2], y = gt[3] + i * gt[4] + j * gt[5];
    extent_ = (i == 0 && j == 0)
                  ? std::array<double, 4>{x, y, x, y}
                  : std::array<double, 4>{std::min(extent_[0], x), std::min(extent_[1], y),
                                          std::max(extent_[2], x), std::max(extent_[3], y)};
  }
  if (extent) {
    // The pixels under a 33 x 33 lattice over the extent (its edges and inside: a pole or
    // a bend of the transform inside it counts), and round them as many as the lattice's
    // cells span (a point between lattice points is within a cell of one) plus two. On a
    // global grid the lattice's longitudes are taken the short way round from its first
    // point, and the window may run past the grid's seam.
    constexpr int kSteps = 32;
    std::vector<std::array<double, 2>> pixel((kSteps + 1) * (kSteps + 1), {NAN, NAN});
    double reference = global_ ? NAN : 0.5 * width_;
    for (int a = 0; a <= kSteps; ++a)
      for (int b = 0; b <= kSteps; ++b) {
        Point2 q{(*extent)[0] + ((*extent)[2] - (*extent)[0]) * a / kSteps,
                 (*extent)[1] + ((*extent)[3] - (*extent)[1]) * b / kSteps};
        if (to_raster_ && !to_raster_->transform(q)) continue;
        double px = inverse_[0] + q.x * inverse_[1] + q.y * inverse_[2];
        if (std::isnan(reference)) reference = px;
        px = nearest_turn(px, reference);
        pixel[a * (kSteps + 1) + b] = {px, inverse_[3] + q.x * inverse_[4] + q.y * inverse_[5]};
      }
    double i_lo = INFINITY, j_lo = INFINITY, i_hi = -INFINITY, j_hi = -INFINITY;
    double span_i = 0, span_j = 0;  // a lattice cell's width and height, in pixels
    for (int a = 0; a <= kSteps; ++a)
      for (int b = 0; b <= kSteps; ++b) {
        const auto& p = pixel[a * (kSteps + 1) + b];
        if (std::isnan(p[0])) continue;
        i_lo = std::min(i_lo, p[0]), i_hi = std::max(i_hi, p[0]);
        j_lo = std::min(j_lo, p[1]), j_hi = std::max(j_hi, p[1]);
        for (const auto& n : {a < kSteps ? pixel[(a + 1) * (kSteps + 1) + b] : p,
                              b < kSteps ? pixel[a * (kSteps + 1) + b + 1] : p})
          if (!std::isnan(n[0])) {
            span_i = std::max(span_i, std::abs(n[0] - p[0]));
            span_j = std::max(span_j, std::abs(n[1] - p[1]));
          }
      }
    auto clamp_to = [](double v, int size) {
      return static_cast<int>(std::clamp(v, 0.0, static_cast<double>(size)));
    };
    if (i_lo <= i_hi && j_lo <= j_hi) {
      const double margin_i = std::ceil(span_i) + 2, margin_j = std::ceil(span_j) + 2;
      int i0 = clamp_to(std::floor(i_lo) - margin_i, width_);
      int i1 = clamp_to(std::ceil(i_hi) + margin_i, width_);
      if (global_) {
        const double lo = std::floor(i_lo) - margin_i, hi = std::ceil(i_hi) + margin_i;
        if (hi - lo >= width_) {
          i0 = 0, i1 = width_;
        } else {  // the window's first column within the grid, the columns past its seam
          i0 = static_cast<int>(lo) - static_cast<int>(std::floor(lo / width_)) * width_;
          i1 = i0 + static_cast<int>(hi - lo);
        }
      }
      const int j0 = clamp_to(std::floor(j_lo) - margin_j, height_);
      const int j1 = clamp_to(std::ceil(j_hi) + margin_j, height_);
      window_ = {i0, j0, std::max(0, i1 - i0), std::max(0, j1 - j0)};
    } else {
      window_ = {0, 0, 0, 0};  // no point of the extent has a place in the raster's CRS
    }
  }
  GDALRasterBand* band = ds->GetRasterBand(1);
  int ok = 0;
  nodata_ = band->GetNoDataValue(&ok);
  has_nodata_ = ok != 0;
  values_.resize(static_cast<std::size_t>(window_[2]) * window_[3]);
  // A window past a global grid's seam is read in two parts, the columns from its first
  // to the grid's last, then from the grid's first on.
  for (int first = window_[0]; first < window_[0] + window_[2] && !values_.empty();) {
    const int column = first % width_,
              columns = std::min(window_[0] + window_[2] - first, width_ - column);
    if (band->RasterIO(GF_Read, column, window_[1], columns, window_[3],
                       values_.data() + (first - window_[0]), columns, window_[3], GDT_Float32,
                       sizeof(float), static_cast<GSpacing>(sizeof(float)) * window_[2]) != CE_None)
      raster_error(what, path, "cannot read band 1 (" + capture.last_message() + ")");
    first += columns;
  }
  // Packed values (a netCDF variable's scale_factor and add_offset): in their units.
  int has_scale = 0, has_offset = 0;
  const double scale = band->GetScale(&has_scale), offset = band->GetOffset(&has_offset);
  if ((has_scale && scale != 1.0) || (has_offset && offset != 0.0))
    for (float& v : values_) {
      if ((has_nodata_ && v == static_cast<float>(nodata_)) || std::isnan(v))
        v = std::numeric_limits<float>::quiet_NaN();
      else
        v = static_cast<float>(v * (has_scale ? scale : 1.0) + (has_offset ? offset : 0.0));
    }
}

RasterField::~RasterField() = default;

std::string RasterField::crs_hint() const {
  if (to_raster_) return "";
  std::ostringstream os;
  os.precision(8);
  os << "'" << path_ << "' has no CRS, so it is read in the meshing CRS";
  const bool lonlat = extent_[0] >= -360 && extent_[2] <= 360 && extent_[1] >= -90.5 &&
                      extent_[3] <= 90.5 && extent_[2] - extent_[0] <= 361;
  if (lonlat)
    os << ", but its extent (" << extent_[0] << " to " << extent_[2] << ", " << extent_[1] << " to "
       << extent_[3]
       << ") looks like longitudes and latitudes: give it its CRS (gdal_translate -a_srs "
          "EPSG:4326 IN OUT.tif)";
  return os.str();
}

double RasterField::nearest_turn(double px, double reference) const {
  if (lon_turn_px_ == 0 || std::isnan(reference)) return px;
  return px + lon_turn_px_ * std::round((reference - px) / lon_turn_px_);
}

bool RasterField::to_pixel(const Point2& p, double& px, double& py) const {
  Point2 q = p;
  if (to_raster_ && !to_raster_->transform(q)) return false;
  // Pixel centres are at half-integer pixel coordinates; these are shifted by half a
  // pixel, so that centres are at integers. A longitude is taken the turn nearest the
  // raster's columns (a global grid's are found past its seam, in cell()).
  px = inverse_[0] + q.x * inverse_[1] + q.y * inverse_[2] - 0.5;
  if (!global_) px = nearest_turn(px, 0.5 * width_);
  py = inverse_[3] + q.x * inverse_[4] + q.y * inverse_[5] - 0.5;
  return true;
}

double RasterField::cell(int i, int j) const {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  i -= window_[0];
  if (global_) i = ((i % width_) + width_) % width_;  // the column's place past the seam
  j -= window_[1];
  if (i < 0 || j < 0 || i >= window_[2] || j >= window_[3]) return nan;  // not read
  const double v = values_[static_cast<std::size_t>(j) * window_[2] + i];
  return (has_nodata_ && v == static_cast<float>(nodata_)) || std::isnan(v) ? nan : v;
}

double RasterField::sample(const Point2& p) const {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  double px = 0.0, py = 0.0;
  if (!to_pixel(p, px, py)) return nan;
  // Points on the raster's edge (a bbox that a download was cut to) come back from the
  // meshing CRS a little off it: a chord of a bbox's side that the simplification kept
  // whole lies up to its sagitta (170 m on a side of 100 km at 40 degrees) outside. Within
  // half a pixel of the edge, a point takes the edge's value. A global grid's columns
  // have no edge: its last one's neighbour is its first.
  constexpr double kEdgeSlack = 0.5;
  if (!((global_ || (px >= -0.5 - kEdgeSlack && px <= width_ - 0.5 + kEdgeSlack)) &&
        py >= -0.5 - kEdgeSlack && py <= height_ - 0.5 + kEdgeSlack))
    return nan;
  const int i0 = global_ ? static_cast<int>(std::floor(px))
                         : std::clamp(static_cast<int>(std::floor(px)), 0, std::max(0, width_ - 2));
  const int j0 = std::clamp(static_cast<int>(std::floor(py)), 0, std::max(0, height_ - 2));
  const int i1 = global_ ? i0 + 1 : std::min(i0 + 1, width_ - 1);
  const int j1 = std::min(j0 + 1, height_ - 1);
  const double tx = std::clamp(px - i0, 0.0, 1.0), ty = std::clamp(py - j0, 0.0, 1.0);
  return (1 - ty) * ((1 - tx) * cell(i0, j0) + tx * cell(i1, j0)) +
         ty * ((1 - tx) * cell(i0, j1) + tx * cell(i1, j1));
}

double RasterField::mean_over(const Point2& p, double half_width) const {
  // Only where the point has a value, as sample() gives it: a point off this raster
  // whose square reaches it is left to the next raster (or to its neighbours).
  const double at_p = sample(p);
  double cx = 0.0, cy = 0.0;
  if (std::isnan(at_p) || !to_pixel(p, cx, cy)) return at_p;
  // The square's corners in pixels; the cells whose centres lie in their bounding box.
  double lo_x = INFINITY, lo_y = INFINITY, hi_x = -INFINITY, hi_y = -INFINITY;
  for (const auto& [sx, sy] : {std::pair<int, int>{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
    double px = 0.0, py = 0.0;
    if (!to_pixel({p.x + sx * half_width, p.y + sy * half_width}, px, py)) return at_p;
    px = nearest_turn(px, cx);  // a global grid's box across its seam stays whole
    lo_x = std::min(lo_x, px), hi_x = std::max(hi_x, px);
    lo_y = std::min(lo_y, py), hi_y = std::max(hi_y, py);
  }
  const int i0 = static_cast<int>(std::ceil(lo_x)), i1 = static_cast<int>(std::floor(hi_x));
  const int j0 = std::max(0, static_cast<int>(std::ceil(lo_y)));
  const int j1 = std::min(height_ - 1, static_cast<int>(std::floor(hi_y)));
  // A raster no finer than the square: its bilinear value.
  if (i1 - i0 < 1 || j1 - j0 < 1) return at_p;
  double sum = 0.0;
  std::size_t count = 0;
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      const double v = cell(i, j);
      if (std::isnan(v)) continue;
      sum += v;
      ++count;
    }
  return count > 0 ? sum / static_cast<double>(count) : std::numeric_limits<double>::quiet_NaN();
}

RasterStack::RasterStack(const std::vector<DepthRaster>& rasters, const CrsInfo& query_crs,
                         const std::optional<std::array<double, 4>>& extent,
                         const RasterStack* share)
    : sources_(rasters), query_wkt_(query_crs.wkt) {
  auto shared = [&](const DepthRaster& r) -> std::shared_ptr<const PointField> {
    if (!share || share->query_wkt_ != query_wkt_) return nullptr;
    for (std::size_t i = 0; i < share->sources_.size(); ++i) {
      const DepthRaster& s = share->sources_[i];
      if (s.path == r.path && s.elevation == r.elevation && s.crs_if_none == r.crs_if_none &&
          s.field == r.field)
        return share->rasters_[i];
    }
    return nullptr;
  };
  for (const DepthRaster& r : rasters) {
    if (is_mesh_file(r.path)) {
      std::shared_ptr<const PointField> field = shared(r);
      if (!field)
        field = std::make_shared<MeshNodeField>(r.path, r.option(), query_crs, r.crs_if_none,
                                                MeshNodeField::Values::nodes, extent);
      rasters_.push_back(std::move(field));
    } else if (is_sample_file(r.path)) {
      std::shared_ptr<const PointField> field = shared(r);
      if (!field)
        field = std::make_shared<SampleField>(r.path, r.option(), query_crs, r.crs_if_none, r.field,
                                              extent);
      rasters_.push_back(std::move(field));
    } else {
      rasters_.push_back(std::make_shared<RasterField>(r.path, r.option(), query_crs, extent));
    }
  }
}

bool RasterStack::has_shareable() const {
  return std::any_of(sources_.begin(), sources_.end(), [](const DepthRaster& r) {
    return is_mesh_file(r.path) || is_sample_file(r.path);
  });
}

RasterStack::~RasterStack() = default;

double RasterStack::sample(const Point2& p) const {
  return mean_over(p, 0.0);
}

double RasterStack::mean_over(const Point2& p, double half_width) const {
  for (std::size_t i = 0; i < rasters_.size(); ++i) {
    const double v =
        half_width > 0 ? rasters_[i]->mean_over(p, half_width) : rasters_[i]->sample(p);
    if (!std::isnan(v)) return sources_[i].elevation ? -v : v;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

std::string RasterStack::crs_hints() const {
  std::string text;
  for (const auto& r : rasters_) {
    const std::string hint = r->crs_hint();
    if (!hint.empty()) text += "; " + hint;
  }
  return text;
}

std::string RasterStack::kept_text() const {
  std::string text;
  for (std::size_t i = 0; i < rasters_.size(); ++i) {
    const std::string kept = rasters_[i]->kept_text();
    if (!kept.empty())
      text += (text.empty() ? "" : "; ") +
              std::filesystem::path(sources_[i].path).filename().string() + ": " + kept;
  }
  return text;
}

std::string RasterStack::paths_text() const {
  std::string text;
  for (const DepthRaster& r : sources_)
    text += (text.empty() ? "" : ", ") + std::string(r.option()) + " '" + r.path + "'";
  return text;
}

}  // namespace isoquad
