// Initialization by frontal seeding, the alternative to merging (2.2) that `--init
// front` selects: generators are placed one tile (2h) apart along the cross field, first
// a row at h inside the boundary (between boundary corners, a whole number of tiles per
// side), then front by front inwards from every placed generator along the four
// directions of its cross. A candidate closer than `min_gap` (h_a + h_b) to a placed
// generator in the L-infinity norm of its frame is dropped, so fronts that meet leave
// one defect line instead of overlapping rows. The tiles are the L-infinity flood of the
// generators (flood_tiling.h).
//
// Why: merging by compactness gives tiles of the right size in no particular
// arrangement, and L-infinity Lloyd iterations keep whatever packing they start from
// (hexagonal packings and lattices at 45 degrees to the cross are fixed points). Seeds
// on the cross field's rows and columns start the relaxation from the square lattice it
// should converge to.
#pragma once

#include <vector>

#include "core/geometry.h"
#include "fields/cross_field.h"
#include "fields/sizing_field.h"
#include "mesh/background_mesh.h"
#include "tiling/tile_geometry.h"
#include "tiling/tiling.h"

namespace isoquad {

struct SeedParams {
  // Two generators with sizes h_a, h_b stay at least min_gap (h_a + h_b) apart in the
  // L-infinity norm of the candidate's cross frame (tiles are 2h wide: 0.7 lets rows
  // that meet come as close as 1.4 h before one is dropped). On mainland France at 11 km,
  // 0.6 / 0.7 / 0.8 / 0.9 give 80 / 82 / 78 / 75% quadrangle tiles after 2.5.
  double min_gap = 0.7;
  // An interior candidate keeps this many h from the boundary along its frame axes;
  // nearer the boundary, the boundary row covers it.
  double clearance = 0.6;
  // Lines inside the domain (metres; --align, whose lines the cross field follows): a
  // row of generators on each, one tile apart, after the boundary rows, so that rows of
  // tiles start from the lines as from the coast.
  std::vector<std::vector<Point2>> lines;
};

struct SeedStats {
  int num_boundary = 0;  // generators of the boundary rows
  int num_lines = 0;     // generators of the lines' rows
  int num_interior = 0;  // generators placed by the fronts
  int num_filled = 0;    // generators added in triangles no flood reached
};

// Labels every triangle; generator[t] is tile t's seed triangle. Deterministic.
Tiling seed_tiling(const BackgroundMesh& mesh, const TriangleGeometry& geom,
                   const SizingField& size, const CrossField& cross,
                   const SeedParams& params = SeedParams(), SeedStats* stats = nullptr);

}  // namespace isoquad
