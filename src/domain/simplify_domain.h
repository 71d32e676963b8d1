// Topology-preserving simplification of every ring of the domain at once
// (CGAL Polyline_simplification_2 on a constrained triangulation holding all rings):
// no vertex is removed if that would make rings cross or touch, or bring another part
// of the boundary closer than `clearance_m` to the ring where it was not already.
//
// Why the clearance: the tolerance lets each bank of a channel move by that much, so a
// channel or a bay's mouth narrower than twice the tolerance can close to a gap of
// centimetres without the rings touching (the Baltic at 1:10m: a bay's mouth of 280 m
// brought to 0.5 m at a tolerance of 385 m). The narrow-feature step keeps such a mouth
// when cutting it would change the topology, and the quads across it then had sides of
// 0.4 m next to sides of a kilometre.
//
// Rings drawn much more finely than the tolerance (a quarter of their vertices or more
// with both neighbours within a quarter of it) are thinned first, away from other parts
// of the boundary, so that the time grows with the number of vertices, not its square.
#pragma once

#include <cstddef>

#include "core/geometry.h"

namespace isoquad {

struct SimplifyParams {
  double tolerance_m = 0.0;  // max distance of a removed vertex from the simplified ring; 0: off
  // No removal brings a vertex of another ring, or of the same ring beyond the stretch
  // next to the new segment, closer to the ring than this, unless it already was (then
  // no closer than it was). 0: off.
  double clearance_m = 0.0;
};

struct SimplifyResult {
  std::size_t num_vertices_before = 0;
  std::size_t num_vertices_after = 0;
};

SimplifyResult simplify_domain(Domain& domain, const SimplifyParams& params);

}  // namespace isoquad
