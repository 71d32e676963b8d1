// Domain corners at the scale of the tiles. A coastline simplified at a fraction of the
// element size still turns sharply at many vertices whose turns cancel within one tile
// (a zigzag); tagging each as a corner would make every coastal tile many-sided and
// split it at every reflex turn. A corner is a boundary vertex where the boundary turns
// by more than a threshold within one tile width (2h) and that turns the most there.
#pragma once

#include "fields/sizing_field.h"
#include "mesh/background_mesh.h"

namespace isoquad {

struct CornerParams {
  // A vertex is a corner when the boundary turns by more than this (degrees, either way)
  // within an arc of one tile width (h on each side) centred on it.
  double corner_angle_deg = 45.0;
  // Window half-width in units of h (1: the window is one tile, 2h, wide).
  double window_h = 1.0;
};

// Rewrites BoundaryChain::is_corner and BoundaryChain::corner_turning_deg of every chain:
// corners are local maxima of the windowed turning (non-maximum suppression within the
// window, ties to the sharper own turn, then the lower chain index), at input vertices
// that turn the same way by at least half the threshold themselves. Deterministic.
void tag_corners(BackgroundMesh& mesh, const SizingField& size, const CornerParams& params);

}  // namespace isoquad
