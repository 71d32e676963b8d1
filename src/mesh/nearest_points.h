// The points of a fixed set nearest a query point: CGAL's kd-tree (Orthogonal
// k-neighbour search) behind a plain interface, for the tools that look up many points
// among many (--embed-points among a mesh's vertices).
#pragma once

#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

#include "core/geometry.h"

namespace isoquad {

class NearestPoints {
 public:
  // `points` is copied; the answers name the points by their index in it.
  explicit NearestPoints(std::vector<Point2> points);
  ~NearestPoints();
  NearestPoints(const NearestPoints&) = delete;
  NearestPoints& operator=(const NearestPoints&) = delete;
  std::size_t size() const { return points_.size(); }
  // The `count` points nearest p (all of them when there are fewer), as (distance,
  // index), nearest first (of those as near, the lower index first).
  std::vector<std::pair<double, int>> nearest(const Point2& p, std::size_t count) const;

 private:
  struct Tree;
  std::vector<Point2> points_;
  std::unique_ptr<Tree> tree_;
};

}  // namespace isoquad
