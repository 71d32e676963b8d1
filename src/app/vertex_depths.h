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

class MapScale;

// The time step each quad allows an explicit model at a gravity-wave Courant number C:
// C times its width (the shorter distance between the midpoints of opposite sides) over
// sqrt(g d), d its deepest vertex's depth. (D-Flow FM's default CFLMax is 0.7.)
struct TimeSteps {
  double courant = 1.0;
  std::vector<double> per_quad_s;       // #Q; NaN for a dry quad (no vertex deeper than 0)
  double min_s = 0.0, median_s = 0.0;   // over the wet quads; 0 when none is wet
  int limiting_quad = -1;               // the quad of min_s
  double width_m = 0.0, depth_m = 0.0;  // its width and depth
  std::size_t num_wet = 0;
  std::size_t num_under_target = 0;  // wet quads under the target time step
};

struct VertexDepths {
  std::vector<double> depth;         // #P metres, positive down
  std::size_t num_filled = 0;        // vertices that took the nearest vertex's depth
  double max_fill_distance_m = 0.0;  // the longest path from one to the vertex it took
  std::size_t num_raised = 0;        // depths raised to min_depth_m
  std::size_t num_dry = 0;           // vertices at depth 0 or above (before min_depth_m)
  bool averaged = false;             // means over squares round the vertices
  std::string kept;                  // RasterStack::kept_text() of the sources read
  double min_m = 0.0, max_m = 0.0;   // the range of the depths written
  TimeSteps time_steps;              // courant_time_steps() of the depths written
};

// With `average`, each vertex's depth is the rasters' mean over the square round it as wide
// as the mean length of its quads' sides at it (RasterStack::mean_over: a raster's
// bilinear value where it is not finer than that). Throws Error(input) when no vertex
// has a value in any of the rasters (an extent or CRS that misses the domain).
VertexDepths vertex_depths(const RasterStack& rasters, const QuadMesh& mesh,
                           std::optional<double> min_depth_m, bool average = false);

// `depth`: #P, as written. `target_s` > 0: count the wet quads whose time step is under it.
// `scale`: the meshing CRS's, by which the widths are divided (their length on the ground)
// where the sizes were multiplied by it.
TimeSteps courant_time_steps(const QuadMesh& mesh, const std::vector<double>& depth,
                             double courant = 1.0, double target_s = 0.0,
                             const MapScale* scale = nullptr);

}  // namespace isoquad
