// Spike tips: a corner of the domain sharper than a few degrees is a corner that every
// quad mesh must have too: the quad there has that angle (French Polynesia at 1:10m:
// 1.9 degrees). The narrow-feature step bevels a spike where it is min_width wide, but
// the simplification after it (whose tolerance is min_width by default) takes the
// bevel's two corners back to one sharp tip; and it keeps whole a spit or an atoll's rim
// narrower than min_width all along when removing it would cut the rim. So, last, such
// a tip is cut back, square across its bisector, to where it is min_width wide.
#pragma once

#include <cstddef>

#include "core/geometry.h"

namespace isoquad {

struct SpikeParams {
  double min_width_m = 0.0;      // the width of the cut end; 0: off
  double max_angle_deg = 15.0;   // tips with an interior angle under this are cut
};

struct SpikeResult {
  std::size_t num_cut = 0;          // cut square where min_width wide
  std::size_t num_cut_at_base = 0;  // spits narrower than that, cut at their base
  double area_removed_m2 = 0.0;     // by both
};

// Cuts every convex vertex of the domain's rings whose interior angle is under
// max_angle_deg: the part of the domain beyond the line across the tip's bisector, at
// the distance where the tip's two sides are min_width apart, that holds the tip, is
// removed. A cut that would change the domain's components or holes, or remove more than
// the tip's triangle could hold, is not made; where the spike ends before the cut (its
// side turns away at a vertex nearer the tip), the tip is cut square at that vertex
// instead. The result is oriented and sorted by area.
SpikeResult cut_spike_tips(Domain& domain, const SpikeParams& params);

}  // namespace isoquad
