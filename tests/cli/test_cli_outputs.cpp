// `isoquad mesh` with every output format in one run, on a small water domain (a bbox
// of sea with an island and a peninsula that crosses the bbox's east side), read back
// by real readers: GDAL (GeoPackage layers, CRS, counts, styles, metadata), the gmsh
// binary, meshio (legacy VTK), python3-netcdf4 (UGRID) and our SCHISM parser; open
// boundary edges on the bbox, depths from a bathymetry raster, all-or-nothing outputs.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <iomanip>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include "core/geometry.h"
#include "gis/gdal_env.h"
#include "support/test_support.h"
#include "support/write_raster.h"

using namespace isoquad::test;

namespace {

const double kBox[4] = {-4.6, 48.2, -4.4, 48.35};

std::string water_input(const TempDir& d) {
  const std::string path = d.file("land.geojson");
  write_file(path, geojson_polygons({"[[[-4.45,48.25],[-4.3,48.25],[-4.3,48.3],[-4.45,48.3],[-4.45,48.25]]]",
                                     "[[[-4.55,48.22],[-4.52,48.22],[-4.52,48.25],[-4.55,48.25],[-4.55,48.22]]]"}));
  return path;
}

double depth_at(double lon, double lat) { return 1000.0 * (lon + 4.7) + 200.0 * (lat - 48.1); }

// A GeoTIFF in lon/lat, depth linear in lon and lat (so bilinear sampling is exact),
// from 4.7 W eastwards over `nx` pixels of 0.01 degrees (40: past the bbox).
std::string bathymetry(const TempDir& d, int nx = 40) {
  return write_geotiff(d.file("dem" + std::to_string(nx) + ".tif"), -4.7, 48.45, 0.01, nx, 35, 4326,
                       depth_at);
}

struct Gr3 {
  std::vector<std::array<double, 3>> nodes;
  std::size_t num_elements = 0;
  std::vector<std::vector<int>> elements;      // node numbers from 1
  std::size_t open_total = 0, land_total = 0;  // the files' NETA and NVEL
  std::vector<std::vector<int>> open, land;
  std::vector<int> land_flags;
};

Gr3 parse_gr3(const std::string& path) {
  std::istringstream in(read_file(path));
  Gr3 g;
  std::string line;
  std::getline(in, line);
  std::size_t ne = 0, np = 0;
  in >> ne >> np;
  g.num_elements = ne;
  for (std::size_t i = 0; i < np; ++i) {
    int id;
    std::array<double, 3> n;
    in >> id >> n[0] >> n[1] >> n[2];
    g.nodes.push_back(n);
  }
  for (std::size_t e = 0; e < ne; ++e) {
    int id, k;
    in >> id >> k;
    EXPECT_TRUE(k == 3 || k == 4) << path;
    std::vector<int> element(std::max(0, k));
    for (int& v : element) in >> v;
    g.elements.push_back(element);
  }
  std::size_t n = 0;
  in >> n;
  std::getline(in, line);
  in >> g.open_total;
  std::getline(in, line);
  for (std::size_t s = 0; s < n; ++s) {
    std::size_t m = 0;
    in >> m;
    std::getline(in, line);
    std::vector<int> seg(m);
    for (int& v : seg) in >> v;
    g.open.push_back(seg);
  }
  in >> n;
  std::getline(in, line);
  in >> g.land_total;
  std::getline(in, line);
  for (std::size_t s = 0; s < n; ++s) {
    std::size_t m = 0;
    int flag = -1;
    in >> m >> flag;
    std::getline(in, line);
    std::vector<int> seg(m);
    for (int& v : seg) in >> v;
    g.land.push_back(seg);
    g.land_flags.push_back(flag);
  }
  EXPECT_FALSE(in.fail()) << path;
  return g;
}

// A vector file written by isoquad, opened with GDAL (null when it cannot be).
GDALDataset* open_vector(const std::string& path) {
  isoquad::ensure_gdal_registered();
  return static_cast<GDALDataset*>(
      GDALOpenEx(path.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr));
}

bool on_bbox(double lon, double lat, double tol) {
  return std::abs(lon - kBox[0]) < tol || std::abs(lon - kBox[2]) < tol ||
         std::abs(lat - kBox[1]) < tol || std::abs(lat - kBox[3]) < tol;
}

// stderr without the warning that a .gr3 has quads SCHISM's manual asks split (most
// meshes have some), for the tests that expect no other warning.
std::string without_schism_warning(const std::string& err) {
  std::istringstream in(err);
  std::string out, line;
  while (std::getline(in, line))
    if (line.find(" quads fail SCHISM's checks ") == std::string::npos) out += line + "\n";
  return out;
}

// A JSON report's unsigned integer `"key": N` (-1 when absent).
long report_count(const std::string& report, const std::string& key) {
  const std::size_t at = report.find("\"" + key + "\": ");
  return at == std::string::npos ? -1 : std::stol(report.substr(at + key.size() + 4));
}

// `isoquad mesh` on the water box (kBox) with the `extra` arguments.
CliResult mesh_box(const TempDir& dir, const std::vector<std::string>& extra) {
  std::vector<std::string> args = {"mesh",  water_input(dir), "--domain",
                                   "water", "--bbox",         "-4.6,48.2,-4.4,48.35"};
  args.insert(args.end(), extra.begin(), extra.end());
  return run_cli(args, dir);
}

// The same at 800 m with the `extra` arguments.
CliResult mesh_box_800(const TempDir& dir, std::vector<std::string> extra) {
  extra.insert(extra.begin(), {"--size", "800"});
  return mesh_box(dir, extra);
}

// A GeoTIFF in lon/lat over the whole water box and round it, `value` everywhere.
std::string uniform_raster(const TempDir& dir, const std::string& name, double value) {
  return write_geotiff(dir.file(name), -4.8, 48.5, 0.15, 4, 4, 4326,
                       [value](double, double) { return value; });
}

// The same at 800 m with the bathymetry (depths), quiet, with the `extra` arguments (the
// outputs).
CliResult mesh_water_box(const TempDir& dir, const std::vector<std::string>& extra) {
  std::vector<std::string> args = {"--size", "800", "--bathymetry", bathymetry(dir), "-q"};
  args.insert(args.end(), extra.begin(), extra.end());
  return mesh_box(dir, args);
}

// QGIS's mesh reader (MDAL) on each file: a line "vertices faces [sides] lowest-z" per
// file, then "lonlat X Y": the last file's first vertex in EPSG:4326 (by the file's CRS).
// python3-qgis is one of the project's dependencies (tools/install-deps.sh): without it
// the check fails.
std::string read_mesh_layers_in_qgis(const TempDir& dir, const std::vector<std::string>& paths) {
  return python_check(
      dir,
      "import os, sys\n"
      "os.environ.setdefault('QT_QPA_PLATFORM', 'offscreen')\n"
      "from qgis.core import *\n"
      "app = QgsApplication([], False)\n"
      "app.initQgis()\n"
      "for path in sys.argv[1:]:\n"
      "    layer = QgsMeshLayer(path, 'm', 'mdal')\n"
      "    assert layer.isValid()\n"
      "    mesh = QgsMesh()\n"
      "    layer.dataProvider().populateMesh(mesh)\n"
      "    sides = {len(mesh.face(i)) for i in range(mesh.faceCount())}\n"
      "    low = min(mesh.vertex(i).z() for i in range(mesh.vertexCount()))\n"
      "    print(mesh.vertexCount(), mesh.faceCount(), sorted(sides), '%.3f' % low)\n"
      "to = QgsCoordinateTransform(layer.crs(), QgsCoordinateReferenceSystem('EPSG:4326'),\n"
      "                            QgsProject.instance())\n"
      "p = to.transform(QgsPointXY(mesh.vertex(0).x(), mesh.vertex(0).y()))\n"
      "print('lonlat %.7f %.7f' % (p.x(), p.y()))\n",
      paths);
}

}  // namespace

TEST(CliOutputs, EveryFormatInOneRunLoadsInItsReader) {
  TempDir dir;
  const std::string input = water_input(dir);
  const std::string dem = bathymetry(dir);
  const CliResult r = run_cli(
      {"mesh", input, "--domain", "water", "--bbox", "-4.6,48.2,-4.4,48.35", "--size", "800",
       "--bathymetry", dem, "-o", dir.file("m.gpkg"), "-o", dir.file("m.msh"), "-o",
       dir.file("hgrid.gr3"), "-o", dir.file("m.vtk"), "-o", dir.file("m.nc"), "-o",
       dir.file("m.vtu"), "--output-crs", "EPSG:4326"},
      dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Every vertex has a depth; the one warning is of SCHISM's quads (checked below).
  EXPECT_EQ(without_schism_warning(r.err).find("warning"), std::string::npos) << r.err;

  // SCHISM: the projected grid and its lon/lat companion.
  const Gr3 g = parse_gr3(dir.file("hgrid.gr3"));
  const Gr3 ll = parse_gr3(dir.file("hgrid.ll"));
  const std::size_t np = g.nodes.size(), ne = g.num_elements;
  ASSERT_GT(ne, 100u);
  ASSERT_EQ(ll.nodes.size(), np);
  EXPECT_EQ(ll.open, g.open);
  EXPECT_EQ(ll.land, g.land);
  for (std::size_t i = 0; i < np; ++i) {
    EXPECT_GT(std::abs(g.nodes[i][0]), 1.0);  // metres, not degrees
    EXPECT_NEAR(ll.nodes[i][2], depth_at(ll.nodes[i][0], ll.nodes[i][1]), 0.01) << i;
    EXPECT_EQ(g.nodes[i][2], ll.nodes[i][2]);
  }
  // One open segment (the peninsula cuts the east side off from the rest of the sea
  // boundary only at its two ends), the mainland coast and the island (flag 1).
  ASSERT_EQ(g.open.size(), 1u);
  ASSERT_EQ(g.land.size(), 2u);
  EXPECT_EQ(g.land_flags, (std::vector<int>{0, 1}));
  // Within 1e-4 degrees (11 m): simplification (200 m here) keeps the bbox corners but
  // may replace a curved parallel by chords.
  for (int n : g.open[0]) EXPECT_TRUE(on_bbox(ll.nodes[n - 1][0], ll.nodes[n - 1][1], 1e-4)) << n;
  for (const auto& seg : g.land) {
    int inside = 0;
    for (int n : seg) inside += !on_bbox(ll.nodes[n - 1][0], ll.nodes[n - 1][1], 1e-3);
    EXPECT_GE(inside, static_cast<int>(seg.size()) - 2);  // at most the two ends on the bbox
  }
  // The open segment runs counter-clockwise (sea on its left) from where the peninsula's
  // north coast meets the east side, round by north, west and south, to its south coast.
  const auto& first = ll.nodes[g.open[0].front() - 1];
  const auto& last = ll.nodes[g.open[0].back() - 1];
  EXPECT_NEAR(first[0], -4.4, 1e-5);
  EXPECT_NEAR(first[1], 48.3, 1e-6);
  EXPECT_NEAR(last[0], -4.4, 1e-5);
  EXPECT_NEAR(last[1], 48.25, 1e-6);

  // GeoPackage through GDAL: layers, CRS (EPSG:4326 by --output-crs), counts, depth,
  // boundary kinds, metadata, styles.
  GDALDataset* ds = open_vector(dir.file("m.gpkg"));
  ASSERT_NE(ds, nullptr);
  OGRLayer* quads = ds->GetLayerByName("quads");
  OGRLayer* vertices = ds->GetLayerByName("vertices");
  OGRLayer* boundary = ds->GetLayerByName("boundary");
  OGRLayer* metadata = ds->GetLayerByName("metadata");
  OGRLayer* styles = ds->GetLayerByName("layer_styles");
  ASSERT_TRUE(quads && vertices && boundary && metadata && styles);
  EXPECT_EQ(quads->GetFeatureCount(), static_cast<GIntBig>(ne));
  EXPECT_EQ(vertices->GetFeatureCount(), static_cast<GIntBig>(np));
  for (OGRLayer* l : {quads, vertices, boundary}) {
    ASSERT_NE(l->GetSpatialRef(), nullptr);
    EXPECT_STREQ(l->GetSpatialRef()->GetAuthorityCode(nullptr), "4326");
  }
  for (auto& f : *vertices) {
    const OGRPoint* p = f->GetGeometryRef()->toPoint();
    const int id = static_cast<int>(f->GetFieldAsInteger64("id")) - 1;  // numbered from 1
    EXPECT_NEAR(p->getX(), ll.nodes[id][0], 1e-9);
    EXPECT_NEAR(p->getY(), ll.nodes[id][1], 1e-9);
    EXPECT_NEAR(f->GetFieldAsDouble("depth"), ll.nodes[id][2], 1e-5);
  }
  // Flags are GeoPackage booleans (check boxes in QGIS), not numbers.
  for (auto [layer, field] : {std::pair{vertices, "boundary"}, std::pair{boundary, "island"},
                              std::pair{styles, "useAsDefault"}}) {
    const OGRFieldDefn* def =
        layer->GetLayerDefn()->GetFieldDefn(layer->GetLayerDefn()->GetFieldIndex(field));
    ASSERT_NE(def, nullptr) << field;
    EXPECT_EQ(def->GetSubType(), OFSTBoolean) << field;
  }
  std::map<std::string, int> kinds;
  int islands = 0;
  for (auto& f : *boundary) {
    islands += f->GetFieldAsInteger("island");
    const std::string kind = f->GetFieldAsString("kind");
    ++kinds[kind];
    const OGRLineString* line = f->GetGeometryRef()->toLineString();
    if (kind == "open") {
      for (int i = 0; i < line->getNumPoints(); ++i)
        EXPECT_TRUE(on_bbox(line->getX(i), line->getY(i), 1e-4));
    }
  }
  EXPECT_EQ(kinds["open"], 1);
  EXPECT_EQ(kinds["land"], 2);
  EXPECT_EQ(islands, 1);  // the outer loop is not an island
  std::map<std::string, std::string> meta;
  for (auto& f : *metadata) meta[f->GetFieldAsString("key")] = f->GetFieldAsString("value");
  EXPECT_FALSE(meta["isoquad_version"].empty());
  EXPECT_EQ(meta["libraries"].rfind("CGAL ", 0), 0u) << meta["libraries"];
  EXPECT_NE(meta["libraries"].find(std::string(", GDAL ") + GDALVersionInfo("RELEASE_NAME")),
            std::string::npos)
      << meta["libraries"];
  EXPECT_NE(meta["command_line"].find("--output-crs EPSG:4326"), std::string::npos);
  EXPECT_NE(meta["crs_wkt"].find("WGS 84"), std::string::npos);
  EXPECT_EQ(meta["quality.num_quads"], std::to_string(ne));
  const std::string schism_failures = meta["quality.schism_failures"];
  ASSERT_FALSE(schism_failures.empty());
  EXPECT_EQ(r.err.find("warning: " + dir.file("hgrid.gr3") + ": " + schism_failures +
                       " quads fail SCHISM's checks") != std::string::npos,
            schism_failures != "0")
      << r.err;
  // The mesh's area against the domain's (a water domain of a bbox with islands).
  const double mesh_area = std::stod(meta["quality.mesh_area_m2"]);
  EXPECT_NEAR(mesh_area, std::stod(meta["quality.domain_area_m2"]), 0.01 * mesh_area);
  EXPECT_GE(std::stod(meta["quality.boundary_departure_max_m"]), 0.0);
  // Each quad's largest D-Flow FM orthogonality: over the quads, the report's largest.
  double orthogonality = -1;
  for (auto& f : *quads)
    orthogonality = std::max(orthogonality, f->GetFieldAsDouble("orthogonality"));
  EXPECT_NEAR(orthogonality, std::stod(meta["quality.dflowfm_orthogonality_max"]),
              1e-5);  // 6 digits
  EXPECT_GT(orthogonality, 0.0);
  std::set<std::string> styled;
  for (auto& f : *styles) {
    const std::string qml = f->GetFieldAsString("styleQML");
    EXPECT_NE(qml.find("<renderer-v2"), std::string::npos);
    EXPECT_EQ(std::string(f->GetFieldAsString("f_geometry_column")), "geom");
    if (f->GetFieldAsInteger("useAsDefault")) styled.insert(f->GetFieldAsString("f_table_name"));
  }
  EXPECT_EQ(styled, (std::set<std::string>{"quads", "vertices", "boundary"}));
  GDALClose(ds);

  // Gmsh reads the .msh; it writes it back as 2.2 with the same elements and groups.
  const CliResult gm = run_cli_program(
      "gmsh", {dir.file("m.msh"), "-0", "-format", "msh22", "-o", dir.file("re.msh")}, dir);
  ASSERT_EQ(gm.exit_code, 0) << gm.out << gm.err;
  std::istringstream in(read_file(dir.file("re.msh")));
  std::string line;
  std::map<std::pair<int, int>, std::size_t> count;
  while (std::getline(in, line))
    if (line == "$Elements") {
      int n = 0;
      in >> n;
      for (int i = 0; i < n; ++i) {
        int id, type, ntags, phys;
        in >> id >> type >> ntags >> phys;
        std::getline(in, line);
        ++count[{type, phys}];
      }
    }
  std::size_t open_edges = 0, land_edges = 0;
  for (const auto& s : g.open) open_edges += s.size() - 1;
  for (std::size_t s = 0; s < g.land.size(); ++s) land_edges += g.land[s].size() - (g.land_flags[s] ? 0 : 1);
  EXPECT_EQ(count[std::make_pair(3, 3)], ne);
  EXPECT_EQ(count[std::make_pair(1, 2)], open_edges);
  EXPECT_EQ(count[std::make_pair(1, 1)], land_edges);

  // Legacy VTK and VTU in meshio, UGRID in netCDF4: the same counts, lon/lat, depth, time
  // steps.
  python_check(dir,
               "import sys, meshio, netCDF4, numpy as np\n"
               "np_, ne = int(sys.argv[3]), int(sys.argv[4])\n"
               "for f in sys.argv[1:3]:\n"
               "    m = meshio.read(f)\n"
               "    assert m.points.shape[0] == np_ and m.cells_dict['quad'].shape == (ne, 4), f\n"
               "    assert -4.61 < m.points[:, 0].min() and m.points[:, 0].max() < -4.39, f\n"
               "    assert np.ravel(m.point_data['depth']).min() > 100, f\n"
               "    steps = np.ravel(m.cell_data['time_step_s'][0])\n"
               "    assert steps.shape == (ne,) and (steps > 0).all(), f\n"
               "d = netCDF4.Dataset(sys.argv[5])\n"
               "assert np.allclose(d['time_step_s'][:], steps, rtol=1e-12)\n"
               "assert d['time_step_s'].units == 's'\n"
               "assert d.dimensions['n_node'].size == np_ and d.dimensions['n_face'].size == ne\n"
               "assert d['mesh_node_x'].standard_name == 'longitude'\n"
               "assert 'WGS 84' in d['wgs84'].crs_wkt\n"
               "assert d['wgs84'].grid_mapping_name == 'latitude_longitude'\n"
               "faces = d['mesh_face_nodes'][:]\n"
               "assert faces.min() == 1 and faces.max() == np_\n"
               "assert d['wgs84'][:] == 4326 and d['wgs84'].epsg == 4326\n"
               "assert np.allclose(d['mesh_node_z'][:], -d['depth'][:])\n",
               {dir.file("m.vtk"), dir.file("m.vtu"), std::to_string(np), std::to_string(ne),
                dir.file("m.nc")});
}

TEST(CliOutputs, OpenBoundaryLinesGiveTheSeaBoundary) {
  // The water box with --open-boundary: a line along its west side only. That side is
  // the one open segment (every point on it), the bbox's other sides are land; lines
  // that follow none of the domain's boundary stop the run before anything is written.
  TempDir dir;
  const std::string input = water_input(dir);
  auto line_file = [&dir](const std::string& name, const std::string& coordinates) {
    const std::string path = dir.file(name);
    write_file(path, R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},)"
                     R"("geometry":{"type":"LineString","coordinates":)" +
                         coordinates + "}}]}");
    return path;
  };
  auto run = [&](const std::string& lines, const std::string& output) {
    return run_cli({"mesh", input, "--domain", "water", "--bbox", "-4.6,48.2,-4.4,48.35", "--size",
                    "800", "-q", "--output-crs", "EPSG:4326", "--open-boundary", lines, "-o",
                    dir.file(output), "--report", dir.file(output + ".json")},
                   dir);
  };
  // The open boundary's segments in the GeoPackage, as lon/lat points.
  auto open_segments = [&dir](const std::string& output) {
    std::unique_ptr<GDALDataset> ds(open_vector(dir.file(output)));
    std::vector<std::vector<std::pair<double, double>>> segments;
    EXPECT_TRUE(ds);
    if (!ds) return segments;
    for (auto& f : *ds->GetLayerByName("boundary")) {
      if (std::string(f->GetFieldAsString("kind")) != "open") continue;
      const OGRLineString* line = f->GetGeometryRef()->toLineString();
      segments.emplace_back();
      for (int i = 0; i < line->getNumPoints(); ++i)
        segments.back().emplace_back(line->getX(i), line->getY(i));
    }
    return segments;
  };

  CliResult r = run(line_file("west.geojson", "[[-4.6,48.35],[-4.6,48.2]]"), "m.gpkg");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto segments = open_segments("m.gpkg");
  ASSERT_EQ(segments.size(), 1u);
  EXPECT_GE(segments[0].size(), 15u);  // 16.7 km of side at 800 m
  for (const auto& [lon, lat] : segments[0]) EXPECT_NEAR(lon, -4.6, 1e-4) << lat;
  // Counter-clockwise round the sea: down the west side.
  EXPECT_GT(segments[0].front().second, segments[0].back().second);
  // The report counts them.
  const std::string report = read_file(dir.file("m.gpkg.json"));
  EXPECT_NE(report.find("\"num_open_segments\": 1,"), std::string::npos) << report;
  EXPECT_NE(report.find("\"num_open_edges\": " + std::to_string(segments[0].size() - 1) + ","),
            std::string::npos);

  // A line that stops halfway along the side: the open segment stops there too, at a
  // mesh vertex within the tolerance (the simplification's, 200 m) of the line's end.
  r = run(line_file("half.geojson", "[[-4.6,48.275],[-4.6,48.2]]"), "h.gpkg");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  segments = open_segments("h.gpkg");
  ASSERT_EQ(segments.size(), 1u);
  EXPECT_GE(segments[0].size(), 7u);  // 8.3 km at 800 m
  for (const auto& [lon, lat] : segments[0]) {
    EXPECT_NEAR(lon, -4.6, 1e-4) << lat;
    EXPECT_LT(lat, 48.275 + 0.0019);  // 210 m
  }

  // `domain` says, before any meshing, how much of the boundary the lines follow: the
  // west side's 16.68 km, and up to the tolerance (202 m) round each corner.
  r = run_cli({"domain", input, "--domain", "water", "--bbox", "-4.6,48.2,-4.4,48.35", "--size",
               "800", "--open-boundary", dir.file("west.geojson"), "-o", dir.file("d.gpkg")},
              dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::size_t along = r.err.find("1 line(s), along ");
  ASSERT_NE(along, std::string::npos) << r.err;
  const double km = std::stod(r.err.substr(along + 17));
  EXPECT_GE(km, 16.6) << r.err;
  EXPECT_LE(km, 16.68 + 2 * 0.21) << r.err;

  r = run(line_file("off.geojson", "[[-4.58,48.3],[-4.5,48.3]]"), "n.gpkg");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("follow none of the domain's boundary"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("n.gpkg")));
}

// --domain sea: a polygon of sea (the water round the island and the peninsula, cut out
// of a larger box) within the bbox is the bbox's water, open where the bbox cuts it: the
// same grid, byte for byte, as --domain water gives from the land. Without a bbox
// nothing is open: a warning says so, and a .pli is refused before meshing.
TEST(CliOutputs, ASeaPolygonCutByTheBboxIsOpenAlongIt) {
  TempDir dir;
  const std::string land = water_input(dir);
  const std::string sea = dir.file("sea.geojson");
  write_file(sea,
             geojson_polygons(
                 {"[[[-4.8,48.0],[-4.2,48.0],[-4.2,48.5],[-4.8,48.5],[-4.8,48.0]],"
                  "[[-4.45,48.25],[-4.45,48.3],[-4.3,48.3],[-4.3,48.25],[-4.45,48.25]],"
                  "[[-4.55,48.22],[-4.55,48.25],[-4.52,48.25],[-4.52,48.22],[-4.55,48.22]]]"}));
  const std::string bbox = "--bbox=-4.6,48.2,-4.4,48.35";
  CliResult r = run_cli(
      {"mesh", land, "--domain", "water", bbox, "--size", "800", "-q", "-o", dir.file("water.gr3")},
      dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_cli(
      {"mesh", sea, "--domain", "sea", bbox, "--size", "800", "-q", "-o", dir.file("sea.gr3")},
      dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_file(dir.file("sea.gr3")), read_file(dir.file("water.gr3")));
  const Gr3 g = parse_gr3(dir.file("sea.ll"));
  ASSERT_EQ(g.open.size(), 1u);
  ASSERT_GE(g.open[0].size(), 20u);
  for (int n : g.open[0]) EXPECT_TRUE(on_bbox(g.nodes[n - 1][0], g.nodes[n - 1][1], 1e-4)) << n;
  // The same polygon read as land: the bbox's sides are land.
  r = run_cli({"mesh", sea, bbox, "--size", "800", "-q", "-o", dir.file("land.gr3")}, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(parse_gr3(dir.file("land.gr3")).open.empty());

  r = run_cli({"mesh", sea, "--domain", "sea", "--size", "2000", "-o", dir.file("whole.gr3")}, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("--domain sea: the polygons' edge meets neither"), std::string::npos)
      << r.err;
  EXPECT_TRUE(parse_gr3(dir.file("whole.gr3")).open.empty());
  r = run_cli({"mesh", sea, "--domain", "sea", "--size", "2000", "-o", dir.file("whole.pli")}, dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--domain water (or sea) with --bbox or --clip"), std::string::npos)
      << r.err;
}

// A file of sea areas that border each other: one of them (--where, or each with --each)
// meshed with --domain sea is open along its borders with the others, a segment per
// neighbour, and land along the rest (the coast); as land it is all land.
TEST(CliOutputs, SeaAreasAreOpenWhereTheyBorderEachOther) {
  TempDir dir;
  const std::string areas = dir.file("areas.geojson");
  write_file(areas,
             "{\"type\":\"FeatureCollection\",\"features\":["
             "{\"type\":\"Feature\",\"properties\":{\"name\":\"west\"},\"geometry\":{\"type\":"
             "\"Polygon\",\"coordinates\":[[[-5,47],[-4,47],[-4,47.5],[-4,48],[-5,48],[-5,47]]]}},"
             "{\"type\":\"Feature\",\"properties\":{\"name\":\"east\"},\"geometry\":{\"type\":"
             "\"Polygon\",\"coordinates\":[[[-4,47],[-3,47],[-3,48],[-4,48],[-4,47.5],[-4,47]]]}},"
             "{\"type\":\"Feature\",\"properties\":{\"name\":\"north\"},\"geometry\":{\"type\":"
             "\"Polygon\",\"coordinates\":[[[-5,48],[-3,48],[-3,48.5],[-5,48.5],[-5,48]]]}},"
             // Far away, drawn across the antimeridian: its edge from 179 to -179 E along
             // 47 N is 2 degrees long, not the parallel through the west area's coast.
             "{\"type\":\"Feature\",\"properties\":{\"name\":\"far\"},\"geometry\":{\"type\":"
             "\"Polygon\",\"coordinates\":[[[179,47],[-179,47],[-179,48],[179,48],[179,47]]]}}]}");
  CliResult r = run_cli({"mesh", areas, "--domain", "sea", "--where", "name = 'west'", "--size",
                         "5000", "-q", "-o", dir.file("west.gr3")},
                        dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Gr3 g = parse_gr3(dir.file("west.ll"));
  ASSERT_EQ(g.open.size(), 2u);  // the border with the east, then with the north
  ASSERT_EQ(g.land.size(), 1u);  // the coast, west and south
  // Within 0.002 degrees: the domain's sides are the chords of the areas' one-degree
  // edges (a parallel's, 0.0011 degrees from it at its middle), and the quads' sides lie
  // along them. The two borders and the coast are a degree apart.
  std::set<int> open_nodes;
  for (const auto& segment : g.open) {
    for (int n : segment) {
      const double lon = g.nodes[n - 1][0], lat = g.nodes[n - 1][1];
      EXPECT_TRUE(std::abs(lon + 4) < 2e-3 || std::abs(lat - 48) < 2e-3) << lon << " " << lat;
      open_nodes.insert(n);
    }
  }
  for (int n : g.land[0]) {
    const double lon = g.nodes[n - 1][0], lat = g.nodes[n - 1][1];
    if (open_nodes.count(n)) continue;  // the land segment's two ends
    EXPECT_TRUE(std::abs(lon + 5) < 2e-3 || std::abs(lat - 47) < 2e-3) << lon << " " << lat;
  }
  // --each: the same region, the same grid.
  r = run_cli({"mesh", areas, "--domain", "sea", "--each", "name", "--size", "5000", "-q", "-o",
               dir.file("each_{}.gr3")},
              dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_file(dir.file("each_west.gr3")), read_file(dir.file("west.gr3")));
  EXPECT_EQ(parse_gr3(dir.file("each_north.ll")).open.size(), 2u);
  r = run_cli({"mesh", areas, "--where", "name = 'west'", "--size", "5000", "-q", "-o",
               dir.file("land.gr3")},
              dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(parse_gr3(dir.file("land.gr3")).open.empty());
}

// A sea area that borders nothing (its neighbour 0.01 degrees away, 750 m, near enough to
// be read as one, within the 1% of its box's diagonal, and beyond the open boundary's
// tolerance at 2 km, touches it nowhere) is all land, with a warning, as one without
// neighbours.
TEST(CliOutputs, ASeaAreaThatBordersNothingIsLandWithAWarning) {
  TempDir dir;
  const std::string areas = dir.file("areas.geojson");
  write_file(
      areas,
      "{\"type\":\"FeatureCollection\",\"features\":["
      "{\"type\":\"Feature\",\"properties\":{\"name\":\"lone\"},\"geometry\":{\"type\":"
      "\"Polygon\",\"coordinates\":[[[-5,47],[-4,47],[-4,48],[-5,48],[-5,47]]]}},"
      "{\"type\":\"Feature\",\"properties\":{\"name\":\"near\"},\"geometry\":{\"type\":"
      "\"Polygon\",\"coordinates\":[[[-3.99,47],[-3,47],[-3,48],[-3.99,48],[-3.99,47]]]}}]}");
  for (const std::vector<std::string>& selection :
       {std::vector<std::string>{"--where", "name = 'lone'"}, std::vector<std::string>{}}) {
    std::vector<std::string> args{"mesh", areas, "--domain",        "sea",        "--size",
                                  "2000", "-o",  dir.file("m.gr3"), "--overwrite"};
    args.insert(args.end(), selection.begin(), selection.end());
    const CliResult r = run_cli(args, dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("warning: --domain sea: the polygons' edge meets neither"),
              std::string::npos)
        << r.err;
    EXPECT_TRUE(parse_gr3(dir.file("m.gr3")).open.empty());
  }
}

TEST(CliOutputs, AnOpenBoundaryDenserThanTheDomainsEdgeTakesTheWholeEdge) {
  // A 2 x 1.5 degree box whose south side is one edge of 151 km, projected as a chord
  // that the side's curved image leaves by 470 m; the open boundary drawn along it in
  // 200 pieces follows the curve. Every boundary edge on that side is open all the same:
  // 50 at 3 km, in one segment (the simplification's 100 m leaves the chord alone).
  TempDir dir;
  const std::string box = dir.file("box.geojson");
  write_file(box, geojson_polygons({"[[[-6,47],[-4,47],[-4,48.5],[-6,48.5],[-6,47]]]"}));
  std::string points;
  for (int k = 0; k <= 200; ++k)
    points += (k ? "," : "") + ("[" + std::to_string(-6.0 + 2.0 * k / 200) + ",47]");
  const std::string south = dir.file("south.geojson");
  write_file(south, R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},)"
                    R"("geometry":{"type":"LineString","coordinates":[)" +
                        points + "]}}]}");
  const CliResult r =
      run_cli({"mesh", box, "--size", "3000", "--simplify", "100", "--open-boundary", south, "-o",
               dir.file("m.gpkg"), "--report", dir.file("m.json"), "-q"},
              dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string report = read_file(dir.file("m.json"));
  EXPECT_NE(report.find("\"num_open_segments\": 1,"), std::string::npos) << report;
  const std::size_t at = report.find("\"num_open_edges\": ");
  ASSERT_NE(at, std::string::npos);
  const int open = std::stoi(report.substr(at + 18));
  EXPECT_GE(open, 48);
  EXPECT_LE(open, 52);
}

// The GeoPackage's quads find the quads SCHISM's checks fail, as the report counts them:
// `aspect_ratio` over 5, min_angle_deg / max_angle_deg under 0.5, either.
TEST(CliOutputs, TheQuadsFieldsFindWhatSchismsChecksFail) {
  TempDir dir;
  const CliResult r =
      mesh_box_800(dir, {"-o", dir.file("m.gpkg"), "--report", dir.file("m.json"), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string report = read_file(dir.file("m.json"));
  GDALDataset* ds = open_vector(dir.file("m.gpkg"));
  ASSERT_NE(ds, nullptr);
  long quads = 0, aspect = 0, ratio = 0, either = 0;
  double largest = 0;
  for (auto& f : *ds->GetLayerByName("quads")) {
    const double a = f->GetFieldAsDouble("aspect_ratio");
    EXPECT_GE(a, 1.0);
    largest = std::max(largest, a);
    const bool bad_aspect = a > 5, bad_ratio = f->GetFieldAsDouble("min_angle_deg") <
                                               0.5 * f->GetFieldAsDouble("max_angle_deg");
    ++quads;
    aspect += bad_aspect;
    ratio += bad_ratio;
    either += bad_aspect || bad_ratio;
  }
  GDALClose(ds);
  EXPECT_EQ(quads, report_count(report, "num_quads"));
  EXPECT_EQ(aspect, report_count(report, "schism_aspect_ratio_violations"));
  EXPECT_EQ(ratio, report_count(report, "schism_angle_ratio_violations"));
  EXPECT_EQ(either, report_count(report, "schism_failures"));
  EXPECT_GT(ratio, 0) << report;
  EXPECT_GT(largest, 1.5);
}

// --schism-split: hgrid.gr3 has each quad that fails SCHISM's checks (as the report
// counts them) as two counter-clockwise triangles in its place, and no quad left that
// fails them (measured here); without it the run warns with the same count.
TEST(CliOutputs, SchismSplitWritesTheFailingQuadsAsTrianglePairs) {
  TempDir dir;
  const CliResult plain =
      mesh_box_800(dir, {"-o", dir.file("quads.gr3"), "--report", dir.file("q.json")});
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  const std::string report = read_file(dir.file("q.json"));
  const long quads = report_count(report, "num_quads"),
             failures = report_count(report, "schism_failures");
  ASSERT_GT(failures, 0) << report;
  EXPECT_GE(failures, std::max(report_count(report, "schism_angle_ratio_violations"),
                               report_count(report, "schism_aspect_ratio_violations")));
  EXPECT_NE(plain.err.find(dir.file("quads.gr3") + ": " + std::to_string(failures) +
                           " quads fail SCHISM's checks"),
            std::string::npos)
      << plain.err;

  const CliResult split = mesh_box_800(dir, {"-o", dir.file("split.gr3"), "--schism-split"});
  ASSERT_EQ(split.exit_code, 0) << split.err;
  EXPECT_EQ(split.err.find("warning"), std::string::npos) << split.err;
  EXPECT_NE(split.err.find("SCHISM split: " + std::to_string(failures) + " quads failing"),
            std::string::npos)
      << split.err;
  const Gr3 q = parse_gr3(dir.file("quads.gr3"));
  const Gr3 g = parse_gr3(dir.file("split.gr3"));
  ASSERT_EQ(static_cast<long>(q.num_elements), quads);
  ASSERT_EQ(static_cast<long>(g.num_elements), quads + failures);
  EXPECT_EQ(g.nodes, q.nodes);
  EXPECT_EQ(g.open, q.open);
  EXPECT_EQ(g.land, q.land);
  EXPECT_EQ(parse_gr3(dir.file("split.ll")).elements, g.elements);
  auto xy = [&g](int n) { return std::array<double, 2>{g.nodes[n - 1][0], g.nodes[n - 1][1]}; };
  auto twice_area = [&](const std::vector<int>& e) {
    double a = 0;
    for (std::size_t k = 0; k < e.size(); ++k) {
      const auto p = xy(e[k]), r = xy(e[(k + 1) % e.size()]);
      a += p[0] * r[1] - r[0] * p[1];
    }
    return a;
  };
  // Walk both files together: a quad of the first is the same quad, or two triangles
  // with its four corners and its area, in the second.
  std::size_t e = 0;
  long triangles = 0;
  for (const auto& quad : q.elements) {
    ASSERT_LT(e, g.elements.size());
    if (g.elements[e].size() == 4) {
      EXPECT_EQ(g.elements[e], quad);
      std::array<double, 4> angle{}, side{};
      for (int k = 0; k < 4; ++k) {
        const auto p = xy(quad[(k + 3) % 4]), c = xy(quad[k]), n = xy(quad[(k + 1) % 4]);
        const double ax = p[0] - c[0], ay = p[1] - c[1], bx = n[0] - c[0], by = n[1] - c[1];
        angle[k] = std::acos((ax * bx + ay * by) / std::hypot(ax, ay) / std::hypot(bx, by));
        side[k] = std::hypot(bx, by);
      }
      EXPECT_GE(*std::min_element(angle.begin(), angle.end()),
                0.5 * *std::max_element(angle.begin(), angle.end()));
      EXPECT_LE(*std::max_element(side.begin(), side.end()),
                5 * *std::min_element(side.begin(), side.end()));
      ++e;
      continue;
    }
    ASSERT_LT(e + 1, g.elements.size());
    const auto &t0 = g.elements[e], &t1 = g.elements[e + 1];
    ASSERT_EQ(t0.size(), 3u);
    ASSERT_EQ(t1.size(), 3u);
    EXPECT_GT(twice_area(t0), 0);
    EXPECT_GT(twice_area(t1), 0);
    EXPECT_NEAR(twice_area(t0) + twice_area(t1), twice_area(quad), 1e-6 * twice_area(quad));
    std::set<int> corners(t0.begin(), t0.end());
    corners.insert(t1.begin(), t1.end());
    EXPECT_EQ(corners, std::set<int>(quad.begin(), quad.end()));
    triangles += 2;
    e += 2;
  }
  EXPECT_EQ(e, g.elements.size());
  EXPECT_EQ(triangles, 2 * failures);
}

TEST(CliOutputs, UnwritableSecondOutputLeavesNothing) {
  TempDir dir;
  const std::string input = water_input(dir);
  std::filesystem::create_directory(dir.file("locked"));
  std::filesystem::permissions(dir.file("locked"), std::filesystem::perms::owner_read |
                                                       std::filesystem::perms::owner_exec);
  const std::vector<std::string> base = {"mesh", input, "--domain", "water", "--bbox",
                                         "-4.6,48.2,-4.4,48.35", "--size", "800", "-q"};
  auto run = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = base;
    args.insert(args.end(), extra.begin(), extra.end());
    return run_cli(args, dir);
  };
  const std::set<std::string> before = {"land.geojson", "locked"};
  auto entries = [&dir] {
    const auto e = dir.entries();
    return std::set<std::string>(e.begin(), e.end());
  };
  // A directory that does not exist, one that is not writable (unless we are root), a
  // file given twice, an unknown format.
  CliResult r = run({"-o", dir.file("a.gpkg"), "-o", dir.file("missing/b.msh")});
  EXPECT_EQ(r.exit_code, 6) << r.err;
  EXPECT_EQ(entries(), before);
  if (access(dir.file("locked").c_str(), W_OK) != 0) {  // not root
    r = run({"-o", dir.file("a.gpkg"), "-o", dir.file("locked/b.msh")});
    EXPECT_EQ(r.exit_code, 6) << r.err;
    EXPECT_EQ(entries(), before);
  }
  r = run({"-o", dir.file("a.gpkg"), "-o", dir.file("a.gpkg")});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(entries(), before);
  // Given once, and written beside another output too (hgrid.gr3's hgrid.ll).
  r = run({"-o", dir.file("hgrid.gr3"), "--report", dir.file("hgrid.ll")});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("hgrid.ll' would be written twice: given twice, or given once and also "
                       "written beside another output (a .gr3's .ll"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(entries(), before);
  r = run({"-o", dir.file("a.gpkg"), "-o", dir.file("b.shp")});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(entries(), before);
  r = run({"-o", dir.file("a.gpkg"), "--output-format", "gpkg", "--output-format", "msh"});
  EXPECT_EQ(r.exit_code, 2) << r.err;  // two formats for one output
  // The .ll companion exists: without --overwrite nothing is written.
  write_file(dir.file("hgrid.ll"), "old");
  r = run({"-o", dir.file("a.gpkg"), "-o", dir.file("hgrid.gr3")});
  EXPECT_EQ(r.exit_code, 6) << r.err;
  EXPECT_NE(r.err.find("hgrid.ll"), std::string::npos) << r.err;
  EXPECT_EQ(entries(), (std::set<std::string>{"land.geojson", "locked", "hgrid.ll"}));
  EXPECT_EQ(read_file(dir.file("hgrid.ll")), "old");
  // --output-format by position, and --msh-version 2.2; the report joins the outputs.
  r = run({"-o", dir.file("x.data"), "-o", dir.file("y.data"), "--output-format", "msh",
           "--output-format", "vtk", "--msh-version", "2.2", "--report", dir.file("r.json")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(read_file(dir.file("r.json")).find("\"num_quads\""), std::string::npos);
  EXPECT_EQ(read_file(dir.file("x.data")).substr(0, 20), "$MeshFormat\n2.2 0 8\n");
  EXPECT_EQ(read_file(dir.file("y.data")).substr(0, 26), "# vtk DataFile Version 3.0");
  std::filesystem::permissions(dir.file("locked"), std::filesystem::perms::owner_all);
}

// Stopped by SIGTERM while writing its outputs (frozen by SIGSTOP as soon as a temporary
// file appears, so that the signal comes mid-write), a run leaves no temporary file and no
// output, says so, and ends by the signal. A run that finishes before it is caught is
// tried again with more quads.
TEST(CliOutputs, ASignalWhileWritingLeavesNoTemporaryFile) {
  TempDir dir;
  const std::string input = water_input(dir);
  auto entries = [&dir] {
    std::set<std::string> e;
    for (const std::string& name : dir.entries())
      if (name != "land.geojson" && name != "err.txt") e.insert(name);
    return e;
  };
  auto temporary = [&] {
    for (const std::string& name : entries())
      if (name.find(".tmp-") != std::string::npos) return true;
    return false;
  };
  bool caught = false;
  for (const char* size : {"800", "400", "200", "100"}) {
    const std::vector<std::string> args = {ISOQUAD_CLI,
                                           "mesh",
                                           input,
                                           "--domain",
                                           "water",
                                           "--bbox",
                                           "-4.6,48.2,-4.4,48.35",
                                           "--size",
                                           size,
                                           "-o",
                                           dir.file("m.gpkg"),
                                           "-o",
                                           dir.file("m.vtu"),
                                           "-o",
                                           dir.file("m.msh"),
                                           "-o",
                                           dir.file("hgrid.gr3"),
                                           "--report",
                                           dir.file("r.json"),
                                           "-q"};
    const pid_t child = start_program(args, dir.file("err.txt"));
    ASSERT_GE(child, 0);
    const int status = wait_or_stop(
        child, temporary,
        [&] {
          kill(child, SIGSTOP);
          caught = temporary();  // still writing, frozen
          kill(child, caught ? SIGTERM : SIGKILL);
          kill(child, SIGCONT);
        },
        200);
    ASSERT_NE(status, -1) << "the run did not end";
    if (!caught) {  // finished first (or killed above): clear its outputs and try again
      for (const std::string& name : entries()) std::filesystem::remove(dir.file(name));
      continue;
    }
    ASSERT_TRUE(WIFSIGNALED(status)) << read_file(dir.file("err.txt"));
    EXPECT_EQ(WTERMSIG(status), SIGTERM);
    EXPECT_EQ(entries(), std::set<std::string>{}) << read_file(dir.file("err.txt"));
    EXPECT_NE(read_file(dir.file("err.txt"))
                  .find("stopped by SIGTERM; the unfinished outputs were removed"),
              std::string::npos)
        << read_file(dir.file("err.txt"));
    break;
  }
  EXPECT_TRUE(caught) << "no run was caught while writing";
}

// QGIS's Python bindings, which tools/install-deps.sh installs (python3-qgis): the tests
// that run QGIS fail without them rather than pass unrun.
bool qgis_importable(const TempDir& dir) {
  return run_cli_program("/usr/bin/python3", {"-c", "import qgis.core"}, dir).exit_code == 0;
}
constexpr const char* kQgisMissing =
    "/usr/bin/python3 cannot import qgis.core: run tools/install-deps.sh (python3-qgis)";

// tools/render_gpkg_qgis.py: a GeoPackage's layers drawn by QGIS to `png`, `size` pixels
// wide (`more`: its other options, --layers, --style), every stored style of those layers
// applied once on the way.
CliResult render_in_qgis(const TempDir& dir, const std::string& gpkg, const std::string& png,
                         int size, const std::vector<std::string>& more = {}) {
  std::vector<std::string> args = {source_dir() + "/tools/render_gpkg_qgis.py", gpkg, png, "--size",
                                   std::to_string(size)};
  args.insert(args.end(), more.begin(), more.end());
  return run_cli_program("/usr/bin/python3", args, dir);
}

// Python that reads the PNG sys.argv[1] as `img`, an array of rows of (r, g, b).
constexpr const char* kPngPixels =
    "import sys\n"
    "from osgeo import gdal\n"
    "import numpy as np\n"
    "ds = gdal.Open(sys.argv[1])\n"
    "img = np.dstack([ds.GetRasterBand(b).ReadAsArray() for b in (1, 2, 3)]).astype(int)\n";

// The pixels of a PNG within `tolerance` (|dr| + |dg| + |db|) of each named colour.
std::map<std::string, int> pixels_near(const TempDir& dir, const std::string& png,
                                       const std::map<std::string, std::array<int, 3>>& colours,
                                       int tolerance) {
  std::ostringstream wanted;
  for (const auto& [name, c] : colours)
    wanted << "('" << name << "', (" << c[0] << ", " << c[1] << ", " << c[2] << ")), ";
  const std::string out =
      python_check(dir,
                   std::string(kPngPixels) + "for name, c in [" + wanted.str() +
                       "]:\n"
                       "    print(name, int((np.abs(img - np.array(c)).sum(axis=2) <= " +
                       std::to_string(tolerance) + ").sum()))\n",
                   {png});
  std::istringstream in(out);
  std::map<std::string, int> pixels;
  std::string name;
  int n = 0;
  while (in >> name >> n) pixels[name] = n;
  return pixels;
}

// Acceptance: QGIS 3.22 (python3-qgis, headless) opens the GeoPackage with its embedded
// styles and renders it; the PNG shows the size-conformance colours of styles/quads_size.qml
// and the boundary colours of styles/boundary_kind.qml.
TEST(CliOutputs, QgisRendersTheEmbeddedStyles) {
  TempDir dir;
  ASSERT_TRUE(qgis_importable(dir)) << kQgisMissing;
  const CliResult r = run_cli({"mesh", water_input(dir), "--domain", "water", "--bbox",
                               "-4.6,48.2,-4.4,48.35", "--size", "800", "-o", dir.file("m.gpkg"), "-q"},
                              dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CliResult q = render_in_qgis(dir, dir.file("m.gpkg"), dir.file("m.png"), 600);
  ASSERT_EQ(q.exit_code, 0) << q.out << q.err;
  EXPECT_NE(q.out.find("quads: "), std::string::npos) << q.out;
  EXPECT_NE(q.out.find("renderer graduatedSymbol"), std::string::npos) << q.out;
  EXPECT_NE(q.out.find("boundary: 3 features, renderer categorizedSymbol"), std::string::npos) << q.out;
  // Pixel colours: the five size classes, land and open boundary lines.
  std::map<std::string, int> pixels = pixels_near(dir, dir.file("m.png"),
                                                  {{"small", {44, 123, 182}},
                                                   {"low", {171, 217, 233}},
                                                   {"ok", {255, 255, 191}},
                                                   {"high", {253, 174, 97}},
                                                   {"large", {215, 25, 28}},
                                                   {"land", {140, 81, 10}},
                                                   {"open", {1, 102, 94}}},
                                                  6);
  int fill = 0;
  for (const char* c : {"small", "low", "ok", "high", "large"}) fill += pixels[c];
  EXPECT_GT(fill, 600 * 600 / 4);  // the styled quads cover much of the picture
  EXPECT_GT(pixels["land"], 100);
  EXPECT_GT(pixels["open"], 100);
}

// Every style stored in the GeoPackage applies in QGIS: the embedded paths' and the
// depths' too (tools/render_gpkg_qgis.py applies each; a style QGIS cannot read, such
// as one that is not XML, fails it, where QGIS alone would draw a random colour).
TEST(CliOutputs, QgisAppliesEveryStoredStyle) {
  TempDir dir;
  ASSERT_TRUE(qgis_importable(dir)) << kQgisMissing;
  const std::string lane = dir.file("lane.geojson");
  write_file(lane,
             R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},)"
             R"("geometry":{"type":"LineString","coordinates":[[-4.58,48.32],[-4.42,48.32]]}}]})");
  const CliResult r = run_cli({"mesh", water_input(dir), "--domain", "water", "--bbox",
                               "-4.6,48.2,-4.4,48.35", "--size", "800", "--align", lane, "--embed",
                               "--bathymetry", bathymetry(dir), "-o", dir.file("m.gpkg"), "-q"},
                              dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CliResult q = render_in_qgis(dir, dir.file("m.gpkg"), dir.file("m.png"), 300,
                                     {"--layers", "quads,vertices,boundary,embedded"});
  ASSERT_EQ(q.exit_code, 0) << q.out << q.err;
  for (const char* style : {"quads/size", "quads/orientation", "quads/irregular", "quads/checks",
                            "vertices/degree", "vertices/depth", "boundary/kind", "embedded/line"})
    EXPECT_NE(q.out.find(std::string("style ") + style + ": applies"), std::string::npos)
        << style << "\n"
        << q.out;
}

// `isoquad fields -o .gpkg` opens in QGIS coloured by size (styles/triangles_size.qml, a
// ramp over the layer's own range of h), with the cross's angle as a second style: the
// picture holds many colours, from the fine coast to the coarse inland.
TEST(CliOutputs, QgisDrawsTheFieldsBySize) {
  TempDir dir;
  ASSERT_TRUE(qgis_importable(dir)) << kQgisMissing;
  const CliResult r = run_cli(
      {"fields", sample("corsica.shp"), "--hmax", "8000", "-o", dir.file("f.gpkg"), "-q"}, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CliResult q =
      render_in_qgis(dir, dir.file("f.gpkg"), dir.file("f.png"), 300, {"--layers", "triangles"});
  ASSERT_EQ(q.exit_code, 0) << q.out << q.err;
  EXPECT_NE(q.out.find("style triangles/size: applies"), std::string::npos) << q.out;
  EXPECT_NE(q.out.find("style triangles/cross: applies"), std::string::npos) << q.out;
  const std::string out =
      python_check(dir,
                   std::string(kPngPixels) +
                       "px = img.reshape(-1, 3)\n"
                       "px = px[(px != 255).any(axis=1)]\n"
                       "red = ((px[:, 0] > 180) & (px[:, 2] < 80)).sum()\n"
                       "blueish = (px[:, 2] > px[:, 0] + 40).sum()\n"
                       "print(len(px), len({tuple(p) for p in px // 8}), red, blueish)\n",
                   {dir.file("f.png")});
  std::istringstream in(out);
  long drawn = 0, colours = 0, red = 0, blueish = 0;
  in >> drawn >> colours >> red >> blueish;
  EXPECT_GT(drawn, 300 * 300 / 5) << out;
  EXPECT_GT(colours, 30) << out;      // a ramp, not one colour
  EXPECT_GT(red, drawn / 10) << out;  // the coarse inland
  EXPECT_GT(blueish, 0) << out;       // the finest sizes, at the coast
}

// `isoquad domain -o .gpkg` opens in QGIS styled: the domain filled, its open boundary in
// the mesh's open green (styles/domain_area.qml, domain_open.qml).
TEST(CliOutputs, QgisDrawsTheDomainStyled) {
  TempDir dir;
  ASSERT_TRUE(qgis_importable(dir)) << kQgisMissing;
  const CliResult r =
      run_cli({"domain", water_input(dir), "--domain", "water", "--bbox", "-4.6,48.2,-4.4,48.35",
               "--size", "800", "-o", dir.file("d.gpkg"), "-q"},
              dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CliResult q = render_in_qgis(dir, dir.file("d.gpkg"), dir.file("d.png"), 300,
                                     {"--layers", "domain,open_boundary"});
  ASSERT_EQ(q.exit_code, 0) << q.out << q.err;
  EXPECT_NE(q.out.find("style domain/area: applies"), std::string::npos) << q.out;
  EXPECT_NE(q.out.find("style open_boundary/open: applies"), std::string::npos) << q.out;
  std::map<std::string, int> pixels =
      pixels_near(dir, dir.file("d.png"), {{"open", {1, 102, 94}}, {"water", {196, 224, 238}}}, 12);
  EXPECT_GT(pixels["open"], 100);             // the bbox's sides across the water
  EXPECT_GT(pixels["water"], 300 * 300 / 4);  // the domain's fill over white
}

// The stored style `checks` of the quads (styles/quads_checks.qml), applied by QGIS: its
// rules select as many quads as the report counts for SCHISM's checks and D-Flow FM's
// orthogonality (each link over 0.5 marks its two quads).
TEST(CliOutputs, QgisFindsTheQuadsThatFailTheModelsChecks) {
  TempDir dir;
  ASSERT_TRUE(qgis_importable(dir)) << kQgisMissing;
  const CliResult r =
      mesh_box_800(dir, {"-o", dir.file("m.gpkg"), "--report", dir.file("m.json"), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string report = read_file(dir.file("m.json"));
  const CliResult q = render_in_qgis(dir, dir.file("m.gpkg"), dir.file("m.png"), 300,
                                     {"--layers", "quads", "--style", "quads=checks"});
  ASSERT_EQ(q.exit_code, 0) << q.out << q.err;
  EXPECT_NE(q.out.find("renderer RuleRenderer"), std::string::npos) << q.out;
  auto selected = [&q](const std::string& label) {
    const std::string key = "rule " + label + ": ";
    const std::size_t at = q.out.find(key);
    return at == std::string::npos ? -1L : std::stol(q.out.substr(at + key.size()));
  };
  const long angle = report_count(report, "schism_angle_ratio_violations");
  ASSERT_GT(angle, 0) << report;
  EXPECT_EQ(selected("SCHISM: min/max angle under 0.5"), angle) << q.out;
  EXPECT_EQ(selected("SCHISM: aspect ratio over 5"),
            report_count(report, "schism_aspect_ratio_violations"))
      << q.out;
  const long links = report_count(report, "dflowfm_orthogonality_violations");
  const long marked = selected("D-Flow FM: a link's orthogonality over 0.5");
  EXPECT_GE(marked, links > 0 ? 2 : 0) << q.out;
  EXPECT_LE(marked, 2 * links) << q.out;
  EXPECT_NE(q.out.find("rule every check passed: else"), std::string::npos) << q.out;
}

// SMS .2dm: the same nodes, elements and boundary as hgrid.gr3 of the same run, z the
// elevation (minus the depth), one nodestring per boundary segment (open ones first), an
// island's loop as two that share their ends (SMS allows no nodestring that ends where it
// begins). Then QGIS's mesh reader (MDAL) opens it and the UGRID file of the same run, in
// its CRS (the automatic projection, from the variable `projected_coordinate_system`), the
// first node at hgrid.ll's first node.
TEST(CliOutputs, Sms2dmHoldsTheGr3sMeshWithElevationsAndNodestrings) {
  TempDir dir;
  const CliResult r = mesh_water_box(
      dir, {"-o", dir.file("m.2dm"), "-o", dir.file("hgrid.gr3"), "-o", dir.file("m.nc")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Gr3 g = parse_gr3(dir.file("hgrid.gr3"));
  std::istringstream in(read_file(dir.file("m.2dm")));
  std::string line;
  ASSERT_TRUE(std::getline(in, line));
  EXPECT_EQ(line, "MESH2D");
  std::vector<std::array<double, 3>> nodes;
  std::size_t elements = 0;
  std::vector<std::vector<int>> strings(1);
  while (std::getline(in, line)) {
    std::istringstream card(line);
    std::string name;
    card >> name;
    if (name == "E4Q") {
      int id = 0, n = 0, material = 0;
      card >> id;
      EXPECT_EQ(id, static_cast<int>(++elements));
      for (int k = 0; k < 4; ++k) {
        card >> n;
        EXPECT_TRUE(n >= 1 && n <= static_cast<int>(g.nodes.size())) << line;
      }
      card >> material;
      EXPECT_EQ(material, 1) << line;
    } else if (name == "ND") {
      int id = 0;
      std::array<double, 3> p;
      card >> id >> p[0] >> p[1] >> p[2];
      EXPECT_EQ(id, static_cast<int>(nodes.size() + 1));
      nodes.push_back(p);
    } else if (name == "NS") {
      for (int id = 0; card >> id;) {
        strings.back().push_back(std::abs(id));
        if (id < 0) strings.emplace_back();
      }
    } else {
      EXPECT_EQ(line, "NUM_MATERIALS_PER_ELEM 1");
    }
    EXPECT_FALSE(card.fail() && !card.eof()) << line;
  }
  EXPECT_TRUE(strings.back().empty());  // the last nodestring ended with a negative id
  strings.pop_back();
  EXPECT_EQ(elements, g.num_elements);
  ASSERT_EQ(nodes.size(), g.nodes.size());
  double deepest = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    EXPECT_NEAR(nodes[i][0], g.nodes[i][0], 1e-6);
    EXPECT_NEAR(nodes[i][1], g.nodes[i][1], 1e-6);
    EXPECT_NEAR(nodes[i][2], -g.nodes[i][2], 1e-6);
    deepest = std::min(deepest, nodes[i][2]);
  }
  EXPECT_LT(deepest, -100.0);
  std::vector<std::vector<int>> expected = g.open;
  for (std::size_t s = 0; s < g.land.size(); ++s) {
    const std::vector<int>& land = g.land[s];
    if (!g.land_flags[s]) {
      expected.push_back(land);
      continue;
    }
    // An island: its first half, then the rest back to its first node.
    const std::size_t half = land.size() / 2;
    expected.emplace_back(land.begin(), land.begin() + half + 1);
    expected.emplace_back(land.begin() + half, land.end());
    expected.back().push_back(land.front());
  }
  EXPECT_EQ(strings, expected);
  ASSERT_EQ(strings.size(), 4u);  // one open segment, the mainland coast, the island's two
  for (const std::vector<int>& ns : strings) EXPECT_NE(ns.front(), ns.back());

  const std::string out = read_mesh_layers_in_qgis(dir, {dir.file("m.2dm"), dir.file("m.nc")});
  double low = 0;
  for (const auto& n : nodes) low = std::min(low, n[2]);
  std::ostringstream want;
  want << nodes.size() << " " << elements << " [4] " << std::fixed << std::setprecision(3) << low;
  EXPECT_NE(out.find(want.str() + "\n" + want.str() + "\n"), std::string::npos) << out;
  const Gr3 ll = parse_gr3(dir.file("hgrid.ll"));
  const std::size_t at = out.find("lonlat ");
  ASSERT_NE(at, std::string::npos) << out;
  std::istringstream lonlat(out.substr(at + 7));
  double lon = 0, lat = 0;
  lonlat >> lon >> lat;
  EXPECT_NEAR(lon, ll.nodes[0][0], 1e-7) << out;
  EXPECT_NEAR(lat, ll.nodes[0][1], 1e-7) << out;
}

// MIKE 21/3 FM .mesh: hgrid.gr3's nodes (z the bed level, minus the depth) and quads
// of the same run; the open segment's nodes, its ends included, code 2, the land
// segments' other nodes 1, the rest 0: every boundary node coded, none inside.
TEST(CliOutputs, MikeMeshHoldsTheGr3sMeshWithBoundaryCodes) {
  TempDir dir;
  const CliResult r = mesh_water_box(dir, {"-o", dir.file("m.mesh"), "-o", dir.file("hgrid.gr3")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Gr3 g = parse_gr3(dir.file("hgrid.gr3"));
  std::istringstream in(read_file(dir.file("m.mesh")));
  std::string header;
  ASSERT_TRUE(std::getline(in, header));
  std::istringstream head(header);
  std::string item, unit, projection;
  std::size_t np = 0;
  head >> item >> unit >> np >> projection;
  EXPECT_EQ(item + " " + unit, "100079 1000") << header;
  ASSERT_EQ(np, g.nodes.size());
  EXPECT_EQ(projection.rfind("PROJCS[", 0), 0u) << header;  // the automatic projection
  std::vector<int> code(np);
  for (std::size_t i = 0; i < np; ++i) {
    std::size_t id = 0;
    std::array<double, 3> p{};
    in >> id >> p[0] >> p[1] >> p[2] >> code[i];
    EXPECT_EQ(id, i + 1);
    EXPECT_NEAR(p[0], g.nodes[i][0], 1e-6);
    EXPECT_NEAR(p[1], g.nodes[i][1], 1e-6);
    EXPECT_NEAR(p[2], -g.nodes[i][2], 1e-6);
  }
  std::size_t ne = 0, max_nodes = 0, kind = 0;
  in >> ne >> max_nodes >> kind;
  EXPECT_EQ(ne, g.num_elements);
  EXPECT_EQ(max_nodes, 4u);
  EXPECT_EQ(kind, 25u);
  for (std::size_t e = 0; e < ne; ++e) {
    std::vector<int> el(5);
    for (int& v : el) in >> v;
    EXPECT_EQ(el[0], static_cast<int>(e + 1));
    EXPECT_EQ(std::vector<int>(el.begin() + 1, el.end()), g.elements[e]) << e;
  }
  EXPECT_FALSE(in.fail());
  ASSERT_EQ(g.open.size(), 1u);
  std::vector<int> expected(np, 0);
  for (const auto& s : g.land)
    for (int n : s) expected[n - 1] = 1;
  for (int n : g.open[0]) expected[n - 1] = 2;
  EXPECT_EQ(code, expected);
}

// D-Flow FM .pli: a polyline file per open segment, named after its file (the prefix of
// its support points in .bc forcing files), holding the segment's nodes as hgrid.gr3 of
// the same run has them; one segment writes the path given, two write STEM_1 and
// STEM_2. A domain without open boundary stops the run before meshing.
TEST(CliOutputs, PliFilesHoldTheOpenBoundarySegments) {
  TempDir dir;
  const std::string input = water_input(dir);
  struct Pli {
    std::string name;
    std::vector<std::array<double, 2>> points;
  };
  auto parse_pli = [](const std::string& path) {
    std::istringstream in(read_file(path));
    Pli p;
    std::size_t rows = 0, cols = 0;
    std::getline(in, p.name);
    in >> rows >> cols;
    EXPECT_EQ(cols, 2u) << path;
    p.points.resize(rows);
    for (auto& xy : p.points) in >> xy[0] >> xy[1];
    std::string rest;
    in >> rest;
    EXPECT_TRUE(in.eof() && rest.empty()) << path << ": " << rest;
    return p;
  };
  auto expect_segment = [](const Pli& p, const std::vector<int>& nodes, const Gr3& g) {
    ASSERT_EQ(p.points.size(), nodes.size());
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      EXPECT_NEAR(p.points[i][0], g.nodes[nodes[i] - 1][0], 1e-6) << p.name << " " << i;
      EXPECT_NEAR(p.points[i][1], g.nodes[nodes[i] - 1][1], 1e-6) << p.name << " " << i;
    }
  };
  auto mesh = [&](const std::vector<std::string>& extra) {
    std::vector<std::string> args = {"mesh",   input,    "--domain",
                                     "water",  "--bbox", "-4.6,48.2,-4.4,48.35",
                                     "--size", "800",    "-q"};
    args.insert(args.end(), extra.begin(), extra.end());
    return run_cli(args, dir);
  };
  // The bbox: one open segment, round by north, west and south.
  CliResult r = mesh({"-o", dir.file("open.pli"), "-o", dir.file("one.gr3")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Gr3 one = parse_gr3(dir.file("one.gr3"));
  ASSERT_EQ(one.open.size(), 1u);
  const Pli bbox = parse_pli(dir.file("open.pli"));
  EXPECT_EQ(bbox.name, "open");
  expect_segment(bbox, one.open[0], one);

  // Lines along the west side and the east side north of the peninsula: two segments.
  const std::string lines = dir.file("lines.geojson");
  write_file(lines, R"({"type":"FeatureCollection","features":[)"
                    R"({"type":"Feature","properties":{},"geometry":{"type":"LineString",)"
                    R"("coordinates":[[-4.6,48.2],[-4.6,48.35]]}},)"
                    R"({"type":"Feature","properties":{},"geometry":{"type":"LineString",)"
                    R"("coordinates":[[-4.4,48.3],[-4.4,48.35]]}}]})");
  r = mesh({"--open-boundary", lines, "-o", dir.file("sea.pli"), "-o", dir.file("two.gr3")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Gr3 two = parse_gr3(dir.file("two.gr3"));
  ASSERT_EQ(two.open.size(), 2u);
  EXPECT_FALSE(std::filesystem::exists(dir.file("sea.pli")));
  for (std::size_t k = 0; k < 2; ++k) {
    const std::string stem = "sea_" + std::to_string(k + 1);
    const Pli p = parse_pli(dir.file(stem + ".pli"));
    EXPECT_EQ(p.name, stem);
    expect_segment(p, two.open[k], two);
  }
  EXPECT_FALSE(std::filesystem::exists(dir.file("sea_3.pli")));
  // Again without --overwrite: sea_1.pli exists, and the run says so before meshing (not
  // that it "appeared while writing", after).
  r = mesh({"--open-boundary", lines, "-o", dir.file("sea.pli"), "-o", dir.file("again.gr3")});
  EXPECT_EQ(r.exit_code, 6) << r.err;
  EXPECT_NE(r.err.find("sea_1.pli' already exists"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("again.gr3")));
  // A file of a run with more segments (sea_3.pli), and the single file of a run with one
  // (sea.pli): refused without --overwrite, removed with it, so that stem_*.pli are the
  // mesh's segments.
  std::filesystem::remove(dir.file("sea_1.pli"));
  std::filesystem::remove(dir.file("sea_2.pli"));
  write_file(dir.file("sea_3.pli"), "old\n");
  r = mesh({"--open-boundary", lines, "-o", dir.file("sea.pli"), "-o", dir.file("again.gr3")});
  EXPECT_EQ(r.exit_code, 6) << r.err;
  EXPECT_NE(r.err.find("sea_3.pli' already exists"), std::string::npos) << r.err;
  write_file(dir.file("sea.pli"), "old\n");
  write_file(dir.file("sea_10.pli"), "old\n");
  write_file(dir.file("sea_x.pli"), "not ours\n");
  r = mesh({"--open-boundary", lines, "-o", dir.file("sea.pli"), "--overwrite"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* gone : {"sea.pli", "sea_3.pli", "sea_10.pli"})
    EXPECT_FALSE(std::filesystem::exists(dir.file(gone))) << gone;
  for (std::size_t k = 0; k < 2; ++k)
    expect_segment(parse_pli(dir.file("sea_" + std::to_string(k + 1) + ".pli")), two.open[k], two);
  EXPECT_TRUE(std::filesystem::exists(dir.file("sea_x.pli")));

  // A land domain has no open boundary: exit 2 before meshing, nothing written.
  r = run_cli({"mesh", input, "--size", "800", "-q", "-o", dir.file("land.pli"), "-o",
               dir.file("land.gpkg")},
              dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("'" + dir.file("land.pli") + "': a .pli holds the open boundary"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("land.gpkg")));
}

// TELEMAC-2D: the Selafin geometry, read record by record (big-endian, double
// precision), holds two counter-clockwise triangles per quad covering the mesh's area,
// BOTTOM = minus the depth of hgrid.gr3's nodes, IPOBO = each boundary node's .cli
// line; the .cli lists every boundary node once (13 fields, K its line), walls on land
// and prescribed elevation on the open segments, the outer contour counter-clockwise
// from its south-west node, then the island clockwise. QGIS's mesh reader opens the
// geometry.
// ADCIRC's fort.14: hgrid.gr3's nodes (in longitude and latitude, as hgrid.ll) and depths,
// each quad as two counter-clockwise triangles, the open segments as the gr3's, and flux
// boundaries that cover every other boundary edge once: mainland (IBTYPE 20) first, then
// the island (21), closed by its first node again.
TEST(CliOutputs, AdcircGridHasTheTrianglesAndBoundariesOfTheQuads) {
  TempDir dir;
  const CliResult r = mesh_water_box(dir, {"-o", dir.file("fort.14"), "-o", dir.file("hgrid.gr3")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Gr3 g = parse_gr3(dir.file("hgrid.gr3"));
  const Gr3 ll = parse_gr3(dir.file("hgrid.ll"));
  const Gr3 a = parse_gr3(dir.file("fort.14"));
  ASSERT_EQ(a.nodes.size(), g.nodes.size());
  for (std::size_t i = 0; i < a.nodes.size(); ++i)
    for (int k : {0, 1, 2}) EXPECT_NEAR(a.nodes[i][k], ll.nodes[i][k], 1e-9) << i;
  // Triangles: twice the quads, counter-clockwise, covering the quads' area.
  ASSERT_EQ(a.elements.size(), 2 * g.elements.size());
  auto area = [](const std::vector<std::array<double, 3>>& nodes, const std::vector<int>& e) {
    double s = 0;
    for (std::size_t i = 0; i < e.size(); ++i) {
      const auto &p = nodes[e[i] - 1], &q = nodes[e[(i + 1) % e.size()] - 1];
      s += p[0] * q[1] - q[0] * p[1];
    }
    return s / 2;
  };
  double quads = 0, triangles = 0;
  for (const auto& e : g.elements) quads += area(g.nodes, e);
  std::map<std::pair<int, int>, int> edges;  // undirected, how many triangles
  for (const auto& e : a.elements) {
    ASSERT_EQ(e.size(), 3u);
    EXPECT_GT(area(a.nodes, e), 0.0);  // counter-clockwise in longitude and latitude
    triangles += area(g.nodes, e);
    for (int i = 0; i < 3; ++i) ++edges[std::minmax(e[i], e[(i + 1) % 3])];
  }
  EXPECT_NEAR(triangles, quads, 1e-9 * quads);
  // Boundaries: the open segments are the gr3's; with the land segments, every boundary
  // edge (of one triangle) once.
  EXPECT_EQ(a.open, g.open);
  std::size_t open_nodes = 0, land_nodes = 0;
  std::map<std::pair<int, int>, int> listed;
  auto add = [&](const std::vector<int>& s) {
    for (std::size_t i = 0; i + 1 < s.size(); ++i) ++listed[std::minmax(s[i], s[i + 1])];
  };
  for (const auto& s : a.open) open_nodes += s.size(), add(s);
  EXPECT_EQ(a.open_total, open_nodes);
  ASSERT_EQ(a.land.size(), g.land.size());
  std::size_t islands = 0;
  for (std::size_t k = 0; k < a.land.size(); ++k) {
    const auto& s = a.land[k];
    land_nodes += s.size();
    add(s);
    ASSERT_TRUE(a.land_flags[k] == 20 || a.land_flags[k] == 21) << k;
    if (a.land_flags[k] == 21) {
      ++islands;
      EXPECT_EQ(s.front(), s.back()) << k;  // closed
    } else {
      EXPECT_EQ(islands, 0u) << "a mainland segment after an island";
    }
  }
  EXPECT_EQ(islands, 1u);
  EXPECT_EQ(a.land_total, land_nodes);
  std::map<std::pair<int, int>, int> boundary;
  for (const auto& [edge, n] : edges)
    if (n == 1) boundary[edge] = 1;
  EXPECT_EQ(listed, boundary);
  // Depths as the gr3's.
  for (std::size_t i = 0; i < a.nodes.size(); ++i) EXPECT_EQ(a.nodes[i][2], g.nodes[i][2]);
  // --output-crs: the coordinates the user asks for (a Cartesian ADCIRC run, ICS = 1).
  const CliResult utm =
      mesh_water_box(dir, {"-o", dir.file("utm.14"), "--output-crs", "EPSG:32630"});
  ASSERT_EQ(utm.exit_code, 0) << utm.err;
  const Gr3 u = parse_gr3(dir.file("utm.14"));
  ASSERT_EQ(u.nodes.size(), a.nodes.size());
  EXPECT_GT(u.nodes[0][0], 100000.0);  // metres
  EXPECT_EQ(u.elements, a.elements);
}

// An island across the antimeridian (drawn in two halves, as Natural Earth draws Fiji):
// in longitude and latitude its outputs stay whole, with longitudes past 180.
TEST(CliOutputs, LonLatOutputsAcrossTheAntimeridianStayWhole) {
  TempDir dir;
  const std::string input = dir.file("island.geojson");
  write_file(input, geojson_polygons(
                        {"[[[179.6,-17],[180,-17],[180,-16.6],[179.6,-16.6],[179.6,-17]]]",
                         "[[[-180,-17],[-179.6,-17],[-179.6,-16.6],[-180,-16.6],[-180,-17]]]"}));
  for (const bool output_crs : {false, true}) {
    std::vector<std::string> args = {"mesh",           input, "--size",          "5000",       "-o",
                                     dir.file("a.14"), "-o",  dir.file("a.gr3"), "--overwrite"};
    if (output_crs)
      args.insert(args.end(), {"-o", dir.file("a.gpkg"), "--output-crs", "EPSG:4326"});
    const CliResult r = run_cli(args, dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* file : {"a.14", "a.ll"}) {
      const Gr3 g = parse_gr3(dir.file(file));
      ASSERT_GT(g.nodes.size(), 50u);
      double lo = 1e9, hi = -1e9;
      for (const auto& n : g.nodes) lo = std::min(lo, n[0]), hi = std::max(hi, n[0]);
      EXPECT_NEAR(lo, 179.6, 1e-6) << file;
      EXPECT_NEAR(hi, 180.4, 1e-6) << file;
    }
  }
  GDALDataset* ds = open_vector(dir.file("a.gpkg"));
  ASSERT_NE(ds, nullptr);
  OGREnvelope extent;
  ASSERT_EQ(ds->GetLayerByName("quads")->GetExtent(&extent), OGRERR_NONE);
  GDALClose(ds);
  EXPECT_NEAR(extent.MinX, 179.6, 1e-6);
  EXPECT_NEAR(extent.MaxX, 180.4, 1e-6);
}

// Python: record() returns the next Fortran record of the Selafin file sys.argv[1] (a
// 4-byte big-endian length before and after it, both checked).
constexpr const char* kSelafinRecords =
    "import struct, sys\n"
    "import numpy as np\n"
    "data = open(sys.argv[1], 'rb').read()\n"
    "pos = 0\n"
    "def record():\n"
    "    global pos\n"
    "    (n,) = struct.unpack('>i', data[pos:pos + 4])\n"
    "    body = data[pos + 4:pos + 4 + n]\n"
    "    assert struct.unpack('>i', data[pos + 4 + n:pos + 8 + n]) == (n,)\n"
    "    pos += n + 8\n"
    "    return body\n";

TEST(CliOutputs, TelemacGeometryAndBoundaryConditions) {
  TempDir dir;
  const CliResult r = mesh_water_box(dir, {"-o", dir.file("geo.slf"), "-o", dir.file("hgrid.gr3"),
                                           "--report", dir.file("r.json")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Gr3 g = parse_gr3(dir.file("hgrid.gr3"));

  // The .cli.
  std::istringstream in(read_file(dir.file("geo.cli")));
  std::vector<int> nodes;
  std::vector<bool> open;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::vector<std::string> f;
    for (std::string s; fields >> s;) f.push_back(s);
    ASSERT_EQ(f.size(), 13u) << line;
    EXPECT_EQ(std::stoul(f[12]), nodes.size() + 1) << line;
    const std::string codes = f[0] + f[1] + f[2] + f[7];
    EXPECT_TRUE(codes == "2222" || codes == "5444") << line;
    nodes.push_back(std::stoi(f[11]));
    open.push_back(codes == "5444");
  }
  std::set<int> open_nodes, boundary_nodes;
  for (const auto& s : g.open)
    for (int n : s) open_nodes.insert(n), boundary_nodes.insert(n);
  for (const auto& s : g.land) boundary_nodes.insert(s.begin(), s.end());
  EXPECT_EQ(std::set<int>(nodes.begin(), nodes.end()), boundary_nodes);
  ASSERT_EQ(nodes.size(), boundary_nodes.size());  // each once
  for (std::size_t k = 0; k < nodes.size(); ++k)
    EXPECT_EQ(open[k], open_nodes.count(nodes[k]) > 0) << k;
  // The island (the land segment flagged 1) comes last; the outer contour first, from its
  // south-west node, counter-clockwise.
  std::size_t island = 0;
  for (std::size_t s = 0; s < g.land.size(); ++s)
    if (g.land_flags[s]) island = g.land[s].size();
  ASSERT_GT(island, 3u);
  auto signed_area = [&](std::size_t from, std::size_t to) {
    double a = 0;
    for (std::size_t k = from; k < to; ++k) {
      const auto &p = g.nodes[nodes[k] - 1], &q = g.nodes[nodes[k + 1 < to ? k + 1 : from] - 1];
      a += 0.5 * (p[0] * q[1] - q[0] * p[1]);
    }
    return a;
  };
  const std::size_t outer = nodes.size() - island;
  EXPECT_GT(signed_area(0, outer), 0.0);
  EXPECT_LT(signed_area(outer, nodes.size()), 0.0);
  for (std::size_t k = 1; k < outer; ++k) {
    const auto &first = g.nodes[nodes[0] - 1], &p = g.nodes[nodes[k] - 1];
    EXPECT_LE(first[0] + first[1], p[0] + p[1]) << k;
  }

  // The geometry, and the mesh's area from the report.
  const std::string report = read_file(dir.file("r.json"));
  const std::size_t at = report.find("\"mesh_area_m2\":");
  ASSERT_NE(at, std::string::npos);
  const double mesh_area = std::stod(report.substr(at + 15));
  std::ostringstream cli_nodes, depths;
  for (int n : nodes) cli_nodes << n << " ";
  for (const auto& n : g.nodes) depths << n[2] << " ";
  write_file(dir.file("nodes.txt"), cli_nodes.str());
  write_file(dir.file("depths.txt"), depths.str());
  python_check(
      dir,
      std::string(kSelafinRecords) +
          "ints = lambda b: np.frombuffer(b, '>i4')\n"
          "reals = lambda b: np.frombuffer(b, '>f8')\n"
          "title = record()\n"
          "assert len(title) == 80 and title.endswith(b'SERAFIND'), title\n"
          "assert ints(record()).tolist() == [1, 0]\n"
          "assert record() == b'BOTTOM'.ljust(16) + b'M'.ljust(16)\n"
          "iparam = ints(record())\n"
          "nelem, npoin, ndp, one = ints(record())\n"
          "assert ndp == 3 and one == 1 and nelem == 2 * int(sys.argv[3])\n"
          "ikle = ints(record()).reshape(nelem, 3) - 1\n"
          "ipobo = ints(record())\n"
          "x, y = reals(record()), reals(record())\n"
          "assert reals(record()).tolist() == [0.0]\n"
          "bottom = reals(record())\n"
          "assert pos == len(data)\n"
          "cli = [int(n) - 1 for n in open(sys.argv[4]).read().split()]\n"
          "assert iparam.tolist() == [1, 0, 0, 0, 0, 0, 0, 0, 0, 0] and len(ipobo) == npoin\n"
          "want = np.zeros(npoin, int)\n"
          "want[cli] = np.arange(1, len(cli) + 1)\n"
          "assert (ipobo == want).all()\n"
          "depth = np.array(open(sys.argv[5]).read().split(), float)\n"
          "assert len(depth) == npoin and np.allclose(bottom, -depth, atol=1e-6) and "
          "bottom.min() < -100\n"
          "a, b, c = ikle[:, 0], ikle[:, 1], ikle[:, 2]\n"
          "area = 0.5 * ((x[b] - x[a]) * (y[c] - y[a]) - (x[c] - x[a]) * (y[b] - y[a]))\n"
          "assert area.min() > 0, area.min()\n"
          "assert abs(area.sum() - float(sys.argv[2])) < 1e-6 * area.sum(), (area.sum(), "
          "sys.argv[2])\n",
      {dir.file("geo.slf"), std::to_string(mesh_area), std::to_string(g.num_elements),
       dir.file("nodes.txt"), dir.file("depths.txt")});

  const std::string out = read_mesh_layers_in_qgis(dir, {dir.file("geo.slf")});
  // (MDAL reads BOTTOM as a data set, not as the vertices' z.)
  const std::string want =
      std::to_string(g.nodes.size()) + " " + std::to_string(2 * g.num_elements) + " [3] ";
  EXPECT_EQ(out.substr(0, want.size()), want) << out;
}

// Open and land whatever the simplification: without it the bbox sides keep every
// densified vertex (and the quads' boundary vertices lie on chords of the projected,
// curved parallels); with it the sides may be chords of up to the tolerance.
TEST(CliOutputs, OpenBoundaryFollowsTheBboxWithAndWithoutSimplification) {
  TempDir dir;
  const std::string input = water_input(dir);
  for (const char* simplify : {"0", "50", "400"}) {
    const std::string gr3 = dir.file(std::string("s") + simplify + ".gr3");
    const CliResult r = run_cli({"mesh", input, "--domain", "water", "--bbox", "-4.6,48.2,-4.4,48.35",
                                 "--size", "800", "--simplify", simplify, "-o", gr3, "-q"},
                                dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Gr3 g = parse_gr3(gr3);
    const Gr3 ll = parse_gr3(gr3.substr(0, gr3.size() - 4) + ".ll");
    ASSERT_EQ(g.open.size(), 1u) << simplify;
    EXPECT_EQ(g.land_flags, (std::vector<int>{0, 1})) << simplify;
    for (int n : g.open[0])
      EXPECT_TRUE(on_bbox(ll.nodes[n - 1][0], ll.nodes[n - 1][1], 1e-4)) << simplify << " " << n;
    // A land segment touches the bbox only at its ends.
    for (const auto& seg : g.land)
      for (std::size_t i = 1; i + 1 < seg.size(); ++i)
        EXPECT_FALSE(on_bbox(ll.nodes[seg[i] - 1][0], ll.nodes[seg[i] - 1][1], 1e-6))
            << simplify << " " << seg[i];
  }
}

// Vertices outside the bathymetry take the depth of the nearest vertex with one (along
// the mesh's edges), with a warning that counts them; the report says so too.
TEST(CliOutputs, VerticesOutsideTheBathymetryTakeTheNearestDepth) {
  TempDir dir;
  const std::string dem = bathymetry(dir, 20);  // 4.7 W to 4.5 W: the west of the bbox
  const CliResult r =
      run_cli({"mesh", water_input(dir), "--domain", "water", "--bbox", "-4.6,48.2,-4.4,48.35",
               "--size", "800", "--bathymetry", dem, "-o", dir.file("hgrid.gr3"), "-o",
               dir.file("m.nc"), "--report", dir.file("m.json")},
              dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The UGRID file in the automatic local projection, depth on nodes as in the gr3.
  python_check(dir,
               "import sys, netCDF4, numpy as np\n"
               "d = netCDF4.Dataset(sys.argv[1])\n"
               "c = d['projected_coordinate_system']\n"
               "assert c.grid_mapping_name == 'oblique_stereographic', c.grid_mapping_name\n"
               "assert abs(c.latitude_of_projection_origin - 48.275) < 0.01\n"
               "assert abs(c.longitude_of_central_meridian + 4.5) < 0.01\n"
               "assert d['mesh_node_x'].standard_name == 'projection_x_coordinate'\n"
               "gr3 = np.loadtxt(sys.argv[2], skiprows=2, max_rows=d.dimensions['n_node'].size)\n"
               "assert np.allclose(gr3[:, 3], d['depth'][:], atol=1e-6)\n"
               "assert np.allclose(gr3[:, 1], d['mesh_node_x'][:], atol=1e-6)\n",
               {dir.file("m.nc"), dir.file("hgrid.gr3")});
  const Gr3 ll = parse_gr3(dir.file("hgrid.ll"));
  // The depths where the raster has them (it ends at 4.5 W: past its last pixel centre,
  // and up to half a pixel past its edge, the values are its edge's), the set every
  // vertex's depth must come from.
  std::vector<double> sampled;
  std::size_t filled = 0;
  for (const auto& n : ll.nodes) {
    if (n[0] < -4.505) {
      EXPECT_NEAR(n[2], depth_at(n[0], n[1]), 0.01);
    } else if (n[0] <= -4.495) {
      EXPECT_NEAR(n[2], depth_at(-4.505, n[1]), 0.01);
    }
    if (n[0] <= -4.495) {
      sampled.push_back(n[2]);
    } else {
      ++filled;
    }
  }
  for (const auto& n : ll.nodes)
    EXPECT_TRUE(std::any_of(sampled.begin(), sampled.end(),
                            [&](double z) { return std::abs(z - n[2]) < 1e-6; }))
        << n[0] << " " << n[1] << " " << n[2];
  EXPECT_GT(filled, ll.nodes.size() / 4);
  EXPECT_NE(
      r.err.find("warning: " + std::to_string(filled) + " vertices lie outside the bathymetry"),
      std::string::npos)
      << r.err;
  const std::string report = read_file(dir.file("m.json"));
  EXPECT_NE(report.find("\"num_filled\": " + std::to_string(filled) + ","), std::string::npos)
      << report;
}

// Several rasters: at each vertex the first with a depth gives it; --min-depth raises the
// shallower ones; a raster that cannot be read stops the run before the meshing.
TEST(CliOutputs, BathymetryRastersInPriorityOrderAndMinimumDepth) {
  TempDir dir;
  const std::string west = bathymetry(dir, 20);  // 4.7 W to 4.5 W
  const std::string deep = uniform_raster(dir, "deep.tif", 500.0);
  auto run = [&](const std::vector<std::string>& extra) { return mesh_box_800(dir, extra); };
  CliResult r = run({"--bathymetry", west, "--bathymetry", deep, "-o", dir.file("a.gr3")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(without_schism_warning(r.err).find("warning"), std::string::npos) << r.err;
  Gr3 ll = parse_gr3(dir.file("a.ll"));
  for (const auto& n : ll.nodes) {
    if (n[0] < -4.51) {
      EXPECT_NEAR(n[2], depth_at(n[0], n[1]), 0.01);
    } else if (n[0] > -4.49) {
      EXPECT_NEAR(n[2], 500.0, 1e-6);
    }
  }
  // The other order: the deep raster covers everything.
  r = run({"--bathymetry", deep, "--bathymetry", west, "--min-depth", "600", "-o",
           dir.file("b.gr3"), "-o", dir.file("b.gpkg")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ll = parse_gr3(dir.file("b.ll"));
  for (const auto& n : ll.nodes) EXPECT_NEAR(n[2], 600.0, 1e-6);
  EXPECT_NE(r.err.find("depths:       600 .. 600 m, " + std::to_string(ll.nodes.size()) +
                       " vertices raised to --min-depth"),
            std::string::npos)
      << r.err;
  // Each quad's time step at Courant 1: its width (between opposite sides' midpoints)
  // over sqrt(g 600 m); the summary gives the smallest.
  {
    GDALDataset* ds = open_vector(dir.file("b.gpkg"));
    ASSERT_NE(ds, nullptr);
    OGRLayer* quads = ds->GetLayerByName("quads");
    ASSERT_NE(quads, nullptr);
    double smallest = INFINITY;
    std::size_t n = 0;
    for (auto& f : *quads) {
      const OGRLinearRing* ring =
          dynamic_cast<const OGRPolygon*>(f->GetGeometryRef())->getExteriorRing();
      auto mid = [&](int i) {
        return std::array<double, 2>{(ring->getX(i) + ring->getX(i + 1)) / 2,
                                     (ring->getY(i) + ring->getY(i + 1)) / 2};
      };
      auto apart = [&](int i, int j) {
        return std::hypot(mid(i)[0] - mid(j)[0], mid(i)[1] - mid(j)[1]);
      };
      const double expected = std::min(apart(0, 2), apart(1, 3)) / std::sqrt(9.81 * 600);
      const double dt = f->GetFieldAsDouble("time_step_s");
      EXPECT_NEAR(dt, expected, 1e-6 * expected) << f->GetFID();
      smallest = std::min(smallest, dt);
      ++n;
    }
    GDALClose(ds);
    EXPECT_GT(n, 100u);
    char line[64];
    std::snprintf(line, sizeof line, "time step:    %.3g s at a gravity-wave Courant", smallest);
    EXPECT_NE(r.err.find(line), std::string::npos) << line << "\n" << r.err;
  }
  // An unreadable raster: exit 3 at once, naming it, nothing written.
  write_file(dir.file("bad.tif"), "not a raster");
  r = run({"--bathymetry", west, "--bathymetry", dir.file("bad.tif"), "-o", dir.file("c.gr3")});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("bad.tif"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("quads:"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("c.gr3")));
  // --min-depth alone means nothing.
  r = run({"--min-depth", "5", "-o", dir.file("d.gr3")});
  EXPECT_EQ(r.exit_code, 2) << r.err;
}

// --elevation reads a raster positive up (as GEBCO's) as depths, in one priority list with
// --bathymetry in the order given; a raster of elevations given as depths leaves the mesh
// dry, with a warning.
TEST(CliOutputs, ElevationRastersGiveTheSameDepths) {
  TempDir dir;
  const std::string west = bathymetry(dir, 20);  // depths, 4.7 W to 4.5 W
  const std::string west_z =
      write_geotiff(dir.file("west_z.tif"), -4.7, 48.45, 0.01, 20, 35, 4326,
                    [](double lon, double lat) { return -depth_at(lon, lat); });
  const std::string deep_z = uniform_raster(dir, "deep_z.tif", -500.0);
  auto run = [&](const std::vector<std::string>& extra) { return mesh_box_800(dir, extra); };
  // Elevations only, and depths then elevations: the same depths.
  CliResult r = run({"--elevation", west_z, "--elevation", deep_z, "-o", dir.file("z.gr3")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(without_schism_warning(r.err).find("warning"), std::string::npos) << r.err;
  const Gr3 z = parse_gr3(dir.file("z.ll"));
  r = run({"--bathymetry", west, "--elevation", deep_z, "-o", dir.file("d.gr3")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Gr3 d = parse_gr3(dir.file("d.ll"));
  ASSERT_EQ(z.nodes.size(), d.nodes.size());
  std::size_t west_nodes = 0, east_nodes = 0;
  for (std::size_t i = 0; i < z.nodes.size(); ++i) {
    EXPECT_NEAR(z.nodes[i][2], d.nodes[i][2], 1e-9) << i;
    if (z.nodes[i][0] < -4.51) {
      EXPECT_NEAR(z.nodes[i][2], depth_at(z.nodes[i][0], z.nodes[i][1]), 0.01) << i;
      ++west_nodes;
    } else if (z.nodes[i][0] > -4.49) {
      EXPECT_NEAR(z.nodes[i][2], 500.0, 1e-6) << i;
      ++east_nodes;
    }
  }
  EXPECT_GT(west_nodes, 20u);
  EXPECT_GT(east_nodes, 20u);
  // The order given is the priority: deep_z first covers everything.
  r = run({"--elevation", deep_z, "--bathymetry", west, "-o", dir.file("e.gr3")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const auto& n : parse_gr3(dir.file("e.ll")).nodes) EXPECT_NEAR(n[2], 500.0, 1e-6);
  // Elevations given as depths: every vertex dry, a warning says what to do.
  r = run({"--bathymetry", deep_z, "-o", dir.file("w.gr3"), "--report", dir.file("w.json")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::size_t n = parse_gr3(dir.file("w.ll")).nodes.size();
  EXPECT_NE(r.err.find("warning: " + std::to_string(n) + " of the mesh's " + std::to_string(n) +
                       " vertices are dry (depth 0 or less)"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("--elevation"), std::string::npos) << r.err;
  EXPECT_NE(read_file(dir.file("w.json")).find("\"num_dry\": " + std::to_string(n)),
            std::string::npos);
  // An unreadable elevation raster is named with its option.
  write_file(dir.file("bad.tif"), "not a raster");
  r = run({"--elevation", dir.file("bad.tif"), "-o", dir.file("f.gr3")});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("--elevation"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("bad.tif"), std::string::npos) << r.err;
}

namespace {

// The quads' time steps (time_step_s) of a GeoPackage written by `isoquad mesh`.
std::vector<double> quad_time_steps(const std::string& gpkg) {
  std::vector<double> steps;
  GDALDataset* ds = open_vector(gpkg);
  if (!ds) return steps;
  if (OGRLayer* quads = ds->GetLayerByName("quads"))
    for (auto& f : *quads) steps.push_back(f->GetFieldAsDouble("time_step_s"));
  GDALClose(ds);
  return steps;
}

}  // namespace

// A model's grid meshed again: hgrid.ll as INPUT (its outline the domain, its open
// boundaries kept) and as --bathymetry (its depths, linear over its elements, at the new
// vertices). The raster's depths are linear in lon/lat, so the old grid's give them again
// inside it; the new boundary vertices take the value of the old grid's nearest boundary
// point.
TEST(CliOutputs, AModelsGridMeshedAgainKeepsItsSeaBoundaryAndDepths) {
  TempDir dir;
  CliResult r = mesh_water_box(dir, {"-o", dir.file("hgrid.gr3"), "-o", dir.file("net.nc")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Gr3 old = parse_gr3(dir.file("hgrid.ll"));
  ASSERT_FALSE(old.open.empty());
  r = run_cli({"mesh", dir.file("hgrid.ll"), "--size", "1200", "--bathymetry", dir.file("hgrid.ll"),
               "-o", dir.file("again.gr3")},
              dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("outside the bathymetry"), std::string::npos) << r.err;
  const Gr3 again = parse_gr3(dir.file("again.ll"));
  EXPECT_EQ(again.open.size(), old.open.size());
  EXPECT_LT(again.nodes.size(), old.nodes.size());
  std::size_t close = 0;
  for (const auto& n : again.nodes) {
    const double error = std::abs(n[2] - depth_at(n[0], n[1]));
    EXPECT_LT(error, 10.0) << n[0] << " " << n[1];
    close += error < 0.5;
  }
  EXPECT_GT(close, 0.9 * again.nodes.size());
  // The UGRID file's bed levels (mesh_node_z, positive up) give the same depths.
  r = run_cli({"mesh", dir.file("hgrid.ll"), "--size", "1200", "--elevation", dir.file("net.nc"),
               "-o", dir.file("from_nc.gr3")},
              dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Gr3 from_nc = parse_gr3(dir.file("from_nc.ll"));
  ASSERT_EQ(from_nc.nodes.size(), again.nodes.size());
  for (std::size_t i = 0; i < again.nodes.size(); ++i)
    EXPECT_NEAR(from_nc.nodes[i][2], again.nodes[i][2], 0.01) << i;
  // An ADCIRC grid in lon/lat: another mesher's fort.14 says no CRS, and is read in
  // --src-crs; without it, in the meshing CRS, where it gives no vertex a depth.
  // isoquad's own names its CRS in its title line.
  r = mesh_water_box(dir, {"-o", dir.file("lonlat.14"), "--output-crs", "EPSG:4326"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_cli({"mesh", dir.file("hgrid.ll"), "--src-crs", "EPSG:4326", "--size", "1200",
               "--bathymetry", dir.file("lonlat.14"), "-o", dir.file("from_14.gr3")},
              dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Gr3 from_14 = parse_gr3(dir.file("from_14.ll"));
  ASSERT_EQ(from_14.nodes.size(), again.nodes.size());
  for (std::size_t i = 0; i < again.nodes.size(); ++i)
    EXPECT_NEAR(from_14.nodes[i][2], again.nodes[i][2], 0.01) << i;
  r = run_cli({"mesh", dir.file("hgrid.ll"), "--size", "1200", "--bathymetry",
               dir.file("lonlat.14"), "-o", dir.file("own_crs.gr3")},
              dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Gr3 own_crs = parse_gr3(dir.file("own_crs.ll"));
  ASSERT_EQ(own_crs.nodes.size(), again.nodes.size());
  for (std::size_t i = 0; i < again.nodes.size(); ++i)
    EXPECT_NEAR(own_crs.nodes[i][2], again.nodes[i][2], 0.01) << i;
  std::string other = read_file(dir.file("lonlat.14"));
  ASSERT_NE(other.find(" CRS: EPSG:4326\n"), std::string::npos);
  other.replace(0, other.find('\n'), "a grid from another mesher");
  write_file(dir.file("other.14"), other);
  r = run_cli({"mesh", dir.file("hgrid.ll"), "--size", "1200", "--bathymetry", dir.file("other.14"),
               "-o", dir.file("no_crs.gr3")},
              dir);
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.err.find("no vertex of the mesh lies where it has a depth"), std::string::npos)
      << r.err;
}

// A Gmsh .msh keeps its sea boundary when meshed again: the lines of its physical groups
// named open..., or of the groups given with --open-groups; groups of other names leave
// the boundary land, with a warning that names them. The same with a .2dm's nodestrings.
TEST(CliOutputs, AGmshGridMeshedAgainKeepsTheOpenBoundaryOfItsPhysicalGroups) {
  TempDir dir;
  CliResult r = mesh_water_box(dir, {"--dst-crs", "EPSG:32630", "-o", dir.file("hgrid.gr3"), "-o",
                                     dir.file("grid.msh"), "-o", dir.file("grid.2dm")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Gr3 old = parse_gr3(dir.file("hgrid.gr3"));
  ASSERT_FALSE(old.open.empty());
  auto again = [&](const std::string& input, std::vector<std::string> extra) {
    std::vector<std::string> args = {"mesh", input, "--src-crs",           "EPSG:32630", "--size",
                                     "1200", "-o",  dir.file("again.gr3"), "--overwrite"};
    args.insert(args.end(), extra.begin(), extra.end());
    return run_cli(args, dir);
  };
  r = again(dir.file("grid.msh"), {});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("physical groups"), std::string::npos) << r.err;
  EXPECT_EQ(parse_gr3(dir.file("again.gr3")).open.size(), old.open.size());
  // The groups renamed as a model's set-up may name them: land until named.
  std::string text = read_file(dir.file("grid.msh"));
  text.replace(text.find("\"open\""), 6, "\"ocean\"");
  write_file(dir.file("renamed.msh"), text);
  r = again(dir.file("renamed.msh"), {});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("physical groups of curves 1 \"land\", 2 \"ocean\", none named open"),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(parse_gr3(dir.file("again.gr3")).open.empty());
  // By its name, its number, or both (a group named twice counts once).
  for (const char* group : {"ocean", "2", "ocean,2"}) {
    r = again(dir.file("renamed.msh"), {"--open-groups", group});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(parse_gr3(dir.file("again.gr3")).open.size(), old.open.size());
  }
  // Every group open: the whole outline, one open boundary a ring.
  r = again(dir.file("renamed.msh"), {"--open-groups", "land,ocean"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(parse_gr3(dir.file("again.gr3")).land.empty());
  r = again(dir.file("renamed.msh"), {"--open-groups", "sea"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no physical group of curves 'sea'"), std::string::npos) << r.err;
  // isoquad's .2dm: nodestrings without names, the open segments' first.
  r = again(dir.file("grid.2dm"), {});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("nodestrings 1, 2"), std::string::npos) << r.err;
  EXPECT_TRUE(parse_gr3(dir.file("again.gr3")).open.empty());
  r = again(dir.file("grid.2dm"), {"--open-groups", "1"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(parse_gr3(dir.file("again.gr3")).open.size(), old.open.size());
  r = again(dir.file("hgrid.gr3"), {"--open-groups", "open"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("neither a Gmsh .msh nor an SMS .2dm"), std::string::npos) << r.err;
}

// An ADCIRC grid whose first land boundary is a river's inflow (IBTYPE 22): meshed again,
// it is an open boundary of its own, next to the sea's (two open lines that meet stay two
// segments), with a warning.
TEST(CliOutputs, AnAdcircRiverBoundaryStaysAnOpenBoundaryOfItsOwn) {
  TempDir dir;
  CliResult r = mesh_water_box(
      dir, {"--dst-crs", "EPSG:32630", "--output-crs", "EPSG:32630", "-o", dir.file("grid.14")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::string text = read_file(dir.file("grid.14"));
  const std::size_t at = text.find(" 20 = Number of nodes for land boundary 1");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 3, " 22");
  write_file(dir.file("river.14"), text);
  auto open_count = [&](const std::string& input) {
    const CliResult m = run_cli({"mesh", input, "--src-crs", "EPSG:32630", "--size", "800", "-o",
                                 dir.file("again.gr3"), "--overwrite"},
                                dir);
    EXPECT_EQ(m.exit_code, 0) << m.err;
    return std::make_pair(parse_gr3(dir.file("again.gr3")).open.size(), m.err);
  };
  const auto [sea, sea_err] = open_count(dir.file("grid.14"));
  const auto [river, river_err] = open_count(dir.file("river.14"));
  EXPECT_GE(sea, 1u);
  EXPECT_EQ(river, sea + 1);
  EXPECT_EQ(sea_err.find("flux boundary"), std::string::npos) << sea_err;
  EXPECT_NE(river_err.find("1 flux boundary(ies) of"), std::string::npos) << river_err;
  // The domain's open parts, before meshing, cut alike.
  EXPECT_NE(river_err.find("open parts:   " + std::to_string(river) + " run(s)"), std::string::npos)
      << river_err;
}

// The quads alone as GeoJSON (longitudes and latitudes, RFC 7946) and FlatGeobuf (the
// mesh's CRS), read with GDAL: the GeoPackage's quads, the same metrics by id, every
// ring closed and counter-clockwise; the same bytes from a second run; and read back by
// `isoquad quality` as a mesh of polygons.
TEST(CliOutputs, QuadsAsGeoJsonAndFlatGeobuf) {
  TempDir dir;
  const std::vector<std::string> outputs = {"-o", dir.file("m.gpkg"), "-o", dir.file("m.geojson"),
                                            "-o", dir.file("m.fgb")};
  CliResult r = mesh_box_800(dir, outputs);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The metrics of each quad by id, from a layer.
  auto metrics = [](OGRLayer* layer) {
    std::map<GIntBig, std::array<double, 3>> by_id;
    for (auto& f : *layer)
      by_id[f->GetFieldAsInteger64("id")] = {f->GetFieldAsDouble("size_ratio"),
                                             f->GetFieldAsDouble("min_angle_deg"),
                                             f->GetFieldAsDouble("orthogonality")};
    return by_id;
  };
  GDALDataset* gpkg = open_vector(dir.file("m.gpkg"));
  ASSERT_NE(gpkg, nullptr);
  const auto expected = metrics(gpkg->GetLayerByName("quads"));
  OGREnvelope native;
  ASSERT_EQ(gpkg->GetLayerByName("quads")->GetExtent(&native), OGRERR_NONE);
  GDALClose(gpkg);
  ASSERT_GT(expected.size(), 50u);
  for (const char* name : {"m.geojson", "m.fgb"}) {
    SCOPED_TRACE(name);
    GDALDataset* ds = open_vector(dir.file(name));
    ASSERT_NE(ds, nullptr);
    ASSERT_EQ(ds->GetLayerCount(), 1);
    OGRLayer* layer = ds->GetLayer(0);
    const auto got = metrics(layer);
    ASSERT_EQ(got.size(), expected.size());
    for (const auto& [id, m] : expected)
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(got.at(id)[k], m[k], 1e-9) << id;
    const bool geojson = std::string(name) == "m.geojson";
    layer->ResetReading();
    for (auto& f : *layer) {
      const OGRLinearRing* ring = f->GetGeometryRef()->toPolygon()->getExteriorRing();
      ASSERT_EQ(ring->getNumPoints(), 5);
      EXPECT_TRUE(ring->get_IsClosed());
      EXPECT_FALSE(ring->isClockwise());
      for (int i = 0; i < 4; ++i)
        if (geojson) {  // within the box, to its projected sides' chords
          EXPECT_TRUE(ring->getX(i) > kBox[0] - 1e-3 && ring->getX(i) < kBox[2] + 1e-3);
          EXPECT_TRUE(ring->getY(i) > kBox[1] - 1e-3 && ring->getY(i) < kBox[3] + 1e-3);
        }
    }
    OGREnvelope e;
    ASSERT_EQ(layer->GetExtent(&e), OGRERR_NONE);
    if (!geojson) {  // the mesh's CRS and coordinates
      EXPECT_NEAR(e.MinX, native.MinX, 1e-6);
      EXPECT_NEAR(e.MaxY, native.MaxY, 1e-6);
    }
    ASSERT_NE(layer->GetSpatialRef(), nullptr);
    EXPECT_EQ(layer->GetSpatialRef()->IsGeographic(), geojson);
    GDALClose(ds);
  }
  const std::string first = read_file(dir.file("m.geojson"));
  const std::string first_fgb = read_file(dir.file("m.fgb"));
  r = mesh_box_800(dir, {"-o", dir.file("m.geojson"), "-o", dir.file("m.fgb"), "--overwrite"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(read_file(dir.file("m.geojson")) == first);
  EXPECT_TRUE(read_file(dir.file("m.fgb")) == first_fgb);
  r = run_cli({"quality", "--mesh", dir.file("m.geojson")}, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find(std::to_string(expected.size()) + " quads"), std::string::npos)
      << r.err;  // Another CRS named by its EPSG code in the file; one without a code refused
                 // before
  // any meshing (a reader would take its coordinates for longitudes and latitudes).
  r = mesh_box_800(dir, {"-o", dir.file("l93.geojson"), "--output-crs", "EPSG:2154"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(read_file(dir.file("l93.geojson")).find("urn:ogc:def:crs:EPSG::2154"),
            std::string::npos);
  r = mesh_box_800(dir, {"-o", dir.file("custom.geojson"), "--output-crs",
                         "+proj=stere +lat_0=48 +lon_0=-4 +datum=WGS84"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("names its CRS by an EPSG code"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("custom.geojson")));
}

// Quads of 1 cm (a laboratory flume) as GeoJSON in longitude and latitude: RFC 7946's 7
// decimals (about 1 cm) left a tenth of them non-convex; the file gets the decimals they
// need.
TEST(CliOutputs, SmallQuadsAsGeoJsonStayConvex) {
  TempDir dir;
  write_file(dir.file("flume.geojson"),
             geojson_polygons({"[[[500000,5000000],[500000.5,5000000],[500000.5,5000000.5],"
                               "[500000,5000000.5],[500000,5000000]]]"},
                              kUtm31nCrsMember));
  const CliResult r = run_cli(
      {"mesh", dir.file("flume.geojson"), "--size", "0.01", "-o", dir.file("m.geojson"), "-q"},
      dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string out = python_check(
      dir,
      "import json, sys\n"
      "d = json.load(open(sys.argv[1]))\n"
      "bad = 0\n"
      "for f in d['features']:\n"
      "    p = f['geometry']['coordinates'][0][:4]\n"
      "    for k in range(4):\n"
      "        a, b, c = p[k], p[(k + 1) % 4], p[(k + 2) % 4]\n"
      "        if (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]) <= 0:\n"
      "            bad += 1\n"
      "            break\n"
      "print(len(d['features']), bad)\n",
      {dir.file("m.geojson")});
  int quads = 0, bad = -1;
  std::istringstream(out) >> quads >> bad;
  EXPECT_GT(quads, 2000) << out;
  EXPECT_EQ(bad, 0) << out;
}

// --exclude: a breakwater drawn in UTM 30N (3 x 1 km) removed from the water box in
// lon/lat: a land loop more, no node inside it; one outside the box excludes nothing and
// changes no byte; a ring that crosses itself is refused, named by its feature.
TEST(CliOutputs, ExcludeRemovesPolygonsDrawnInAnotherCrs) {
  TempDir dir;
  write_file(dir.file("breakwater.geojson"),
             geojson_polygons(
                 {"[[[388800,5353000],[391800,5353000],[391800,5354000],"
                  "[388800,5354000],[388800,5353000]]]",
                  "[[[300000,5000000],[301000,5000000],[301000,5001000],"
                  "[300000,5001000],[300000,5000000]]]"},
                 R"("crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::32630"}},)"));
  CliResult r = mesh_box_800(dir, {"-o", dir.file("plain.gr3")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = mesh_box_800(dir, {"--exclude", dir.file("breakwater.geojson"), "-o", dir.file("m.gr3")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The second polygon lies far south of the box: not read. 3 km2 (UTM's scale against
  // the meshing CRS's: within 0.1%).
  EXPECT_NE(
      r.err.find("excluded:     1 polygon(s) of " + dir.file("breakwater.geojson") + ": 3.00"),
      std::string::npos)
      << r.err;
  const Gr3 plain = parse_gr3(dir.file("plain.ll")), ll = parse_gr3(dir.file("m.ll"));
  EXPECT_EQ(ll.land.size(), plain.land.size() + 1);
  EXPECT_EQ(ll.open.size(), plain.open.size());
  // The breakwater's corners in lon/lat (its sides stay straight to 1e-6 degree).
  const std::vector<isoquad::Point2> wall = {{-4.500038, 48.320403},
                                             {-4.459583, 48.320924},
                                             {-4.45984, 48.329917},
                                             {-4.500302, 48.329397}};
  auto depth_inside = [&](double x, double y) {  // > 0 inside, in degrees from the sides
    double d = 1e9;
    for (std::size_t i = 0; i < wall.size(); ++i) {
      const isoquad::Point2 &a = wall[i], &b = wall[(i + 1) % wall.size()];
      d = std::min(d, ((b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x)) /
                          std::hypot(b.x - a.x, b.y - a.y));
    }
    return d;
  };
  std::size_t on_wall = 0;
  for (const auto& n : ll.nodes) {
    const double d = depth_inside(n[0], n[1]);
    EXPECT_LT(d, 1e-4) << n[0] << " " << n[1];
    if (std::abs(d) < 1e-4) ++on_wall;
  }
  EXPECT_GE(on_wall, 8u);  // the breakwater's edge, 8 km long, meshed at 800 m
  // Picked away by --exclude-where: nothing excluded, a warning, the same bytes.
  r = mesh_box_800(dir, {"--exclude", dir.file("breakwater.geojson"), "--exclude-where",
                         "name = 'f1'", "-o", dir.file("none.gr3")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("has no polygon in the area meshed: nothing is excluded"), std::string::npos)
      << r.err;
  EXPECT_EQ(read_file(dir.file("none.gr3")), read_file(dir.file("plain.gr3")));
  // A file whose every polygon lies far from the box (its extent misses it): the same.
  write_file(dir.file("far.geojson"),
             geojson_polygons({"[[[10,10],[11,10],[11,11],[10,11],[10,10]]]"}));
  r = mesh_box_800(dir, {"--exclude", dir.file("far.geojson"), "-o", dir.file("far.gr3")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("nothing is excluded"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(dir.file("far.gr3")), read_file(dir.file("plain.gr3")));
  // With --clip, a polygon within the area's box but outside the area (a triangle): read
  // as far as its box, then left out, the same.
  write_file(dir.file("triangle.geojson"),
             geojson_polygons({"[[[-4.6,48.2],[-4.3,48.2],[-4.6,48.35],[-4.6,48.2]]]"}));
  write_file(dir.file("corner.geojson"),
             geojson_polygons({"[[[-4.33,48.32],[-4.31,48.32],[-4.31,48.34],[-4.33,48.34],"
                               "[-4.33,48.32]]]"}));
  const std::vector<std::string> clipped = {"mesh",     water_input(dir),
                                            "--domain", "water",
                                            "--clip",   dir.file("triangle.geojson"),
                                            "--size",   "800",
                                            "-q"};
  std::vector<std::string> args = clipped;
  args.insert(args.end(), {"-o", dir.file("tri.gr3")});
  r = run_cli(args, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  args = clipped;
  args.insert(args.end(), {"--exclude", dir.file("corner.geojson"), "-o", dir.file("tri_x.gr3")});
  r = run_cli(args, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_file(dir.file("tri_x.gr3")), read_file(dir.file("tri.gr3")));
  // A pier of 100 x 100 m under quads of 800 m: a hole under --min-island-area, dropped,
  // and said so.
  write_file(dir.file("pier.geojson"),
             geojson_polygons(
                 {"[[[390000,5353000],[390100,5353000],[390100,5353100],"
                  "[390000,5353100],[390000,5353000]]]"},
                 R"("crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::32630"}},)"));
  r = mesh_box_800(dir, {"--exclude", dir.file("pier.geojson"), "-o", dir.file("pier.gr3")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("1 of its 1 area(s) lie mostly in the domain after all"), std::string::npos)
      << r.err;
  EXPECT_EQ(parse_gr3(dir.file("pier.ll")).land.size(), plain.land.size());
  // Invalid: refused without --repair, with the feature and where, in the file's CRS.
  write_file(
      dir.file("bowtie.geojson"),
      geojson_polygons({"[[[-4.5,48.32],[-4.46,48.33],[-4.46,48.32],[-4.5,48.33],[-4.5,48.32]]]"}));
  r = mesh_box_800(dir, {"--exclude", dir.file("bowtie.geojson"), "-o", dir.file("x.gr3")});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.err.find("--exclude '" + dir.file("bowtie.geojson") +
                       "': feature 0 is invalid: Self-intersection at or near (-4.48"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("x.gr3")));
  r = mesh_box_800(dir,
                   {"--exclude", dir.file("bowtie.geojson"), "--repair", "-o", dir.file("x.gr3")});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  r = mesh_box_800(dir, {"--exclude-layer", "a", "-o", dir.file("y.gr3")});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--exclude-layer and --exclude-where need --exclude"), std::string::npos)
      << r.err;
}

// --each-clip: a mesh per polygon of --clip from one land file, each the same bytes as
// the run with --clip-where picking that polygon, every node in its area; the batch's
// table a row per area.
TEST(CliOutputs, EachClipMeshesEveryAreaOfTheClipFile) {
  TempDir dir;
  write_file(dir.file("areas.geojson"),
             geojson_polygons({"[[[-4.6,48.2],[-4.35,48.18],[-4.3,48.33],[-4.45,48.4],[-4.62,"
                               "48.33],[-4.6,48.2]]]",
                               "[[[-4.58,48.21],[-4.5,48.21],[-4.5,48.26],[-4.58,48.26],[-4.58,"
                               "48.21]]]"}));
  CliResult r = run_cli({"mesh", water_input(dir), "--domain", "water", "--clip",
                         dir.file("areas.geojson"), "--each-clip", "name", "--size", "800", "-q",
                         "-o", dir.file("m_{}.gr3"), "--each-table", dir.file("areas.csv")},
                        dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string table = read_file(dir.file("areas.csv"));
  EXPECT_NE(table.find("\nf0,f0,meshed,0,"), std::string::npos) << table;
  EXPECT_NE(table.find("\nf1,f1,meshed,0,"), std::string::npos) << table;
  for (const std::string name : {"f0", "f1"}) {
    r = run_cli({"mesh", water_input(dir), "--domain", "water", "--clip", dir.file("areas.geojson"),
                 "--clip-where", "name = '" + name + "'", "--size", "800", "-q", "-o",
                 dir.file("one_" + name + ".gr3")},
                dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(read_file(dir.file("m_" + name + ".gr3")),
              read_file(dir.file("one_" + name + ".gr3")))
        << name;
  }
  // The rectangle's nodes within it (its edges to 1e-4 degree).
  for (const auto& n : parse_gr3(dir.file("m_f1.ll")).nodes) {
    EXPECT_GT(n[0], -4.58 - 1e-4);
    EXPECT_LT(n[0], -4.5 + 1e-4);
    EXPECT_GT(n[1], 48.21 - 1e-4);
    EXPECT_LT(n[1], 48.26 + 1e-4);
  }
  r = run_cli({"mesh", water_input(dir), "--domain", "water", "--each-clip", "name", "-o",
               dir.file("x_{}.gr3")},
              dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--each-clip makes a mesh per polygon of --clip: give --clip"),
            std::string::npos)
      << r.err;
  // Two polygons with one value: refused before any meshing, the value named.
  write_file(
      dir.file("twice.geojson"),
      R"({"type":"FeatureCollection","features":[)"
      R"({"type":"Feature","properties":{"name":"bay"},"geometry":{"type":"Polygon",)"
      R"("coordinates":[[[-4.58,48.21],[-4.5,48.21],[-4.5,48.26],[-4.58,48.26],[-4.58,48.21]]]}},)"
      R"({"type":"Feature","properties":{"name":"bay"},"geometry":{"type":"Polygon",)"
      R"("coordinates":[[[-4.4,48.21],[-4.35,48.21],[-4.35,48.26],[-4.4,48.26],[-4.4,48.21]]]}}]})");
  r = run_cli({"mesh", water_input(dir), "--domain", "water", "--clip", dir.file("twice.geojson"),
               "--each-clip", "name", "--size", "800", "-o", dir.file("t_{}.gr3")},
              dir);
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("--each-clip name meshes one polygon per value, and several polygons "
                       "have the value 'bay' (2 polygons): give each its own value"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("=="), std::string::npos) << r.err;  // no region started
  EXPECT_FALSE(std::filesystem::exists(dir.file("t_bay.gr3")));
  // A multi-polygon of two parts: the same.
  write_file(
      dir.file("parts.geojson"),
      R"({"type":"FeatureCollection","features":[)"
      R"({"type":"Feature","properties":{"name":"one"},"geometry":{"type":"Polygon",)"
      R"("coordinates":[[[-4.6,48.2],[-4.59,48.2],[-4.59,48.21],[-4.6,48.21],[-4.6,48.2]]]}},)"
      R"({"type":"Feature","properties":{"name":"bays"},"geometry":{"type":"MultiPolygon",)"
      R"("coordinates":[[[[-4.58,48.21],[-4.5,48.21],[-4.5,48.26],[-4.58,48.26],[-4.58,48.21]]],)"
      R"([[[-4.4,48.21],[-4.35,48.21],[-4.35,48.26],[-4.4,48.26],[-4.4,48.21]]]]}}]})");
  r = run_cli({"mesh", water_input(dir), "--domain", "water", "--clip", dir.file("parts.geojson"),
               "--each-clip", "name", "--size", "800", "-o", dir.file("p_{}.gr3")},
              dir);
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("have the value 'bays' (a multi-polygon of 2 parts)"), std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("p_one.gr3")));
}

// --clip: the water within a drawn polygon instead of a bbox. Every vertex of the mesh
// inside the polygon; the open boundary on its edges, where they cross water; the land
// inside it land. One polygon only, and not with --bbox.
TEST(CliOutputs, ClipMeshesTheWaterOfADrawnArea) {
  TempDir dir;
  const std::vector<isoquad::Point2> area = {
      {-4.6, 48.2}, {-4.35, 48.18}, {-4.3, 48.33}, {-4.45, 48.4}, {-4.62, 48.33}};
  std::string ring;
  for (std::size_t i = 0; i <= area.size(); ++i) {
    const isoquad::Point2& p = area[i % area.size()];
    ring += std::string(i ? "," : "") + "[" + std::to_string(p.x) + "," + std::to_string(p.y) + "]";
  }
  write_file(dir.file("area.geojson"), geojson_polygons({"[[" + ring + "]]"}));
  CliResult r = run_cli({"mesh", water_input(dir), "--domain", "water", "--clip",
                         dir.file("area.geojson"), "--size", "800", "-q", "-o", dir.file("m.gr3")},
                        dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Gr3 ll = parse_gr3(dir.file("m.ll"));
  ASSERT_GT(ll.elements.size(), 50u);
  // Distance in degrees from a point to the area's edges, and whether it is inside.
  auto to_edge = [&](double x, double y) {
    double best = 1e9;
    for (std::size_t i = 0; i < area.size(); ++i) {
      const isoquad::Point2 &a = area[i], &b = area[(i + 1) % area.size()];
      const double dx = b.x - a.x, dy = b.y - a.y;
      const double t =
          std::clamp(((x - a.x) * dx + (y - a.y) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
      best = std::min(best, std::hypot(x - a.x - t * dx, y - a.y - t * dy));
    }
    return best;
  };
  auto inside = [&](double x, double y) {
    bool in = false;
    for (std::size_t i = 0, j = area.size() - 1; i < area.size(); j = i++)
      if ((area[i].y > y) != (area[j].y > y) &&
          x < (area[j].x - area[i].x) * (y - area[i].y) / (area[j].y - area[i].y) + area[i].x)
        in = !in;
    return in;
  };
  for (const auto& n : ll.nodes) EXPECT_TRUE(inside(n[0], n[1]) || to_edge(n[0], n[1]) < 1e-4);
  ASSERT_FALSE(ll.open.empty());
  std::size_t open_nodes = 0;
  for (const auto& segment : ll.open)
    for (int n : segment) {
      EXPECT_LT(to_edge(ll.nodes[n - 1][0], ll.nodes[n - 1][1]), 1e-4) << n;
      ++open_nodes;
    }
  EXPECT_GT(open_nodes, 20u);
  // The big island reaches across the area's east edge: its coast there is land, between
  // the two ends of the one open segment, which runs round the rest of the area; the
  // small island a land boundary of its own.
  EXPECT_EQ(ll.open.size(), 1u);
  EXPECT_EQ(ll.land.size(), 2u);
  r = run_cli({"mesh", water_input(dir), "--domain", "water", "--clip", dir.file("area.geojson"),
               "--bbox=-4.6,48.2,-4.4,48.35", "-o", dir.file("x.gpkg")},
              dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--bbox (with --bbox-crs) or --clip"), std::string::npos) << r.err;
  r = run_cli({"mesh", water_input(dir), "--domain", "water", "--clip", water_input(dir), "-o",
               dir.file("x.gpkg")},
              dir);
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.err.find("holds 2 polygons: it takes one"), std::string::npos) << r.err;
  // One of several picked by --clip-where: the drawn area among others gives the same
  // mesh, byte for byte.
  write_file(dir.file("areas.geojson"),
             geojson_polygons(
                 {"[[[-4.7,48.1],[-4.69,48.1],[-4.69,48.11],[-4.7,48.1]]]", "[[" + ring + "]]"}));
  r = run_cli({"mesh", water_input(dir), "--domain", "water", "--clip", dir.file("areas.geojson"),
               "--clip-where", "name = 'f1'", "--size", "800", "-q", "-o", dir.file("f1.gr3")},
              dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_file(dir.file("f1.gr3")), read_file(dir.file("m.gr3")));
  r = run_cli({"mesh", water_input(dir), "--domain", "water", "--clip", dir.file("areas.geojson"),
               "--clip-where", "name = 'f9'", "-o", dir.file("x.gpkg")},
              dir);
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.err.find("--clip-where 'name = 'f9''"), std::string::npos) << r.err;
  // A ring that crosses itself, named with where.
  write_file(
      dir.file("bowtie.geojson"),
      geojson_polygons({"[[[-4.6,48.2],[-4.3,48.35],[-4.3,48.2],[-4.6,48.35],[-4.6,48.2]]]"}));
  r = run_cli({"mesh", water_input(dir), "--domain", "water", "--clip", dir.file("bowtie.geojson"),
               "-o", dir.file("x.gpkg")},
              dir);
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.err.find("its polygon is invalid (Self-intersection at or near point -4.4"),
            std::string::npos)
      << r.err;
  // --each over the features that reach the area only: the big island, cut to it.
  write_file(dir.file("east.geojson"),
             geojson_polygons({"[[[-4.47,48.24],[-4.36,48.24],[-4.36,48.32],[-4.47,48.24]]]"}));
  r = run_cli({"mesh", water_input(dir), "--clip", dir.file("east.geojson"), "--each", "name",
               "--size", "400", "-q", "-o", dir.file("each_{}.gr3")},
              dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir.file("each_f0.gr3")));
  EXPECT_FALSE(std::filesystem::exists(dir.file("each_f1.gr3")));
}

// A DEM as INPUT: its cells at or below 0 m are the sea, bounded by the 0 m contour (an
// island's coast) and by the cells without a value (land), open where the sea reaches
// the raster's edge.
TEST(CliOutputs, ADemBelowZeroIsTheSeaWithItsEdgeOpen) {
  TempDir dir;
  const double kPi = 3.14159265358979323846;
  // 20 x 20 km in UTM 31N at 100 m; a cone-shaped island 6 km round; 2 x 2 km without a
  // value in the north-west corner.
  const std::string dem = write_geotiff(
      dir.file("dem.tif"), 500000, 5000000, 100, 200, 200, 32631, [](double x, double y) {
        if (x < 502000 && y > 4998000) return std::nan("");
        return 0.01 * (6000 - std::hypot(x - 510000, y - 4990000));
      });
  CliResult r = run_cli({"mesh", dem, "--zmax", "0", "--dst-crs", "EPSG:32631", "--size", "800",
                         "-o", dir.file("m.gr3")},
                        dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("contour:      "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("m.gr3: no depths (the DEM INPUT bounds the domain; give it as "
                       "--elevation"),
            std::string::npos)
      << r.err;
  const Gr3 g = parse_gr3(dir.file("m.gr3"));
  ASSERT_GT(g.elements.size(), 300u);
  auto on_edge = [](const std::array<double, 3>& n) {
    return std::min({n[0] - 500000, 520000 - n[0], n[1] - 4980000, 5000000 - n[1]}) < 1e-3;
  };
  // One open segment round the raster's edge, but along the corner without values; the
  // island and that corner's wall are land.
  ASSERT_EQ(g.open.size(), 1u);
  for (int n : g.open[0]) {
    const auto& p = g.nodes[n - 1];
    EXPECT_TRUE(on_edge(p)) << p[0] << " " << p[1];
    EXPECT_FALSE(p[0] < 501900 && p[1] > 4998100) << p[0] << " " << p[1];
  }
  ASSERT_EQ(g.land.size(), 2u);
  std::size_t coast_nodes = 0;
  for (const auto& segment : g.land)
    for (int n : segment) {
      const auto& p = g.nodes[n - 1];
      const double r = std::hypot(p[0] - 510000, p[1] - 4990000);
      if (r < 7000) {
        EXPECT_NEAR(r, 6000, 200);  // within the simplification's 200 m of the coast
        ++coast_nodes;
      }
    }
  EXPECT_GT(coast_nodes, 30u);
  double mesh_area = 0.0;
  for (const auto& e : g.elements)
    for (std::size_t k = 0; k < e.size(); ++k) {
      const auto &a = g.nodes[e[k] - 1], &b = g.nodes[e[(k + 1) % e.size()] - 1];
      mesh_area += 0.5 * (a[0] * b[1] - b[0] * a[1]);
    }
  EXPECT_NEAR(mesh_area, 400e6 - kPi * 36e6 - 2050.0 * 2050.0, 0.01 * 400e6);

  // What a raster INPUT refuses, and a vector INPUT with its options.
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"mesh", dem, "-o", dir.file("x.gpkg")},
        {"mesh", dem, "--zmax", "0", "--domain", "water", "-o", dir.file("x.gpkg")},
        {"mesh", dem, "--zmax", "0", "--each", "name", "-o", dir.file("{}.gpkg")},
        {"mesh", water_input(dir), "--zmax", "0", "-o", dir.file("x.gpkg")}}) {
    r = run_cli(args, dir);
    EXPECT_EQ(r.exit_code, 2) << r.err;
  }
  r = run_cli({"mesh", dem, "--zmin", "100", "-o", dir.file("x.gpkg")}, dir);
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.err.find("has no cell in [100, inf]"), std::string::npos) << r.err;
  // A sea of one cell is smaller than the DEM can tell: dropped as an island under a
  // cell's area, not meshed in quads of centimetres.
  const std::string one = write_geotiff(
      dir.file("one.tif"), 500000, 5000000, 100, 20, 20, 32631,
      [](double x, double y) { return std::hypot(x - 501050, y - 4998950) < 10 ? -1.0 : 10.0; });
  r = run_cli({"mesh", one, "--zmax", "0", "-o", dir.file("x.gpkg")}, dir);
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("nothing is left to mesh"), std::string::npos) << r.err;
}

// --time-step raises the sizes to what an explicit model needs at that step and Courant
// number: fewer quads under it than without; every time step reported at --courant.
TEST(CliOutputs, TimeStepRuleWidensTheQuadsInDeepWater) {
  TempDir dir;
  const std::string dem = bathymetry(dir);  // 130 to 330 m deep over the box
  auto run = [&](std::vector<std::string> extra) {
    extra.insert(extra.begin(), {"--hmax", "800", "--bathymetry", dem, "--courant", "0.7"});
    return mesh_box(dir, extra);
  };
  CliResult plain = run({"-o", dir.file("plain.gpkg")});
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  CliResult wide =
      run({"--time-step", "6", "-o", dir.file("wide.gpkg"), "--report", dir.file("wide.json")});
  ASSERT_EQ(wide.exit_code, 0) << wide.err;
  const std::vector<double> before = quad_time_steps(dir.file("plain.gpkg"));
  const std::vector<double> after = quad_time_steps(dir.file("wide.gpkg"));
  ASSERT_GT(before.size(), 100u);
  ASSERT_GT(after.size(), 20u);
  auto under = [](const std::vector<double>& steps) {
    return static_cast<std::size_t>(
        std::count_if(steps.begin(), steps.end(), [](double s) { return s < 6.0; }));
  };
  const std::size_t under_before = under(before), under_after = under(after);
  EXPECT_GT(under_before, before.size() / 2);
  EXPECT_LT(under_after, after.size() / 10);        // 12 of 572 when measured
  EXPECT_LT(after.size(), before.size() * 7 / 10);  // 1,176 -> 572 quads when measured
  EXPECT_GT(*std::min_element(after.begin(), after.end()),
            *std::min_element(before.begin(), before.end()));
  // The summary and the report count them, at Courant 0.7.
  EXPECT_NE(wide.err.find("; " + std::to_string(under_after) + " of " +
                          std::to_string(after.size()) + " wet quads under --time-step 6 s"),
            std::string::npos)
      << wide.err;
  EXPECT_NE(wide.err.find("at a gravity-wave Courant number of 0.7,"), std::string::npos)
      << wide.err;
  EXPECT_NE(wide.err.find("dt floor:     sizes for 6 s at a Courant number of 0.7 set at "),
            std::string::npos)
      << wide.err;
  const std::string report = read_file(dir.file("wide.json"));
  EXPECT_NE(report.find("\"num_under_time_step\": " + std::to_string(under_after)),
            std::string::npos)
      << report;
  // Without depths, --time-step and --courant mean nothing.
  for (const std::vector<std::string>& bad : {std::vector<std::string>{"--time-step", "6"},
                                              std::vector<std::string>{"--courant", "0.5"}}) {
    std::vector<std::string> args = {"-o", dir.file("x.gpkg")};
    args.insert(args.end(), bad.begin(), bad.end());
    const CliResult r = mesh_box(dir, args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(bad[0] + " needs depths: --bathymetry or --elevation"), std::string::npos)
        << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("x.gpkg")));
  }
  // A time step that asks for infinite cells (which gave vertices at NaN): refused.
  const CliResult infinite = run({"--time-step", "1e308", "-o", dir.file("x.2dm")});
  EXPECT_EQ(infinite.exit_code, 2) << infinite.err;
  EXPECT_NE(infinite.err.find("sizes must be finite"), std::string::npos) << infinite.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("x.2dm")));
}

namespace {

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

}  // namespace

// --size-expr in d, the depth: quads of 300 m where the water is shallower than 200 m,
// up to --hmax (800 m) deeper; without depths, the expression is refused.
TEST(CliOutputs, AnExpressionInTheDepthSizesTheShallowWater) {
  TempDir dir;
  const std::string dem = bathymetry(dir);  // 130 to 330 m deep over the box
  CliResult r = mesh_box(dir, {"--hmax", "800", "--bathymetry", dem, "--size-expr",
                               "d < 200 ? 300 : 1e9", "-o", dir.file("m.gr3")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("expression d < 200 ? 300 : 1e9 + bathymetry "), std::string::npos) << r.err;
  const Gr3 g = parse_gr3(dir.file("m.gr3"));
  std::vector<double> shallow, deep;  // sqrt(area) of the quads by their mean depth
  for (const std::vector<int>& e : g.elements) {
    double a = 0.0, depth = 0.0;
    for (std::size_t k = 0; k < e.size(); ++k) {
      const auto& p = g.nodes[e[k] - 1];
      const auto& q = g.nodes[e[(k + 1) % e.size()] - 1];
      a += 0.5 * (p[0] * q[1] - q[0] * p[1]);
      depth += p[2] / static_cast<double>(e.size());
    }
    if (depth < 180) shallow.push_back(std::sqrt(a));
    if (depth > 280) deep.push_back(std::sqrt(a));
  }
  ASSERT_GT(shallow.size(), 50u);
  ASSERT_GT(deep.size(), 10u);
  EXPECT_NEAR(median(shallow), 300, 45);  // 302 when measured
  EXPECT_GT(median(deep), 600);           // 877
  r = mesh_box(dir,
               {"--hmax", "800", "--size-expr", "d < 200 ? 300 : 1e9", "-o", dir.file("x.gr3")});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("uses d, the depth: give --bathymetry or --elevation"), std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("x.gr3")));
}

// --size-expr in c, the distance to the coast (OceanMesh2D's 'dis'): quads of 300 m at
// the land, growing offshore, large again along the open sea boundary away from the land
// (it is no coast); a water box with no land in it is refused.
TEST(CliOutputs, AnExpressionInTheDistanceToTheCoast) {
  TempDir dir;
  CliResult r =
      mesh_box(dir, {"--hmax", "2000", "--size-expr", "300 + 0.3 * c", "-o", dir.file("m.gr3")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Gr3 g = parse_gr3(dir.file("m.gr3"));
  auto nearest = [&g](const std::vector<std::vector<int>>& lists, double x, double y) {
    double best = 1e300;
    for (const auto& list : lists)
      for (int n : list)
        best = std::min(best, std::hypot(g.nodes[n - 1][0] - x, g.nodes[n - 1][1] - y));
    return best;
  };
  std::vector<double> at_land, open_sea;  // sqrt(area) of the quads
  for (const std::vector<int>& e : g.elements) {
    double a = 0.0, x = 0.0, y = 0.0;
    for (std::size_t k = 0; k < e.size(); ++k) {
      const auto& p = g.nodes[e[k] - 1];
      const auto& q = g.nodes[e[(k + 1) % e.size()] - 1];
      a += 0.5 * (p[0] * q[1] - q[0] * p[1]);
      x += p[0] / static_cast<double>(e.size());
      y += p[1] / static_cast<double>(e.size());
    }
    const double land = nearest(g.land, x, y), open = nearest(g.open, x, y);
    if (land < 400) at_land.push_back(std::sqrt(a));
    if (open < 1500 && land > 4000) open_sea.push_back(std::sqrt(a));
  }
  ASSERT_GT(at_land.size(), 50u);
  ASSERT_GT(open_sea.size(), 5u);
  EXPECT_LT(median(at_land), 450);
  EXPECT_GT(median(open_sea), 1200);
  r = run_cli({"mesh", water_input(dir), "--domain", "water", "--bbox", "-4.51,48.26,-4.46,48.3",
               "--size-expr", "300 + 0.3 * c", "-o", dir.file("x.gr3")},
              dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("uses c, the distance to the coast"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("x.gr3")));
}

// --embed-points: a station in the water gets a vertex exactly there (hgrid.ll's node at
// its longitude and latitude), one on the land a warning; none inside stops the run. A
// station 150 m inland of the coast (the land's west side, lon 4.45 W) and one 100 m
// offshore, in quads of 800 m, get a node on the coast beside them.
TEST(CliOutputs, EmbeddedPointsGetVertices) {
  TempDir dir;
  write_file(
      dir.file("stations.geojson"),
      R"({"type":"FeatureCollection","features":[)"
      R"({"type":"Feature","properties":{},"geometry":{"type":"Point","coordinates":[-4.5123,48.3217]}},)"
      R"({"type":"Feature","properties":{},"geometry":{"type":"Point","coordinates":[-4.4071,48.2345]}},)"
      R"({"type":"Feature","properties":{},"geometry":{"type":"Point","coordinates":[-4.38,48.27]}},)"
      R"({"type":"Feature","properties":{},"geometry":{"type":"Point","coordinates":[-4.44798,48.275]}},)"
      R"({"type":"Feature","properties":{},"geometry":{"type":"Point","coordinates":[-4.45135,48.26]}},)"
      R"({"type":"Feature","properties":{},"geometry":{"type":"Point","coordinates":[-4.5123,48.3217]}}]})");
  CliResult r =
      mesh_box_800(dir, {"--embed-points", dir.file("stations.geojson"), "-o", dir.file("s.gr3"),
                         "-o", dir.file("s.gpkg"), "--report", dir.file("s.json")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(
      r.err.find("points:       4 of the 5 points in or next to the domain on their vertex (2 "
                 "of them at the coast's point nearest them, up to 1"),
      std::string::npos)
      << r.err;
  EXPECT_NE(
      r.err.find("; 1 shares the vertex of a point before it within a fifth of a quad (at the "
                 "same place)\n"),
      std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("warning: --embed-points: 1 of the 6 points of"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("m from it (point 3): they get no vertex"), std::string::npos) << r.err;
  const std::string report = read_file(dir.file("s.json"));
  EXPECT_NE(report.find("\"embed_points_on_vertex\": 4"), std::string::npos);
  EXPECT_NE(report.find("\"embed_points_on_coast\": 2"), std::string::npos);
  const Gr3 g = parse_gr3(dir.file("s.ll"));
  // The report's node of each point, numbered as hgrid.ll's: at the point (the .ll's 7
  // decimals), or on the coast beside it where the projected side is nearest (2 m); the
  // point given twice at the first one's node; the one on the land far off, none.
  std::map<int, std::size_t> node_of;
  const std::regex entry("\"point\": (\\d+),\\s*\"node\": (\\d+)");
  for (auto it = std::sregex_iterator(report.begin(), report.end(), entry);
       it != std::sregex_iterator(); ++it)
    node_of[std::stoi((*it)[1])] = std::stoul((*it)[2]);
  ASSERT_EQ(node_of.size(), 5u);  // the 6 read but the one far on the land
  EXPECT_EQ(node_of.count(3), 0u);
  EXPECT_EQ(node_of[6], node_of[1]);
  const std::map<int, std::pair<double, double>> where = {
      {1, {-4.5123, 48.3217}}, {2, {-4.4071, 48.2345}}, {4, {-4.45, 48.275}}, {5, {-4.45, 48.26}}};
  for (const auto& [point, at] : where) {
    ASSERT_GE(node_of[point], 1u);
    ASSERT_LE(node_of[point], g.nodes.size());
    const auto& n = g.nodes[node_of[point] - 1];
    EXPECT_LT(std::hypot(n[0] - at.first, n[1] - at.second), point >= 4 ? 2e-5 : 1e-6) << point;
  }
  // The GeoPackage's vertices name their points by number in the file.
  std::multiset<long long> numbers;
  GDALDataset* ds = open_vector(dir.file("s.gpkg"));
  ASSERT_NE(ds, nullptr);
  for (auto& f : *ds->GetLayerByName("vertices"))
    if (f->GetFieldAsInteger64("point") != 0) numbers.insert(f->GetFieldAsInteger64("point"));
  GDALClose(ds);
  EXPECT_EQ(numbers, (std::multiset<long long>{1, 2, 4, 5}));
  // Named stations (their `name`, or --embed-points-name's attribute): each name in the
  // report's entry and as the GeoPackage's point_name of its vertex; an attribute the
  // file lacks stops the run before the meshing.
  write_file(
      dir.file("named.geojson"),
      R"({"type":"FeatureCollection","features":[)"
      R"({"type":"Feature","properties":{"name":"Le Conquet","code":"LC"},"geometry":{"type":"Point","coordinates":[-4.5123,48.3217]}},)"
      R"({"type":"Feature","properties":{"name":"Camaret","code":"CA"},"geometry":{"type":"Point","coordinates":[-4.4071,48.2345]}}]})");
  for (const char* field : {"", "code"}) {
    std::vector<std::string> args = {
        "--embed-points", dir.file("named.geojson"), "-o",         dir.file("n.gpkg"),
        "--report",       dir.file("n.json"),        "--overwrite"};
    if (*field) args.insert(args.end(), {"--embed-points-name", field});
    r = mesh_box_800(dir, args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string named = read_file(dir.file("n.json"));
    const std::vector<std::string> names = *field
                                               ? std::vector<std::string>{"LC", "CA"}
                                               : std::vector<std::string>{"Le Conquet", "Camaret"};
    for (std::size_t k = 0; k < 2; ++k)
      EXPECT_NE(named.find("\"point\": " + std::to_string(k + 1) + ",\n      \"name\": \"" +
                           names[k] + "\""),
                std::string::npos)
          << named;
    std::multiset<std::string> in_gpkg;
    ds = open_vector(dir.file("n.gpkg"));
    ASSERT_NE(ds, nullptr);
    for (auto& f : *ds->GetLayerByName("vertices"))
      if (f->GetFieldAsInteger64("point") != 0) in_gpkg.insert(f->GetFieldAsString("point_name"));
    GDALClose(ds);
    EXPECT_EQ(in_gpkg, std::multiset<std::string>(names.begin(), names.end()));
  }
  r = mesh_box_800(dir, {"--embed-points", dir.file("named.geojson"), "--embed-points-name",
                         "station", "-o", dir.file("m.gpkg")});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("has no attribute 'station' (--embed-points-name; attributes: name, code)"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("m.gpkg")));
  write_file(dir.file("onland.geojson"),
             R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},)"
             R"("geometry":{"type":"Point","coordinates":[-4.38,48.27]}}]})");
  r = mesh_box_800(dir, {"--embed-points", dir.file("onland.geojson"), "-o", dir.file("t.gr3")});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("1 of the 1 points of"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("t.gr3")));
  // A CSV row whose longitude is not a number: an error naming it, not a station lost.
  write_file(dir.file("rows.csv"), "name,lon,lat\nA,-4.45,48.3\nC,abc,48.3\n");
  r = mesh_box_800(dir, {"--embed-points", dir.file("rows.csv"), "-o", dir.file("t.gr3")});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("rows.csv': 1 feature(s) without a point, the first feature 2 "
                       "(coordinates that are not numbers, or empty)"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("Warning 1:"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("t.gr3")));
}

// --depth-average: the depths as means over squares round the vertices, said in the
// summary and the report; on a grid of depths linear in lon/lat, within half a cell's
// slope of the bilinear ones (a cell of 0.001 degrees: 1 m). Without depths, refused.
TEST(CliOutputs, DepthAverageIsSaidAndStaysNearALinearGrid) {
  TempDir dir;
  // The depths of bathymetry() in cells ten times finer (0.001 degrees): about 10 across
  // a square of 800 m.
  const std::string dem =
      write_geotiff(dir.file("fine.tif"), -4.7, 48.45, 0.001, 400, 350, 4326, depth_at);
  CliResult plain = mesh_box(dir, {"--hmax", "800", "--bathymetry", dem, "-o", dir.file("p.gr3")});
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  CliResult mean = mesh_box(dir, {"--hmax", "800", "--bathymetry", dem, "--depth-average", "-o",
                                  dir.file("m.gr3"), "--report", dir.file("m.json")});
  ASSERT_EQ(mean.exit_code, 0) << mean.err;
  EXPECT_NE(mean.err.find("(each a mean over a square as wide as the vertex's quads)"),
            std::string::npos)
      << mean.err;
  EXPECT_NE(read_file(dir.file("m.json")).find("\"averaged\": true"), std::string::npos);
  const Gr3 p = parse_gr3(dir.file("p.gr3")), m = parse_gr3(dir.file("m.gr3"));
  ASSERT_EQ(p.nodes.size(), m.nodes.size());
  double largest = 0.0;
  for (std::size_t v = 0; v < p.nodes.size(); ++v)
    largest = std::max(largest, std::abs(p.nodes[v][2] - m.nodes[v][2]));
  EXPECT_GT(largest, 0.0);
  EXPECT_LT(largest, 1.0);
  const CliResult bad =
      mesh_box(dir, {"--hmax", "800", "--depth-average", "-o", dir.file("x.gr3")});
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_NE(bad.err.find("--depth-average needs depths"), std::string::npos) << bad.err;
}

// Soundings as --bathymetry: an .xyz of scattered samples in lon/lat (--depth-crs) gives
// the depths linear between them; without a CRS, or with --depth-field and no points, the
// run stops before meshing.
TEST(CliOutputs, SoundingsGiveTheDepthsBetweenThem) {
  TempDir dir;
  std::string text = "lon lat depth\n";
  unsigned state = 7;
  auto next = [&state] {
    state = state * 1103515245u + 12345u;
    return static_cast<double>((state >> 8) & 0xffff) / 65535.0;
  };
  auto add = [&text](double lon, double lat) {
    text += std::to_string(lon) + " " + std::to_string(lat) + " " +
            std::to_string(depth_at(lon, lat)) + "\n";
  };
  for (int i = 0; i < 3000; ++i) add(-4.62 + 0.24 * next(), 48.18 + 0.19 * next());
  for (const auto& [lon, lat] :
       {std::pair{-4.62, 48.18}, {-4.38, 48.18}, {-4.38, 48.37}, {-4.62, 48.37}})
    add(lon, lat);
  for (int i = 0; i < 6; ++i) add(-3.0 + 0.01 * i, 47.0 + 0.02 * (i % 2));  // far off, left out
  write_file(dir.file("soundings.xyz"), text);
  CliResult r = mesh_box_800(dir, {"--bathymetry", dir.file("soundings.xyz"), "--depth-crs",
                                   "EPSG:4326", "-o", dir.file("s.gr3")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(without_schism_warning(r.err).find("warning"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(" m (from soundings.xyz: 3004 of its 3010 samples, those round the "
                       "domain)\n"),
            std::string::npos)
      << r.err;
  const Gr3 g = parse_gr3(dir.file("s.ll"));
  ASSERT_GT(g.nodes.size(), 50u);
  for (const auto& n : g.nodes)
    EXPECT_NEAR(n[2], depth_at(n[0], n[1]), 0.05) << n[0] << " " << n[1];
  // Sizes from the same depths: the outputs' depths from the sizes' triangulation, as
  // exact.
  r = mesh_box(dir,
               {"--size-expr", "400 + 4 * d", "--hmax", "1500", "--bathymetry",
                dir.file("soundings.xyz"), "--depth-crs", "EPSG:4326", "-o", dir.file("d.gr3")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Gr3 d = parse_gr3(dir.file("d.ll"));
  EXPECT_NE(d.nodes.size(), g.nodes.size());
  for (const auto& n : d.nodes)
    EXPECT_NEAR(n[2], depth_at(n[0], n[1]), 0.05) << n[0] << " " << n[1];

  r = mesh_box_800(dir, {"--bathymetry", dir.file("soundings.xyz"), "-o", dir.file("t.gr3")});
  EXPECT_EQ(r.exit_code, 4) << r.err;
  EXPECT_NE(r.err.find("give it with --depth-crs"), std::string::npos) << r.err;
  r = mesh_box_800(
      dir, {"--bathymetry", bathymetry(dir), "--depth-field", "z", "-o", dir.file("u.gr3")});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--depth-field names the attribute of a layer of points"), std::string::npos)
      << r.err;
  // An .xyz has no attribute to name: refused, not ignored.
  r = mesh_box_800(dir, {"--bathymetry", dir.file("soundings.xyz"), "--depth-crs", "EPSG:4326",
                         "--depth-field", "z", "-o", dir.file("u.gr3")});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("an .xyz holds x, y and the value only"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("t.gr3")));
  EXPECT_FALSE(std::filesystem::exists(dir.file("u.gr3")));
}

// --zones: each quad's zone in the GeoPackage's quads and as the .2dm's material, each
// node's as TELEMAC's FRIC_ID, the summary's count and a warning for the quads in none;
// a bad file stops the run before the meshing, with nothing written.
TEST(CliOutputs, ZonesAreTheQuadsMaterials) {
  TempDir dir;
  write_file(dir.file("zones.geojson"),
             "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\","
             "\"properties\":{\"class\":7},\"geometry\":{\"type\":\"Polygon\",\"coordinates\":"
             "[[[-4.7,48.1],[-4.5,48.1],[-4.5,48.4],[-4.7,48.4],[-4.7,48.1]]]}}]}");
  CliResult r =
      mesh_box_800(dir, {"--zones", dir.file("zones.geojson"), "--zones-field", "class", "-o",
                         dir.file("m.gpkg"), "-o", dir.file("m.2dm"), "-o", dir.file("m.msh"), "-o",
                         dir.file("m.gr3"), "-o", dir.file("m.slf")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_EQ(mesh_box_800(dir, {"--zones", dir.file("zones.geojson"), "--zones-field", "class",
                               "--msh-version", "2.2", "-o", dir.file("m22.msh")})
                .exit_code,
            0);
  std::size_t in_zone = 0, in_none = 0;
  std::map<int, int> zone_of;  // by the quad's id
  GDALDataset* ds = open_vector(dir.file("m.gpkg"));
  ASSERT_NE(ds, nullptr);
  for (auto& f : *ds->GetLayerByName("quads")) {
    const int zone = f->GetFieldAsInteger("zone");
    EXPECT_TRUE(zone == 0 || zone == 7) << zone;
    ++(zone == 7 ? in_zone : in_none);
    zone_of[f->GetFieldAsInteger("id")] = zone;
  }
  GDALClose(ds);
  // SCHISM's hgrid.prop: each of hgrid.gr3's elements (the quads, in order) with its zone.
  const Gr3 g = parse_gr3(dir.file("m.gr3"));
  std::istringstream prop(read_file(dir.file("m.prop")));
  std::size_t element = 0;
  for (long long e = 0, z = 0; prop >> e >> z; ++element) {
    EXPECT_EQ(e, static_cast<long long>(element + 1));
    EXPECT_EQ(z, zone_of[static_cast<int>(e)]) << e;  // the quads' ids, the elements' numbers
  }
  EXPECT_EQ(element, g.elements.size());
  EXPECT_EQ(element, zone_of.size());
  EXPECT_GT(in_zone, 20u);
  EXPECT_GT(in_none, 20u);
  std::size_t materials_7 = 0;
  std::istringstream lines(read_file(dir.file("m.2dm")));
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("E4Q ", 0) == 0 && line.size() > 2 && line.substr(line.size() - 2) == " 7")
      ++materials_7;
  EXPECT_EQ(materials_7, in_zone);
  // The .slf's second variable, FRIC_ID: each node's zone, that of most of its quads (the
  // .2dm's materials), 7 on a tie; the nodes in zone 7 and in none both many.
  const std::string fric =
      python_check(dir,
                   std::string(kSelafinRecords) +
                       "import collections\n"
                       "record()\n"
                       "assert np.frombuffer(record(), '>i4').tolist() == [2, 0]\n"
                       "assert record() == b'BOTTOM'.ljust(16) + b'M'.ljust(16)\n"
                       "assert record() == b'FRIC_ID'.ljust(32)\n"
                       "record()\n"
                       "nelem, npoin, ndp, one = np.frombuffer(record(), '>i4')\n"
                       "for k in range(6): record()  # ikle, ipobo, x, y, the time, bottom\n"
                       "fric = np.frombuffer(record(), '>f8')\n"
                       "assert pos == len(data) and len(fric) == npoin\n"
                       "votes = collections.defaultdict(collections.Counter)\n"
                       "for line in open(sys.argv[2]):\n"
                       "    f = line.split()\n"
                       "    if f and f[0] == 'E4Q':\n"
                       "        for n in f[2:6]: votes[int(n) - 1][int(f[6])] += 1\n"
                       "assert len(votes) == npoin\n"
                       "for n, c in votes.items():\n"
                       "    want = 7 if c[7] >= c[0] else 0\n"
                       "    assert fric[n] == want, (n, c, fric[n])\n"
                       "print((fric == 7).sum(), (fric == 0).sum())\n",
                   {dir.file("m.slf"), dir.file("m.2dm")});
  std::istringstream counts(fric);
  std::size_t nodes_7 = 0, nodes_0 = 0;
  counts >> nodes_7 >> nodes_0;
  EXPECT_GT(nodes_7, 20u) << fric;
  EXPECT_GT(nodes_0, 20u) << fric;
  EXPECT_NE(r.err.find("zones:        1 polygon(s) of " + dir.file("zones.geojson") + ": " +
                       std::to_string(in_none) + " quads in none; 7: " + std::to_string(in_zone) +
                       " quads"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("lie in no polygon of"), std::string::npos) << r.err;
  // Gmsh's files, read by meshio: the quads of zone 7 in the physical group of tag 7
  // named zone_7, the others in no_zone (8); MSH 4.1 and 2.2 alike.
  const std::string groups =
      python_check(dir,
                   "import sys, collections, meshio\n"
                   "for path in sys.argv[1:]:\n"
                   "    m = meshio.read(path)\n"
                   "    c = collections.Counter()\n"
                   "    for b, t in zip(m.cells, m.cell_data['gmsh:physical']):\n"
                   "        if b.type == 'quad': c.update(t.tolist())\n"
                   "    print(sorted(c.items()), sorted(m.field_data))\n",
                   {dir.file("m.msh"), dir.file("m22.msh")});
  const std::string expected = "[(7, " + std::to_string(in_zone) + "), (8, " +
                               std::to_string(in_none) +
                               ")] ['land', 'no_zone', 'open', 'zone_7']\n";
  const std::size_t first = groups.find(expected);  // meshio prints blank lines too
  EXPECT_NE(first, std::string::npos) << groups;
  EXPECT_NE(groups.find(expected, first + 1), std::string::npos) << groups;
  // The quads' element tags are their numbers in the .2dm (and the GeoPackage's ids), in
  // either version, their zones' blocks apart: 1 to the number of quads, the lines after.
  python_check(dir,
               "import sys\n"
               "want = {}\n"
               "for line in open(sys.argv[1]):\n"
               "    w = line.split()\n"
               "    if w and w[0] == 'E4Q': want[int(w[1])] = [int(x) for x in w[2:6]]\n"
               "def elements(path):\n"
               "    lines = open(path).read().split('$Elements\\n')[1].split('$EndElements')[0]\n"
               "    rows = [list(map(int, l.split())) for l in lines.strip().split('\\n')]\n"
               "    quads = {}\n"
               "    if path.endswith('22.msh'):\n"
               "        for r in rows[1:]:\n"
               "            if r[1] == 3: quads[r[0]] = r[3 + r[2]:]\n"
               "        lines_ = [r[0] for r in rows[1:] if r[1] == 1]\n"
               "    else:\n"
               "        i, lines_ = 1, []\n"
               "        while i < len(rows):\n"
               "            dim, n = rows[i][0], rows[i][3]\n"
               "            for r in rows[i + 1:i + 1 + n]:\n"
               "                if dim == 2: quads[r[0]] = r[1:]\n"
               "                else: lines_.append(r[0])\n"
               "            i += 1 + n\n"
               "    return quads, lines_\n"
               "for path in sys.argv[2:]:\n"
               "    quads, lines_ = elements(path)\n"
               "    assert quads == want, path\n"
               "    assert min(lines_) == len(want) + 1, (path, min(lines_))\n",
               {dir.file("m.2dm"), dir.file("m.msh"), dir.file("m22.msh")});
  // Polygons that miss the domain (another region's, or in a wrong CRS): said so.
  write_file(dir.file("far.geojson"),
             "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\","
             "\"properties\":{\"zone\":2},\"geometry\":{\"type\":\"Polygon\",\"coordinates\":"
             "[[[3.7,43.1],[3.9,43.1],[3.9,43.3],[3.7,43.3],[3.7,43.1]]]}}]}");
  r = mesh_box_800(dir, {"--zones", dir.file("far.geojson"), "-o", dir.file("far.gpkg")});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("none of the " + std::to_string(in_zone + in_none) +
                       " quads lies in a polygon of " + dir.file("far.geojson")),
            std::string::npos)
      << r.err;
  // The default attribute, zone, is not in the file.
  r = mesh_box_800(dir, {"--zones", dir.file("zones.geojson"), "-o", dir.file("x.gpkg")});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("has no attribute 'zone' for the zones (attributes: class)"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("quads:"), std::string::npos) << r.err;  // stopped before the meshing
  EXPECT_FALSE(std::filesystem::exists(dir.file("x.gpkg")));
}

TEST(CliOutputs, GoldenToolStartsACaseThatChecksAndCatchesAChange) {
  // tools/golden.py init: a user's own regression case from an isoquad mesh command
  // line; `check` passes on it, and fails once an expected value is off.
  TempDir dir;
  const std::string golden = std::string(ISOQUAD_SOURCE_DIR) + "/tools/golden.py";
  const std::string case_dir = dir.file("square_case");
  std::filesystem::create_directories(case_dir);
  write_file(case_dir + "/input.geojson",
             geojson_polygons({"[[[0,0],[1000,0],[1000,1000],[0,1000],[0,0]]]"}));
  CliResult r = run_cli_program(
      "/usr/bin/python3",
      {golden, "init", case_dir, "--isoquad", ISOQUAD_CLI, "--", case_dir + "/input.geojson",
       "--src-crs", "EPSG:3857", "--size", "100", "-o", "mesh.geojson"},
      dir);
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  // The input inside the case is written relative to it, so the case can move; so is the
  // quads' file, kept in the case and written again by each check.
  EXPECT_NE(read_file(case_dir + "/args.txt").find("{dir}/input.geojson"), std::string::npos);
  EXPECT_NE(read_file(case_dir + "/args.txt").find("{dir}/mesh.geojson"), std::string::npos);
  const std::string quads_file = read_file(case_dir + "/mesh.geojson");
  EXPECT_FALSE(std::filesystem::exists(dir.file("mesh.geojson")));
  r = run_cli_program("/usr/bin/python3", {golden, "check", case_dir, "--isoquad", ISOQUAD_CLI}, dir);
  EXPECT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_EQ(read_file(case_dir + "/mesh.geojson"), quads_file);
  EXPECT_NE(r.out.find("quality.num_quads"), std::string::npos) << r.out;
  // A second init would overwrite the case: refused.
  r = run_cli_program("/usr/bin/python3",
                      {golden, "init", case_dir, "--isoquad", ISOQUAD_CLI, "--", "x.geojson"}, dir);
  EXPECT_NE(r.exit_code, 0);
  // Twice the quads expected (tolerance 10%): check fails and names the value.
  std::string expected = read_file(case_dir + "/expected.json");
  const std::string key = "\"quality.num_quads\": {\n    \"rtol\": 0.1,\n    \"value\": ";
  const std::size_t at = expected.find(key);
  ASSERT_NE(at, std::string::npos) << expected;
  const std::size_t begin = at + key.size(), end = expected.find('\n', begin);
  const int quads = std::stoi(expected.substr(begin, end - begin));
  EXPECT_GT(quads, 50);  // a 1 km square at 100 m: about 100 quads
  expected.replace(begin, end - begin, std::to_string(2 * quads));
  write_file(case_dir + "/expected.json", expected);
  r = run_cli_program("/usr/bin/python3", {golden, "check", case_dir, "--isoquad", ISOQUAD_CLI}, dir);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("quality.num_quads"), std::string::npos) << r.err;
  // A directory that is not a case (no args.txt): named, without a traceback.
  std::filesystem::create_directories(dir.file("not_a_case"));
  r = run_cli_program("/usr/bin/python3",
                      {golden, "update", dir.file("not_a_case"), "--isoquad", ISOQUAD_CLI}, dir);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("not_a_case is not a case (no args.txt)"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("Traceback"), std::string::npos) << r.err;
}
