// The tiling pictures of the paper (Figures 3, 4, 7, 9): tiles filled, meta-edges
// drawn, meta-vertices incident to 3 tiles (blue) and to 5 or more (red) marked.
#pragma once

#include <string>

#include "mesh/background_mesh.h"
#include "tiling/meta_graph.h"
#include "tiling/tiling.h"

namespace isoquad {

struct PlotTilingParams {
  std::string path;
  int width_px = 1600;
  bool overwrite = false;
};

void plot_tiling(const BackgroundMesh& mesh, const Tiling& tiling, const MetaGraph& graph,
                 const PlotTilingParams& params);

}  // namespace isoquad
