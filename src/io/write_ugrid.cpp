// UGRID-1.0 netCDF (CF-1.8): mesh topology variable `mesh` with node coordinates, face
// node connectivity (1-based, fill value -1), edge node connectivity, the CRS as a
// grid-mapping variable (crs_wkt, the CF attributes for common projections, the EPSG
// code as its value), per-face metrics, and depth and bed level on nodes when known:
// a net file for D-Flow FM too.
#include <netcdf.h>
#include <ogr_spatialref.h>

#include <cstdlib>
#include <cstring>
#include <map>

#include "core/error.h"
#include "gis/crs.h"
#include "gis/gdal_env.h"
#include "io/mesh_formats.h"

namespace isoquad {

namespace {

class NcFile {
 public:
  NcFile(const std::string& path, std::string what) : what_(std::move(what)) {
    check(nc_create(path.c_str(), NC_CLOBBER | NC_NETCDF4, &id_), "cannot create");
  }
  ~NcFile() {
    if (id_ >= 0) nc_close(id_);
  }
  void check(int status, const std::string& doing) const {
    if (status != NC_NOERR)
      throw Error(ErrorClass::output, "write", "'" + what_ + "': " + doing + ": " + nc_strerror(status));
  }
  int dim(const char* name, std::size_t n) {
    int d = -1;
    check(nc_def_dim(id_, name, n, &d), std::string("dimension ") + name);
    return d;
  }
  int var(const char* name, nc_type type, std::vector<int> dims) {
    int v = -1;
    check(nc_def_var(id_, name, type, static_cast<int>(dims.size()), dims.data(), &v),
          std::string("variable ") + name);
    return v;
  }
  void text(int var, const char* name, const std::string& value) {
    check(nc_put_att_text(id_, var, name, value.size(), value.c_str()), std::string("attribute ") + name);
  }
  void integer(int var, const char* name, int value) {
    check(nc_put_att_int(id_, var, name, NC_INT, 1, &value), std::string("attribute ") + name);
  }
  void close() {
    const int id = id_;
    id_ = -1;
    check(nc_close(id), "cannot finish");
  }
  void real(int var, const char* name, double value) {
    check(nc_put_att_double(id_, var, name, NC_DOUBLE, 1, &value), std::string("attribute ") + name);
  }
  int id() const { return id_; }

 private:
  int id_ = -1;
  std::string what_;
};

// CF grid-mapping attributes for the common cases (lon/lat and the projections isoquad
// uses or users pick: transverse Mercator, stereographic, Mercator, Lambert conformal
// conic), the way GDAL's netCDF driver writes them; other projections keep only
// crs_wkt, which GDAL and CF-1.7+ readers use first.
void write_cf_grid_mapping(NcFile& nc, int var, const std::string& wkt) {
  OGRSpatialReference srs;
  if (wkt.empty() || srs.importFromWkt(wkt.c_str()) != OGRERR_NONE) return;
  OGRErr err = OGRERR_NONE;
  const double a = srs.GetSemiMajor(&err);
  if (err == OGRERR_NONE) nc.real(var, "semi_major_axis", a);
  const double inv_f = srs.GetInvFlattening(&err);
  if (err == OGRERR_NONE) nc.real(var, "inverse_flattening", inv_f);
  nc.real(var, "longitude_of_prime_meridian", srs.GetPrimeMeridian());
  if (srs.IsGeographic()) {
    nc.text(var, "grid_mapping_name", "latitude_longitude");
    return;
  }
  const char* method = srs.GetAttrValue("PROJECTION");
  if (!srs.IsProjected() || !method) return;
  auto parm = [&srs](const char* name) { return srs.GetNormProjParm(name, 0.0); };
  auto false_origin = [&] {
    nc.real(var, "false_easting", parm(SRS_PP_FALSE_EASTING));
    nc.real(var, "false_northing", parm(SRS_PP_FALSE_NORTHING));
  };
  if (!std::strcmp(method, SRS_PT_TRANSVERSE_MERCATOR)) {
    nc.text(var, "grid_mapping_name", "transverse_mercator");
    nc.real(var, "scale_factor_at_central_meridian", parm(SRS_PP_SCALE_FACTOR));
    nc.real(var, "longitude_of_central_meridian", parm(SRS_PP_CENTRAL_MERIDIAN));
    nc.real(var, "latitude_of_projection_origin", parm(SRS_PP_LATITUDE_OF_ORIGIN));
    false_origin();
  } else if (!std::strcmp(method, SRS_PT_OBLIQUE_STEREOGRAPHIC) ||
             !std::strcmp(method, SRS_PT_STEREOGRAPHIC)) {
    // CF has no oblique (double) stereographic, isoquad's automatic projection: we use
    // GDAL's name for it, as GDAL's netCDF driver writes and reads it.
    const bool oblique = !std::strcmp(method, SRS_PT_OBLIQUE_STEREOGRAPHIC);
    nc.text(var, "grid_mapping_name", oblique ? "oblique_stereographic" : "stereographic");
    nc.real(var, "scale_factor_at_projection_origin", parm(SRS_PP_SCALE_FACTOR));
    if (oblique) nc.real(var, "scale_factor_at_central_meridian", parm(SRS_PP_SCALE_FACTOR));
    nc.real(var, oblique ? "longitude_of_central_meridian" : "longitude_of_projection_origin",
            parm(SRS_PP_CENTRAL_MERIDIAN));
    nc.real(var, "latitude_of_projection_origin", parm(SRS_PP_LATITUDE_OF_ORIGIN));
    false_origin();
  } else if (!std::strcmp(method, SRS_PT_MERCATOR_1SP)) {
    nc.text(var, "grid_mapping_name", "mercator");
    nc.real(var, "longitude_of_projection_origin", parm(SRS_PP_CENTRAL_MERIDIAN));
    nc.real(var, "scale_factor_at_projection_origin", parm(SRS_PP_SCALE_FACTOR));
    false_origin();
  } else if (!std::strcmp(method, SRS_PT_LAMBERT_CONFORMAL_CONIC_2SP)) {
    nc.text(var, "grid_mapping_name", "lambert_conformal_conic");
    const double parallels[2] = {parm(SRS_PP_STANDARD_PARALLEL_1), parm(SRS_PP_STANDARD_PARALLEL_2)};
    nc.check(nc_put_att_double(nc.id(), var, "standard_parallel", NC_DOUBLE, 2, parallels),
             "attribute standard_parallel");
    nc.real(var, "longitude_of_central_meridian", parm(SRS_PP_CENTRAL_MERIDIAN));
    nc.real(var, "latitude_of_projection_origin", parm(SRS_PP_LATITUDE_OF_ORIGIN));
    false_origin();
  }
}

}  // namespace

void write_ugrid_file(const MeshView& v, const std::string& path, const std::string& what) {
  const std::lock_guard<std::recursive_mutex> netcdf(netcdf_mutex());
  const QuadMesh& m = *v.data->mesh;
  // Unique edges, in order of first appearance around the quads.
  std::map<std::pair<int, int>, int> edge_id;
  std::vector<int> edges;
  for (const auto& c : m.quads)
    for (int i = 0; i < 4; ++i) {
      const int a = c[i], b = c[(i + 1) % 4];
      if (edge_id.emplace(std::make_pair(std::min(a, b), std::max(a, b)), int(edges.size() / 2)).second) {
        edges.push_back(a);
        edges.push_back(b);
      }
    }
  NcFile nc(path, what);
  const int g = NC_GLOBAL;
  nc.text(g, "Conventions", "CF-1.8 UGRID-1.0");
  nc.text(g, "title", "isoquad quad mesh");
  nc.text(g, "source", std::string("isoquad ") + ISOQUAD_VERSION);
  if (!v.data->command_line.empty()) nc.text(g, "history", v.data->command_line);
  const int dn = nc.dim("n_node", m.points.size());
  const int df = nc.dim("n_face", m.quads.size());
  const int de = nc.dim("n_edge", edges.size() / 2);
  const int d2 = nc.dim("two", 2);
  const int d4 = nc.dim("max_face_nodes", 4);

  const int mesh = nc.var("mesh", NC_INT, {});
  nc.text(mesh, "cf_role", "mesh_topology");
  nc.text(mesh, "long_name", "Topology data of 2D unstructured mesh");
  nc.integer(mesh, "topology_dimension", 2);
  nc.text(mesh, "node_coordinates", "mesh_node_x mesh_node_y");
  nc.text(mesh, "face_node_connectivity", "mesh_face_nodes");
  nc.text(mesh, "face_dimension", "n_face");
  nc.text(mesh, "edge_node_connectivity", "mesh_edge_nodes");
  nc.text(mesh, "edge_dimension", "n_edge");

  // The CRS's variable by the names D-Flow FM writes and its readers look for (its older
  // ones by these names only; a lon/lat net found by neither is read as metres).
  const char* const crs_name = v.geographic ? "wgs84" : "projected_coordinate_system";
  const int crs = nc.var(crs_name, NC_INT, {});
  nc.text(crs, "crs_wkt", v.crs_wkt);
  nc.text(crs, "spatial_ref", v.crs_wkt);  // GDAL's name
  nc.text(crs, "wkt", v.crs_wkt);          // Deltares' name, which QGIS's reader (MDAL) reads
  write_cf_grid_mapping(nc, crs, v.crs_wkt);
  // D-Flow FM reads the EPSG code from the variable's value, then from this attribute
  // (0: none; it treats every CRS but EPSG:4326 as Cartesian).
  const int epsg = epsg_code(v.crs_wkt);
  nc.integer(crs, "epsg", epsg);

  // A variable on the nodes, in the CRS of `crs`.
  auto node_var = [&](const char* name, const char* standard_name, const char* units) {
    const int id = nc.var(name, NC_DOUBLE, {dn});
    nc.text(id, "standard_name", standard_name);
    nc.text(id, "units", units);
    nc.text(id, "mesh", "mesh");
    nc.text(id, "location", "node");
    nc.text(id, "grid_mapping", crs_name);
    return id;
  };
  const int vx = node_var("mesh_node_x", v.geographic ? "longitude" : "projection_x_coordinate",
                          v.geographic ? "degrees_east" : "m");
  const int vy = node_var("mesh_node_y", v.geographic ? "latitude" : "projection_y_coordinate",
                          v.geographic ? "degrees_north" : "m");

  const int vf = nc.var("mesh_face_nodes", NC_INT, {df, d4});
  nc.text(vf, "cf_role", "face_node_connectivity");
  nc.text(vf, "long_name", "Maps every face to its corner nodes (counter-clockwise)");
  // Numbered from 1, as D-Flow FM's older readers assume (the others read start_index).
  nc.integer(vf, "start_index", 1);
  const int fill = -1;
  nc.check(nc_def_var_fill(nc.id(), vf, 0, &fill), "fill value");
  const int ve = nc.var("mesh_edge_nodes", NC_INT, {de, d2});
  nc.text(ve, "cf_role", "edge_node_connectivity");
  nc.text(ve, "long_name", "Maps every edge to the two nodes it connects");
  nc.integer(ve, "start_index", 1);

  const std::vector<QuadField> face_vars = quad_fields(*v.data);
  std::vector<int> face_var_ids;
  for (const QuadField& fv : face_vars) {
    const int id = nc.var(fv.name, NC_DOUBLE, {df});
    nc.text(id, "mesh", "mesh");
    nc.text(id, "location", "face");
    nc.text(id, "units", fv.units);
    face_var_ids.push_back(id);
  }
  int vd = -1, vz = -1;
  if (!v.data->depth.empty()) {
    vd = node_var("depth", "sea_floor_depth_below_geoid", "m");
    nc.text(vd, "long_name", "depth (positive down)");  // the name QGIS shows
    nc.text(vd, "positive", "down");
    // The bed level by the name D-Flow FM's and HYDROLIB's net readers look for.
    vz = node_var("mesh_node_z", "altitude", "m");
    nc.text(vz, "long_name", "bed level (minus the depth)");
    nc.text(vz, "positive", "up");
  }
  nc.check(nc_enddef(nc.id()), "cannot finish the header");

  std::vector<double> xs, ys;
  for (const Point2& p : v.points) xs.push_back(p.x), ys.push_back(p.y);
  nc.check(nc_put_var_double(nc.id(), vx, xs.data()), "node x");
  nc.check(nc_put_var_double(nc.id(), vy, ys.data()), "node y");
  nc.check(nc_put_var_int(nc.id(), crs, &epsg), crs_name);
  std::vector<int> faces;
  for (const auto& c : m.quads)
    for (int n : c) faces.push_back(n + 1);
  for (int& n : edges) ++n;
  if (!faces.empty()) nc.check(nc_put_var_int(nc.id(), vf, faces.data()), "faces");
  if (!edges.empty()) nc.check(nc_put_var_int(nc.id(), ve, edges.data()), "edges");
  for (std::size_t k = 0; k < face_vars.size(); ++k) {
    const QuadField& fv = face_vars[k];
    if (!fv.values->empty())
      nc.check(nc_put_var_double(nc.id(), face_var_ids[k], fv.values->data()), fv.name);
  }
  if (vd >= 0) {
    nc.check(nc_put_var_double(nc.id(), vd, v.data->depth.data()), "depth");
    std::vector<double> z;
    for (double d : v.data->depth) z.push_back(-d + 0.0);
    nc.check(nc_put_var_double(nc.id(), vz, z.data()), "bed level");
  }
  nc.close();
}

}  // namespace isoquad
