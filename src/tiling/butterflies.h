// Butterfly removal by local parameterization (paper, section 2.5): a short meta-edge
// between two degree-3 meta-vertices shared by four tiles A, B, C, D is replaced by one
// degree-4 meta-vertex, by mapping the four tiles onto a square (mean value
// coordinates) and relabelling their triangles along four non-crossing edge paths.
#pragma once

#include "core/progress.h"
#include "fields/sizing_field.h"
#include "mesh/background_mesh.h"
#include "tiling/meta_graph.h"
#include "tiling/tiling.h"

namespace isoquad {

struct ButterflyParams {
  // Only inner meta-edges shorter than this times h (at their midpoint) are removed.
  double max_length_ratio = 0.5;
  MetaGraphParams graph;
};

struct ButterflyStats {
  int found = 0;    // butterflies met (short inner meta-edge, two degree-3 ends, 4 tiles)
  int removed = 0;  // successfully reparameterized
};

// Removes butterflies in order of increasing inner meta-edge length (dynamic priority
// queue). A butterfly that fails any check is left unchanged. Keeps the invariants of
// check_tiling. Reports progress as stage "tiling butterflies".
ButterflyStats remove_butterflies(const BackgroundMesh& mesh, const SizingField& size,
                                  Tiling& tiling, const ButterflyParams& params,
                                  const Progress& progress = Progress());

}  // namespace isoquad
