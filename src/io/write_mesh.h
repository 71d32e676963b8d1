// Writers of the quad mesh: GeoPackage (layers `quads` with per-quad metrics and
// `vertices` with degree) and VTK XML (.vtu, cell data size ratio, orientation
// deviation, min and max angle; point data degree), chosen by extension.
#pragma once

#include <string>

#include "quad/quad_mesh.h"
#include "quad/quad_quality.h"

namespace isoquad {

struct MeshOutput {
  std::string path;
  bool overwrite = false;
};

// Throws Error(usage) for an unknown extension, Error(output) when writing fails. The
// file is written atomically.
void write_mesh(const QuadMesh& mesh, const QuadMetrics& metrics, const std::string& crs_wkt,
                const MeshOutput& output);

// Fails early (Error(usage)) for an extension write_mesh does not know.
void check_mesh_output_format(const std::string& path);

}  // namespace isoquad
