// The smoothing's sweeps over the quad mesh's vertices (paper, section 2.7): the
// untangling that makes quads convex, the field-aligned sweeps and the angle sweeps.
// Every move keeps the quads around the vertex convex. The parameters and their
// measurements are SmoothParams' (smooth_quads.h).
#pragma once

#include <memory>
#include <vector>

#include "fields/cross_field.h"
#include "fields/sizing_field.h"
#include "mesh/background_mesh.h"
#include "mesh/locate.h"
#include "quad/quad_mesh.h"
#include "quad/quad_topology.h"
#include "quad/smooth_quads.h"

namespace isoquad {

// Moves the vertices of quads not more convex than params.min_convexity until they are
// (params.untangle_iterations sweeps at most); with `only`, just those quads (ascending
// ids). With may_free_corners, domain corners may slide along the boundary at last.
void untangle(const BackgroundMesh& bg, QuadMesh& m, const QuadTopology& t,
              const SmoothParams& params, SmoothStats& stats, bool may_free_corners = true,
              const std::vector<int>* only = nullptr);

// The field-aligned sweeps (SmoothParams::aligned_iterations).
void aligned_sweeps(const BackgroundMesh& bg, QuadMesh& m, const QuadTopology& t,
                    const SizingField& size, const CrossField& cross, const SmoothParams& params,
                    const Progress& progress = Progress());

// What the angle sweeps set up over the whole mesh, the same for every call on one
// background mesh and one topology (the positions may change between calls): the point
// locator (built at the first call that needs it) and the vertices' colouring. Calls
// with `only` that share one (the embedding's rounds) then cost what their vertices do.
struct SweepSetup {
  std::unique_ptr<TriangleLocator> locator;
  std::vector<std::vector<int>> colours;  // empty until the first call
};

// The angle sweeps (SmoothParams::angle_iterations, or `iterations`); with `only`, the
// vertices it marks move, the others stay. The mesh is the same with any number of
// threads, and with or without `setup`.
void angle_sweeps(const BackgroundMesh& bg, QuadMesh& m, const QuadTopology& t,
                  const SmoothParams& params, const CrossField* cross, const SizingField* size,
                  const std::vector<char>* only = nullptr, int iterations = -1,
                  const Progress& progress = Progress(), SweepSetup* setup = nullptr);

// Lowers the D-Flow FM orthogonality of the links over params.max_orthogonality: in up
// to params.orthogonality_rounds rounds, each interior corner of their quads takes the
// move (of 8 directions and 3 lengths, a share of its shortest edge) that most lowers
// how far the links of the quads round it are over the bound (summed), when every quad
// round it stays more convex than params.lift_convexity. Returns the links still over
// (`before`: those over at the start).
int orthogonality_sweeps(QuadMesh& m, const QuadTopology& t, const SmoothParams& params,
                         int* before = nullptr);

}  // namespace isoquad
