// The QGIS styles of styles/*.qml, built into the program and embedded in the `layer_styles`
// table of every GeoPackage isoquad writes (mesh, fields, domain), so that QGIS opens the
// layers styled.
#pragma once

#include <vector>

namespace isoquad {

struct LayerStyle {
  const char* layer;  // quads, vertices, boundary, triangles, domain...
  const char* name;   // style name shown in QGIS
  const char* description;
  const char* qml;  // the .qml document
  bool is_default;  // QGIS applies it when the layer is opened
};

const std::vector<LayerStyle>& mesh_styles();

// The styles of `isoquad fields`' GeoPackage: its triangles by size (the default) and by
// the cross field's angle.
const std::vector<LayerStyle>& fields_styles();

// The styles of `isoquad domain`'s GeoPackage: the domain and its open boundary.
const std::vector<LayerStyle>& domain_styles();

class VectorWriter;

// Writes the table layer_styles, as QGIS creates it, with these styles (the GeoPackage's
// geometry column `geom`).
void write_layer_styles(VectorWriter& w, const std::vector<const LayerStyle*>& styles);

}  // namespace isoquad
