// Dropping what is too small to mesh: islands (components) and holes below an area,
// and every component but the largest when asked.
#pragma once

#include <cstddef>
#include <functional>

#include "core/geometry.h"

namespace isoquad {

struct CleanParams {
  double min_island_area_m2 = 0.0;  // components smaller than this are dropped
  double min_hole_area_m2 = 0.0;    // holes (islands in a water domain) smaller are dropped
  bool largest = false;             // keep only the largest component
  // Whether the user gave min_island_area_m2 (--min-island-area), or it is the default
  // (the size squared): the message when nothing is left says which to change.
  bool min_island_area_given = false;
  // When set, each ring's area is multiplied by it at the middle of the ring's box before
  // the comparisons: a map's (k_min / k)^2, areas as they would be at its smallest scale.
  std::function<double(const Point2&)> area_factor;
};

struct CleanResult {
  std::size_t num_islands_dropped = 0;
  std::size_t num_holes_dropped = 0;
  std::size_t num_components_dropped = 0;  // by `largest`
};

// Components must be sorted by decreasing area (sort_by_area). Throws Error(input) when
// nothing is left.
CleanResult clean_domain(Domain& domain, const CleanParams& params);

}  // namespace isoquad
