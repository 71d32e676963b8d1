// An adaptive quadtree cache of a size function, for the many evaluations that Delaunay
// refinement makes: cells split until they are small relative to the size in them, so
// that bilinear interpolation of the corner values is accurate where it matters. It is
// built depth-first, so that the exact evaluations are spatially coherent (cheap walks
// in the Apollonius graph of the automatic sizing).
#pragma once

#include <array>
#include <functional>
#include <unordered_map>
#include <vector>

#include "core/geometry.h"

namespace isoquad {

class SizeCache {
 public:
  // Covers `box` (xmin, ymin, xmax, ymax). A cell of side s is split while
  // s > cell_ratio * (smallest corner value), up to max_depth levels, and, when `regions`
  // (boxes) are given, only while it overlaps one of them: a domain of islands far apart
  // needs no fine cells over the sea between them (the Netherlands with its Caribbean
  // islands: 1.5 million cells, 2 GB, 8 s without).
  SizeCache(const std::array<double, 4>& box, const std::function<double(const Point2&)>& size,
            double cell_ratio = 0.5, int max_depth = 18,
            std::vector<std::array<double, 4>> regions = {});

  // Bilinear interpolation in the leaf containing p (clamped to the box).
  double operator()(const Point2& p) const;

  std::size_t num_leaves() const { return num_leaves_; }
  std::size_t num_evaluations() const { return corner_value_.size(); }

 private:
  struct Node {
    int child = -1;  // index of the first of 4 children, -1 for a leaf
    std::array<double, 4> corner{};  // values at (x0,y0), (x1,y0), (x0,y1), (x1,y1)
  };
  double corner(long long i, long long j, const std::function<double(const Point2&)>& size);
  void build(int node, int depth, long long i0, long long j0, long long span,
             const std::function<double(const Point2&)>& size);

  bool overlaps_region(long long i0, long long j0, long long span) const;

  std::vector<std::array<double, 4>> regions_;
  double x0_ = 0, y0_ = 0, side_ = 1;
  double cell_ratio_ = 0.5;
  int max_depth_ = 18;
  long long resolution_ = 1;  // lattice points per side at max depth
  std::vector<Node> nodes_;
  std::unordered_map<long long, double> corner_value_;
  std::size_t num_leaves_ = 0;
};

}  // namespace isoquad
