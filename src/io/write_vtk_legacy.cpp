// Legacy VTK (ASCII, version 3.0 file format), readable by ParaView, VisIt and meshio:
// quads (cell type 9) with the per-quad metrics, points with degree and depth.
#include <fstream>
#include <iomanip>

#include "core/error.h"
#include "io/mesh_formats.h"

namespace isoquad {

void write_vtk_legacy_file(const MeshView& v, const std::string& path, const std::string& what) {
  const QuadMesh& m = *v.data->mesh;
  const QuadMetrics& q = *v.data->metrics;
  std::ofstream f(path);
  f << std::setprecision(17);
  f << "# vtk DataFile Version 3.0\nisoquad " << ISOQUAD_VERSION << " quad mesh\nASCII\n"
    << "DATASET UNSTRUCTURED_GRID\nPOINTS " << v.points.size() << " double\n";
  for (const Point2& p : v.points) f << p.x << " " << p.y << " 0\n";
  f << "CELLS " << m.quads.size() << " " << 5 * m.quads.size() << "\n";
  for (const auto& c : m.quads) f << "4 " << c[0] << " " << c[1] << " " << c[2] << " " << c[3] << "\n";
  f << "CELL_TYPES " << m.quads.size() << "\n";
  for (std::size_t i = 0; i < m.quads.size(); ++i) f << "9\n";
  f << "CELL_DATA " << m.quads.size() << "\n";
  for (const QuadField& c : quad_fields(*v.data)) {
    f << "SCALARS " << c.name << " double 1\nLOOKUP_TABLE default\n";
    for (double x : *c.values) f << x << "\n";
  }
  f << "POINT_DATA " << v.points.size() << "\nSCALARS degree int 1\nLOOKUP_TABLE default\n";
  for (int d : q.degree) f << d << "\n";
  f << "SCALARS ideal_degree int 1\nLOOKUP_TABLE default\n";
  for (int d : q.ideal_degree) f << d << "\n";
  f << "SCALARS boundary int 1\nLOOKUP_TABLE default\n";
  for (char b : q.boundary) f << static_cast<int>(b) << "\n";
  if (!v.data->depth.empty()) {
    f << "SCALARS depth double 1\nLOOKUP_TABLE default\n";
    for (double d : v.data->depth) f << d << "\n";
  }
  f.close();
  if (!f) throw Error(ErrorClass::output, "write", "'" + what + "': cannot write");
}

}  // namespace isoquad
