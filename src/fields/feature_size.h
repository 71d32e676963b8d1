// Automatic sizing from the local feature size of the domain boundary (paper, section
// 3: "the largest K-Lipschitz function constrained to match the local feature size").
//
// The true local feature size (distance to the medial axis) is zero at every polyline
// vertex, so it cannot be used on a map coastline as is. We use the lambda-medial axis
// instead: the Voronoi vertices of dense boundary samples whose nearest samples span a
// circle of radius at least lambda. Features narrower than 2 lambda (a kink of the
// polyline, a creek below the resolution) are ignored; a channel of width w >= 2 lambda
// has its centreline at w/2 from each bank. Sizes are sampled ON the boundary and
// extended inside as h(x) = min_i(h_i + K |x - p_i|) (the sites of the cells around x,
// from a grid transform of nearest sites).
#pragma once

#include <memory>
#include <vector>

#include "core/geometry.h"
#include "mesh/nearest_points.h"

namespace isoquad {

class MapScale;

struct FeatureSizeParams {
  double lambda_m = 0.0;          // medial-axis filter radius (> 0)
  double sample_spacing_m = 0.0;  // boundary resampling; 0: lambda / 2
  double cells_across = 2.0;      // at least this many elements across a channel
  double gradation = 1.0;         // K, the Lipschitz constant of the extension
  double max_size_m = 0.0;        // sizes at samples are capped here (hmax, finite)
  // Features narrower than 2 lambda but about 2 narrow_lambda_m wide or more (0: none)
  // get sizes of their own, one element across, down to narrow_floor_m: narrow() below.
  double narrow_lambda_m = 0.0;
  double narrow_floor_m = 0.0;
  // The meshing CRS's scale where sizes are the ground's (map_scale.h; null: 1): the
  // widths above are the ground's, times the scale where a feature is; spacing, grid and
  // max_size_m are the CRS's own.
  const MapScale* scale = nullptr;
};

class BoundaryFeatureSize {
 public:
  BoundaryFeatureSize(const Domain& domain, const FeatureSizeParams& params);
  ~BoundaryFeatureSize();
  BoundaryFeatureSize(const BoundaryFeatureSize&) = delete;
  BoundaryFeatureSize& operator=(const BoundaryFeatureSize&) = delete;

  // h(x) = min_i(h_i + K |x - p_i|), metres.
  double operator()(const Point2& x) const;
  // The same over the medial points of the domain's narrow features alone (channels,
  // inlets and spits from about 2 narrow_lambda to 2 lambda wide, not corners), whose
  // sizes put one element across them but stay above narrow_floor; +inf without any.
  double narrow(const Point2& x) const;
  std::size_t num_narrow_sites() const;

  const std::vector<Point2>& samples() const { return samples_; }
  // #S local feature size at each sample (metres; +inf when no medial point is kept).
  const std::vector<double>& sample_lfs_m() const { return lfs_; }
  // #S size at each sample: lfs times a factor that puts cells_across elements across a
  // channel once the sizes are extended with slope K (see the .cpp), capped at max_size_m.
  const std::vector<double>& sample_size_m() const { return size_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::unique_ptr<Impl> narrow_;
  std::vector<Point2> samples_;
  std::vector<double> lfs_;
  std::vector<double> size_;
};

// The distance in metres to the domain's coast: its boundary but the parts that lie on
// `open` (the open sea boundary's runs, within open_tolerance_m), as OceanMesh2D's
// distance function ('dis') measures it; --size-expr's c. The coast is sampled every
// spacing_m (and at each vertex) and the nearest sample found by a kd-tree: within
// spacing_m / 2 of the true distance. +inf without a coast.
class CoastDistance {
 public:
  CoastDistance(const Domain& domain, const PolylineIndex& open, double open_tolerance_m,
                double spacing_m);
  ~CoastDistance();
  CoastDistance(const CoastDistance&) = delete;
  CoastDistance& operator=(const CoastDistance&) = delete;

  double operator()(const Point2& x) const;
  bool empty() const { return samples_->size() == 0; }

 private:
  std::unique_ptr<NearestPoints> samples_;  // the coast's samples
};

}  // namespace isoquad
