// CGAL's Delaunay triangulation of the samples; everything else on flat arrays.
#include "gis/sample_field.h"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <gdal_priv.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <numeric>
#include <utility>

#include "core/error.h"
#include "core/text.h"
#include "gis/atomic_output.h"
#include "gis/gdal_env.h"
#include "gis/mesh_field.h"
#include "gis/read_points.h"

namespace isoquad {

namespace {

const char* const kStage = "raster";

[[noreturn]] void fail(ErrorClass cls, const std::string& what, const std::string& path,
                       const std::string& problem) {
  throw Error(cls, kStage, what + " '" + path + "': " + problem);
}

bool is_xyz(const std::string& path) {
  return ends_with(lower_case(path), ".xyz");
}

bool opens_as_raster(const std::string& path) {
  ensure_gdal_registered();
  std::string problem;
  const std::string open_path = gdal_path(path, ArchiveContent::raster, problem);
  if (open_path.empty()) return false;
  const auto lock = gdal_raster_lock();
  GdalErrorCapture capture;
  GdalDataset ds(static_cast<GDALDataset*>(
      GDALOpenEx(open_path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
  return ds && ds->GetRasterCount() > 0;
}

// The samples as read, in the file's CRS (`crs`: its text, empty when it has none).
struct RawSamples {
  std::vector<Point2> points;
  std::vector<double> values;
  std::string crs;
};

// The numbers of one line of an .xyz (up to the first three), or how many it had.
int parse_xyz_line(const std::string& line, double out[3]) {
  int n = 0;
  const char* p = line.data();
  const char* end = p + line.size();
  auto separator = [](char c) {
    return c == ' ' || c == '\t' || c == ',' || c == ';' || c == '\r';
  };
  while (p < end && n < 3) {
    while (p < end && separator(*p)) ++p;
    if (p == end) break;
    if (*p == '+') ++p;  // from_chars takes no plus sign
    const auto [next, ec] = std::from_chars(p, end, out[n]);
    if (ec != std::errc() || (next < end && !separator(*next))) return -1;
    p = next;
    ++n;
  }
  return n;
}

bool is_comment(const std::string& line) {
  const std::size_t i = line.find_first_not_of(" \t\r");
  if (i == std::string::npos) return true;  // blank
  const char c = line[i];
  return c == '#' || c == '*' || c == '%' || c == '!' ||
         (c == '/' && i + 1 < line.size() && line[i + 1] == '/');
}

// `max_samples`: stop after that many (the check before a long job).
RawSamples read_xyz(const std::string& path, const std::string& what, std::size_t max_samples) {
  note_input_file(path);  // no output may replace it
  std::ifstream in(path);
  if (!in) fail(ErrorClass::input, what, path, "cannot be opened");
  RawSamples out;
  std::string line;
  std::size_t number = 0;
  bool header_allowed = true;
  while (out.points.size() < max_samples && std::getline(in, line)) {
    ++number;
    if (is_comment(line)) continue;
    double v[3];
    const int n = parse_xyz_line(line, v);
    if (n < 3) {
      if (header_allowed) {  // column names before the first sample
        header_allowed = false;
        continue;
      }
      fail(ErrorClass::input, what, path,
           "line " + std::to_string(number) + " is not a sample (x y value): '" +
               line.substr(0, 80) + "'");
    }
    header_allowed = false;
    if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2])) continue;
    out.points.push_back({v[0], v[1]});
    out.values.push_back(v[2]);
  }
  if (in.bad()) fail(ErrorClass::input, what, path, "cannot be read");
  return out;
}

RawSamples read_points(const std::string& path, const std::string& what, const std::string& field,
                       std::size_t max_samples) {
  PointLayer layer = read_point_layer(path, what, true, field, "--depth-field", max_samples);
  // As an .xyz's line that is not three numbers: an error, not a sounding left out.
  if (layer.num_without_point > 0)
    fail(ErrorClass::input, what, path,
         "has " + std::to_string(layer.num_without_point) +
             " feature(s) without a point, the first feature " +
             std::to_string(layer.first_without_point) +
             " (coordinates that are not numbers, or empty)" +
             (layer.gdal_message.empty() ? "" : ": " + layer.gdal_message));
  return {std::move(layer.points), std::move(layer.values), std::move(layer.crs)};
}

RawSamples read_samples(const std::string& path, const std::string& what, const std::string& field,
                        std::size_t max_samples = std::numeric_limits<std::size_t>::max()) {
  // An .xyz's values are its third column, whatever --depth-field names for the points
  // of other files.
  if (is_xyz(path)) return read_xyz(path, what, max_samples);
  return read_points(path, what, field, max_samples);
}

// The CRS the samples are in: the file's, else crs_if_none. Error(crs) without either.
CrsInfo samples_crs(const RawSamples& raw, const std::string& path, const std::string& what,
                    const std::string& crs_if_none) {
  if (!raw.crs.empty()) return parse_crs(raw.crs, what + " '" + path + "' (its CRS)");
  if (crs_if_none.empty())
    fail(ErrorClass::crs, what, path,
         "does not say its CRS: give it with --depth-crs (or --src-crs)");
  return parse_crs(crs_if_none, "--depth-crs");
}

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb>;
using Delaunay = CGAL::Delaunay_triangulation_2<K, Tds>;

// The Delaunay triangles of distinct points (counter-clockwise); empty when they are all
// on one line.
std::vector<std::array<int, 3>> delaunay_triangles(const std::vector<Point2>& points) {
  std::vector<std::pair<K::Point_2, int>> input;
  input.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    input.emplace_back(K::Point_2(points[i].x, points[i].y), static_cast<int>(i));
  Delaunay dt;
  dt.insert(input.begin(), input.end());
  std::vector<std::array<int, 3>> triangles;
  if (dt.dimension() < 2) return triangles;
  triangles.reserve(dt.number_of_faces());
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f)
    triangles.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
  // CGAL's face order follows its memory; sorted, the same on every run.
  std::sort(triangles.begin(), triangles.end());
  return triangles;
}

}  // namespace

bool is_sample_file(const std::string& path) {
  if (opens_as_raster(path)) return false;
  if (is_xyz(path)) return true;
  return has_point_layer(path);  // else left to the raster reader's message
}

void check_sample_file(const std::string& path, const std::string& what,
                       const std::string& crs_if_none, const std::string& field) {
  const RawSamples raw = read_samples(path, what, field, 1000);
  if (raw.points.empty()) fail(ErrorClass::input, what, path, "holds no sample");
  samples_crs(raw, path, what, crs_if_none);
}

SampleField::SampleField(const std::string& path, const std::string& what, const CrsInfo& query_crs,
                         const std::string& crs_if_none, const std::string& field,
                         const std::optional<std::array<double, 4>>& extent) {
  RawSamples raw = read_samples(path, what, field);
  num_read_ = raw.points.size();
  const CrsTransform transform(samples_crs(raw, path, what, crs_if_none), query_crs);
  const long failed = transform.transform(raw.points);
  if (failed >= 0)
    fail(ErrorClass::crs, what, path,
         "sample " + std::to_string(failed + 1) + " " + format_point(raw.points[failed]) +
             " cannot be transformed into the meshing CRS");
  if (extent) {
    const auto& e = *extent;
    const double margin = 0.25 * std::max(e[2] - e[0], e[3] - e[1]);
    std::size_t kept = 0;
    for (std::size_t i = 0; i < raw.points.size(); ++i) {
      const Point2& p = raw.points[i];
      if (p.x < e[0] - margin || p.x > e[2] + margin || p.y < e[1] - margin || p.y > e[3] + margin)
        continue;
      raw.points[kept] = p;
      raw.values[kept++] = raw.values[i];
    }
    dropped_ = kept < raw.points.size();
    raw.points.resize(kept);
    raw.values.resize(kept);
    if (dropped_ && kept < 3) return;  // none near: NaN everywhere
  }
  // Samples at the same point (a survey's repeated soundings) merged into their mean, in
  // the order of their coordinates.
  std::vector<Point2> points;
  std::vector<double> values;
  std::vector<std::size_t> order(raw.points.size());
  std::iota(order.begin(), order.end(), 0);
  auto less = [&](std::size_t a, std::size_t b) {
    const Point2 &p = raw.points[a], &q = raw.points[b];
    return p.x != q.x ? p.x < q.x : p.y != q.y ? p.y < q.y : a < b;
  };
  std::sort(order.begin(), order.end(), less);
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i;
    double sum = 0.0;
    while (j < order.size() && raw.points[order[j]] == raw.points[order[i]])
      sum += raw.values[order[j++]];
    points.push_back(raw.points[order[i]]);
    values.push_back(sum / static_cast<double>(j - i));
    i = j;
  }
  raw = RawSamples();  // freed before the triangulation, the peak of a large survey
  std::vector<std::size_t>().swap(order);
  std::vector<std::array<int, 3>> triangles = delaunay_triangles(points);
  if (triangles.empty())
    fail(ErrorClass::input, what, path,
         std::to_string(points.size()) +
             " distinct sample(s): a surface through them needs three or more not all on one "
             "line");
  size_ = points.size();
  triangles_ =
      std::make_unique<MeshNodeField>(std::move(points), std::move(values), std::move(triangles));
}

SampleField::~SampleField() = default;

std::string SampleField::kept_text() const {
  if (!dropped_) return "";
  return std::to_string(size_) + " of its " + std::to_string(num_read_) +
         " samples, those round the domain";
}

double SampleField::sample(const Point2& p) const {
  return triangles_ ? triangles_->sample(p) : std::numeric_limits<double>::quiet_NaN();
}

double SampleField::mean_over(const Point2& p, double half_width) const {
  return triangles_ ? triangles_->mean_over(p, half_width)
                    : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace isoquad
