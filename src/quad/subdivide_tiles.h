// Barycentric subdivision (paper, section 2.6): a tile with k meta-edges becomes k
// quads (tile centre, midpoint of meta-edge i-1, meta-vertex i, midpoint of meta-edge
// i). Midpoints sit at the arc-length middle of their edge path and are shared by the
// two tiles, so the quad mesh is conforming; boundary vertices lie on the boundary.
#pragma once

#include "mesh/background_mesh.h"
#include "quad/quad_mesh.h"
#include "tiling/meta_graph.h"
#include "tiling/tiling.h"

namespace isoquad {

struct SubdivideParams {
  // Boundary meta-vertices whose |turning angle| exceeds this are fixed domain corners.
  double corner_angle_deg = 45.0;
  // A tile whose quads around its centroid have a corner turning by less than this
  // (quad_convexity, the sine of the sharpest turn; 0.26 ~ 15 degrees) gets the triangle
  // centroid that makes its flattest quad the most convex as centre instead.
  double centre_min_convexity = 0.26;
};

QuadMesh subdivide_tiles(const BackgroundMesh& background, const Tiling& tiling,
                         const MetaGraph& graph, const SubdivideParams& params = SubdivideParams());

}  // namespace isoquad
