// Projection of the selected polygons to the planar meshing CRS, in metres.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/geometry.h"
#include "gis/crs.h"

namespace isoquad {

struct ProjectParams {
  // --dst-crs. Empty: the source's own CRS when it is projected in metres, conformal over
  // the domain and within 1% of the ground's scale there (UTM, a national conformal CRS:
  // the mesh in the coordinates of the user's other data), else an automatic local
  // projection; "local": that local projection whatever the source; "utm": the UTM zone
  // of the domain's centre (WGS 84).
  std::string dst_crs;
};

struct ProjectResult {
  Domain domain;                          // in the meshing CRS, metres
  std::optional<LocalProjection> local;   // set when the projection was chosen here
  bool source_kept = false;               // the source's projected CRS is the meshing CRS
  // Why a projected source's CRS was not kept ("its scale strays by 49% from the
  // ground's over the domain"); empty otherwise.
  std::string source_not_kept;
  std::string warning;  // "utm": the domain reaches where the zone's scale strays by over 1%
};

// Throws Error(crs) when the target CRS is not projected in metres or a point cannot be
// transformed.
ProjectResult project_domain(const std::vector<Polygon>& polygons, const CrsInfo& source_crs,
                             const ProjectParams& params);

}  // namespace isoquad
