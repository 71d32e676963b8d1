#include "fields/size_features.h"

#include <algorithm>
#include <cmath>

#include "gis/read_size_features.h"

namespace isoquad {

namespace {

constexpr int kRun = 32;

// Squared distance from p to the box (0 inside).
double box_distance2(const Point2& p, double xmin, double ymin, double xmax, double ymax) {
  const double dx = std::max({xmin - p.x, 0.0, p.x - xmax});
  const double dy = std::max({ymin - p.y, 0.0, p.y - ymax});
  return dx * dx + dy * dy;
}

}  // namespace

FeatureSizes::FeatureSizes(const std::vector<SizeFeature>& features, double gradation)
    : gradation_(gradation) {
  for (const SizeFeature& f : features) {
    Item item;
    item.size_m = f.size_m;
    item.half_width_m = 0.5 * f.width_m;
    item.xmin = item.ymin = INFINITY;
    item.xmax = item.ymax = -INFINITY;
    auto grow = [&item](const Point2& p) {
      item.xmin = std::min(item.xmin, p.x), item.xmax = std::max(item.xmax, p.x);
      item.ymin = std::min(item.ymin, p.y), item.ymax = std::max(item.ymax, p.y);
    };
    item.first_ring = static_cast<int>(polylines_.size());
    for (const auto& ring : f.rings) polylines_.push_back(ring);
    item.last_ring = static_cast<int>(polylines_.size());
    for (const auto& line : f.lines) polylines_.push_back(line);
    item.first_run = static_cast<int>(runs_.size());
    for (int l = item.first_ring; l < static_cast<int>(polylines_.size()); ++l) {
      const auto& line = polylines_[l];
      for (const Point2& p : line) grow(p);
      // A single point counts as a segment of length 0.
      const int segments = std::max(1, static_cast<int>(line.size()) - 1);
      for (int s = 0; s < segments; s += kRun) {
        Run r{l, s, std::min(segments, s + kRun), INFINITY, INFINITY, -INFINITY, -INFINITY};
        for (int i = r.first; i <= r.last && i < static_cast<int>(line.size()); ++i) {
          r.xmin = std::min(r.xmin, line[i].x), r.xmax = std::max(r.xmax, line[i].x);
          r.ymin = std::min(r.ymin, line[i].y), r.ymax = std::max(r.ymax, line[i].y);
        }
        runs_.push_back(r);
      }
    }
    item.last_run = static_cast<int>(runs_.size());
    item.first_point = static_cast<int>(points_.size());
    for (const Point2& p : f.points) points_.push_back(p), grow(p);
    item.last_point = static_cast<int>(points_.size());
    items_.push_back(item);
  }
  if (items_.empty()) return;
  min_size_m_ = INFINITY;
  double x1 = -INFINITY, y1 = -INFINITY;
  x0_ = y0_ = INFINITY;
  for (const Item& item : items_) {
    min_size_m_ = std::min(min_size_m_, item.size_m);
    max_half_width_m_ = std::max(max_half_width_m_, item.half_width_m);
    x0_ = std::min(x0_, item.xmin), y0_ = std::min(y0_, item.ymin);
    x1 = std::max(x1, item.xmax), y1 = std::max(y1, item.ymax);
  }
  n_ = std::clamp(static_cast<int>(std::ceil(std::sqrt(static_cast<double>(items_.size())))), 1,
                  256);
  cell_ = std::max({x1 - x0_, y1 - y0_, 1.0}) / n_;
  auto cell_of = [this](double v, double origin) {
    return std::clamp(static_cast<int>(std::floor((v - origin) / cell_)), 0, n_ - 1);
  };
  std::vector<std::vector<int>> cells(static_cast<std::size_t>(n_) * n_);
  for (int k = 0; k < static_cast<int>(items_.size()); ++k) {
    const Item& item = items_[k];
    for (int j = cell_of(item.ymin, y0_); j <= cell_of(item.ymax, y0_); ++j)
      for (int i = cell_of(item.xmin, x0_); i <= cell_of(item.xmax, x0_); ++i)
        cells[static_cast<std::size_t>(j) * n_ + i].push_back(k);
  }
  cell_start_.push_back(0);
  for (const auto& c : cells) {
    cell_items_.insert(cell_items_.end(), c.begin(), c.end());
    cell_start_.push_back(static_cast<int>(cell_items_.size()));
  }
}

bool FeatureSizes::inside(const Item& item, const Point2& p) const {
  if (p.x < item.xmin || p.x > item.xmax || p.y < item.ymin || p.y > item.ymax) return false;
  // Even-odd: the crossings of the ray from p towards +x with the rings' segments, in
  // the runs that reach p's height and its right.
  bool in = false;
  for (int k = item.first_run; k < item.last_run && runs_[k].polyline < item.last_ring; ++k) {
    const Run& r = runs_[k];
    if (p.y < r.ymin || p.y > r.ymax || p.x > r.xmax) continue;
    const auto& ring = polylines_[r.polyline];
    for (int i = r.first; i < r.last && i + 1 < static_cast<int>(ring.size()); ++i) {
      const Point2 &a = ring[i], &b = ring[i + 1];
      if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y))
        in = !in;
    }
  }
  return in;
}

double FeatureSizes::limit(const Point2& p, double h) const {
  // Only items within (h - the smallest size) / K (and the largest half width) of p can
  // lower h: those of the cells within that reach, each once (in ascending order; the
  // minimum is the same in any).
  if (!(h > min_size_m_) || n_ == 0) return h;
  const double reach = (h - min_size_m_) / gradation_ + max_half_width_m_;
  const double fx0 = std::floor((p.x - reach - x0_) / cell_);
  const double fx1 = std::floor((p.x + reach - x0_) / cell_);
  const double fy0 = std::floor((p.y - reach - y0_) / cell_);
  const double fy1 = std::floor((p.y + reach - y0_) / cell_);
  if (fx1 < 0 || fy1 < 0 || fx0 >= n_ || fy0 >= n_) return h;
  const int i0 = static_cast<int>(std::max(fx0, 0.0)),
            i1 = static_cast<int>(std::min(fx1, n_ - 1.0));
  const int j0 = static_cast<int>(std::max(fy0, 0.0)),
            j1 = static_cast<int>(std::min(fy1, n_ - 1.0));
  if (static_cast<std::size_t>(i1 - i0 + 1) * (j1 - j0 + 1) >= items_.size()) {
    for (const Item& item : items_) h = limit_by(item, p, h);
    return h;
  }
  thread_local std::vector<int> near;
  near.clear();
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      const std::size_t c = static_cast<std::size_t>(j) * n_ + i;
      near.insert(near.end(), cell_items_.begin() + cell_start_[c],
                  cell_items_.begin() + cell_start_[c + 1]);
    }
  std::sort(near.begin(), near.end());
  near.erase(std::unique(near.begin(), near.end()), near.end());
  for (int k : near) h = limit_by(items_[k], p, h);
  return h;
}

double FeatureSizes::limit_by(const Item& item, const Point2& p, double h) const {
  if (!(item.size_m < h)) return h;
  const double bound = (h - item.size_m) / gradation_ + item.half_width_m;
  if (box_distance2(p, item.xmin, item.ymin, item.xmax, item.ymax) >= bound * bound) return h;
  if (inside(item, p)) return item.size_m;
  // The nearest segment or point, looked for only where it could lower h.
  double best = bound;
  for (int k = item.first_run; k < item.last_run; ++k) {
    const Run& r = runs_[k];
    if (box_distance2(p, r.xmin, r.ymin, r.xmax, r.ymax) >= best * best) continue;
    const auto& line = polylines_[r.polyline];
    if (line.size() == 1) best = std::min(best, distance(p, line[0]));
    for (int s = r.first; s < r.last && s + 1 < static_cast<int>(line.size()); ++s)
      best = std::min(best, distance_to_segment(p, line[s], line[s + 1]));
  }
  for (int k = item.first_point; k < item.last_point; ++k)
    best = std::min(best, distance(p, points_[k]));
  return std::min(h, item.size_m + gradation_ * std::max(0.0, best - item.half_width_m));
}

}  // namespace isoquad
