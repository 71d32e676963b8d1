// The QGIS styles of styles/*.qml, built into the program and embedded in every mesh
// GeoPackage's `layer_styles` table, so that QGIS opens the layers styled.
#pragma once

#include <vector>

namespace isoquad {

struct MeshStyle {
  const char* layer;        // quads, vertices, boundary
  const char* name;         // style name shown in QGIS
  const char* description;
  const char* qml;          // the .qml document
  bool is_default;          // QGIS applies it when the layer is opened
};

const std::vector<MeshStyle>& mesh_styles();

}  // namespace isoquad
