// Relaxation (paper, section 2.3) and conforming relaxation (2.4): discrete L-infinity
// Lloyd iterations over the background triangles. Each iteration floods the tiles from
// their generators (flood_tiling.h) and relocates every generator to the triangle
// nearest the rho-weighted centroid of its tile; conforming relaxation shifts that
// centroid so that T-junctions close (2.4).
#pragma once

#include <cstddef>
#include <vector>

#include "core/progress.h"
#include "fields/cross_field.h"
#include "mesh/background_mesh.h"
#include "tiling/meta_graph.h"
#include "tiling/tile_geometry.h"
#include "tiling/tiling.h"

namespace isoquad {

struct RelaxParams {
  int max_iters = 50;          // the paper's default cap
  // A generator stays put while its triangle's centroid is within this many h of its
  // tile's target: discrete L-inf Lloyd iterations otherwise jitter between neighbouring
  // triangles, never converge, and every reflood touches the whole mesh.
  double settle_h = 0.15;
  // Stop once the energy H has not fallen by this fraction of its best value for
  // `patience` iterations in a row.
  double energy_tol = 1e-3;
  int patience = 5;
  bool record_energy = false;  // fill RelaxResult::energy_history (one O(#F) pass each)
};

struct RelaxResult {
  int iterations = 0;      // relocations performed
  bool converged = false;  // nothing moved, or the energy stopped falling
  bool cycled = false;     // stopped because a generator set came back
  double energy = 0.0;     // H of the final tiling (tile_geometry.h)
  // H after each flood, the first entry for the flood of the incoming generators.
  std::vector<double> energy_history;
  std::size_t num_flooded = 0;  // triangles assigned over all floods
};

// Relaxation (2.3). In: tiling.label and tiling.generator (bad generators are replaced,
// fix_generators). Out: the flood of the final generators; the number of tiles does not
// change. Stops when a relocation moves nothing, when a generator set repeats (L-inf
// Lloyd iterations may cycle), or after max_iters. After the first iteration only the
// tiles around moved generators are flooded again (LinfFlood::reflood).
RelaxResult relax_tiling(const BackgroundMesh& mesh, const TriangleGeometry& geom,
                         const CrossField& cross, Tiling& tiling, const RelaxParams& params,
                         const Progress& progress = Progress());

// Which meta-edge of a tile drives its shift, and which way (2.4); see conform_tiling.
enum class ConformShiftRule {
  // The shortest meta-edge with exactly one corner end; the tile moves from that corner
  // towards the meta-edge's other end, closing the gap.
  close_shortest,
  // The paper's words: the longest such meta-edge; the centroid moves along a away
  // from its corner end.
  longest_away_from_corner,
  // The longest such meta-edge; the tile moves towards its corner end.
  longest_towards_corner,
  // Every tile moves across each axis of its frame towards the neighbour it shares the
  // most boundary with on each side along the other axis (by `shift` of their offset):
  // the rows and columns of tiles line up, which closes T-junctions from both sides.
  lattice,
};

struct ConformParams {
  int iters = 20;
  double settle_h = 0.15;  // as RelaxParams::settle_h
  double shift = 0.2;  // fraction of the projected meta-edge length
  ConformShiftRule rule = ConformShiftRule::close_shortest;
  MetaGraphParams graph;
  bool record_energy = false;
  // The lattice rule computes again only the tiles the last flood changed and their
  // neighbours; with this, every iteration's relocations are checked against those
  // computed over every tile (slow; for tests). A difference is an internal error.
  bool verify_relocations = false;
};

// Conforming relaxation (2.4): relaxation iterations whose relocation target is the
// tile's weighted centroid shifted, for tiles with more than 4 meta-vertices, along the
// reference direction of one meta-edge with exactly one end at a corner (corners by
// choose_corners, frame = the cross at the relocated triangle). Tiles with 3 or 4
// meta-vertices are not shifted. Stops after params.iters iterations or when the
// generators repeat.
RelaxResult conform_tiling(const BackgroundMesh& mesh, const TriangleGeometry& geom,
                           const CrossField& cross, Tiling& tiling, const ConformParams& params,
                           const Progress& progress = Progress());

// The shifted relocation targets of one conforming iteration, exposed for tests:
// per tile, the weighted centroid plus the shift (zero for tiles with <= 4
// meta-vertices).
struct ConformTargets {
  std::vector<double> x, y;       // #T target
  std::vector<double> shift_m;    // #T length of the shift
};
ConformTargets conform_targets(const BackgroundMesh& mesh, const TriangleGeometry& geom,
                               const CrossField& cross, const Tiling& tiling,
                               const MetaGraph& graph, const ConformParams& params);

}  // namespace isoquad
