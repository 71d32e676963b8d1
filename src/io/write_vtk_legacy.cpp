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
  std::vector<std::pair<const char*, const std::vector<double>*>> cell = {
      {"size_ratio", &q.size_ratio},
      {"orientation_deg", &q.orientation_deg},
      {"min_angle_deg", &q.min_angle_deg},
      {"max_angle_deg", &q.max_angle_deg},
      {"eta", &q.eta},
      {"orthogonality", &q.orthogonality}};
  if (!v.data->time_step_s.empty()) cell.push_back({"time_step_s", &v.data->time_step_s});
  if (!v.data->zone.empty()) cell.push_back({"zone", &v.data->zone});
  for (const auto& [name, values] : cell) {
    f << "SCALARS " << name << " double 1\nLOOKUP_TABLE default\n";
    for (double x : *values) f << x << "\n";
  }
  f << "POINT_DATA " << v.points.size() << "\nSCALARS degree int 1\nLOOKUP_TABLE default\n";
  for (int d : q.degree) f << d << "\n";
  if (!v.data->depth.empty()) {
    f << "SCALARS depth double 1\nLOOKUP_TABLE default\n";
    for (double d : v.data->depth) f << d << "\n";
  }
  f.close();
  if (!f) throw Error(ErrorClass::output, "write", "'" + what + "': cannot write");
}

}  // namespace isoquad
