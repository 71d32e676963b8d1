// The tiling stages of the paper in order: initialization by merging (2.2), discrete
// L-infinity relaxation along the cross field (2.3), conforming relaxation (2.4),
// butterfly removal by local parameterization (2.5), then re-splitting pairs of tiles
// into two quadrangles (resplit_pairs.h, not in the paper).
#pragma once

#include <string>
#include <vector>

#include "core/progress.h"
#include "fields/cross_field.h"
#include "fields/sizing_field.h"
#include "mesh/background_mesh.h"
#include "tiling/meta_graph.h"
#include "tiling/relax_tiling.h"
#include "tiling/corner_barriers.h"
#include "tiling/seed_tiling.h"
#include "tiling/tiling.h"

namespace isoquad {

enum class TilingStep { init, relax, conform, butterfly, resplit, none };

// How the tiling starts (--init): the paper's merging by compactness (2.2), or
// generators seeded front by front along the cross field (seed_tiling.h).
enum class TilingInit { merge, front };

struct TilingParams {
  TilingInit init = TilingInit::front;  // --init
  SeedParams seed;                      // of TilingInit::front
  int relax_iters = 50;         // --relax-iters: cap on L-infinity Lloyd iterations
  int conform_iters = 20;       // --conform-iters
  // --conform-rule and --conform-shift: the shift is a fraction of the offset between
  // neighbouring tiles (lattice) or of the projected meta-edge length (the other rules;
  // the paper uses 0.2 with longest_away_from_corner). From seeded fronts, lattice with
  // 0.2 gives France at about 4,500 quads 70% of angles in range and 76% of quads in
  // the size range, against 68% and 68% with 0.5.
  ConformShiftRule conform_rule = ConformShiftRule::lattice;
  double conform_shift = 0.2;
  // --butterfly-max: remove butterflies whose inner meta-edge is shorter than this times
  // h. The paper's 0.5 is relative to the tile size 2h, i.e. 1 here; longer butterflies
  // still pass the checks of 2.5 (never more irregular meta-vertices) and removing them
  // helps every measure: France at about 4,500 quads, 1 -> 3 gives quadrangle tiles
  // 50% -> 57%, angles in range 66% -> 68%, regular interior vertices 77% -> 83%.
  double butterfly_max = 3.0;
  // --resplit-rounds: rounds of re-splitting pairs of tiles into a quadrangle and the rest after
  // the butterflies (resplit_pairs.h; 0: none).
  int resplit_rounds = 10;
  MetaGraphParams graph;
  CornerBarrierParams barriers;  // --corner-barrier
  TilingStep stop_after = TilingStep::none;  // --stop-after; none: the whole job
  bool verify_repairs = false;               // RepairParams::verify_updates (tests)
  bool verify_relocations = false;           // ConformParams::verify_relocations (tests)
};

// What one step did, for the report (--report) and the summary.
struct TilingStepReport {
  std::string step;  // "init", "relax", "conform", "butterfly", "resplit"
  TilingStats stats;
  int iterations = 0;
  double energy = 0.0;  // the step's objective (relaxation: the discrete energy H)
  int butterflies_found = 0;
  int butterflies_removed = 0;
  int pairs_resplit = 0;  // the resplit step: pairs of tiles re-split into two quadrangles
  double seconds = 0.0;
};

struct TilingResult {
  Tiling tiling;
  MetaGraph graph;  // of the final tiling
  std::vector<TilingStepReport> steps;
};

// Tiles are sized 2h: the final barycentric subdivision halves every edge. The repairs
// may clear corner tags of the mesh's boundary chains that no tiling honours. Throws
// TilingError if an invariant (check_tiling) cannot be restored.
TilingResult build_tiling(BackgroundMesh& mesh, const SizingField& size,
                          const CrossField& cross, const TilingParams& params,
                          const Progress& progress = Progress());

}  // namespace isoquad
