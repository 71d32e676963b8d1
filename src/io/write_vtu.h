// VTK XML unstructured grid (.vtu) writer for planar meshes, binary (base64, inline).
// Readable by ParaView, VTK and meshio.
#pragma once

#include <array>
#include <ostream>
#include <string>
#include <vector>

#include "core/geometry.h"

namespace isoquad {

struct VtuArray {
  std::string name;
  std::vector<double> values;  // one per point or per cell
};

struct VtuMesh {
  const std::vector<Point2>* points = nullptr;  // #V, z = 0
  // #C cells; each cell's vertex ids. Triangles (3) and quads (4) are supported.
  std::vector<std::vector<int>> cells;
  std::vector<VtuArray> point_data;  // each #V
  std::vector<VtuArray> cell_data;   // each #C
};

// Writes atomically (temporary file, then rename). Throws Error(output).
void write_vtu(const VtuMesh& mesh, const std::string& path, bool overwrite);

// The document, written onto `out` as it is encoded.
void write_vtu_document(const VtuMesh& mesh, std::ostream& out);

}  // namespace isoquad
