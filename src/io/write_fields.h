// Writers of the background mesh with its fields, for inspection in ParaView (.vtu) or
// QGIS (.gpkg). Point data: size (metres: as given, the `isoquad fields` job passes them
// on the ground) and cross_angle (degrees, in [0, 90)).
#pragma once

#include <string>

#include "fields/cross_field.h"
#include "fields/sizing_field.h"
#include "mesh/background_mesh.h"

namespace isoquad {

// Chooses the format by extension (.vtu or .gpkg). Throws Error(usage) for another.
void write_fields(const BackgroundMesh& mesh, const SizingField& size, const CrossField& cross,
                  const std::string& crs_wkt, const std::string& path, bool overwrite);

}  // namespace isoquad
