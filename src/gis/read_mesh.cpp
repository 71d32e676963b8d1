#include "gis/read_mesh.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <unordered_set>

#include <ogrsf_frmts.h>

#include "core/error.h"
#include "core/text.h"
#include "gis/atomic_output.h"
#include "gis/crs.h"
#include "gis/gdal_env.h"
#include "gis/mesh_outline.h"
#include "gis/read_mesh_formats.h"

namespace isoquad {
namespace mesh_readers {

// Runs of boundary faces of one open kind along the outline's loops, as node lists (a
// whole loop repeats its first node) into mesh.open_boundaries: kind(a, b) is 0 where
// the face from node a to node b is land, else the open boundary's kind (a code, a
// group), so that two open boundaries that meet stay two. A mesh without an outline has
// none here (false): where the outline is needed, its error comes then.
bool open_runs(ReadMesh& mesh, const std::string& path,
               const std::function<long long(int, int)>& face_kind) {
  std::vector<std::vector<int>> loops;
  try {
    loops = mesh_outline(mesh.points, mesh.quads, mesh.triangles, path, mesh.point_ids);
  } catch (const Error&) {
    return false;
  }
  for (const std::vector<int>& loop : loops) {
    const std::size_t n = loop.size();
    auto kind = [&](std::size_t i) { return face_kind(loop[i % n], loop[(i + 1) % n]); };
    // Start where the kind changes, so that no run wraps round the loop's start.
    std::size_t start = 0;
    while (start < n && kind(start) == kind(start + n - 1)) ++start;
    if (start == n) {  // one kind all round
      if (kind(0) == 0) continue;
      std::vector<int> whole = loop;
      whole.push_back(loop.front());
      mesh.open_boundaries.push_back(std::move(whole));
      continue;
    }
    for (std::size_t k = 0; k < n;) {
      const long long code = kind(start + k);
      std::size_t end = k;
      while (end < n && kind(start + end) == code) ++end;
      if (code != 0) {
        std::vector<int> run;
        for (std::size_t i = k; i <= end; ++i) run.push_back(loop[(start + i) % n]);
        mesh.open_boundaries.push_back(std::move(run));
      }
      k = end;
    }
  }
  return true;
}

// The open boundaries from the nodes' codes (0 inside, 1 land, 2, 3... open: a MIKE
// mesh's), by MIKE's rule: a boundary face is land when either end is, else open with
// its end node's code.
void open_boundaries_from_codes(const std::vector<long long>& codes, const std::string& path,
                                ReadMesh& mesh) {
  if (std::none_of(codes.begin(), codes.end(), [](long long c) { return c > 1; })) return;
  open_runs(mesh, path, [&](int a, int b) { return codes[a] > 1 && codes[b] > 1 ? codes[b] : 0; });
}

}  // namespace mesh_readers

namespace {

using namespace mesh_readers;

// A layer of polygons, each a triangle or a quadrangle (isoquad's GeoPackage layer
// `quads`, or elements exported as polygons): the layer `quads` when there is one, else
// the first of polygons; the nodes are the rings' vertices, the same where their
// coordinates are (so that two polygons that share a corner share the node); the CRS the
// layer's.
void read_polygon_layer(const std::string& path, ReadMesh& mesh) {
  const GdalDataset ds = open_vector_dataset(path, "read");
  OGRLayer* layer = ds->GetLayerByName("quads");
  const auto polygonal = [](OGRwkbGeometryType type) {
    return wkbFlatten(type) == wkbPolygon || wkbFlatten(type) == wkbMultiPolygon;
  };
  for (int i = 0; i < ds->GetLayerCount() && !layer; ++i)
    if (polygonal(ds->GetLayer(i)->GetGeomType())) layer = ds->GetLayer(i);
  // A layer of several geometry types (a GeoJSON of Polygons and MultiPolygons) whose
  // first feature is a polygon.
  for (int i = 0; i < ds->GetLayerCount() && !layer; ++i) {
    OGRLayer* candidate = ds->GetLayer(i);
    if (wkbFlatten(candidate->GetGeomType()) != wkbUnknown) continue;
    candidate->ResetReading();
    const OGRFeatureUniquePtr first(candidate->GetNextFeature());
    if (first && first->GetGeometryRef() && polygonal(first->GetGeometryRef()->getGeometryType()))
      layer = candidate;
  }
  auto fail = [&](const std::string& what) {
    throw Error(ErrorClass::input, "read", "'" + path + "': " + what);
  };
  if (!layer) fail("no layer of polygons (the quads or triangles of a mesh)");
  const std::string name = layer->GetName();
  if (const OGRSpatialReference* srs = layer->GetSpatialRef()) mesh.crs = crs_from_srs(*srs).wkt;
  std::map<std::pair<double, double>, int> nodes;
  std::vector<int> corners;
  layer->ResetReading();
  for (auto& feature : *layer) {
    const std::string which = "layer '" + name + "', feature " + std::to_string(feature->GetFID());
    const OGRGeometry* g = feature->GetGeometryRef();
    if (!g) fail(which + " has no geometry");
    if (const auto* multi = dynamic_cast<const OGRMultiPolygon*>(g)) {
      if (multi->getNumGeometries() != 1) fail(which + " is a multipolygon of several parts");
      g = multi->getGeometryRef(0);
    }
    const auto* polygon = dynamic_cast<const OGRPolygon*>(g);
    if (!polygon || !polygon->getExteriorRing()) fail(which + " is not a polygon");
    if (polygon->getNumInteriorRings() > 0) fail(which + " has a hole");
    const OGRLinearRing* ring = polygon->getExteriorRing();
    int n = ring->getNumPoints();
    if (n > 1 && ring->getX(0) == ring->getX(n - 1) && ring->getY(0) == ring->getY(n - 1)) --n;
    if (n != 3 && n != 4)
      fail(which + " has " + std::to_string(n) +
           " corners: only triangles and quadrangles are read");
    corners.clear();
    for (int i = 0; i < n; ++i) {
      const Point2 p{ring->getX(i), ring->getY(i)};
      if (!std::isfinite(p.x) || !std::isfinite(p.y))
        fail(which + " has a corner that is not finite");
      const auto [it, added] =
          nodes.emplace(std::make_pair(p.x, p.y), static_cast<int>(mesh.points.size()));
      if (added) mesh.points.push_back(p);
      corners.push_back(it->second);
    }
    for (std::size_t i = 0; i < corners.size(); ++i)
      for (std::size_t j = i + 1; j < corners.size(); ++j)
        if (corners[i] == corners[j]) fail(which + " has the same corner twice");
    if (n == 3)
      mesh.triangles.push_back({corners[0], corners[1], corners[2]});
    else
      mesh.quads.push_back({corners[0], corners[1], corners[2], corners[3]});
  }
}

}  // namespace

std::string mesh_file_format(const std::string& path) {
  const std::filesystem::path p(path);
  const std::string ext = lower_case(p.extension().string());
  const std::string name = lower_case(p.filename().string());
  if (ext == ".gr3" || ext == ".ll") return "gr3";
  if (ext == ".14" || ext == ".grd" || name == "fort.14") return "14";
  if (ext == ".2dm") return "2dm";
  if (ext == ".msh") return "msh";
  if (ext == ".mesh") return "mesh";
  if (ext == ".nc") return "nc";
  if (ext == ".slf" || ext == ".srf") return "slf";
  if (ext == ".vtu") return "vtu";
  if (ext == ".vtk") return "vtk";
  if (ext == ".gpkg" || ext == ".shp" || ext == ".geojson" || ext == ".fgb") return "polygons";
  throw Error(
      ErrorClass::usage, "options",
      "'" + path +
          "': a mesh to measure is a .gr3 or .ll (SCHISM), .14 or .grd (ADCIRC), .2dm "
          "(SMS), .msh (Gmsh, ASCII), .mesh (MIKE 21/3 FM), .nc (UGRID, D-Flow FM's net "
          "file), .slf (TELEMAC's Selafin), .vtu or .vtk (VTK) or a layer of polygons, each "
          "a triangle or a quadrangle (.gpkg: isoquad's layer 'quads', .shp, .geojson, "
          ".fgb)");
}

bool is_mesh_file(const std::string& path) {
  std::string format;
  try {
    format = mesh_file_format(path);
  } catch (const Error&) {
    return false;
  }
  if (format != "nc") return format != "polygons";
  return netcdf_holds_mesh(path);
}

namespace {

std::string describe(const ReadMesh::CurveGroup& g) {
  return std::to_string(g.tag) + (g.name.empty() ? "" : " \"" + g.name + "\"");
}

}  // namespace

std::string curve_groups_kind(const ReadMesh& mesh, bool plural) {
  if (mesh.format == "2dm") return plural ? "nodestrings" : "nodestring";
  return plural ? "physical groups of curves" : "physical group of curves";
}

std::string curve_groups_text(const ReadMesh& mesh) {
  constexpr std::size_t kShown = 10;
  std::string text;
  for (std::size_t k = 0; k < mesh.curve_groups.size() && k < kShown; ++k)
    text += (text.empty() ? "" : ", ") + describe(mesh.curve_groups[k]);
  if (mesh.curve_groups.size() > kShown)
    text += "... (" + std::to_string(mesh.curve_groups.size()) + " in all)";
  return text;
}

void open_boundaries_from_groups(ReadMesh& mesh, const std::vector<std::string>& groups,
                                 const std::string& path) {
  if (mesh.format != "msh" && mesh.format != "2dm")
    throw Error(ErrorClass::usage, "read",
                "'" + path +
                    "' is neither a Gmsh .msh nor an SMS .2dm: only these name lines of the "
                    "boundary (physical groups of curves, nodestrings)");
  const std::string kind_name = curve_groups_kind(mesh, false);
  std::vector<const ReadMesh::CurveGroup*> open;
  if (groups.empty()) {
    for (const ReadMesh::CurveGroup& g : mesh.curve_groups)
      if (lower_case(g.name).rfind("open", 0) == 0) open.push_back(&g);
  }
  for (const std::string& given : groups) {
    const auto it = std::find_if(mesh.curve_groups.begin(), mesh.curve_groups.end(),
                                 [&](const ReadMesh::CurveGroup& g) {
                                   return g.name == given || std::to_string(g.tag) == given;
                                 });
    if (it == mesh.curve_groups.end()) {
      const std::string there = curve_groups_text(mesh);
      throw Error(ErrorClass::usage, "read",
                  "'" + path + "' has no " + kind_name + " '" + given + "' (" +
                      (there.empty() ? "it has none" : "it has " + there) + ")");
    }
    // A group named twice (by its name and its number): once.
    if (std::find(open.begin(), open.end(), &*it) == open.end()) open.push_back(&*it);
  }
  mesh.open_boundaries.clear();
  if (open.empty()) return;
  // Each face of the outline's open kind: the index of its group among those open, + 1.
  std::map<std::pair<int, int>, long long> kind;
  for (std::size_t k = 0; k < open.size(); ++k)
    for (const auto& e : open[k]->edges)
      kind.emplace(std::minmax(e[0], e[1]), static_cast<long long>(k) + 1);
  std::vector<bool> on_outline(open.size(), false);
  const bool traced = open_runs(mesh, path, [&](int a, int b) -> long long {
    const auto it = kind.find(std::minmax(a, b));
    if (it == kind.end()) return 0;
    on_outline[it->second - 1] = true;
    return it->second;
  });
  if (groups.empty() || !traced) return;
  for (std::size_t k = 0; k < open.size(); ++k)
    if (!on_outline[k])
      throw Error(ErrorClass::usage, "read",
                  "'" + path + "': no line of " + kind_name + " " + describe(*open[k]) +
                      " lies on the mesh's outline, where an open boundary is");
}

ReadMesh read_mesh(const std::string& path) {
  note_input_file(path);  // no output may replace it
  ReadMesh mesh;
  mesh.format = mesh_file_format(path);
  if (!std::filesystem::is_regular_file(path))
    throw Error(ErrorClass::input, "read", "'" + path + "': no such mesh file");
  if (mesh.format == "nc") {
    read_netcdf(path, mesh);
  } else if (mesh.format == "slf") {
    read_selafin(path, mesh);
    read_telemac_cli(path, mesh);
  } else if (mesh.format == "vtu" || mesh.format == "vtk") {
    read_vtk(path, mesh);
  } else if (mesh.format == "polygons") {
    read_polygon_layer(path, mesh);
  } else {
    LineReader r(path);
    if (mesh.format == "gr3" || mesh.format == "14")
      read_gr3(r, mesh);
    else if (mesh.format == "2dm")
      read_2dm(r, mesh);
    else if (mesh.format == "msh")
      read_msh(r, mesh);
    else
      read_mike(r, mesh);
  }
  if (mesh.quads.empty() && mesh.triangles.empty())
    throw Error(ErrorClass::input, "read",
                "'" + path + "': the mesh has no triangle or quadrangle");
  // An element number given twice (an SMS .2dm's E4Q 7 and E3T 7; SCHISM and ADCIRC
  // read a .gr3's elements in order, whatever their numbers) names no one element: the
  // elements are then numbered in order, as those models do.
  const auto repeated_element_id = [&mesh]() -> std::optional<long long> {
    std::unordered_set<long long> seen;
    for (const std::vector<long long>* ids : {&mesh.quad_ids, &mesh.triangle_ids})
      for (long long id : *ids)
        if (!seen.insert(id).second) return id;
    return std::nullopt;
  };
  if (const std::optional<long long> id = repeated_element_id()) {
    mesh.notes.push_back("'" + path + "': element number " + std::to_string(*id) +
                         " is given to two elements: its elements are numbered from 1 in "
                         "the file's order instead");
    mesh.quad_ids.clear();
    mesh.triangle_ids.clear();
  }
  if (std::any_of(mesh.node_values.begin(), mesh.node_values.end(),
                  [](double v) { return std::isnan(v); }))
    mesh.node_values.clear();
  // SCHISM's hgrid.ll is hgrid.gr3 in longitudes and latitudes.
  if (lower_case(std::filesystem::path(path).extension().string()) == ".ll") mesh.crs = "EPSG:4326";
  return mesh;
}

}  // namespace isoquad
