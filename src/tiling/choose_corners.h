// Which four meta-vertices of a tile are its quadrangle corners (paper, section 2.4):
// the ordered choice c1..c4 and axis a in {u, v} maximising
//   E = min(|(c2-c1).a|, |(c3-c2).a90|, |(c4-c3).a|, |(c1-c4).a90|),
// by dynamic programming over the circular sequence of meta-vertices. Conforming
// relaxation, butterfly removal (2.5) and the quad stages use it.
#pragma once

#include <array>
#include <vector>

#include "core/geometry.h"

namespace isoquad {

struct CornerChoice {
  // Indices into the positions, increasing (counter-clockwise along the tile); -1 when
  // there are fewer than 4 positions.
  std::array<int, 4> corners{{-1, -1, -1, -1}};
  // Side k runs from corners[k] to corners[(k+1)%4]. Its reference direction is u when
  // (k + first_side_along_v) is even, else v (u = the frame direction, v = u turned 90
  // degrees counter-clockwise).
  bool first_side_along_v = false;
  double energy_m = 0.0;  // the maximised E, metres
};

// meta_vertex_positions: #P >= 4 positions in counter-clockwise order around the tile;
// frame_angle_rad: the cross (any of its four directions) giving u. With fewer than 4
// positions, returns the indices 0..P-1 followed by -1 and energy 0.
CornerChoice choose_corners_and_axes(const std::vector<Point2>& meta_vertex_positions,
                                     double frame_angle_rad);

// The corner indices only (see choose_corners_and_axes).
std::array<int, 4> choose_corners(const std::vector<Point2>& meta_vertex_positions,
                                  double frame_angle_rad);

}  // namespace isoquad
