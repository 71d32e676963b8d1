// Topology-preserving simplification of every ring of the domain at once
// (CGAL Polyline_simplification_2 on a constrained triangulation holding all rings):
// no vertex is removed if that would make rings cross or touch.
#pragma once

#include <cstddef>

#include "core/geometry.h"

namespace isoquad {

struct SimplifyParams {
  double tolerance_m = 0.0;  // max distance of a removed vertex from the simplified ring; 0: off
};

struct SimplifyResult {
  std::size_t num_vertices_before = 0;
  std::size_t num_vertices_after = 0;
};

SimplifyResult simplify_domain(Domain& domain, const SimplifyParams& params);

}  // namespace isoquad
