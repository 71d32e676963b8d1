// `isoquad quality`: a mesh read from a file measured as `isoquad mesh` measures its own.
// isoquad's own outputs measured again give the mesh report's figures; a mesh that the
// gmsh binary makes (ASCII .msh 4.1 and 2.2) is read whole, on the domain's boundary,
// with the element counts meshio reads; a mesh in degrees without --mesh-crs, or with
// triangles and -o, stops with a clear message.
#include <gtest/gtest.h>

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <iomanip>
#include <map>
#include <sstream>

#include "gis/gdal_env.h"
#include "support/test_support.h"
#include "support/write_raster.h"

using namespace isoquad::test;

namespace {

// The quality values both reports have, compared within `tolerance` (relative, or
// absolute under 1).
void expect_same_quality(const std::string& mesh_report, const std::string& quality_report,
                         double tolerance, const std::string& what) {
  for (const char* key : {"share_angles_75_105",
                          "min_angle_deg",
                          "max_angle_deg",
                          "eta_mean",
                          "size_ratio_median",
                          "share_size_ratio_08_125",
                          "orientation_mean_deg",
                          "orientation_p90_deg",
                          "share_regular_interior",
                          "share_regular_boundary",
                          "schism_angle_ratio_violations",
                          "schism_aspect_ratio_violations",
                          "dflowfm_orthogonality_mean",
                          "dflowfm_orthogonality_violations",
                          "mesh_area_m2",
                          "domain_area_m2",
                          "boundary_departure_max_m",
                          "boundary_departure_p95_h",
                          "num_boundary_vertices",
                          "num_nonconvex"}) {
    const double a = report_number(mesh_report, key), b = report_number(quality_report, key);
    EXPECT_NEAR(a, b, tolerance * std::max(1.0, std::abs(a))) << what << ": " << key;
  }
}

const std::vector<std::string> kCorsica = {"--hmax", "8000"};

// The segments of a GeoPackage's boundary layer by kind (open, land); none when the file
// cannot be opened.
std::map<std::string, int> boundary_kinds(const std::string& path) {
  isoquad::ensure_gdal_registered();
  std::map<std::string, int> count;
  GDALDataset* ds = static_cast<GDALDataset*>(
      GDALOpenEx(path.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr));
  if (!ds) return count;
  for (auto& f : *ds->GetLayerByName("boundary")) ++count[f->GetFieldAsString("kind")];
  GDALClose(ds);
  return count;
}

std::vector<std::string> quality_args(const std::string& mesh, std::vector<std::string> more = {}) {
  std::vector<std::string> args = {"quality", sample("corsica.geojson"), "--mesh", mesh};
  args.insert(args.end(), kCorsica.begin(), kCorsica.end());
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

}  // namespace

TEST(CliQuality, IsoquadsOwnOutputsMeasureAsTheMeshReportSays) {
  TempDir dir;
  std::vector<std::string> args = {"mesh", sample("corsica.geojson"), "--report",
                                   dir.file("r.json")};
  args.insert(args.end(), kCorsica.begin(), kCorsica.end());
  for (const char* ext : {".gr3", ".msh", ".2dm", ".mesh", ".nc", ".gpkg", ".fgb"}) {
    args.push_back("-o");
    args.push_back(dir.file(std::string("m") + ext));
  }
  const CliResult made = run_cli(args, dir);
  ASSERT_EQ(made.exit_code, 0) << made.err;
  const std::string mesh_report = read_file(dir.file("r.json"));
  for (const char* ext : {".gr3", ".msh", ".2dm", ".mesh", ".nc", ".gpkg", ".fgb"}) {
    const std::string report = dir.file(std::string("q") + ext + ".json");
    const CliResult r =
        run_cli(quality_args(dir.file(std::string("m") + ext), {"--report", report}), dir);
    ASSERT_EQ(r.exit_code, 0) << ext << r.err;
    const std::string q = read_file(report);
    expect_same_quality(mesh_report, q, 1e-6, ext);
    EXPECT_EQ(report_number(q, "num_quads"), report_number(mesh_report, "num_quads")) << ext;
    EXPECT_EQ(report_number(q, "num_boundary_vertices_off_domain"), 0) << ext;
    EXPECT_NE(r.err.find("regularity:"), std::string::npos);
  }
  // hgrid.ll in longitudes and latitudes (its own CRS), transformed back (to 1e-10 degrees).
  const CliResult ll =
      run_cli(quality_args(dir.file("m.ll"), {"--report", dir.file("ll.json")}), dir);
  ASSERT_EQ(ll.exit_code, 0) << ll.err;
  expect_same_quality(mesh_report, read_file(dir.file("ll.json")), 1e-3, ".ll");
  EXPECT_NE(ll.err.find("WGS 84, transformed into the meshing CRS"), std::string::npos) << ll.err;
  // The .ll's nodes as another mesher's .gr3 (a title line that names no CRS) without
  // --mesh-crs: the degrees are read as metres, a clear stop.
  std::string degrees_text = read_file(dir.file("m.ll"));
  degrees_text.replace(0, degrees_text.find('\n'), "a grid in degrees");
  write_file(dir.file("degrees.gr3"), degrees_text);
  const CliResult degrees = run_cli(quality_args(dir.file("degrees.gr3")), dir);
  EXPECT_EQ(degrees.exit_code, 3);
  EXPECT_NE(degrees.err.find("is the mesh in another CRS (give it with --mesh-crs)"),
            std::string::npos)
      << degrees.err;

  // Depths serve the sizes alone here: without a sizing rule they are refused.
  const std::string dem = write_geotiff(dir.file("dem.tif"), 8, 44, 0.1, 30, 40, 4326,
                                        [](double, double) { return 20.0; });
  const CliResult depths = run_cli(quality_args(dir.file("m.gr3"), {"--bathymetry", dem}), dir);
  EXPECT_EQ(depths.exit_code, 2);
  EXPECT_NE(depths.err.find("--bathymetry or --elevation needs --wavelength-period"),
            std::string::npos)
      << depths.err;

  // Quads cut into triangles (all of them in TELEMAC's .slf, SCHISM's failing ones with
  // --schism-split): the coast along the outline of every element, as the mesh report's.
  {
    std::vector<std::string> split = {
        "mesh", sample("corsica.geojson"), "--schism-split", "-o", dir.file("s.gr3"),
        "-o",   dir.file("s.slf"),         "--overwrite"};
    split.insert(split.end(), kCorsica.begin(), kCorsica.end());
    ASSERT_EQ(run_cli(split, dir).exit_code, 0);
    for (const char* file : {"s.gr3", "s.slf"}) {
      const std::string report = dir.file(std::string(file) + ".json");
      const CliResult r = run_cli(quality_args(dir.file(file), {"--report", report}), dir);
      ASSERT_EQ(r.exit_code, 0) << file << r.err;
      const std::string q = read_file(report);
      EXPECT_GT(report_number(q, "num_triangles"), 0) << file;
      // Regularity by the elements' ideal angles: cutting a quad in two makes no vertex
      // regular (it changes a corner's 90 degrees into 60 or 120), and the .gr3 cuts few.
      const bool mixed = std::string(file) == "s.gr3";
      const double regular = report_number(
          q, mixed ? "mixed_share_regular_interior" : "triangle_share_regular_interior");
      EXPECT_LE(regular, report_number(mesh_report, "share_regular_interior")) << file;
      EXPECT_GT(regular, mixed ? 0.7 : 0.1) << file;
      EXPECT_EQ(report_number(q, "num_boundary_vertices_off_domain"), 0) << file;
      for (const char* key :
           {"boundary_departure_max_m", "boundary_departure_p95_h", "mesh_area_m2"})
        EXPECT_NEAR(report_number(q, key), report_number(mesh_report, key),
                    1e-6 * std::max(1.0, report_number(mesh_report, key)))
            << file << ": " << key;
    }
  }

  // Clockwise quads (a .2dm with every E4Q's nodes reversed) are measured reversed.
  std::istringstream in(read_file(dir.file("m.2dm")));
  std::string line, reversed;
  while (std::getline(in, line)) {
    std::istringstream f(line);
    std::string card;
    long id, a, b, c, d, material;
    if (f >> card >> id >> a >> b >> c >> d >> material && card == "E4Q")
      line = "E4Q " + std::to_string(id) + " " + std::to_string(d) + " " + std::to_string(c) + " " +
             std::to_string(b) + " " + std::to_string(a) + " " + std::to_string(material);
    reversed += line + "\n";
  }
  write_file(dir.file("cw.2dm"), reversed);
  const CliResult cw =
      run_cli(quality_args(dir.file("cw.2dm"), {"--report", dir.file("cw.json")}), dir);
  ASSERT_EQ(cw.exit_code, 0) << cw.err;
  EXPECT_NE(cw.err.find("its elements clockwise, measured reversed"), std::string::npos) << cw.err;
  expect_same_quality(mesh_report, read_file(dir.file("cw.json")), 1e-6, "clockwise .2dm");

  // -o and --plot: the measured quads with their metrics, as the mesh job writes them.
  const CliResult out = run_cli(
      quality_args(dir.file("m.gr3"), {"-o", dir.file("q.gpkg"), "--plot", dir.file("q.png")}),
      dir);
  ASSERT_EQ(out.exit_code, 0) << out.err;
  EXPECT_TRUE(std::filesystem::exists(dir.file("q.png")));
  const CliResult geojson =
      run_cli(quality_args(dir.file("m.gr3"), {"-o", dir.file("q.geojson")}), dir);
  ASSERT_EQ(geojson.exit_code, 0) << geojson.err;
  isoquad::ensure_gdal_registered();
  for (const char* name : {"q.gpkg", "q.geojson"}) {
    GDALDataset* ds = static_cast<GDALDataset*>(
        GDALOpenEx(dir.file(name).c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr));
    ASSERT_NE(ds, nullptr) << name;
    OGRLayer* quads = ds->GetLayerByName("quads");
    ASSERT_NE(quads, nullptr) << name;
    EXPECT_EQ(static_cast<double>(quads->GetFeatureCount()),
              report_number(mesh_report, "num_quads"));
    EXPECT_GE(quads->GetLayerDefn()->GetFieldIndex("size_ratio"), 0);
    GDALClose(ds);
  }
}

// A mesh the gmsh binary makes of a 10 x 6 km rectangle (Frontal-Delaunay for quads,
// Blossom full-quad recombination), saved as ASCII 4.1 and 2.2: both read the same, with
// meshio's counts of quads and nodes, every boundary node on the domain's boundary, the
// rectangle's area; with triangles (no recombination) their angles, sizes and D-Flow FM
// links are measured, and -o stops.
TEST(CliQuality, GmshMeshesOfARectangle) {
  TempDir dir;
  const double x0 = 500000, y0 = 5000000, w = 10000, h = 6000;
  write_file(dir.file("rect.geojson"),
             geojson_polygons({"[[[" + std::to_string(x0) + "," + std::to_string(y0) + "],[" +
                               std::to_string(x0 + w) + "," + std::to_string(y0) + "],[" +
                               std::to_string(x0 + w) + "," + std::to_string(y0 + h) + "],[" +
                               std::to_string(x0) + "," + std::to_string(y0 + h) + "],[" +
                               std::to_string(x0) + "," + std::to_string(y0) + "]]]"},
                              kUtm31nCrsMember));
  auto geo = [&](bool recombine) {
    std::string s = "lc = 500;\n";
    s += "Point(1) = {" + std::to_string(x0) + ", " + std::to_string(y0) + ", 0, lc};\n";
    s += "Point(2) = {" + std::to_string(x0 + w) + ", " + std::to_string(y0) + ", 0, lc};\n";
    s += "Point(3) = {" + std::to_string(x0 + w) + ", " + std::to_string(y0 + h) + ", 0, lc};\n";
    s += "Point(4) = {" + std::to_string(x0) + ", " + std::to_string(y0 + h) + ", 0, lc};\n";
    s += "Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};\n";
    s += "Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};\n";
    s += "Physical Surface(1) = {1};\n";
    if (recombine)
      s += "Mesh.Algorithm = 8; Mesh.CrossFieldClosestPoint = 0; Mesh.RecombinationAlgorithm = 3; "
           "Mesh.RecombineAll = 1;\n";
    return s;
  };
  write_file(dir.file("quads.geo"), geo(true));
  write_file(dir.file("tris.geo"), geo(false));
  for (const auto& [geo_file, msh, format] :
       std::vector<std::array<std::string, 3>>{{"quads.geo", "q41.msh", "msh41"},
                                               {"quads.geo", "q22.msh", "msh22"},
                                               {"tris.geo", "t41.msh", "msh41"}}) {
    const CliResult g = run_cli_program(
        "gmsh", {dir.file(geo_file), "-2", "-format", format, "-o", dir.file(msh)}, dir);
    ASSERT_EQ(g.exit_code, 0) << g.out << g.err;
  }
  const std::string counts = python_check(dir, R"(
import sys, meshio
m = meshio.read(sys.argv[1])
print(sum(len(c.data) for c in m.cells if c.type == "quad"), len(m.points))
)",
                                          {dir.file("q41.msh")});
  std::istringstream cin(counts);
  double meshio_quads = 0, meshio_points = 0;
  cin >> meshio_quads >> meshio_points;
  ASSERT_GT(meshio_quads, 100);

  const std::vector<std::string> common = {
      "quality",   dir.file("rect.geojson"), "--size", "500", "--cross-angle", "0", "--dst-crs",
      "EPSG:32631"};
  std::string first;
  for (const char* msh : {"q41.msh", "q22.msh"}) {
    std::vector<std::string> args = common;
    args.insert(args.end(),
                {"--mesh", dir.file(msh), "--report", dir.file(std::string(msh) + ".json")});
    const CliResult r = run_cli(args, dir);
    ASSERT_EQ(r.exit_code, 0) << msh << r.err;
    const std::string q = read_file(dir.file(std::string(msh) + ".json"));
    EXPECT_EQ(report_number(q, "num_quads"), meshio_quads) << msh;
    EXPECT_EQ(report_number(q, "num_vertices"), meshio_points) << msh;
    EXPECT_EQ(report_number(q, "num_triangles"), 0) << msh;
    EXPECT_EQ(report_number(q, "num_nonconvex"), 0) << msh;
    EXPECT_EQ(report_number(q, "num_boundary_vertices_off_domain"), 0) << msh;
    EXPECT_NEAR(report_number(q, "mesh_area_m2"), w * h, 1e-3) << msh;
    EXPECT_LT(report_number(q, "boundary_departure_max_m"), 1e-6) << msh;
    const double regular = report_number(q, "share_regular_interior");
    EXPECT_GT(regular, 0.5) << msh;
    EXPECT_LE(regular, 1.0) << msh;
    if (first.empty())
      first = q;
    else
      expect_same_quality(first, q, 1e-12, "msh 2.2 against 4.1");
  }
  // -o numbers the quads and vertices as the file does: Gmsh's mesh with its element tags
  // from 1001 and its node tags multiplied by 10.
  EXPECT_EQ(python_check(dir, R"(
import sys
lines = open(sys.argv[1]).read().split("\n")
i, j = lines.index("$Nodes"), lines.index("$Elements")
for k in range(i + 2, i + 2 + int(lines[i + 1])):
    f = lines[k].split()
    lines[k] = " ".join([str(10 * int(f[0]))] + f[1:])
for k in range(j + 2, j + 2 + int(lines[j + 1])):
    f = lines[k].split()
    tags = 3 + int(f[2])
    lines[k] = " ".join([str(1000 + int(f[0]))] + f[1:tags] + [str(10 * int(n)) for n in f[tags:]])
open(sys.argv[2], "w").write("\n".join(lines))
print("ok")
)",
                         {dir.file("q22.msh"), dir.file("renumbered.msh")}),
            "ok\n");
  std::vector<std::string> with_ids = common;
  with_ids.insert(with_ids.end(),
                  {"--mesh", dir.file("renumbered.msh"), "-o", dir.file("renumbered.gpkg")});
  const CliResult ids = run_cli(with_ids, dir);
  ASSERT_EQ(ids.exit_code, 0) << ids.err;
  EXPECT_EQ(python_check(dir, R"(
import sqlite3, sys
lines = open(sys.argv[1]).read().split("\n")
i = lines.index("$Nodes")
nodes = [int(l.split()[0]) for l in lines[i + 2:i + 2 + int(lines[i + 1])]]
j = lines.index("$Elements")
quads = [int(l.split()[0]) for l in lines[j + 2:j + 2 + int(lines[j + 1])] if l.split()[1] == "3"]
db = sqlite3.connect(sys.argv[2])
q = [r[0] for r in db.execute("select id from quads order by fid")]
v = [r[0] for r in db.execute("select id from vertices order by fid")]
assert q == quads and q[0] > 1000, (q[:5], quads[:5])
assert v == nodes and v[0] % 10 == 0, (v[:5], nodes[:5])
print("ok")
)",
                         {dir.file("renumbered.msh"), dir.file("renumbered.gpkg")}),
            "ok\n");
  std::vector<std::string> args = common;
  args.insert(args.end(), {"--mesh", dir.file("t41.msh"), "--report", dir.file("t.json")});
  const CliResult tris = run_cli(args, dir);
  ASSERT_EQ(tris.exit_code, 0) << tris.err;
  const std::string t = read_file(dir.file("t.json"));
  EXPECT_GT(report_number(t, "num_triangles"), 100);
  EXPECT_EQ(report_number(t, "num_quads"), 0);
  EXPECT_GT(report_number(t, "triangle_min_angle_deg"), 20);
  EXPECT_LT(report_number(t, "triangle_max_angle_deg"), 120);
  EXPECT_EQ(report_number(t, "num_inverted_triangles"), 0);
  // Gmsh's sides of about lc = h: the equilateral side of a triangle's area near h.
  EXPECT_GT(report_number(t, "triangle_size_ratio_median"), 0.8);
  EXPECT_LT(report_number(t, "triangle_size_ratio_median"), 1.25);
  // Two triangles' circumcentres lie on their shared side's bisector: orthogonal links.
  EXPECT_LT(report_number(t, "dflowfm_orthogonality_max"), 1e-9);
  EXPECT_NEAR(report_number(t, "mesh_area_m2"), w * h, 1e-3);
  // Delaunay-like triangles: most interior vertices in six.
  EXPECT_GT(report_number(t, "triangle_share_regular_interior"), 0.3);
  EXPECT_LE(report_number(t, "triangle_share_regular_interior"), 1.0);
  EXPECT_NE(tris.err.find("their angles, sizes and regularity, the coast and the D-Flow FM "
                          "links are measured"),
            std::string::npos)
      << tris.err;
  // Gmsh's triangles have a node at each of the rectangle's corners: the coast exactly.
  EXPECT_EQ(report_number(t, "num_boundary_vertices_off_domain"), 0);
  EXPECT_LT(report_number(t, "boundary_departure_max_m"), 1e-6);
  args.insert(args.end(), {"-o", dir.file("t.gpkg"), "--overwrite"});
  const CliResult with_output = run_cli(args, dir);
  EXPECT_EQ(with_output.exit_code, 2);
  EXPECT_NE(with_output.err.find("-o and --plot show meshes of quadrangles alone"),
            std::string::npos)
      << with_output.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("t.gpkg")));
}

// The netCDF library is not thread-safe: regions meshed at once write their .nc files,
// and regions measured at once read them, one at a time (a crash, or files that read as
// "not a netCDF file", otherwise).
TEST(CliQuality, RegionsAtOnceWriteAndReadNetcdfMeshes) {
  TempDir dir;
  std::vector<std::string> squares;
  for (int k = 0; k < 6; ++k) {
    const std::string x0 = std::to_string(500000 + 10000 * k),
                      x1 = std::to_string(504000 + 10000 * k);
    squares.push_back("[[[" + x0 + ",5000000],[" + x1 + ",5000000],[" + x1 + ",5004000],[" + x0 +
                      ",5004000],[" + x0 + ",5000000]]]");
  }
  write_file(dir.file("six.geojson"), geojson_polygons(squares, kUtm31nCrsMember));
  const std::vector<std::string> common = {dir.file("six.geojson"),
                                           "--dst-crs",
                                           "EPSG:32631",
                                           "--size",
                                           "500",
                                           "--each",
                                           "name",
                                           "--jobs",
                                           "2",
                                           "-q"};
  std::vector<std::string> mesh = {"mesh"};
  mesh.insert(mesh.end(), common.begin(), common.end());
  mesh.insert(mesh.end(), {"-o", dir.file("{}.nc"), "--each-table", dir.file("made.csv")});
  const CliResult made = run_cli(mesh, dir);
  ASSERT_EQ(made.exit_code, 0) << made.err;
  for (int run = 0; run < 3; ++run) {
    std::vector<std::string> quality = {"quality"};
    quality.insert(quality.end(), common.begin(), common.end());
    quality.insert(quality.end(), {"--mesh", dir.file("{}.nc"), "--each-table",
                                   dir.file("measured.csv"), "--overwrite"});
    const CliResult measured = run_cli(quality, dir);
    ASSERT_EQ(measured.exit_code, 0) << measured.err;
    const std::string table = read_file(dir.file("measured.csv"));
    for (int k = 0; k < 6; ++k)
      EXPECT_NE(table.find("\r\nf" + std::to_string(k) + ",f" + std::to_string(k) + ",measured,0,"),
                std::string::npos)
          << table;
  }
}

// quality --each: each region's mesh ({} in --mesh) measured against its own fields,
// as the mesh job's --each reported it; a region whose mesh is missing fails alone.
TEST(CliQuality, EachRegionsMeshMeasuredAsItsReportSays) {
  TempDir dir;
  write_file(dir.file("two.geojson"),
             geojson_polygons({"[[[500000,5000000],[506000,5000000],[506000,5004000],"
                               "[500000,5004000],[500000,5000000]]]",
                               "[[[520000,5000000],[524000,5000000],[524000,5005000],"
                               "[520000,5005000],[520000,5000000]]]",
                               "[[[540000,5000000],[544000,5000000],[544000,5004000],"
                               "[540000,5004000],[540000,5000000]]]"},
                              kUtm31nCrsMember));
  const std::vector<std::string> common = {
      dir.file("two.geojson"), "--dst-crs", "EPSG:32631", "--size", "400", "--each", "name"};
  std::vector<std::string> mesh = {"mesh"};
  mesh.insert(mesh.end(), common.begin(), common.end());
  mesh.insert(mesh.end(), {"--where", "name <> 'f2'", "-o", dir.file("{}.gr3"), "--report",
                           dir.file("{}.json"), "--each-table", dir.file("made.csv")});
  const CliResult made = run_cli(mesh, dir);
  ASSERT_EQ(made.exit_code, 0) << made.err;
  std::vector<std::string> quality = {"quality"};
  quality.insert(quality.end(), common.begin(), common.end());
  quality.insert(quality.end(),
                 {"--mesh", dir.file("{}.gr3"), "--report", dir.file("{}.q.json"), "--jobs", "2"});
  quality.insert(quality.end(), {"--each-table", dir.file("measured.csv")});
  const CliResult measured = run_cli(quality, dir);
  EXPECT_EQ(measured.exit_code, 3) << measured.err;  // f2 has no mesh
  // The two tables: each region's figures as the mesh run gave them, f2 failed.
  const std::string made_table = read_file(dir.file("made.csv"));
  const std::string measured_table = read_file(dir.file("measured.csv"));
  for (const std::string name : {"f0", "f1"}) {
    const std::string start = "\r\n" + name + "," + name + ",meshed,0,";
    const std::size_t at = made_table.find(start);
    ASSERT_NE(at, std::string::npos) << made_table;
    const std::size_t end = made_table.find("\r\n", at + 2);
    const std::string figures = made_table.substr(at + start.size(), end - at - start.size());
    EXPECT_NE(measured_table.find("\r\n" + name + "," + name + ",measured,0," + figures + "\r\n"),
              std::string::npos)
        << figures << "\n"
        << measured_table;
  }
  EXPECT_NE(measured_table.find("\r\nf2,f2,failed,3,"), std::string::npos) << measured_table;
  EXPECT_NE(measured.err.find("name = f2: read: '" + dir.file("f2.gr3") + "': no such mesh file"),
            std::string::npos)
      << measured.err;
  EXPECT_NE(measured.err.find("--each name: 2 of 3 measured; failed: f2"), std::string::npos)
      << measured.err;
  for (const char* name : {"f0", "f1"})
    expect_same_quality(read_file(dir.file(std::string(name) + ".json")),
                        read_file(dir.file(std::string(name) + ".q.json")), 1e-6, name);
  // --mesh without {} under --each.
  quality[quality.size() - 7] = dir.file("f0.gr3");
  const CliResult no_mark = run_cli(quality, dir);
  EXPECT_EQ(no_mark.exit_code, 2);
  EXPECT_NE(no_mark.err.find("with --each, --mesh needs {}"), std::string::npos) << no_mark.err;
}

// Without INPUT the domain is the mesh's own outline: a water mesh with four islands
// read back from its .gpkg (in the meshing CRS) and its .ll (in lon/lat) has the same
// holes, every boundary vertex on the outline, the outline's area, and the same shapes as
// the mesh report; the .ll's open boundaries stay open (-o's boundary layer as the
// mesh's); a .gr3 without --mesh-crs, and selections from INPUT, stop clearly.
TEST(CliQuality, WithoutInputTheDomainIsTheMeshsOutline) {
  TempDir dir;
  const CliResult made =
      run_cli({"mesh", sample("brittany_land.shp"), "--domain", "water",
               "--bbox=-5.3,46.8,-1.95,49.35", "--hmax", "8000", "-o", dir.file("m.gpkg"), "-o",
               dir.file("m.gr3"), "-o", dir.file("m.msh"), "--report", dir.file("r.json")},
              dir);
  ASSERT_EQ(made.exit_code, 0) << made.err;
  const std::string mesh_report = read_file(dir.file("r.json"));
  ASSERT_GE(report_number(mesh_report, "num_holes"), 2);
  for (const char* file : {"m.gpkg", "m.ll"}) {
    const std::string report = dir.file(std::string(file) + ".json");
    const CliResult r = run_cli({"quality", "--mesh", dir.file(file), "--hmax", "8000", "--report",
                                 report, "-o", dir.file(std::string("q_") + file + ".gpkg")},
                                dir);
    ASSERT_EQ(r.exit_code, 0) << file << r.err;
    EXPECT_NE(r.err.find("domain from:  the mesh's outline"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(std::string("mesh:         ") +
                         (std::string(file) == "m.gpkg" ? "polygons" : "SCHISM .gr3") + " file: "),
              std::string::npos)
        << r.err;
    const std::string q = read_file(report);
    EXPECT_EQ(report_number(q, "num_holes"), report_number(mesh_report, "num_holes")) << file;
    EXPECT_EQ(report_number(q, "num_outline_loops"), 1 + report_number(mesh_report, "num_holes"));
    EXPECT_EQ(report_number(q, "num_quads"), report_number(mesh_report, "num_quads")) << file;
    EXPECT_EQ(report_number(q, "num_boundary_vertices_off_domain"), 0) << file;
    EXPECT_EQ(report_number(q, "num_boundary_vertices"),
              report_number(mesh_report, "num_boundary_vertices"))
        << file;
    EXPECT_NEAR(report_number(q, "mesh_area_m2") / report_number(q, "domain_area_m2"), 1.0, 1e-9);
    // The shapes do not depend on the fields (the .ll in another projection: conformal).
    const double tolerance = std::string(file) == "m.gpkg" ? 1e-9 : 1e-3;
    for (const char* key :
         {"share_angles_75_105", "min_angle_deg", "max_angle_deg", "share_regular_interior",
          "share_regular_boundary", "schism_angle_ratio_violations", "num_nonconvex"}) {
      const double a = report_number(mesh_report, key), b = report_number(q, key);
      EXPECT_NEAR(a, b, tolerance * std::max(1.0, std::abs(a))) << file << ": " << key;
    }
  }

  // The boundary's kinds: open along the bbox, land elsewhere, as the mesh wrote them.
  auto kinds = [&dir](const std::string& name) { return boundary_kinds(dir.file(name)); };
  const std::map<std::string, int> made_kinds = kinds("m.gpkg");
  EXPECT_EQ(made_kinds.count("open") ? made_kinds.at("open") : 0, 3);
  EXPECT_EQ(kinds("q_m.ll.gpkg"), made_kinds);
  // --open-groups names the .msh's own groups: its "land" group open, the rest land (the
  // .msh in the report's meshing CRS, which it does not name).
  const std::string key = "\"meshing_crs_proj\": \"";
  const std::size_t crs_at = mesh_report.find(key) + key.size();
  const std::string crs = mesh_report.substr(crs_at, mesh_report.find('"', crs_at) - crs_at);
  const CliResult groups = run_cli({"quality", "--mesh", dir.file("m.msh"), "--mesh-crs", crs,
                                    "--open-groups", "land", "-o", dir.file("g.gpkg")},
                                   dir);
  ASSERT_EQ(groups.exit_code, 0) << groups.err;
  const std::map<std::string, int> swapped = kinds("g.gpkg");
  EXPECT_EQ(swapped.count("land") ? swapped.at("land") : 0, 3) << groups.err;
  const CliResult both = run_cli({"quality", "--mesh", dir.file("m.msh"), "--open-groups", "land",
                                  "--open-boundary", dir.file("m.gpkg")},
                                 dir);
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_NE(both.err.find("--open-boundary or --open-groups"), std::string::npos) << both.err;

  // isoquad's .gr3 names its CRS in its title line; another mesher's (the same grid, a
  // title without it) stops, naming --mesh-crs and the .ll beside it.
  const CliResult named = run_cli({"quality", "--mesh", dir.file("m.gr3")}, dir);
  EXPECT_EQ(named.exit_code, 0) << named.err;
  // Its fort.14 too (the same title's note).
  const CliResult made14 = run_cli({"mesh", sample("corsica.shp"), "--hmax", "8000", "-o",
                                    dir.file("c.14"), "-o", dir.file("c.gr3"), "-q"},
                                   dir);
  ASSERT_EQ(made14.exit_code, 0) << made14.err;
  const CliResult named14 = run_cli({"quality", "--mesh", dir.file("c.14")}, dir);
  EXPECT_EQ(named14.exit_code, 0) << named14.err;
  EXPECT_NE(named14.err.find("triangles"), std::string::npos) << named14.err;
  std::string other = read_file(dir.file("m.gr3"));
  other.replace(0, other.find('\n'), "a grid from another mesher");
  write_file(dir.file("other.gr3"), other);
  write_file(dir.file("other.ll"), read_file(dir.file("m.ll")));
  const CliResult no_crs = run_cli({"quality", "--mesh", dir.file("other.gr3")}, dir);
  EXPECT_EQ(no_crs.exit_code, 4);
  EXPECT_NE(no_crs.err.find("with --mesh-crs"), std::string::npos) << no_crs.err;
  EXPECT_NE(no_crs.err.find("or give '" + dir.file("other.ll") + "' instead"), std::string::npos)
      << no_crs.err;
  const CliResult where =
      run_cli({"quality", "--mesh", dir.file("m.gpkg"), "--where", "name = 'x'"}, dir);
  EXPECT_EQ(where.exit_code, 2);
  EXPECT_NE(where.err.find("--where selects from INPUT"), std::string::npos) << where.err;
  // Defective elements without INPUT: the outline fails, and the message names them. A
  // bow-tie quad makes the outline cross itself; a quad given twice leaves it empty, or
  // in a larger mesh untraceable.
  struct Defective {
    const char* name;
    const char* text;
    const char* says;
  };
  const Defective defective[] = {
      {"bowtie.gr3",
       "bow-tie\n1 4\n1 500000 5000000 0\n2 501000 5001000 0\n3 501000 5000000 0\n"
       "4 500000 5001000 0\n7 4 1 2 3 4\n",
       "(the mesh has 1 element(s) without area or crossing themselves, the first quad 7)"},
      {"twice.gr3",
       "twice\n2 4\n1 500000 5000000 0\n2 501000 5000000 0\n3 501000 5001000 0\n"
       "4 500000 5001000 0\n1 4 1 2 3 4\n2 4 1 2 3 4\n",
       "(the mesh has 1 element(s) given twice, on the same nodes, the first quad 2 (as quad "
       "1))"},
      {"twice2.gr3",
       "twice\n3 6\n1 500000 5000000 0\n2 501000 5000000 0\n3 502000 5000000 0\n"
       "4 500000 5001000 0\n5 501000 5001000 0\n6 502000 5001000 0\n1 4 1 2 5 4\n"
       "2 4 2 3 6 5\n3 4 2 3 6 5\n",
       "is a side of three or more elements (the mesh has 1 element(s) given twice, on the same "
       "nodes, the first quad 3 (as quad 2))"}};
  for (const Defective& d : defective) {
    write_file(dir.file(d.name), d.text);
    const CliResult r = run_cli(
        {"quality", "--mesh", dir.file(d.name), "--mesh-crs", "EPSG:32630", "--size", "500"}, dir);
    EXPECT_EQ(r.exit_code, 3) << d.name << ": " << r.err;
    EXPECT_NE(r.err.find(d.says), std::string::npos) << d.name << ": " << r.err;
  }
  // A raster INPUT's band of values: nothing to select without INPUT.
  const CliResult zmin = run_cli({"quality", "--mesh", dir.file("m.gpkg"), "--zmin", "0"}, dir);
  EXPECT_EQ(zmin.exit_code, 2);
  EXPECT_NE(zmin.err.find("--zmin selects from INPUT"), std::string::npos) << zmin.err;
  const CliResult each = run_cli({"quality", "--mesh", dir.file("{}.gpkg"), "--each", "name"}, dir);
  EXPECT_EQ(each.exit_code, 2);
  EXPECT_NE(each.err.find("give INPUT"), std::string::npos) << each.err;
}

// A sea polygon as INPUT (the domain's own GeoPackage) with --open-boundary: `quality`
// measures the mesh against it with the mesh's open boundary (-o's boundary layer open
// where the mesh's is; all land without the option), and `fields` leaves the open lines
// out of the distance to the coast, c (sizes that grow with c: larger, fewer quads). The
// quads outside a domain cut short are counted; a mesh read in the wrong CRS stops.
TEST(CliQuality, OpenBoundaryLinesForQualityAndFields) {
  TempDir dir;
  const std::string sea = dir.file("sea.gpkg");
  const CliResult domain = run_cli({"domain", sample("brittany_land.shp"), "--domain", "water",
                                    "--bbox=-5.3,46.8,-1.95,49.35", "--size", "2000", "-o", sea},
                                   dir);
  ASSERT_EQ(domain.exit_code, 0) << domain.err;
  const CliResult made = run_cli({"mesh", sea, "--open-boundary", sea, "--hmax", "8000", "-o",
                                  dir.file("m.gr3"), "--report", dir.file("m.json")},
                                 dir);
  ASSERT_EQ(made.exit_code, 0) << made.err;
  auto kinds = [&dir](const std::string& name) { return boundary_kinds(dir.file(name)); };
  for (const bool lines : {true, false}) {
    std::vector<std::string> args = {"quality", sea,
                                     "--hmax",  "8000",
                                     "--mesh",  dir.file("m.gr3"),
                                     "-o",      dir.file(lines ? "q_open.gpkg" : "q_land.gpkg")};
    if (lines) args.insert(args.end(), {"--open-boundary", sea});
    const CliResult q = run_cli(args, dir);
    ASSERT_EQ(q.exit_code, 0) << q.err;
    const std::map<std::string, int> k = kinds(lines ? "q_open.gpkg" : "q_land.gpkg");
    EXPECT_EQ(k.count("open") ? k.at("open") : 0, lines ? 3 : 0) << q.err;
  }
  // The mesh's quads lie in the domain; a third of the domain cut off leaves some outside,
  // counted with a warning; the mesh read in another CRS (away from the domain) stops.
  const CliResult whole = run_cli({"quality", sea, "--hmax", "8000", "--mesh", dir.file("m.gr3"),
                                   "--report", dir.file("whole.json")},
                                  dir);
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  EXPECT_EQ(report_number(read_file(dir.file("whole.json")), "num_quads_outside_domain"), 0);
  const CliResult part = run_cli(
      {"quality", sea, "--hmax", "8000", "--mesh", dir.file("m.gr3"), "--bbox=-5.3,46.8,-3.0,49.35",
       "--bbox-crs", "EPSG:4326", "--report", dir.file("part.json")},
      dir);
  ASSERT_EQ(part.exit_code, 0) << part.err;
  const double outside =
      report_number(read_file(dir.file("part.json")), "num_quads_outside_domain");
  EXPECT_GT(outside, 0.1 * report_number(read_file(dir.file("m.json")), "num_quads"));
  EXPECT_NE(part.err.find("have their centroid outside the domain"), std::string::npos) << part.err;
  const CliResult elsewhere = run_cli(
      {"quality", sea, "--hmax", "8000", "--mesh", dir.file("m.gr3"), "--mesh-crs", "EPSG:32631"},
      dir);
  EXPECT_EQ(elsewhere.exit_code, 3) << elsewhere.err;
  EXPECT_NE(elsewhere.err.find("0 of its"), std::string::npos) << elsewhere.err;
  auto predicted = [&](bool lines) {
    std::vector<std::string> args = {"fields",      sea,
                                     "--hmax",      "8000",
                                     "--size-expr", "2000 + 0.2 * c",
                                     "-o",          dir.file(lines ? "o.vtu" : "l.vtu")};
    if (lines) args.insert(args.end(), {"--open-boundary", sea});
    const CliResult f = run_cli(args, dir);
    EXPECT_EQ(f.exit_code, 0) << f.err;
    const std::size_t at = f.err.find("; about ");
    return at == std::string::npos ? 0.0 : std::stod(f.err.substr(at + 8));
  };
  const double with_lines = predicted(true), without = predicted(false);
  EXPECT_GT(with_lines, 0);
  EXPECT_LT(with_lines, 0.9 * without) << with_lines << " against " << without;
}

// A lon/lat grid across the antimeridian is read whichever way its longitudes run: the
// water from 176 E to 176 W written as hgrid.ll in [0, 360) (isoquad's way) and again in
// [-180, 180) (where two columns of quads cross the cut) measures the same, and meshes
// again along its open boundary.
TEST(CliQuality, AGridAcrossTheAntimeridianInEitherLongitudes) {
  TempDir dir;
  const CliResult made = run_cli({"mesh", source_dir() + "/tests/data/arctic_110m.geojson",
                                  "--domain", "water", "--bbox", "176,-20,184,-14", "--hmax",
                                  "40000", "-o", dir.file("m.gr3"), "--report", dir.file("r.json")},
                                 dir);
  ASSERT_EQ(made.exit_code, 0) << made.err;
  const std::string mesh_report = read_file(dir.file("r.json"));
  std::istringstream in(read_file(dir.file("m.ll")));
  std::ostringstream out;
  std::string line;
  int num_nodes = 0, across = 0;
  for (int i = 0; std::getline(in, line); ++i) {
    int num_elements = 0;
    if (i == 1) std::istringstream(line) >> num_elements >> num_nodes;
    if (i >= 2 && i < 2 + num_nodes) {
      std::istringstream node(line);
      int id = 0;
      double lon = 0, lat = 0, depth = 0;
      node >> id >> lon >> lat >> depth;
      if (lon >= 180) lon -= 360, ++across;
      out << id << " " << std::setprecision(15) << lon << " " << lat << " " << depth << "\n";
      continue;
    }
    out << line << "\n";
  }
  ASSERT_GT(across, 0);
  ASSERT_LT(across, num_nodes);
  write_file(dir.file("m180.ll"), out.str());
  for (const char* file : {"m.ll", "m180.ll"}) {
    const std::string report = dir.file(std::string(file) + ".json");
    const CliResult r =
        run_cli({"quality", "--mesh", dir.file(file), "--hmax", "40000", "--report", report}, dir);
    ASSERT_EQ(r.exit_code, 0) << file << r.err;
    const std::string q = read_file(report);
    EXPECT_EQ(report_number(q, "num_outline_loops"), 1) << file;
    EXPECT_EQ(report_number(q, "num_quads"), report_number(mesh_report, "num_quads")) << file;
    EXPECT_EQ(report_number(q, "num_boundary_vertices_off_domain"), 0) << file;
    // In a projection centred on the outline (to 2e-6 of the mesh's).
    EXPECT_NEAR(report_number(q, "mesh_area_m2") / report_number(mesh_report, "mesh_area_m2"), 1.0,
                1e-4)
        << file;
    EXPECT_NEAR(report_number(q, "min_angle_deg"), report_number(mesh_report, "min_angle_deg"),
                1e-3)
        << file;

    const CliResult again = run_cli(
        {"mesh", dir.file(file), "--hmax", "40000", "-o", dir.file(std::string(file) + ".gpkg"),
         "--report", dir.file(std::string(file) + ".again.json")},
        dir);
    ASSERT_EQ(again.exit_code, 0) << file << again.err;
    const std::string a = read_file(dir.file(std::string(file) + ".again.json"));
    // Open all round: hgrid.gr3's two open segments (SCHISM's way for a whole loop).
    EXPECT_EQ(report_number(a, "num_open_parts"), 2) << file;
    EXPECT_NEAR(report_number(a, "open_parts_length_m") / report_number(a, "perimeter_m"), 1.0,
                1e-6)
        << file;
    EXPECT_NEAR(report_number(a, "num_quads") / report_number(mesh_report, "num_quads"), 1.0, 0.1)
        << file;
  }
}

// A grid round the globe (the water from 60 S to 60 N at 1,000 km) has no outline in
// longitudes, whatever the cut: its hgrid.ll is read as an annulus round the North Pole,
// measured as its mesh report says and meshed again.
TEST(CliQuality, AGridRoundTheGlobe) {
  TempDir dir;
  const CliResult made =
      run_cli({"mesh", source_dir() + "/tests/data/arctic_110m.geojson", "--domain", "water",
               "--bbox", "-180,-60,180,60", "--size", "1000000", "-o", dir.file("m.gr3"),
               "--report", dir.file("r.json")},
              dir);
  ASSERT_EQ(made.exit_code, 0) << made.err;
  const std::string mesh_report = read_file(dir.file("r.json"));
  ASSERT_EQ(report_number(mesh_report, "num_holes"), 1);
  const CliResult r = run_cli(
      {"quality", "--mesh", dir.file("m.ll"), "--size", "1000000", "--report", dir.file("q.json")},
      dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("CRS isoquad local oblique stereographic"), std::string::npos) << r.err;
  const std::string q = read_file(dir.file("q.json"));
  EXPECT_EQ(report_number(q, "num_outline_loops"), 2);
  EXPECT_EQ(report_number(q, "num_holes"), 1);
  EXPECT_EQ(report_number(q, "num_boundary_vertices_off_domain"), 0);
  EXPECT_NEAR(report_number(q, "mesh_area_m2") / report_number(q, "domain_area_m2"), 1.0, 1e-9);
  for (const char* key : {"num_quads", "num_boundary_vertices", "min_angle_deg",
                          "share_angles_75_105", "share_regular_interior"})
    EXPECT_NEAR(report_number(q, key), report_number(mesh_report, key),
                1e-3 * std::max(1.0, report_number(mesh_report, key)))
        << key;
  const CliResult again = run_cli({"mesh", dir.file("m.ll"), "--size", "1000000", "-o",
                                   dir.file("again.gpkg"), "--report", dir.file("a.json")},
                                  dir);
  ASSERT_EQ(again.exit_code, 0) << again.err;
  const std::string a = read_file(dir.file("a.json"));
  EXPECT_EQ(report_number(a, "num_holes"), 1);
  EXPECT_EQ(report_number(a, "num_nonconvex"), 0);
  EXPECT_NEAR(report_number(a, "num_quads") / report_number(mesh_report, "num_quads"), 1.0, 0.15);
}
