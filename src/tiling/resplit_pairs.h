// Re-splitting pairs of tiles into two quadrangles: a local parameterization after the
// butterflies (2.5) that the paper does not have.
//
// Two adjacent tiles whose union has exactly six meta-vertices on its boundary can
// always be cut into two quadrangles, by an edge path between two opposite ones of the
// six. A pentagon and a triangle (common where rows of tiles split as the size grows),
// two quadrangles whose shared meta-edge joins two degree-5 meta-vertices, a pentagon
// and a quadrangle sharing a degree-3 meta-vertex that the union removes: all become two
// quadrangles whose corners are the union's own meta-vertices. A pair is re-split only
// when the irregularity it leaves in the final mesh, sum |k - 4| over the two tiles
// (their centres' valences after subdivision) plus sum |d - ideal| over the meta-vertices
// whose tile count changes (4 inside; the boundary angle / 90 on the boundary), goes
// down, and the two new tiles have corner quadrilaterals with every angle within
// max_corner_deviation_deg of 90 degrees and areas within a factor max_area_ratio.
#pragma once

#include "mesh/background_mesh.h"
#include "tiling/meta_graph.h"
#include "tiling/tiling.h"

namespace isoquad {

struct ResplitParams {
  double max_corner_deviation_deg = 75.0;
  double max_area_ratio = 3.0;
  int max_rounds = 10;  // rounds of candidates, one meta-graph build each
  MetaGraphParams graph;
};

struct ResplitStats {
  int candidates = 0;  // pairs with six meta-vertices and an irregularity gain, first round
  int resplit = 0;     // pairs re-split over all rounds
  int rounds = 0;
};

// Keeps the invariants of check_tiling (each new tile is a disk bounded by four
// meta-edges). Deterministic.
ResplitStats resplit_pairs(const BackgroundMesh& mesh, Tiling& tiling, const ResplitParams& params);

}  // namespace isoquad
