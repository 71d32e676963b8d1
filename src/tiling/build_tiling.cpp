#include "tiling/build_tiling.h"

#include <chrono>

#include "core/error.h"
#include "tiling/corner_barriers.h"
#include "tiling/init_tiling.h"
#include "tiling/relax_tiling.h"
#include "tiling/repair_tiling.h"
#include "tiling/resplit_pairs.h"
#include "tiling/seed_tiling.h"
#include "tiling/tile_geometry.h"
#ifdef ISOQUAD_HAVE_BUTTERFLIES
#include "tiling/butterflies.h"
#endif

namespace isoquad {

namespace {

const char* const kStage = "tiling";

void validate(const BackgroundMesh& mesh, const SizingField& size, const CrossField& cross,
              const TilingParams& params) {
  if (mesh.triangles.empty()) throw Error(ErrorClass::meshing, kStage, "the background mesh is empty");
  if (size.size_m.size() != mesh.points.size() || cross.angle_rad.size() != mesh.points.size())
    throw Error(ErrorClass::internal, kStage, "the sizing or cross field does not match the mesh");
  if (params.relax_iters < 0) throw Error(ErrorClass::usage, kStage, "--relax-iters must be >= 0");
  if (params.conform_iters < 0)
    throw Error(ErrorClass::usage, kStage, "--conform-iters must be >= 0");
  if (!(params.conform_shift >= 0.0 && params.conform_shift <= 1.0))
    throw Error(ErrorClass::usage, kStage, "--conform-shift must be in [0, 1]");
  if (!(params.butterfly_max >= 0.0))
    throw Error(ErrorClass::usage, kStage, "--butterfly-max must be >= 0");
}

}  // namespace

TilingResult build_tiling(BackgroundMesh& mesh, const SizingField& size,
                          const CrossField& cross, const TilingParams& params,
                          const Progress& progress) {
  validate(mesh, size, cross, params);
  using Clock = std::chrono::steady_clock;
  TriangleGeometry geom = triangle_geometry(mesh, size);
  geom.barrier = corner_barriers(mesh, size, params.barriers);
  RepairParams repair;
  repair.graph = params.graph;
  repair.verify_updates = params.verify_repairs;
  TilingResult result;
  Tiling& tiling = result.tiling;

  // Every step ends with the invariants restored, its meta-graph and its report.
  auto finish = [&](const char* step, Clock::time_point start, int iterations) {
    repair_tiling(mesh, geom, tiling, repair, &result.graph);
    TilingStepReport r;
    r.step = step;
    r.stats = tiling_stats(result.graph);
    r.iterations = iterations;
    r.energy = tiling_energy(mesh, geom, cross, tiling);
    r.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    result.steps.push_back(r);
    return &result.steps.back();
  };

  // A step starts by freeing the meta-graph of the step before (only the last step's is
  // returned): the step and its repair build their own.
  auto begin_step = [&] {
    result.graph = MetaGraph();
    return Clock::now();
  };

  // The shares of the progress follow France at a uniform 3 km: the initialization a
  // tenth, the relaxation a fifth, the conforming a quarter, the butterflies a third.

  // 2.2: merging by compactness, or frontal seeding.
  auto start = begin_step();
  progress.report("tiling init", 0.0);
  tiling = params.init == TilingInit::merge ? init_tiling(mesh, geom)
                                            : seed_tiling(mesh, geom, size, cross, params.seed);
  finish("init", start, 0);
  if (params.stop_after == TilingStep::init) return result;

  // 2.3: L-infinity relaxation.
  start = begin_step();
  RelaxParams relax;
  relax.max_iters = params.relax_iters;
  const RelaxResult relaxed =
      relax_tiling(mesh, geom, cross, tiling, relax, progress.slice(0.1, 0.3));
  finish("relax", start, relaxed.iterations);
  if (params.stop_after == TilingStep::relax) return result;

  // 2.4: conforming relaxation.
  start = begin_step();
  ConformParams conform;
  conform.iters = params.conform_iters;
  conform.shift = params.conform_shift;
  conform.rule = params.conform_rule;
  conform.graph = params.graph;
  conform.verify_relocations = params.verify_relocations;
  const RelaxResult conformed =
      conform_tiling(mesh, geom, cross, tiling, conform, progress.slice(0.3, 0.55));
  finish("conform", start, conformed.iterations);
  if (params.stop_after == TilingStep::conform) return result;

#ifdef ISOQUAD_HAVE_BUTTERFLIES
  // 2.5: butterfly removal by local parameterization.
  start = begin_step();
  progress.report("tiling butterflies", 0.55);
  ButterflyParams butterfly;
  butterfly.max_length_ratio = params.butterfly_max;
  butterfly.graph = params.graph;
  const ButterflyStats removed =
      remove_butterflies(mesh, size, tiling, butterfly, progress.slice(0.55, 0.9));
  TilingStepReport* r = finish("butterfly", start, 0);
  r->butterflies_found = removed.found;
  r->butterflies_removed = removed.removed;
#endif
  if (params.stop_after == TilingStep::butterfly) return result;

  // After 2.5: pairs of tiles re-split into a quadrangle and the rest when that leaves
  // fewer irregular vertices.
  if (params.resplit_rounds > 0) {
    start = begin_step();
    progress.report("tiling pairs", 0.9);
    ResplitParams resplit;
    resplit.max_rounds = params.resplit_rounds;
    resplit.graph = params.graph;
    const ResplitStats pairs = resplit_pairs(mesh, tiling, resplit, progress.slice(0.9, 1.0));
    TilingStepReport* rr = finish("resplit", start, pairs.rounds);
    rr->pairs_resplit = pairs.resplit;
  }
  progress.report("tiling", 1.0);
  return result;
}

}  // namespace isoquad
