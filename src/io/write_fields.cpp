#include "io/write_fields.h"

#include <cmath>
#include <filesystem>

#include "core/error.h"
#include "gis/layer_styles.h"
#include "gis/vector_writer.h"
#include "io/write_vtu.h"

namespace isoquad {

namespace {

double degrees(double rad) { return rad * 180.0 / M_PI; }

void write_vtu_fields(const BackgroundMesh& mesh, const SizingField& size, const CrossField& cross,
                      const std::string& path, bool overwrite) {
  VtuMesh v;
  v.points = &mesh.points;
  for (const auto& t : mesh.triangles) v.cells.push_back({t[0], t[1], t[2]});
  VtuArray angle{"cross_angle", {}};
  for (double a : cross.angle_rad) angle.values.push_back(degrees(a));
  v.point_data = {{"size", size.size_m}, angle};
  write_vtu(v, path, overwrite);
}

void write_gpkg_fields(const BackgroundMesh& mesh, const SizingField& size, const CrossField& cross,
                       const std::string& crs_wkt, const std::string& path, bool overwrite) {
  VectorWriter w(path, overwrite, crs_wkt);
  w.begin_layer("vertices", GeometryKind::point,
                {{"size_m", FieldType::real},
                 {"cross_angle_deg", FieldType::real},
                 {"boundary_chain", FieldType::integer}},
                {"isoquad fields: vertices",
                 "The background mesh's vertices: the size h (m), the cross field's angle "
                 "(degrees), and the boundary chain each lies on (-1 inside)."});
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
    w.add_point(mesh.points[i], {FieldValue::real(size.size_m[i]),
                                 FieldValue::real(degrees(cross.angle_rad[i])),
                                 FieldValue::integer(mesh.boundary_chain_of_vertex[i])});
  w.begin_layer("triangles", GeometryKind::polygon,
                {{"size_m", FieldType::real}, {"cross_angle_deg", FieldType::real}},
                {"isoquad fields: triangles",
                 "The background mesh's triangles: the size h (m) and the cross field's angle "
                 "(degrees) at their centroids."});
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    const std::array<double, 3> centre{1.0 / 3, 1.0 / 3, 1.0 / 3};
    w.add_polygon(std::vector<Point2>{mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]},
                  {FieldValue::real(size.at(mesh, static_cast<int>(f), centre)),
                   FieldValue::real(degrees(cross_angle_at(mesh, cross, static_cast<int>(f), centre)))});
  }
  std::vector<const LayerStyle*> styles;
  for (const LayerStyle& s : fields_styles()) styles.push_back(&s);
  write_layer_styles(w, styles);
  w.commit();
}

}  // namespace

void write_fields(const BackgroundMesh& mesh, const SizingField& size, const CrossField& cross,
                  const std::string& crs_wkt, const std::string& path, bool overwrite) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".vtu")
    write_vtu_fields(mesh, size, cross, path, overwrite);
  else if (ext == ".gpkg")
    write_gpkg_fields(mesh, size, cross, crs_wkt, path, overwrite);
  else
    throw Error(ErrorClass::usage, "options",
                "'" + path + "': the fields are written as .vtu or .gpkg");
}

}  // namespace isoquad
