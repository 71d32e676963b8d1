// The smoothing's local repairs of the quad mesh's topology, where moving vertices is
// not enough: edge flips and diagonal collapses of non-convex quads, unfolding where
// boundary edges cross, slivers, and reflex corners in two quads. The parameters and
// their measurements are SmoothParams' (smooth_quads.h). Collapses drop vertices: the
// vertex ids are renumbered.
#pragma once

#include <functional>
#include <vector>

#include "mesh/background_mesh.h"
#include "quad/quad_mesh.h"
#include "quad/quad_topology.h"
#include "quad/smooth_quads.h"

namespace isoquad {

// Edge flips of non-convex quads with a neighbour, kept when they make the pair more
// convex. Returns the number of flips.
int flip_nonconvex(QuadMesh& m, double min_convexity);

// Diagonal collapses of the quads `wanted` accepts (`choice` picks among a quad's
// possible collapses, the shorter diagonal first). Returns the number of quads removed.
int collapse_quads(QuadMesh& m, const std::function<bool(int)>& wanted, int choice = 0);

// The non-convex quads left, one at a time: collapses, then flips, each kept when fewer
// quads are left non-convex. Returns the number of collapses kept.
int collapse_one_by_one(const BackgroundMesh& bg, QuadMesh& m, const SmoothParams& params,
                        SmoothStats& stats);

// Slides the ends of crossing boundary edges along the boundary. Returns the crossings
// left.
std::size_t unfold_boundary(const BackgroundMesh& bg, QuadMesh& m, const QuadTopology& t,
                            const SmoothParams& params);

// Folds the slides leave, by collapses or flips. Returns the number of collapses kept.
int collapse_folds(const BackgroundMesh& bg, QuadMesh& m, const SmoothParams& params,
                   SmoothStats& stats);

// Slivers (SmoothParams::sliver_convexity), every quad convex; with `relocate`, each try
// moves the interior vertices next to the change to their neighbours' middle first
// (SmoothParams::sliver_relocate).
void collapse_slivers(const BackgroundMesh& bg, QuadMesh& m, const SmoothParams& params,
                      const SmoothParams& lift, SmoothStats& stats, bool relocate = false);

// Thin quads (SmoothParams::thin_aspect), every quad convex, by the same changes as the
// slivers'; counted in SmoothStats::num_thin_repairs.
void collapse_thin(const BackgroundMesh& bg, QuadMesh& m, const SmoothParams& params,
                   const SmoothParams& lift, SmoothStats& stats);

// Reflex corners in two quads (SmoothParams::doubled_corner_side). Returns where the kept
// splits left their quads' vertices.
std::vector<Point2> split_doubled_corners(const BackgroundMesh& bg, QuadMesh& m,
                                          const SmoothParams& params, const SmoothParams& lift,
                                          SmoothStats& stats);

}  // namespace isoquad
