// Initialization of the tiling (paper, section 2.2): one tile per background triangle,
// then pairs of adjacent tiles merged in order of decreasing compactness (area /
// perimeter^2 of the union) while the union stays within one ideally sized tile.
#pragma once

#include "mesh/background_mesh.h"
#include "tiling/tile_geometry.h"
#include "tiling/tiling.h"

namespace isoquad {

struct InitParams {
  // A merge is allowed while the union's mass (sum of area / (2h)^2, 1 = one tile of
  // side 2h) stays at most this.
  double max_mass = 1.0;
  // Then merges the pairs of smallest union mass until the number of tiles is the total
  // mass rounded (each tile then has about the target area on average; the relaxation
  // keeps the number of tiles, so it sets their size).
  bool match_count = true;
};

struct InitStats {
  int num_compact_merges = 0;  // merges by compactness
  int num_count_merges = 0;    // merges to reach the target number of tiles
  double total_mass = 0.0;     // the target number of tiles before rounding
};

// Labels every triangle; generator[t] is the relocated triangle of tile t (2.3). Tiles
// are connected but may wrap an island (see repair_tiling). Deterministic.
Tiling init_tiling(const BackgroundMesh& mesh, const TriangleGeometry& geom,
                   const InitParams& params = InitParams(), InitStats* stats = nullptr);

}  // namespace isoquad
