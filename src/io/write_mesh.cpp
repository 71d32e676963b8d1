#include "io/write_mesh.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>

#include "core/error.h"
#include "core/text.h"
#include "gis/atomic_output.h"
#include "gis/crs.h"
#include "gis/layer_styles.h"
#include "gis/read_mesh.h"
#include "gis/vector_writer.h"
#include "io/mesh_formats.h"
#include "io/write_vtu.h"

namespace isoquad {

namespace {

const std::map<std::string, MeshFormat>& format_names() {
  static const std::map<std::string, MeshFormat> names = {
      {"gpkg", MeshFormat::gpkg},  {"vtu", MeshFormat::vtu},   {"vtk", MeshFormat::vtk},
      {"msh", MeshFormat::msh},    {"gr3", MeshFormat::gr3},   {"nc", MeshFormat::nc},
      {"2dm", MeshFormat::sms2dm}, {"mesh", MeshFormat::mike}, {"pli", MeshFormat::pli},
      {"slf", MeshFormat::slf},    {"14", MeshFormat::fort14}, {"geojson", MeshFormat::geojson},
      {"fgb", MeshFormat::fgb}};
  return names;
}

std::string companion(const std::string& path, const char* extension) {
  return std::filesystem::path(path).replace_extension(extension).string();
}

// The quads as polygons with their metrics: the GeoPackage's layer `quads`, and the
// whole of a GeoJSON or FlatGeobuf output. Their `id` is the element's number in the
// model files (from 1), as the vertices' is the node's.
void write_quads_layer(const MeshView& v, VectorWriter& w) {
  const QuadMesh& m = *v.data->mesh;
  const auto& pts = v.points;
  const std::vector<QuadField> fields = quad_fields(*v.data);
  std::vector<FieldDef> defs = {{"id", FieldType::integer}};
  for (const QuadField& f : fields)  // a NaN time step is NULL (dry)
    defs.push_back({f.name, f.integer ? FieldType::integer : FieldType::real});
  const std::string source =
      v.data->command_line.empty() ? "" : " Made by: " + v.data->command_line;
  w.begin_layer("quads", GeometryKind::polygon, defs,
                {"isoquad mesh: quads",
                 "The mesh's quadrangles with their metrics (size_ratio: sqrt(area)/h; "
                 "orientation_deg: deviation from the cross field; angles; aspect ratio; "
                 "Gmsh's eta; D-Flow FM's orthogonality); id: the element's number in the "
                 "model files." +
                     source});
  std::vector<FieldValue> values;
  for (std::size_t i = 0; i < m.quads.size(); ++i) {
    const auto& t = m.quads[i];
    values.assign(1, FieldValue::integer(file_number(v.data->quad_ids, i)));
    for (const QuadField& f : fields) {
      const double x = (*f.values)[i];
      values.push_back(f.integer ? FieldValue::integer(static_cast<long long>(x))
                                 : FieldValue::real(x));
    }
    w.add_polygon(std::vector<Point2>{pts[t[0]], pts[t[1]], pts[t[2]], pts[t[3]]}, values);
  }
}

// GeoJSON (`geojson`: RFC 7946 when in longitudes and latitudes) or FlatGeobuf: the quads.
void write_quad_polygons(const MeshView& v, const std::string& path, const std::string& what,
                         const std::string& driver) {
  std::vector<std::string> options;
  if (driver == "GeoJSON" && v.geographic) {
    options.push_back("RFC7946=YES");
    // RFC 7946's 7 decimals of a degree round by about 1 cm: quads with sides under 10 m
    // (a flume, a harbour's details) get the decimals that keep the rounding under a
    // thousandth of their shortest side, or they could come out non-convex.
    const QuadMesh& mesh = *v.data->mesh;
    double shortest = std::numeric_limits<double>::infinity();
    for (const auto& q : mesh.quads)
      for (int k = 0; k < 4; ++k) {
        const Point2& a = mesh.points[q[k]];
        const Point2& b = mesh.points[q[(k + 1) % 4]];
        shortest = std::min(shortest, std::hypot(b.x - a.x, b.y - a.y));
      }
    if (shortest < 10.0) {
      const int decimals = std::min(
          15, 7 + static_cast<int>(std::ceil(std::log10(10.0 / std::max(shortest, 1e-8)))));
      options.push_back("COORDINATE_PRECISION=" + std::to_string(decimals));
    }
  }
  VectorWriter w(path, true, v.crs_wkt, driver, options, what);
  write_quads_layer(v, w);
  w.commit();
}

void write_gpkg(const MeshView& v, const std::string& path, const std::string& what) {
  const QuadMetrics& q = *v.data->metrics;
  const auto& pts = v.points;
  VectorWriter w(path, true, v.crs_wkt, "GPKG", {}, what);
  write_quads_layer(v, w);
  std::vector<FieldDef> vfields = {{"id", FieldType::integer},
                                   {"degree", FieldType::integer},
                                   {"ideal_degree", FieldType::integer},
                                   {"boundary", FieldType::boolean}};
  const bool depth = !v.data->depth.empty();
  if (depth) vfields.push_back({"depth", FieldType::real});
  const bool point = !v.data->vertex_point.empty();
  if (point) vfields.push_back({"point", FieldType::integer});
  const bool named = !v.data->vertex_point_name.empty();
  if (named) vfields.push_back({"point_name", FieldType::text});
  w.begin_layer("vertices", GeometryKind::point, vfields,
                {"isoquad mesh: vertices",
                 "The mesh's nodes: id, the node's number in the model files; degree, the quads "
                 "at the node (ideal_degree, what its corner of the domain asks); boundary, 1 "
                 "(true) on the boundary" +
                     std::string(depth ? "; depth in metres, positive down" : "") + "."});
  for (std::size_t i = 0; i < pts.size(); ++i) {
    std::vector<FieldValue> values = {
        FieldValue::integer(file_number(v.data->vertex_ids, i)), FieldValue::integer(q.degree[i]),
        FieldValue::integer(q.ideal_degree[i]), FieldValue::boolean(q.boundary[i] != 0)};
    if (depth) values.push_back(FieldValue::real(v.data->depth[i]));
    if (point) values.push_back(FieldValue::integer(v.data->vertex_point[i]));
    if (named) {  // NULL but at the named points' vertices
      const std::string& name = v.data->vertex_point_name[i];
      values.push_back(name.empty() ? FieldValue::none() : FieldValue::text(name));
    }
    w.add_point(pts[i], values);
  }
  w.begin_layer("boundary", GeometryKind::line,
                {{"id", FieldType::integer},
                 {"kind", FieldType::text},
                 {"loop", FieldType::integer},
                 {"island", FieldType::boolean},
                 {"num_nodes", FieldType::integer}},
                {"isoquad mesh: boundary",
                 "The mesh's boundary in segments of one kind: open (the sea's boundary, a "
                 "model's forcing) or land (a coast), in hgrid.gr3's order."});
  const auto& segs = v.data->boundary.segments;
  for (std::size_t s = 0; s < segs.size(); ++s) {
    std::vector<Point2> line;
    for (int n : segs[s].nodes) line.push_back(pts[n]);
    if (segs[s].closed && !line.empty()) line.push_back(line.front());
    w.add_line(line, {FieldValue::integer(static_cast<long long>(s)),
                      FieldValue::text(boundary_kind_name(segs[s].kind)),
                      FieldValue::integer(segs[s].loop), FieldValue::boolean(segs[s].island),
                      FieldValue::integer(static_cast<long long>(segs[s].nodes.size()))});
  }
  if (!v.data->embedded.empty()) {
    w.begin_layer("embedded", GeometryKind::line,
                  {{"id", FieldType::integer},
                   {"line", FieldType::integer},
                   {"num_nodes", FieldType::integer}},
                  {"isoquad mesh: embedded paths",
                   "Paths of quad edges along the lines of --embed (line: the line's number "
                   "in its file, from 0)."});
    const auto& paths = v.data->embedded;
    for (std::size_t k = 0; k < paths.size(); ++k) {
      std::vector<Point2> line;
      for (int n : paths[k]) line.push_back(pts[n]);
      w.add_line(line, {FieldValue::integer(static_cast<long long>(k)),
                        FieldValue::integer(v.data->embedded_line[k]),
                        FieldValue::integer(static_cast<long long>(paths[k].size()))});
    }
  }
  w.begin_layer("metadata", GeometryKind::none,
                {{"key", FieldType::text}, {"value", FieldType::text}},
                {"isoquad mesh: metadata",
                 "The run: isoquad's version, its command line, the libraries' versions, the "
                 "CRS and the quality summary."});
  auto row = [&w](const std::string& k, const std::string& val) {
    w.add_row({FieldValue::text(k), FieldValue::text(val)});
  };
  row("isoquad_version", ISOQUAD_VERSION);
  row("command_line", v.data->command_line);
  for (const auto& [k, val] : v.data->metadata) row(k, val);
  row("libraries", v.data->libraries);
  row("crs_wkt", v.crs_wkt);
  row("mesh_crs_wkt", v.data->crs_wkt);
  row("num_open_boundary_edges", std::to_string(v.data->boundary.num_open_edges));
  row("num_land_boundary_edges", std::to_string(v.data->boundary.num_land_edges));
  row("depth", depth ? "metres, positive down" : "unknown");
  for (const auto& [k, val] : v.data->quality) row("quality." + k, val);
  // QGIS reads a layer's styles from this table.
  std::vector<const LayerStyle*> styles;
  for (const LayerStyle& s : mesh_styles()) {
    if (!depth && std::string(s.layer) == "vertices" && std::string(s.name) == "depth") continue;
    if (v.data->embedded.empty() && std::string(s.layer) == "embedded") continue;
    styles.push_back(&s);
  }
  write_layer_styles(w, styles);
  w.commit();
}

// The file of open segment k (from 1) of a .pli output that has several: the path's stem
// numbered.
std::string numbered_pli_path(const std::string& path, std::size_t k) {
  std::filesystem::path p(path);
  p.replace_filename(p.stem().string() + "_" + std::to_string(k) + p.extension().string());
  return p.string();
}

// The files of a .pli output that exist: the path, and its stem numbered (stem_K.pli),
// which an earlier run may have written for another number of segments.
std::vector<std::string> existing_pli_files(const std::string& path) {
  std::vector<std::string> found;
  std::error_code ec;
  if (std::filesystem::exists(path, ec)) found.push_back(path);
  const std::filesystem::path p(path);
  const std::string stem = p.stem().string() + "_", extension = p.extension().string();
  const std::filesystem::path dir = p.has_parent_path() ? p.parent_path() : ".";
  std::vector<std::pair<unsigned long, std::string>> numbered;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.size() <= stem.size() + extension.size() || name.rfind(stem, 0) != 0 ||
        name.compare(name.size() - extension.size(), extension.size(), extension) != 0)
      continue;
    const std::string k = name.substr(stem.size(), name.size() - stem.size() - extension.size());
    if (k.size() > 9 || k.find_first_not_of("0123456789") != std::string::npos || k[0] == '0')
      continue;
    numbered.emplace_back(std::stoul(k), numbered_pli_path(path, std::stoul(k)));
  }
  std::sort(numbered.begin(), numbered.end());
  for (auto& [k, file] : numbered) found.push_back(std::move(file));
  return found;
}

// A .pli output: a file per open segment (in hgrid.gr3's order), the path itself for
// one, else the path's stem numbered from 1. With overwrite, the files of an earlier
// run that these do not replace go (a D-Flow FM model reading stem_*.pli would find a
// segment the mesh no longer has).
std::vector<std::string> write_open_boundary_polylines(const MeshView& v, const MeshOutput& o,
                                                       OutputSet& set) {
  std::vector<const BoundarySegment*> open;
  for (const BoundarySegment& s : v.data->boundary.segments)
    if (s.kind == BoundaryKind::open) open.push_back(&s);
  if (open.empty())
    throw Error(ErrorClass::meshing, "write",
                "'" + o.path +
                    "': the mesh has no open boundary to write (give --open-boundary FILE, or "
                    "--domain water with --bbox)");
  std::vector<std::string> files;
  for (std::size_t k = 0; k < open.size(); ++k) {
    files.push_back(open.size() > 1 ? numbered_pli_path(o.path, k + 1) : o.path);
    write_pli_file(v, *open[k], set.add(files.back(), o.overwrite), files.back());
  }
  if (o.overwrite)
    for (const std::string& f : existing_pli_files(o.path))
      if (std::find(files.begin(), files.end(), f) == files.end()) set.remove_on_commit(f);
  return files;
}

void write_vtu_mesh(const MeshView& mv, const std::string& path) {
  const QuadMetrics& q = *mv.data->metrics;
  VtuMesh v;
  v.points = &mv.points;
  for (const auto& t : mv.data->mesh->quads) v.cells.push_back({t[0], t[1], t[2], t[3]});
  std::vector<double> degree(q.degree.begin(), q.degree.end());
  std::vector<double> ideal(q.ideal_degree.begin(), q.ideal_degree.end());
  std::vector<double> boundary(q.boundary.begin(), q.boundary.end());
  v.point_data = {{"degree", degree}, {"ideal_degree", ideal}, {"boundary", boundary}};
  if (!mv.data->depth.empty()) v.point_data.push_back({"depth", mv.data->depth});
  for (const QuadField& f : quad_fields(*mv.data)) v.cell_data.push_back({f.name, *f.values});
  write_vtu(v, path, true);
}

}  // namespace

std::vector<QuadField> quad_fields(const MeshOutputData& data) {
  const QuadMetrics& q = *data.metrics;
  std::vector<QuadField> fields = {{"size_ratio", &q.size_ratio, "1"},
                                   {"orientation_deg", &q.orientation_deg, "degree"},
                                   {"min_angle_deg", &q.min_angle_deg, "degree"},
                                   {"max_angle_deg", &q.max_angle_deg, "degree"},
                                   {"aspect_ratio", &q.aspect_ratio, "1"},
                                   {"eta", &q.eta, "1"},
                                   {"orthogonality", &q.orthogonality, "1"}};
  if (!data.time_step_s.empty()) fields.push_back({"time_step_s", &data.time_step_s, "s"});
  if (!data.zone.empty()) fields.push_back({"zone", &data.zone, "1", true});
  fields.push_back({"irregular_corners", &q.irregular_corners, "1", true});
  for (const QuadField& f : fields)
    if (f.values->size() != data.mesh->quads.size())
      throw Error(ErrorClass::internal, "write",
                  std::string("the quads' ") + f.name + " has " + std::to_string(f.values->size()) +
                      " values for " + std::to_string(data.mesh->quads.size()) + " quads");
  return fields;
}

bool unwrap_antimeridian(const QuadMesh& mesh, std::vector<Point2>& lonlat) {
  auto spans_half_the_globe = [&](const std::vector<Point2>& ll) {
    for (const auto& q : mesh.quads) {
      double lo = ll[q[0]].x, hi = lo;
      for (int v : q) lo = std::min(lo, ll[v].x), hi = std::max(hi, ll[v].x);
      if (hi - lo > 180.0) return true;
    }
    return false;
  };
  if (!spans_half_the_globe(lonlat)) return false;
  std::vector<Point2> shifted = lonlat;
  for (Point2& p : shifted)
    if (p.x < 0) p.x += 360.0;
  if (spans_half_the_globe(shifted)) return false;  // round a pole: no cut helps
  lonlat = std::move(shifted);
  return true;
}

MeshFormat mesh_output_format(const MeshOutput& out) {
  const std::string ext = lower_case(std::filesystem::path(out.path).extension().string());
  const std::string name =
      out.format.empty() ? (ext.empty() ? "" : ext.substr(1)) : lower_case(out.format);
  // --output-format is for names without a format's extension (hgrid.txt): a .gpkg
  // written as SCHISM's text would be a file no reader takes for what it is named.
  if (!out.format.empty() && ext.size() > 1 && format_names().count(ext.substr(1)) &&
      ext.substr(1) != name)
    throw Error(ErrorClass::usage, "options",
                "'" + out.path + "': --output-format " + out.format + " under a name of format " +
                    ext + "; name it ." + name + ", or leave --output-format out");
  const auto it = format_names().find(name);
  if (it == format_names().end())
    throw Error(ErrorClass::usage, "options",
                out.format.empty()
                    ? "'" + out.path + "': unknown mesh format '" + ext +
                          "'; use .gpkg, .vtu, .vtk, .msh, .gr3, .nc, .2dm, .mesh, .pli, "
                          ".slf, .14, .geojson or .fgb (or --output-format)"
                    : "unknown --output-format '" + out.format +
                          "'; use gpkg, vtu, vtk, msh, gr3, nc, 2dm, mesh, pli, slf, 14, geojson "
                          "or fgb");
  return it->second;
}

std::vector<std::string> mesh_output_files(const MeshOutput& out) {
  const MeshFormat f = mesh_output_format(out);
  if (f == MeshFormat::gr3 && out.zones)
    return {out.path, companion(out.path, ".ll"), companion(out.path, ".prop")};
  if (f == MeshFormat::gr3) return {out.path, companion(out.path, ".ll")};
  if (f == MeshFormat::slf) return {out.path, companion(out.path, ".cli")};
  return {out.path};
}

bool mesh_output_exists(const MeshOutput& out) {
  std::error_code ec;
  for (const std::string& f : mesh_output_files(out)) {
    if (std::filesystem::exists(f, ec)) continue;
    if (mesh_output_format(out) != MeshFormat::pli ||
        !std::filesystem::exists(numbered_pli_path(f, 1), ec))
      return false;
  }
  return true;
}

void check_mesh_output_format(const std::string& path) { mesh_output_format(MeshOutput{path, "", false}); }

void check_mesh_outputs(const std::vector<MeshOutput>& outputs, const MeshWriteOptions& options) {
  if (outputs.empty()) throw Error(ErrorClass::usage, "options", "no output: give -o FILE");
  if (options.msh_groups != "kind" && options.msh_groups != "segment")
    throw Error(ErrorClass::usage, "options", "--msh-groups must be kind or segment");
  if (options.msh_version != "4.1" && options.msh_version != "2.2")
    throw Error(ErrorClass::usage, "options", "--msh-version must be 4.1 or 2.2");
  if (!options.output_crs.empty()) {
    const CrsInfo crs = parse_crs(options.output_crs, "--output-crs");
    // Planar files hold two coordinates: a geocentric or vertical CRS's would be nonsense.
    if (!crs.geographic && !crs.projected)
      throw Error(ErrorClass::crs, "options",
                  "--output-crs '" + options.output_crs + "' (" + crs.name +
                      ") is neither geographic nor projected: the outputs hold two "
                      "coordinates, longitude and latitude or planar ones");
    // A GeoJSON names its CRS by an EPSG code, and is read as lon/lat without one.
    for (const MeshOutput& o : outputs)
      if (mesh_output_format(o) == MeshFormat::geojson && epsg_code(crs.wkt) == 0)
        throw Error(ErrorClass::usage, "options",
                    "'" + o.path + "': a GeoJSON names its CRS by an EPSG code, and '" +
                        options.output_crs +
                        "' (--output-crs) has none: readers would take its coordinates for "
                        "longitudes and latitudes; write .fgb or .gpkg, or give an EPSG CRS");
  }
  OutputPathCheck probe;  // every path: exists, directory writable, given twice
  for (const MeshOutput& o : outputs) {
    if (o.path == "-")
      throw Error(ErrorClass::usage, "options",
                  "-o -: the mesh outputs are files (only --report - writes to stdout)");
    for (const std::string& f : mesh_output_files(o)) probe.add(f, o.overwrite);
    // A .pli's numbered files, written for several open segments: found now rather than
    // after the meshing.
    if (mesh_output_format(o) == MeshFormat::pli && !o.overwrite)
      for (const std::string& f : existing_pli_files(o.path)) check_output_path(f, false);
  }
}

std::vector<std::string> write_mesh_outputs(const MeshOutputData& data,
                                            const std::vector<MeshOutput>& outputs,
                                            const MeshWriteOptions& options) {
  OutputSet set;
  std::vector<std::string> files = write_mesh_outputs(data, outputs, options, set);
  set.commit_all();
  return files;
}

std::vector<std::string> write_mesh_outputs(const MeshOutputData& data,
                                            const std::vector<MeshOutput>& outputs,
                                            const MeshWriteOptions& options, OutputSet& set) {
  check_mesh_outputs(outputs, options);
  MeshView native;
  native.data = &data;
  native.points = data.mesh->points;
  native.crs_wkt = data.crs_wkt;
  MeshView reprojected;
  const MeshView* view = &native;
  if (!options.output_crs.empty()) {
    const CrsInfo to = parse_crs(options.output_crs, "--output-crs");
    reprojected = native;
    reprojected.crs_wkt = to.wkt;
    reprojected.geographic = to.geographic;
    CrsTransform t(CrsInfo{data.crs_wkt, "mesh CRS"}, to);
    const long bad = t.transform(reprojected.points);
    if (bad >= 0)
      throw Error(ErrorClass::crs, "write",
                  "vertex " + format_point(native.points[bad]) + " cannot be transformed to '" +
                      to.name + "' (--output-crs)");
    if (to.geographic) unwrap_antimeridian(*data.mesh, reprojected.points);
    view = &reprojected;
  }
  // Longitudes and latitudes (hgrid.ll, and fort.14 without --output-crs), once; in
  // [0, 360) for a mesh across the antimeridian (unwrap_antimeridian).
  std::vector<Point2> lonlat;
  auto lonlat_view = [&](const char* what) {
    if (lonlat.empty()) {
      lonlat = native.points;
      CrsTransform t(CrsInfo{data.crs_wkt, "mesh CRS"}, parse_crs("EPSG:4326", what));
      const long bad = t.transform(lonlat);
      if (bad >= 0)
        throw Error(
            ErrorClass::crs, "write",
            "vertex " + format_point(native.points[bad]) + " has no longitude and latitude");
      unwrap_antimeridian(*data.mesh, lonlat);
    }
    MeshView ll = native;
    ll.points = lonlat;
    ll.crs_wkt = parse_crs("EPSG:4326", what).wkt;
    ll.geographic = true;
    return ll;
  };
  std::vector<std::string> files;
  for (const MeshOutput& o : outputs) {
    const MeshFormat fmt = mesh_output_format(o);
    if (fmt == MeshFormat::pli) {
      for (const std::string& f : write_open_boundary_polylines(*view, o, set)) files.push_back(f);
      continue;
    }
    const std::string tmp = set.add(o.path, o.overwrite);
    files.push_back(o.path);
    switch (fmt) {
      case MeshFormat::gpkg: write_gpkg(*view, tmp, o.path); break;
      case MeshFormat::geojson:
        // GeoJSON is read as longitudes and latitudes (RFC 7946) unless --output-crs says.
        write_quad_polygons(options.output_crs.empty() ? lonlat_view("GeoJSON") : *view, tmp,
                            o.path, "GeoJSON");
        break;
      case MeshFormat::fgb:
        write_quad_polygons(*view, tmp, o.path, "FlatGeobuf");
        break;
      case MeshFormat::vtu: write_vtu_mesh(*view, tmp); break;
      case MeshFormat::vtk: write_vtk_legacy_file(*view, tmp, o.path); break;
      case MeshFormat::msh:
        write_msh_file(*view, tmp, o.path, options.msh_version, options.msh_groups == "segment");
        break;
      case MeshFormat::nc: write_ugrid_file(*view, tmp, o.path); break;
      case MeshFormat::sms2dm:
        write_2dm_file(*view, tmp, o.path);
        break;
      case MeshFormat::mike:
        write_mike_mesh_file(*view, tmp, o.path);
        break;
      case MeshFormat::gr3: {
        write_gr3_file(native, native.points, tmp, o.path, options.schism_split);
        const MeshView ll = lonlat_view("hgrid.ll");
        const std::string ll_path = companion(o.path, ".ll");
        write_gr3_file(ll, ll.points, set.add(ll_path, o.overwrite), ll_path, options.schism_split);
        files.push_back(ll_path);
        if (o.zones && !data.zone.empty()) {
          const std::string prop = companion(o.path, ".prop");
          write_prop_file(native, set.add(prop, o.overwrite), prop, options.schism_split);
          files.push_back(prop);
        }
        break;
      }
      case MeshFormat::slf: {
        const std::string cli = companion(o.path, ".cli");
        write_telemac_files(*view, tmp, o.path, set.add(cli, o.overwrite), cli);
        files.push_back(cli);
        break;
      }
      case MeshFormat::fort14:
        // ADCIRC's spherical coordinates (ICS = 2) are longitudes and latitudes.
        write_fort14_file(options.output_crs.empty() ? lonlat_view("fort.14") : *view, tmp, o.path);
        break;
      case MeshFormat::pli:
        break;  // above
    }
  }
  return files;
}

void write_mesh(const QuadMesh& mesh, const QuadMetrics& metrics, const std::string& crs_wkt,
                const MeshOutput& output) {
  MeshOutputData d;
  d.mesh = &mesh;
  d.metrics = &metrics;
  d.crs_wkt = crs_wkt;
  d.boundary = extract_boundary(mesh, PolylineIndex(), 0.0);
  write_mesh_outputs(d, {output});
}

}  // namespace isoquad
