#include "gis/raster_domain.h"

#include <gdal_alg.h>
#include <gdal_priv.h>
#include <ogr_geometry.h>
#include <ogrsf_frmts.h>

#include <sys/stat.h>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <vector>

#include "core/error.h"
#include "gis/gdal_env.h"
#include "gis/read_mesh.h"
#include "gis/rings_from_lines.h"

namespace isoquad {

namespace {

// Points per side of the raster's extent ring, so that it bends as it should once
// projected (as the bbox's).
constexpr int kExtentPointsPerSide = 64;

std::string fmt(double v) {
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

std::string range_text(const std::optional<double>& zmin, const std::optional<double>& zmax) {
  return "[" + (zmin ? fmt(*zmin) : std::string("-inf")) + ", " +
         (zmax ? fmt(*zmax) : std::string("inf")) + "]";
}

// The path for GDAL to open `path` with as a raster: an archive's grid inside it, else
// the path itself (a file, or GDAL's syntax: NETCDF:"gebco.nc":elevation).
std::string raster_open_path(const std::string& path) {
  std::string problem;
  const std::string open_path = gdal_path(path, ArchiveContent::raster, problem);
  return open_path.empty() ? path : open_path;
}

// A ring as an OGR polygon (closed).
OGRPolygon to_polygon(const Ring& ring) {
  OGRLinearRing r;
  for (const Point2& p : ring) r.addPoint(p.x, p.y);
  r.closeRings();
  OGRPolygon poly;
  poly.addRing(&r);
  return poly;
}

class RasterDomainReader {
 public:
  explicit RasterDomainReader(const ReadParams& p) : p_(p) {}

  SourceData read() {
    if (!p_.zmin && !p_.zmax)
      fail(ErrorClass::usage,
           "is a raster: give the values the domain covers, --zmax (a sea "
           "below it) and/or --zmin");
    if (p_.zmin && p_.zmax && !(*p_.zmin <= *p_.zmax))
      throw Error(ErrorClass::usage, "read", "--zmin must not be greater than --zmax");
    if ((p_.zmin && !std::isfinite(*p_.zmin)) || (p_.zmax && !std::isfinite(*p_.zmax)))
      throw Error(ErrorClass::usage, "read", "--zmin and --zmax must be finite numbers");
    open();
    area_ring();
    window();
    read_values();
    contours();
    return std::move(out_);
  }

 private:
  [[noreturn]] void fail(ErrorClass cls, const std::string& problem) const {
    throw Error(cls, "read", "'" + p_.path + "' " + problem);
  }

  void open() {
    ensure_gdal_registered();
    const std::string open_path = raster_open_path(p_.path);
    GdalErrorCapture capture;
    ds_.reset(static_cast<GDALDataset*>(GDALOpenEx(
        open_path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
    struct stat st {};
    if (!ds_ && stat(p_.path.c_str(), &st) != 0) fail(ErrorClass::input, "does not exist");
    if (!ds_)
      fail(ErrorClass::input, "cannot be read as a raster (" + capture.last_message() + ")");
    if (ds_->GetRasterCount() < 1) {
      // A netCDF file of several variables: GDAL names each grid as a data set of its own.
      std::string grids;
      if (char** sub = ds_->GetMetadata("SUBDATASETS"))
        for (int k = 0; sub[k]; ++k) {
          const std::string entry = sub[k];
          const std::size_t eq = entry.find("_NAME=");
          if (eq != std::string::npos) grids += (grids.empty() ? "" : ", ") + entry.substr(eq + 6);
        }
      fail(ErrorClass::input, grids.empty() ? std::string("has no raster band")
                                            : "holds several grids: give one as INPUT, " + grids);
    }
    if (ds_->GetGeoTransform(gt_) != CE_None)
      fail(ErrorClass::input, "has no georeferencing (geotransform)");
    if (!GDALInvGeoTransform(gt_, inverse_)) fail(ErrorClass::input, "has a singular geotransform");
    if (!p_.src_crs.empty()) {
      out_.crs = parse_crs(p_.src_crs, "--src-crs");
    } else if (const OGRSpatialReference* srs = ds_->GetSpatialRef()) {
      out_.crs = crs_from_srs(*srs);
    } else {
      // Its corners: longitudes and latitudes are the usual reason (a CF grid without
      // its grid mapping).
      const int w = ds_->GetRasterXSize(), h = ds_->GetRasterYSize();
      bool lonlat = true;
      for (const Point2& c : {georef(0, 0), georef(w, 0), georef(0, h), georef(w, h)})
        lonlat = lonlat && c.x >= -360 && c.x <= 360 && c.y >= -90.5 && c.y <= 90.5;
      fail(ErrorClass::crs, std::string("has no CRS: give it with --src-crs") +
                                (lonlat ? " (its corners look like longitudes and latitudes: "
                                          "--src-crs EPSG:4326)"
                                        : ""));
    }
    raster_.columns = ds_->GetRasterXSize();
    raster_.rows = ds_->GetRasterYSize();
    // A lon/lat grid whose columns go round the globe: an area across its seam (the
    // antimeridian of a grid from -180 to 180) reads the columns on both sides.
    global_ = out_.crs.geographic && gt_[2] == 0 && gt_[4] == 0 &&
              std::abs(360.0 / std::abs(gt_[1]) - raster_.columns) <= 0.5;
    raster_.zmin = p_.zmin;
    raster_.zmax = p_.zmax;
    out_.layer_name = "band 1";
  }

  Point2 georef(double column, double row) const {
    return {gt_[0] + column * gt_[1] + row * gt_[2], gt_[3] + column * gt_[4] + row * gt_[5]};
  }

  // The area read: the raster's extent (the cells' outer edges), or its part under
  // --bbox or --clip.
  void area_ring() {
    if (!p_.bbox && !p_.clip) {
      area_ = extent_ring(0, raster_.columns);
      return;
    }
    std::string what;
    const Ring ring = selection_area(p_, out_.crs, what);
    GdalErrorCapture capture;
    // A global grid's columns repeat every turn; the area meets another lon/lat grid
    // at the turn of its longitudes that overlaps it most (-178 on a grid from 0 to 360
    // is 182).
    const int w = raster_.columns;
    const OGRPolygon raster = to_polygon(global_ ? extent_ring(-w, 2 * w) : extent_ring(0, w));
    std::unique_ptr<OGRGeometry> common;
    for (double turn : out_.crs.geographic && !global_ ? std::vector<double>{0, -360, 360}
                                                       : std::vector<double>{0}) {
      Ring shifted = ring;
      for (Point2& q : shifted) q.x += turn;
      std::unique_ptr<OGRGeometry> part(to_polygon(shifted).Intersection(&raster));
      if (part && !part->IsEmpty() && (!common || area_of(*part) > area_of(*common)))
        common = std::move(part);
    }
    if (!common || common->IsEmpty()) fail(ErrorClass::input, "has no cell under " + what);
    const OGRPolygon* poly = dynamic_cast<const OGRPolygon*>(common.get());
    if (!poly || poly->getNumInteriorRings() > 0)
      fail(ErrorClass::input, "and " + what +
                                  " overlap in more than one piece: give an area "
                                  "that the raster covers, or one that covers it");
    const OGRLinearRing* r = poly->getExteriorRing();
    for (int i = 0; i + 1 < r->getNumPoints(); ++i) area_.push_back({r->getX(i), r->getY(i)});
    if (signed_area(area_) < 0) std::reverse(area_.begin(), area_.end());
    // An area reaching past the raster (or across a lon/lat grid's antimeridian, in the
    // grid's own longitudes) is meshed where the raster is: say so.
    const double share = std::abs(signed_area(area_)) / std::abs(signed_area(ring));
    if (share < 0.999)
      out_.warnings.push_back("'" + p_.path + "' covers " + fmt(std::round(1000 * share) / 10) +
                              "% of " + what + ": the domain is the part it covers");
  }

  // The raster's extent (the cells' outer edges) from column `first` to column `last`
  // (beyond the grid's columns: the turns of longitude before or after them).
  Ring extent_ring(int first, int last) const {
    const double h = raster_.rows;
    const Point2 corners[4] = {georef(first, 0), georef(last, 0), georef(last, h),
                               georef(first, h)};
    Ring extent;
    for (int s = 0; s < 4; ++s)
      for (int i = 0; i < kExtentPointsPerSide; ++i) {
        const double t = static_cast<double>(i) / kExtentPointsPerSide;
        const Point2 a = corners[s], b = corners[(s + 1) % 4];
        extent.push_back({a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)});
      }
    if (signed_area(extent) < 0) std::reverse(extent.begin(), extent.end());
    return extent;
  }

  static double area_of(const OGRGeometry& g) {
    const auto* surface = dynamic_cast<const OGRSurface*>(&g);
    return surface ? surface->get_Area() : 0.0;
  }

  // The cells under the area, and one more round them. On a grid round the globe the
  // columns may run past its last into its first (or before its first from its last).
  void window() {
    double i_lo = INFINITY, i_hi = -INFINITY, j_lo = INFINITY, j_hi = -INFINITY;
    for (const Point2& q : area_) {
      const double i = inverse_[0] + q.x * inverse_[1] + q.y * inverse_[2];
      const double j = inverse_[3] + q.x * inverse_[4] + q.y * inverse_[5];
      i_lo = std::min(i_lo, i), i_hi = std::max(i_hi, i);
      j_lo = std::min(j_lo, j), j_hi = std::max(j_hi, j);
    }
    auto clamp_to = [](double v, int size) {
      return static_cast<int>(std::clamp(v, 0.0, static_cast<double>(size)));
    };
    const int w = raster_.columns;
    int i0 = clamp_to(std::floor(i_lo) - 1, w);
    int i1 = clamp_to(std::ceil(i_hi) + 1, w);
    if (global_ && std::ceil(i_hi) - std::floor(i_lo) + 2 < w)
      i0 = static_cast<int>(std::floor(i_lo)) - 1, i1 = static_cast<int>(std::ceil(i_hi)) + 1;
    const int j0 = clamp_to(std::floor(j_lo) - 1, raster_.rows);
    const int j1 = clamp_to(std::ceil(j_hi) + 1, raster_.rows);
    window_ = {i0, j0, std::max(0, i1 - i0), std::max(0, j1 - j0)};
    if (window_[2] == 0 || window_[3] == 0) fail(ErrorClass::input, "has no cell in the area");
    const double cells = static_cast<double>(window_[2]) * window_[3];
    const double limit = static_cast<double>(std::max<std::size_t>(p_.max_raster_cells, 1));
    raster_.averaged = cells > limit ? static_cast<int>(std::ceil(std::sqrt(cells / limit))) : 1;
    // Across the seam, the columns up to it are whole blocks of the averaging: the
    // window starts a few columns further west.
    const int seam = (i0 >= 0 ? (i0 / w + 1) * w : -((-i0) / w) * w) - i0;
    if (seam < window_[2]) {
      const int more = (raster_.averaged - seam % raster_.averaged) % raster_.averaged;
      window_[0] -= more, window_[2] += more;
    }
    raster_.read_columns = (window_[2] + raster_.averaged - 1) / raster_.averaged;
    raster_.read_rows = (window_[3] + raster_.averaged - 1) / raster_.averaged;
    if (raster_.averaged > 1)
      out_.warnings.push_back(
          "'" + p_.path + "': " + std::to_string(window_[2]) + " x " + std::to_string(window_[3]) +
          " cells in the area, read as " + std::to_string(raster_.read_columns) + " x " +
          std::to_string(raster_.read_rows) + " (each the mean of " +
          std::to_string(raster_.averaged) + " x " + std::to_string(raster_.averaged) +
          "): the contour follows the coarser grid");
    // The geotransform of the cells read.
    const double sx = static_cast<double>(window_[2]) / raster_.read_columns;
    const double sy = static_cast<double>(window_[3]) / raster_.read_rows;
    const Point2 origin = georef(window_[0], window_[1]);
    read_gt_[0] = origin.x, read_gt_[1] = gt_[1] * sx, read_gt_[2] = gt_[2] * sy;
    read_gt_[3] = origin.y, read_gt_[4] = gt_[4] * sx, read_gt_[5] = gt_[5] * sy;
    // A cell's sides in metres: in lon/lat, at the area's mean latitude.
    double x_m = 1.0, y_m = 1.0;
    if (out_.crs.geographic) {
      double mean_lat = 0.0;
      for (const Point2& q : area_) mean_lat += q.y / static_cast<double>(area_.size());
      constexpr double kMetresPerDegree = 111195.0;  // on a sphere of 6,371 km
      x_m = kMetresPerDegree * std::cos(mean_lat * 3.14159265358979323846 / 180.0);
      y_m = kMetresPerDegree;
    } else {
      x_m = y_m = out_.crs.linear_unit_m;
    }
    raster_.cell_size_m = std::max(std::hypot(read_gt_[1] * x_m, read_gt_[4] * y_m),
                                   std::hypot(read_gt_[2] * x_m, read_gt_[5] * y_m));
  }

  // g = how far a value lies out of [zmin, zmax] (positive out, at most -kInside in),
  // on the cells read and a frame two cells wide round them: the first ring repeats the
  // nearest cell read, so that a contour that reaches the edge goes on straight across
  // it, and the second is in the range, so that every contour closes beyond the edge
  // (the area read cuts them there). Cells without a value are far out.
  void read_values() {
    GDALRasterBand* band = ds_->GetRasterBand(1);
    int has = 0, has_scale = 0, has_offset = 0;
    const double nodata = band->GetNoDataValue(&has);
    // Packed values (a netCDF variable's scale_factor and add_offset): in their units.
    const double scale = band->GetScale(&has_scale), offset = band->GetOffset(&has_offset);
    const int w = raster_.read_columns, h = raster_.read_rows;
    std::vector<double> values(static_cast<std::size_t>(w) * h);
    GDALRasterIOExtraArg extra;
    INIT_RASTERIO_EXTRA_ARG(extra);
    extra.eResampleAlg = raster_.averaged > 1 ? GRIORA_Average : GRIORA_NearestNeighbour;
    GdalErrorCapture capture;
    // A window across a global grid's seam is read in two parts, each whole blocks of the
    // averaging but the last.
    const int turn = raster_.columns;
    for (int first = window_[0]; first < window_[0] + window_[2];) {
      const int column = ((first % turn) + turn) % turn;
      const int columns = std::min(window_[0] + window_[2] - first, turn - column);
      const int offset = (first - window_[0]) / raster_.averaged;
      const int out_columns =
          first + columns == window_[0] + window_[2] ? w - offset : columns / raster_.averaged;
      if (band->RasterIO(GF_Read, column, window_[1], columns, window_[3], values.data() + offset,
                         out_columns, h, GDT_Float64, sizeof(double),
                         static_cast<GSpacing>(sizeof(double)) * w, &extra) != CE_None)
        fail(ErrorClass::input, "cannot be read (band 1: " + capture.last_message() + ")");
      first += columns;
    }
    padded_w_ = w + 2 * kFrame;
    padded_h_ = h + 2 * kFrame;
    g_.assign(static_cast<std::size_t>(padded_w_) * padded_h_, -kInside);
    raster_.value_min = INFINITY;
    raster_.value_max = -INFINITY;
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) {
        const double raw = values[static_cast<std::size_t>(j) * w + i];
        double& g = g_[static_cast<std::size_t>(j + kFrame) * padded_w_ + i + kFrame];
        if (!std::isfinite(raw) || (has && raw == nodata)) {
          g = kNoValue;
          continue;
        }
        const double v = raw * (has_scale ? scale : 1.0) + (has_offset ? offset : 0.0);
        ++raster_.num_valid_cells;
        raster_.value_min = std::min(raster_.value_min, v);
        raster_.value_max = std::max(raster_.value_max, v);
        g = -std::numeric_limits<double>::infinity();
        if (p_.zmax) g = std::max(g, v - *p_.zmax);
        if (p_.zmin) g = std::max(g, *p_.zmin - v);
        if (g <= 0.0) {
          g = std::min(g, -kInside);
          ++raster_.num_cells_in_range;
        }
      }
    for (int j = 1; j + 1 < padded_h_; ++j)
      for (int i = 1; i + 1 < padded_w_; ++i) {
        if (i >= kFrame && i < w + kFrame && j >= kFrame && j < h + kFrame) continue;
        const int ci = std::clamp(i, kFrame, w + kFrame - 1),
                  cj = std::clamp(j, kFrame, h + kFrame - 1);
        g_[static_cast<std::size_t>(j) * padded_w_ + i] =
            g_[static_cast<std::size_t>(cj) * padded_w_ + ci];
      }
    if (raster_.num_valid_cells == 0) fail(ErrorClass::input, "has no value in the area");
    if (raster_.num_cells_in_range == 0)
      fail(ErrorClass::input, "has no cell in " + range_text(p_.zmin, p_.zmax) +
                                  " in the area (its values there: " + fmt(raster_.value_min) +
                                  " to " + fmt(raster_.value_max) + ")");
  }

  // The contours of g = 0 as closed lines, nested into the polygons out of the range.
  void contours() {
    GdalErrorCapture capture;
    GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
    GDALDriver* memory = GetGDALDriverManager()->GetDriverByName("Memory");
    if (!mem || !memory)
      throw Error(ErrorClass::internal, "read", "GDAL's MEM and Memory drivers are missing");
    GdalDataset grid(mem->Create("", padded_w_, padded_h_, 1, GDT_Float64, nullptr));
    GdalDataset lines(memory->Create("", 0, 0, 0, GDT_Unknown, nullptr));
    if (!grid || !lines)
      throw Error(ErrorClass::internal, "read", "cannot create GDAL's in-memory data sets");
    // The frame's cells before the first cell read.
    double frame_gt[6] = {
        read_gt_[0] - kFrame * (read_gt_[1] + read_gt_[2]), read_gt_[1], read_gt_[2],
        read_gt_[3] - kFrame * (read_gt_[4] + read_gt_[5]), read_gt_[4], read_gt_[5]};
    grid->SetGeoTransform(frame_gt);
    GDALRasterBand* band = grid->GetRasterBand(1);
    if (band->RasterIO(GF_Write, 0, 0, padded_w_, padded_h_, g_.data(), padded_w_, padded_h_,
                       GDT_Float64, 0, 0) != CE_None)
      throw Error(ErrorClass::internal, "read", "cannot fill the in-memory grid");
    std::vector<double>().swap(g_);  // the grid holds it now
    OGRLayer* layer = lines->CreateLayer("contour", nullptr, wkbLineString, nullptr);
    OGRFieldDefn id("id", OFTInteger), level("level", OFTReal);
    if (!layer || layer->CreateField(&id) != OGRERR_NONE ||
        layer->CreateField(&level) != OGRERR_NONE)
      throw Error(ErrorClass::internal, "read", "cannot create the contours' layer");
    const char* options[] = {"FIXED_LEVELS=0", "ID_FIELD=0", "ELEV_FIELD=1", nullptr};
    if (GDALContourGenerateEx(GDALRasterBand::ToHandle(band), OGRLayer::ToHandle(layer),
                              const_cast<char**>(options), nullptr, nullptr) != CE_None)
      fail(ErrorClass::input, "cannot be contoured (" + capture.last_message() + ")");
    std::vector<SourceLine> source_lines;
    layer->ResetReading();
    for (auto& feature : *layer) {
      const OGRLineString* line = dynamic_cast<const OGRLineString*>(feature->GetGeometryRef());
      if (!line) continue;
      SourceLine s;
      s.fid = feature->GetFID();
      for (int i = 0; i < line->getNumPoints(); ++i)
        s.points.push_back({line->getX(i), line->getY(i)});
      source_lines.push_back(std::move(s));
    }
    LineRings rings;
    try {
      rings = rings_from_lines(source_lines, out_.crs.geographic ? "degrees" : "units");
    } catch (const LinesError& e) {
      throw Error(ErrorClass::internal, "read",
                  "the contours of '" + p_.path + "' do not close: " + e.what());
    }
    out_.polygons = std::move(rings.polygons);
    out_.num_features = out_.polygons.size();
    out_.bbox_ring = std::move(area_);
    out_.raster = raster_;
  }

  // In-range cells are at least this far inside (the contour of 0 never passes through
  // a cell centre); cells without a value this far out.
  static constexpr double kInside = 1e-6;
  static constexpr double kNoValue = 1e30;
  static constexpr int kFrame = 2;  // cells round the cells read

  const ReadParams& p_;
  SourceData out_;
  SourceData::Raster raster_;
  GdalDataset ds_;
  double gt_[6] = {}, inverse_[6] = {}, read_gt_[6] = {};
  Ring area_;
  std::array<int, 4> window_{};
  bool global_ = false;  // a lon/lat grid whose columns go round the globe
  int padded_w_ = 0, padded_h_ = 0;
  std::vector<double> g_;
};

}  // namespace

bool is_raster_input(const std::string& path) {
  if (path.empty() || is_mesh_file(path)) return false;
  ensure_gdal_registered();
  const std::string open_path = raster_open_path(path);
  // The raster drivers first: they turn a vector file down by its header, where opening
  // it as a vector could parse all of it (a GeoJSON).
  const auto lock = gdal_raster_lock();
  GdalErrorCapture capture;
  GdalDataset raster(static_cast<GDALDataset*>(
      GDALOpenEx(open_path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
  if (!raster) return false;
  // A netCDF file of several grids has no band of its own, but subdatasets.
  if (raster->GetRasterCount() == 0 && !raster->GetMetadata("SUBDATASETS")) return false;
  GdalDataset vector(static_cast<GDALDataset*>(
      GDALOpenEx(open_path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
  return !vector || vector->GetLayerCount() == 0;
}

SourceData read_raster_domain(const ReadParams& read) {
  const auto lock = gdal_raster_lock();
  return RasterDomainReader(read).read();
}

}  // namespace isoquad
