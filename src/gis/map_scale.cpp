#include "gis/map_scale.h"

#include <GeographicLib/Geodesic.hpp>

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace isoquad {

MapScale::MapScale(const CrsInfo& crs, const std::array<double, 4>& box, int cells)
    : box_(box), n_(std::max(1, cells) + 1) {
  const double width = std::max(box[2] - box[0], 1.0), height = std::max(box[3] - box[1], 1.0);
  dx_ = width / (n_ - 1);
  dy_ = height / (n_ - 1);
  // Steps short against the changes of the scale (a thousandth of a cell) and long against
  // the coordinates' rounding.
  const double step = std::max(1.0, 1e-3 * std::min(dx_, dy_));

  // Each node and its two steps, transformed at once.
  std::vector<Point2> points;
  points.reserve(3 * n_ * n_);
  for (int j = 0; j < n_; ++j)
    for (int i = 0; i < n_; ++i) {
      const Point2 p{box[0] + i * dx_, box[1] + j * dy_};
      points.push_back(p);
      points.push_back({p.x + step, p.y});
      points.push_back({p.x, p.y + step});
    }
  const CrsTransform to_lonlat(crs, geographic_base(crs));
  std::vector<char> valid(points.size(), 0);
  {
    // Transformed one by one where the batch fails, so that one point outside the
    // projection's domain costs only its own node.
    std::vector<Point2> batch = points;
    if (to_lonlat.transform(batch) < 0) {
      points = std::move(batch);
      std::fill(valid.begin(), valid.end(), 1);
    } else {
      for (std::size_t i = 0; i < points.size(); ++i) valid[i] = to_lonlat.transform(points[i]);
    }
  }
  const GeographicLib::Geodesic& geod = GeographicLib::Geodesic::WGS84();
  k_.assign(n_ * n_, 0.0);
  bool any = false;
  for (int node = 0; node < n_ * n_; ++node) {
    const std::size_t i = 3 * node;
    if (!valid[i] || !valid[i + 1] || !valid[i + 2]) continue;
    double sx = 0.0, sy = 0.0;
    geod.Inverse(points[i].y, points[i].x, points[i + 1].y, points[i + 1].x, sx);
    geod.Inverse(points[i].y, points[i].x, points[i + 2].y, points[i + 2].x, sy);
    if (!(sx > 0) || !(sy > 0)) continue;
    k_[node] = step / std::sqrt(sx * sy);
    any = any || std::isfinite(k_[node]);
    if (!std::isfinite(k_[node])) k_[node] = 0.0;
  }
  if (!any)
    throw Error(ErrorClass::crs, "crs",
                "the meshing CRS '" + crs.name + "' has no inverse over the domain");
  // Nodes without a scale take the mean of their neighbours' that have one, ring by ring
  // outwards from those.
  for (bool missing = true; missing;) {
    missing = false;
    std::vector<double> next = k_;
    for (int j = 0; j < n_; ++j)
      for (int i = 0; i < n_; ++i) {
        if (k_[j * n_ + i] > 0) continue;
        double sum = 0.0;
        int count = 0;
        for (auto [di, dj] : {std::pair{-1, 0}, {1, 0}, {0, -1}, {0, 1}}) {
          const int a = i + di, b = j + dj;
          if (a < 0 || b < 0 || a >= n_ || b >= n_ || !(k_[b * n_ + a] > 0)) continue;
          sum += k_[b * n_ + a];
          ++count;
        }
        if (count > 0)
          next[j * n_ + i] = sum / count;
        else
          missing = true;
      }
    k_.swap(next);
  }
  min_ = *std::min_element(k_.begin(), k_.end());
  max_ = *std::max_element(k_.begin(), k_.end());
}

double MapScale::at(const Point2& p) const {
  const double u = std::clamp((p.x - box_[0]) / dx_, 0.0, double(n_ - 1));
  const double v = std::clamp((p.y - box_[1]) / dy_, 0.0, double(n_ - 1));
  const int i = std::min(static_cast<int>(u), std::max(0, n_ - 2));
  const int j = std::min(static_cast<int>(v), std::max(0, n_ - 2));
  const double fu = u - i, fv = v - j;
  const double* row0 = &k_[j * n_ + i];
  const double* row1 = row0 + n_;
  return (1 - fv) * ((1 - fu) * row0[0] + fu * row0[1]) + fv * ((1 - fu) * row1[0] + fu * row1[1]);
}

double MapScale::max_error() const {
  return std::max(max_ - 1.0, 1.0 - min_);
}

CrsDistortion crs_distortion(const CrsInfo& crs, const std::vector<Point2>& points) {
  CrsDistortion d;
  if (points.empty()) return d;
  const std::size_t stride = std::max<std::size_t>(1, points.size() / 1000);
  constexpr double kStep = 1.0;  // metres of the CRS
  const CrsTransform to_lonlat(crs, geographic_base(crs));
  const GeographicLib::Geodesic& geod = GeographicLib::Geodesic::WGS84();
  for (std::size_t i = 0; i < points.size(); i += stride) {
    Point2 p = points[i], px{p.x + kStep, p.y}, py{p.x, p.y + kStep};
    if (!to_lonlat.transform(p) || !to_lonlat.transform(px) || !to_lonlat.transform(py)) continue;
    double sx = 0.0, sy = 0.0, ax = 0.0, ay = 0.0, a2 = 0.0;
    geod.Inverse(p.y, p.x, px.y, px.x, sx, ax, a2);
    geod.Inverse(p.y, p.x, py.y, py.x, sy, ay, a2);
    if (!(sx > 0) || !(sy > 0)) continue;
    d.measured = true;
    const double kx = kStep / sx, ky = kStep / sy;
    d.max_scale_error = std::max(d.max_scale_error, std::abs(std::sqrt(kx * ky) - 1.0));
    d.max_anisotropy = std::max(d.max_anisotropy, std::abs(kx / ky - 1.0));
    // The x step's azimuth is the y step's plus 90 degrees (clockwise from north).
    const double skew = std::remainder(ax - ay - 90.0, 360.0);
    d.max_skew_deg = std::max(d.max_skew_deg, std::abs(skew));
  }
  return d;
}

}  // namespace isoquad
