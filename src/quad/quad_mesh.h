// The all-quadrangle mesh (paper, sections 2.6 and 2.7) as flat arrays, with what
// smoothing needs to slide boundary vertices along the domain boundary.
#pragma once

#include <array>
#include <vector>

#include "core/geometry.h"
#include "mesh/background_mesh.h"

namespace isoquad {

struct QuadMesh {
  std::vector<Point2> points;            // #P positions, metres (meshing CRS)
  std::vector<std::array<int, 4>> quads;  // #Q vertex ids, counter-clockwise
  std::vector<int> chain;                // #P boundary chain (BackgroundMesh::chains) or -1
  std::vector<double> arc_m;             // #P arc length along that chain
  std::vector<char> fixed;               // #P 1 for domain corners: never moved
};

// The point at arc length `arc_m` (taken modulo the chain length) along a boundary chain.
Point2 chain_point(const BackgroundMesh& mesh, const BoundaryChain& chain, double arc_m);

// Convexity of a quad: the smallest sine of its four turning angles (positive for every
// corner of a strictly convex counter-clockwise quad, in (-1, 1]).
double quad_convexity(const Point2& a, const Point2& b, const Point2& c, const Point2& d);
double quad_convexity(const QuadMesh& mesh, int q);

// The four interior angles in degrees.
std::array<double, 4> quad_angles_deg(const QuadMesh& mesh, int q);
double quad_area(const QuadMesh& mesh, int q);

}  // namespace isoquad
