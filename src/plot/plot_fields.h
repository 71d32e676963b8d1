// The fields picture: h as a colour ramp over the background mesh, the crosses as short
// ticks, the boundary, and the singularities of the cross field.
#pragma once

#include <string>

#include "core/geometry.h"
#include "fields/cross_field.h"
#include "fields/sizing_field.h"
#include "mesh/background_mesh.h"

namespace isoquad {

struct PlotFieldsParams {
  std::string path;
  int width_px = 1600;
  int crosses_across = 45;  // ticks along the width
  bool overwrite = false;
};

void plot_fields(const BackgroundMesh& mesh, const SizingField& size, const CrossField& cross,
                 const std::vector<Singularity>& singularities, const PlotFieldsParams& params);

}  // namespace isoquad
