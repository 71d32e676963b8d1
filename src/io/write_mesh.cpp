#include "io/write_mesh.h"

#include <filesystem>

#include "core/error.h"
#include "gis/gpkg_writer.h"
#include "io/write_vtu.h"

namespace isoquad {

namespace {

std::string extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

void write_gpkg(const QuadMesh& m, const QuadMetrics& q, const std::string& crs_wkt,
                const MeshOutput& out) {
  GpkgWriter w(out.path, out.overwrite, crs_wkt);
  w.begin_layer("quads", GeometryKind::polygon,
                {{"id", FieldType::integer},
                 {"size_ratio", FieldType::real},
                 {"orientation_deg", FieldType::real},
                 {"min_angle_deg", FieldType::real},
                 {"max_angle_deg", FieldType::real},
                 {"eta", FieldType::real}});
  for (std::size_t i = 0; i < m.quads.size(); ++i) {
    const auto& t = m.quads[i];
    w.add_polygon(std::vector<Point2>{m.points[t[0]], m.points[t[1]], m.points[t[2]], m.points[t[3]]},
                  {FieldValue::integer(static_cast<long long>(i)), FieldValue::real(q.size_ratio[i]),
                   FieldValue::real(q.orientation_deg[i]), FieldValue::real(q.min_angle_deg[i]),
                   FieldValue::real(q.max_angle_deg[i]), FieldValue::real(q.eta[i])});
  }
  w.begin_layer("vertices", GeometryKind::point,
                {{"id", FieldType::integer},
                 {"degree", FieldType::integer},
                 {"ideal_degree", FieldType::integer},
                 {"boundary", FieldType::integer}});
  for (std::size_t v = 0; v < m.points.size(); ++v)
    w.add_point(m.points[v], {FieldValue::integer(static_cast<long long>(v)),
                              FieldValue::integer(q.degree[v]), FieldValue::integer(q.ideal_degree[v]),
                              FieldValue::integer(q.boundary[v])});
  w.commit();
}

void write_vtu_mesh(const QuadMesh& m, const QuadMetrics& q, const MeshOutput& out) {
  VtuMesh v;
  v.points = &m.points;
  for (const auto& t : m.quads) v.cells.push_back({t[0], t[1], t[2], t[3]});
  std::vector<double> degree(q.degree.begin(), q.degree.end());
  v.point_data = {{"degree", degree}};
  v.cell_data = {{"size_ratio", q.size_ratio},
                 {"orientation_deg", q.orientation_deg},
                 {"min_angle_deg", q.min_angle_deg},
                 {"max_angle_deg", q.max_angle_deg}};
  write_vtu(v, out.path, out.overwrite);
}

}  // namespace

void check_mesh_output_format(const std::string& path) {
  const std::string ext = extension(path);
  if (ext != ".gpkg" && ext != ".vtu")
    throw Error(ErrorClass::usage, "options",
                "'" + path + "': unknown mesh format '" + ext + "'; use .gpkg or .vtu");
}

void write_mesh(const QuadMesh& m, const QuadMetrics& q, const std::string& crs_wkt,
                const MeshOutput& out) {
  check_mesh_output_format(out.path);
  if (extension(out.path) == ".gpkg")
    write_gpkg(m, q, crs_wkt, out);
  else
    write_vtu_mesh(m, q, out);
}

}  // namespace isoquad
