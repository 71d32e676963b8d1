// Writes the cleaned planar domain as a GeoPackage polygon layer.
#pragma once

#include <string>

#include "core/geometry.h"

namespace isoquad {

struct WriteDomainParams {
  std::string path;            // .gpkg
  std::string layer = "domain";
  bool overwrite = false;
};

// One feature per component: polygon with holes, fields component, area_m2,
// perimeter_m, num_holes, num_vertices. Written atomically. Throws Error(output).
void write_domain_gpkg(const Domain& domain, const WriteDomainParams& params);

}  // namespace isoquad
