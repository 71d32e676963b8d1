// Mean value coordinates (Floater 2003, the paper's reference [15]): the map of a
// triangulated disk onto a convex polygon used by the local parameterizations of
// butterfly removal (paper, section 2.5).
#pragma once

#include <array>
#include <vector>

#include "core/geometry.h"

namespace isoquad {

// Maps a triangulated region into the plane with some vertices fixed: every free vertex
// becomes the weighted average of its neighbours with the mean value weights
//   w_ij = (tan(a/2) + tan(b/2)) / |p_j - p_i|,
// a and b the angles at p_i of the two triangles along edge ij. The weights are positive,
// so a disk whose boundary is fixed on a convex polygon maps one-to-one (Tutte, Floater),
// and affine maps are reproduced exactly. The system is not symmetric: one sparse LU
// factorisation, two right-hand sides.
//   positions  #n vertex positions, metres
//   triangles  #m local vertex ids, counter-clockwise
//   is_fixed   #n 1 where uv is given (at least one vertex per connected component)
//   uv         #n in: the images of the fixed vertices; out: the image of every vertex
// Returns false (uv of the free vertices unspecified) when the factorisation fails, i.e.
// some free vertex is not connected to a fixed one.
bool mean_value_parameterization(const std::vector<Point2>& positions,
                                 const std::vector<std::array<int, 3>>& triangles,
                                 const std::vector<char>& is_fixed, std::vector<Point2>& uv);

}  // namespace isoquad
