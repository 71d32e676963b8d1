// The meshing CRS's scale: how many of its metres a metre on the ground (the ellipsoid)
// takes at each point. A conformal projection (the automatic oblique stereographic,
// Mercator, UTM, Lambert's conformal conic) scales lengths alike in every direction, so
// quads of size k(x) h in it are quads of size h on the ground, as square and as turned.
// Sizes given in metres (--size, --hmax, a raster of sizes, the depth rules) are the
// ground's; the sizing multiplies them by k where the scale is far enough from 1 to
// matter (SizingOracle).
#pragma once

#include <array>
#include <vector>

#include "core/geometry.h"
#include "gis/crs.h"

namespace isoquad {

class MapScale {
 public:
  // The scale of `crs` (projected, metres) over `box` (xmin, ymin, xmax, ymax in it),
  // sampled on a grid of `cells` x `cells` cells: at each node, the lengths of two short
  // steps along x and y measured on the ellipsoid (GeographicLib's geodesics on WGS 84)
  // against theirs in the CRS, k the geometric mean of the two ratios (their areal
  // scale's square root, exact for a conformal CRS). Nodes where the CRS has no inverse
  // take their neighbours' scales, ring by ring outwards from the nodes that have one. Throws
  // Error(crs) when no node has.
  MapScale(const CrsInfo& crs, const std::array<double, 4>& box, int cells = 64);

  // k at p, bilinear between the grid's nodes (the nearest edge's value outside the box).
  double at(const Point2& p) const;
  double min() const { return min_; }
  double max() const { return max_; }
  // The largest |k - 1| over the grid.
  double max_error() const;

 private:
  std::array<double, 4> box_;
  int n_ = 0;  // nodes per side
  double dx_ = 1.0, dy_ = 1.0;
  std::vector<double> k_;  // n_ x n_, row by row from ymin
  double min_ = 1.0, max_ = 1.0;
};

// How far a projected CRS (in metres) strays from the ground at some of its points
// (`points` in it; at most about 1,000 of them are measured, evenly through the list):
// at each, two short steps along x and y measured on the ellipsoid (GeographicLib's
// geodesics on WGS 84). A conformal CRS scales both alike (`max_anisotropy`, the largest
// |kx / ky - 1|, is 0) and keeps them square (`max_skew_deg`, the largest departure of
// the angle between their images from 90 degrees, is 0); `max_scale_error` is the
// largest |k - 1| (k the two ratios' geometric mean). `measured` is false when no point
// could be transformed to longitude and latitude.
struct CrsDistortion {
  bool measured = false;
  double max_scale_error = 0.0;
  double max_anisotropy = 0.0;
  double max_skew_deg = 0.0;
};
CrsDistortion crs_distortion(const CrsInfo& crs, const std::vector<Point2>& points);

}  // namespace isoquad
