// Re-splitting pairs of tiles: a local parameterization after the butterflies (2.5)
// that the paper does not have.
//
// Two adjacent tiles whose union has n meta-vertices on its boundary can be cut into a
// quadrangle and an (n-2)-gon by an edge path between two meta-vertices three apart on
// the union's boundary. With n = 6 both are quadrangles: a pentagon and a triangle
// (common where rows of tiles split as the size grows), two quadrangles whose shared
// meta-edge joins two degree-5 meta-vertices, or a pentagon and a quadrangle sharing a
// degree-3 meta-vertex that the union removes all become two quadrangles. A pair is
// re-split only when the irregularity it leaves in the final mesh goes down (or stays,
// with more quadrangle tiles; quads_on_ties): sum |k - 4|
// over the tiles whose meta-vertex count k changes (their centres' valences after
// subdivision) plus sum |d - ideal| over the meta-vertices whose tile count d changes (4
// inside; the boundary angle / 90 on the boundary). The new quadrangle's corners (and,
// for n = 6, the other one's) must be within max_corner_deviation_deg of 90 degrees,
// another tile's corners between 10 and 200 degrees, and the two areas within a factor
// max_area_ratio.
#pragma once

#include "core/progress.h"
#include "mesh/background_mesh.h"
#include "tiling/meta_graph.h"
#include "tiling/tiling.h"

namespace isoquad {

struct ResplitParams {
  double max_corner_deviation_deg = 75.0;
  // Unions with this many meta-vertices are split into a quadrangle and the rest (six:
  // two quadrangles; five: a quadrangle and a triangle; seven: and a pentagon...).
  // France automatic at about 4,300 quads: six only 70% quadrangle tiles, 85.7% regular
  // interior vertices, 77.7% of angles in range; five to eight 73%, 88.0%, 79.2%.
  int min_union_vertices = 5;
  int max_union_vertices = 8;
  double max_area_ratio = 3.0;
  // The quads that barycentric subdivision would make of each new tile (around its
  // area centroid) must have convexity (the smallest sine of their turns) at least this:
  // -0.6 lets smoothing straighten mildly bent quads and turns away tiles bent round a
  // coastal spike, which folded Corsica's quickstart mesh. France automatic: 0.1 keeps
  // 68% quadrangle tiles, -0.6 73%, no check 74%.
  double min_subdivision_convexity = -0.6;
  // A split that leaves the irregularity as it was is still made when it leaves more
  // quadrangle tiles (an irregular tile centre traded for an irregular meta-vertex).
  // France automatic at hmax 28 km: quadrangle tiles 72% -> 80%, regular interior
  // vertices 87.7% -> 89.4%, angles in range 80.1% both, orientation 12.6 -> 13.1 deg.
  bool quads_on_ties = true;
  int max_rounds = 10;  // rounds of candidates, one meta-graph build each
  MetaGraphParams graph;
};

struct ResplitStats {
  int candidates = 0;  // pairs with a valid split that lowers the irregularity, first round
  int resplit = 0;     // pairs re-split over all rounds
  int rounds = 0;
};

// Keeps the invariants of check_tiling (each new tile is a disk). Deterministic.
ResplitStats resplit_pairs(const BackgroundMesh& mesh, Tiling& tiling, const ResplitParams& params,
                           const Progress& progress = Progress());

}  // namespace isoquad
