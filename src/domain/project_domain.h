// Projection of the selected polygons to the planar meshing CRS, in metres.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/geometry.h"
#include "gis/crs.h"

namespace isoquad {

struct ProjectParams {
  std::string dst_crs;  // --dst-crs; empty: an automatic local projection
};

struct ProjectResult {
  Domain domain;                          // in the meshing CRS, metres
  std::optional<LocalProjection> local;   // set when the projection was chosen here
};

// Throws Error(crs) when the target CRS is not projected in metres or a point cannot be
// transformed.
ProjectResult project_domain(const std::vector<Polygon>& polygons, const CrsInfo& source_crs,
                             const ProjectParams& params);

}  // namespace isoquad
