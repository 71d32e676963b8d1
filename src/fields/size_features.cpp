#include "fields/size_features.h"

#include <algorithm>
#include <cmath>

#include "gis/read_size_features.h"

namespace isoquad {

namespace {

constexpr int kRun = 32;

// Distance from p to the box (0 inside).
double box_distance(const Point2& p, double xmin, double ymin, double xmax, double ymax) {
  const double dx = std::max({xmin - p.x, 0.0, p.x - xmax});
  const double dy = std::max({ymin - p.y, 0.0, p.y - ymax});
  return std::hypot(dx, dy);
}

}  // namespace

FeatureSizes::FeatureSizes(const std::vector<SizeFeature>& features, double gradation)
    : gradation_(gradation) {
  for (const SizeFeature& f : features) {
    Item item;
    item.size_m = f.size_m;
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
  for (const Item& item : items_) {
    if (item.size_m + gradation_ * box_distance(p, item.xmin, item.ymin, item.xmax, item.ymax) >= h)
      continue;
    if (inside(item, p)) {
      h = std::min(h, item.size_m);
      continue;
    }
    // The nearest segment or point, looked for only where it could lower h.
    double best = (h - item.size_m) / gradation_;
    for (int k = item.first_run; k < item.last_run; ++k) {
      const Run& r = runs_[k];
      if (box_distance(p, r.xmin, r.ymin, r.xmax, r.ymax) >= best) continue;
      const auto& line = polylines_[r.polyline];
      if (line.size() == 1) best = std::min(best, distance(p, line[0]));
      for (int s = r.first; s < r.last && s + 1 < static_cast<int>(line.size()); ++s)
        best = std::min(best, distance_to_segment(p, line[s], line[s + 1]));
    }
    for (int k = item.first_point; k < item.last_point; ++k)
      best = std::min(best, distance(p, points_[k]));
    h = std::min(h, item.size_m + gradation_ * best);
  }
  return h;
}

}  // namespace isoquad
