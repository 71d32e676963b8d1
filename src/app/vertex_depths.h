// The depths of a quad mesh's vertices for the ocean-model outputs: sampled from one or
// more bathymetry rasters in priority order, the vertices without a value in any (outside
// them, or next to nodata) given the depth of the nearest vertex with one (along the
// mesh's edges), and depths shallower than a minimum raised to it.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "gis/raster_field.h"
#include "quad/quad_mesh.h"

namespace isoquad {

struct VertexDepths {
  std::vector<double> depth;         // #P metres, positive down
  std::size_t num_filled = 0;        // vertices that took the nearest vertex's depth
  double max_fill_distance_m = 0.0;  // the longest path from one to the vertex it took
  std::size_t num_raised = 0;        // depths raised to min_depth_m
  double min_m = 0.0, max_m = 0.0;   // the range of the depths written
};

// Throws Error(input) when no vertex has a value in any of the rasters (an extent or CRS
// that misses the domain).
VertexDepths vertex_depths(const RasterStack& rasters, const QuadMesh& mesh,
                           std::optional<double> min_depth_m);

}  // namespace isoquad
