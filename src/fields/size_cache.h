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

  std::size_t num_leaves() const { return leaf_corner_.size(); }
  // Exact evaluations of the size function made by the build (each lattice point once).
  std::size_t num_evaluations() const { return num_evaluations_; }

 private:
  // The values at the lattice points evaluated so far, during the build only (a cell's
  // corners are shared with up to three other cells): millions of entries for fine
  // sizes, which stayed resident beside the background mesh when the cache kept them.
  using CornerTable = std::unordered_map<long long, double>;
  double corner(long long i, long long j, const std::function<double(const Point2&)>& size,
                CornerTable& table);
  void build(int node, int depth, long long i0, long long j0, long long span,
             const std::function<double(const Point2&)>& size, CornerTable& table);

  bool overlaps_region(long long i0, long long j0, long long span) const;

  std::vector<std::array<double, 4>> regions_;
  double x0_ = 0, y0_ = 0, side_ = 1;
  double cell_ratio_ = 0.5;
  int max_depth_ = 18;
  long long resolution_ = 1;  // lattice points per side at max depth
  // Per node: the index of the first of its 4 children, or -1 - (its leaf's index).
  std::vector<int> child_;
  // Per leaf: the values at (x0,y0), (x1,y0), (x0,y1), (x1,y1).
  std::vector<std::array<double, 4>> leaf_corner_;
  std::size_t num_evaluations_ = 0;
};

}  // namespace isoquad
