// The QGIS styles of styles/*.qml, built into the program and embedded in every mesh (and
// fields) GeoPackage's `layer_styles` table, so that QGIS opens the layers styled.
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

// The styles of `isoquad fields`' GeoPackage: its triangles by size (the default) and by
// the cross field's angle.
const std::vector<MeshStyle>& fields_styles();

class VectorWriter;

// Writes the table layer_styles, as QGIS creates it, with these styles (the GeoPackage's
// geometry column `geom`).
void write_layer_styles(VectorWriter& w, const std::vector<const MeshStyle*>& styles);

}  // namespace isoquad
