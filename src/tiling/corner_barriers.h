// Barriers at reflex domain corners. A tile must not wrap around a reflex corner (the
// quads there could not be convex; section 2.1's invariant), but the L-infinity flood
// of 2.3 measures straight-line distance and happily does. Repairs can split such a
// tile afterwards, yet every split adds a tile, and each relaxation step floods the
// corner over again. Instead, short edge paths of the background mesh run from each
// reflex corner into the domain, splitting its interior angle evenly, and no flood or
// merge crosses them: the tiles on either side meet at the corner by construction.
#pragma once

#include <cstdint>
#include <vector>

#include "fields/sizing_field.h"
#include "mesh/background_mesh.h"

namespace isoquad {

struct CornerBarrierParams {
  // Barrier length in units of h at the corner (0 disables barriers). A tile is 2h wide,
  // so a generator on one side reaches around a barrier of length h only where no tile
  // on the other side is nearer.
  double length_h = 1.0;
  // A reflex corner turning by more than this many degrees is split into 3 tiles, else
  // into 2 (RepairParams::sharp_reflex_deg).
  double sharp_reflex_deg = 120.0;
};

// #F bitmask: bit i of [f] is set when the edge opposite triangles[f][i] is a barrier
// (both triangles on the edge carry the bit). Reflex corners are the chain vertices with
// is_corner and a negative corner_turning_deg (tag_corners). Barrier paths never touch
// the domain boundary or another barrier away from their own corner, so the triangles
// stay connected across the domain.
std::vector<std::uint8_t> corner_barriers(const BackgroundMesh& mesh, const SizingField& size,
                                          const CornerBarrierParams& params);

}  // namespace isoquad
