// Sizes asked for by vector features (--refine): at most a feature's size inside its
// polygons and on its lines and points (and within half its width of them), growing by
// the gradation K with the distance beyond (a graded cone, as the sizing field's
// gradation would make it).
#pragma once

#include <vector>

#include "core/geometry.h"

namespace isoquad {

struct SizeFeature;

class FeatureSizes {
 public:
  // `features` in the meshing CRS.
  FeatureSizes(const std::vector<SizeFeature>& features, double gradation);
  // min(h, the smallest of size + K * max(0, distance - width / 2) over the features):
  // features whose bound cannot go below h are skipped.
  double limit(const Point2& p, double h) const;

 private:
  struct Run {  // up to kRun consecutive segments of one polyline, with their box
    int polyline = 0, first = 0, last = 0;
    double xmin = 0, ymin = 0, xmax = 0, ymax = 0;
  };
  struct Item {
    double size_m = 0.0;
    double half_width_m = 0.0;
    double xmin = 0, ymin = 0, xmax = 0, ymax = 0;
    int first_ring = 0, last_ring = 0;  // polylines [first_ring, last_ring) are rings
    int first_run = 0, last_run = 0;    // runs of its rings and lines
    int first_point = 0, last_point = 0;
  };
  bool inside(const Item& item, const Point2& p) const;
  // min(h, item's size + K * distance).
  double limit_by(const Item& item, const Point2& p, double h) const;

  double gradation_ = 0.2;
  double min_size_m_ = 0.0;
  double max_half_width_m_ = 0.0;
  std::vector<std::vector<Point2>> polylines_;
  std::vector<Point2> points_;
  std::vector<Run> runs_;
  std::vector<Item> items_;
  // A grid of n x n cells over the items' boxes: cell c lists the items whose box meets
  // it, in cell_items_[cell_start_[c] .. cell_start_[c + 1]).
  double x0_ = 0, y0_ = 0, cell_ = 1;
  int n_ = 0;
  std::vector<int> cell_start_, cell_items_;
};

}  // namespace isoquad
