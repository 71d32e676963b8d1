#include "fields/size_cache.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace isoquad {

SizeCache::SizeCache(const std::array<double, 4>& box,
                     const std::function<double(const Point2&)>& size, double cell_ratio,
                     int max_depth, std::vector<std::array<double, 4>> regions)
    : regions_(std::move(regions)), cell_ratio_(cell_ratio), max_depth_(max_depth) {
  side_ = std::max(box[2] - box[0], box[3] - box[1]);
  side_ = side_ > 0 ? side_ * (1 + 1e-9) : 1.0;
  x0_ = box[0];
  y0_ = box[1];
  resolution_ = 1LL << max_depth_;
  child_.push_back(-1);
  CornerTable table;
  build(0, 0, 0, 0, resolution_, size, table);
}

double SizeCache::corner(long long i, long long j, const std::function<double(const Point2&)>& size,
                         CornerTable& table) {
  const auto [it, added] = table.try_emplace(i * (resolution_ + 1) + j, 0.0);
  if (!added) return it->second;
  const double s = side_ / static_cast<double>(resolution_);
  it->second = size({x0_ + i * s, y0_ + j * s});
  ++num_evaluations_;
  return it->second;
}

void SizeCache::build(int node, int depth, long long i0, long long j0, long long span,
                      const std::function<double(const Point2&)>& size, CornerTable& table) {
  const std::array<double, 4> c{corner(i0, j0, size, table), corner(i0 + span, j0, size, table),
                                corner(i0, j0 + span, size, table),
                                corner(i0 + span, j0 + span, size, table)};
  const double cell = side_ * static_cast<double>(span) / static_cast<double>(resolution_);
  const double smallest = *std::min_element(c.begin(), c.end());
  if (depth >= max_depth_ || cell <= cell_ratio_ * smallest || !overlaps_region(i0, j0, span)) {
    child_[node] = -1 - static_cast<int>(leaf_corner_.size());
    leaf_corner_.push_back(c);
    return;
  }
  const int first = static_cast<int>(child_.size());
  child_[node] = first;
  child_.resize(child_.size() + 4);
  const long long half = span / 2;
  build(first + 0, depth + 1, i0, j0, half, size, table);
  build(first + 1, depth + 1, i0 + half, j0, half, size, table);
  build(first + 2, depth + 1, i0, j0 + half, half, size, table);
  build(first + 3, depth + 1, i0 + half, j0 + half, half, size, table);
}

bool SizeCache::overlaps_region(long long i0, long long j0, long long span) const {
  if (regions_.empty()) return true;
  const double s = side_ / static_cast<double>(resolution_);
  const double x0 = x0_ + i0 * s, y0 = y0_ + j0 * s, x1 = x0 + span * s, y1 = y0 + span * s;
  for (const auto& r : regions_)
    if (x0 <= r[2] && r[0] <= x1 && y0 <= r[3] && r[1] <= y1) return true;
  return false;
}

double SizeCache::operator()(const Point2& p) const {
  double u = std::clamp((p.x - x0_) / side_, 0.0, 1.0);
  double v = std::clamp((p.y - y0_) / side_, 0.0, 1.0);
  int node = 0;
  while (child_[node] >= 0) {
    const int qx = u >= 0.5 ? 1 : 0, qy = v >= 0.5 ? 1 : 0;
    u = 2 * u - qx;
    v = 2 * v - qy;
    node = child_[node] + qx + 2 * qy;
  }
  const auto& c = leaf_corner_[-1 - child_[node]];
  return (1 - v) * ((1 - u) * c[0] + u * c[1]) + v * ((1 - u) * c[2] + u * c[3]);
}

}  // namespace isoquad
