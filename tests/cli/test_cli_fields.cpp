// `isoquad fields`: the background mesh and fields as a user opens them.
#include <gtest/gtest.h>

#include <algorithm>

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include "gis/gdal_env.h"
#include "support/fixtures.h"
#include "support/write_raster.h"

using namespace isoquad::test;

TEST(CliFields, VtuLoadsInMeshioWithSizeAndCrossAngle) {
  TempDir dir;
  const std::string vtu = dir.file("fields.vtu"), png = dir.file("fields.png");
  const CliResult r = run_cli({"fields", sample("corsica.geojson"), "-o", vtu, "--plot", png,
                               "--hmax", "8000"},
                              dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("singularities"), std::string::npos) << r.err;
  // A real reader: meshio (Debian's python3-meshio, under /usr/bin/python3).
  const std::string script = dir.file("check.py");
  write_file(script,
             "import sys, meshio, numpy as np\n"
             "m = meshio.read(sys.argv[1])\n"
             "tri = m.cells_dict['triangle']\n"
             "size = m.point_data['size']; cross = m.point_data['cross_angle']\n"
             "assert len(m.points) > 100 and len(tri) > 100\n"
             "assert size.shape == (len(m.points),) and cross.shape == (len(m.points),)\n"
             "assert size.min() > 0 and size.max() <= 8000 * (1 + 1e-9)\n"
             "assert cross.min() >= 0 and cross.max() < 90\n"
             "p = m.points[:, :2]; a = p[tri[:, 1]] - p[tri[:, 0]]; b = p[tri[:, 2]] - p[tri[:, 0]]\n"
             "assert (a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]).min() > 0\n"
             "print('ok', len(m.points), len(tri))\n");
  const CliResult py = run_cli_program("/usr/bin/python3", {script, vtu}, dir);
  EXPECT_EQ(py.exit_code, 0) << py.err << py.out;
  EXPECT_EQ(py.out.rfind("ok ", 0), 0u) << py.out;
  // The plot is a PNG.
  EXPECT_EQ(read_file(png).substr(1, 3), "PNG");
}

TEST(CliFields, ReportHasTheDomainSizingBackgroundCrossFieldAndStages) {
  // The report holds what the summary prints, and its numbers are those of the fields
  // written: read back with meshio.
  TempDir dir;
  const std::string vtu = dir.file("fields.vtu"), report = dir.file("fields.json");
  const CliResult r = run_cli({"fields", sample("corsica.geojson"), "-o", vtu, "--report", report,
                               "--hmax", "8000", "-q"},
                              dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string script = dir.file("check.py");
  write_file(
      script,
      "import sys, json, meshio\n"
      "m = meshio.read(sys.argv[1]); r = json.load(open(sys.argv[2]))\n"
      "assert 'fields' in r['command_line'] and r['isoquad_version']\n"
      "from osgeo import gdal\n"
      "L = r['libraries']  # in a fixed order, GDAL's as Python's GDAL has it\n"
      "assert list(L)[0] == 'CGAL' and L['SLEEF'] and L['GDAL'] == gdal.__version__, L\n"
      "assert r['domain']['num_components'] >= 1 and r['domain']['area_m2'] > 0\n"
      "s = r['sizing']; size = m.point_data['size']\n"
      "assert s['hmax_m'] == 8000 and 0 < s['hmin_m'] < s['hmax_m']\n"
      "assert abs(s['size_min_m'] - size.min()) <= 1e-6 * size.min(), s\n"
      "assert abs(s['size_max_m'] - size.max()) <= 1e-6 * size.max(), s\n"
      "assert s['predicted_quads'] > 10\n"
      "b = r['background']\n"
      "assert b['num_vertices'] == len(m.points), b\n"
      "assert b['num_triangles'] == len(m.cells_dict['triangle']), b\n"
      "c = r['cross_field']\n"
      "assert c['num_singularities'] == b['num_singularities'] == "
      "c['num_index_plus_quarter'] + c['num_index_minus_quarter_or_less'], c\n"
      "stages = [t['stage'] for t in r['stages']]\n"
      "assert stages[0] == 'front end' and stages[-2:] == ['cross field', 'output'], stages\n"
      "assert all(t['seconds'] >= 0 and t['peak_mb'] > 0 for t in r['stages'])\n"
      "print('ok')\n");
  const CliResult py = run_cli_program("/usr/bin/python3", {script, vtu, report}, dir);
  EXPECT_EQ(py.exit_code, 0) << py.err << py.out;
  EXPECT_EQ(py.out.rfind("ok", 0), 0u) << py.out;
}

TEST(CliFields, GeoPackageHasVerticesAndTriangles) {
  TempDir dir;
  const std::string gpkg = dir.file("fields.gpkg");
  const CliResult r = run_cli({"fields", sample("corsica.shp"), "-o", gpkg, "--size", "4000",
                               "--cross-angle", "30"},
                              dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  isoquad::ensure_gdal_registered();
  GDALDataset* ds = static_cast<GDALDataset*>(
      GDALOpenEx(gpkg.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr));
  ASSERT_NE(ds, nullptr);
  OGRLayer* v = ds->GetLayerByName("vertices");
  OGRLayer* t = ds->GetLayerByName("triangles");
  ASSERT_NE(v, nullptr);
  ASSERT_NE(t, nullptr);
  EXPECT_GT(v->GetFeatureCount(), 100);
  EXPECT_GT(t->GetFeatureCount(), 100);
  for (auto& f : *v) {
    ASSERT_DOUBLE_EQ(f->GetFieldAsDouble("size_m"), 4000.0);
    ASSERT_NEAR(f->GetFieldAsDouble("cross_angle_deg"), 30.0, 1e-9);
  }
  GDALClose(ds);
}

TEST(CliFields, BadSizingOptionsFailCleanly) {
  TempDir dir;
  const std::string out = dir.file("f.vtu");
  for (const auto& extra : std::vector<std::vector<std::string>>{
           {"--size-expr", "2*"},
           {"--size-expr", "x-1e12"},
           {"--hmin", "5000", "--hmax", "100"},
           {"--cross-angle", "10", "--cross-raster", "a.tif"},
           {"--size-raster", dir.file("missing.tif")}}) {
    std::vector<std::string> args{"fields", sample("corsica.geojson"), "-o", out};
    args.insert(args.end(), extra.begin(), extra.end());
    const CliResult r = run_cli(args, dir);
    EXPECT_NE(r.exit_code, 0) << extra[0];
    EXPECT_NE(r.exit_code, 70) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << extra[0];
  }
  // A raster of sizes or angles far from the domain (lon/lat 0..1, Corsica at 9 E 42 N):
  // refused, not ignored.
  const std::string far = write_geotiff(dir.file("far.tif"), 0.0, 1.0, 0.1, 10, 10, 4326,
                                        [](double, double) { return 3000.0; });
  for (const auto& [option, message] : std::vector<std::pair<std::string, std::string>>{
           {"--size-raster", "has no size anywhere over the domain"},
           {"--cross-raster", "has no angle anywhere over the domain"}}) {
    const CliResult r = run_cli(
        {"fields", sample("corsica.geojson"), "--hmax", "20000", option, far, "-o", out}, dir);
    EXPECT_EQ(r.exit_code, 3) << r.err;
    EXPECT_NE(r.err.find(option + " '" + far + "' " + message), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
  // Sizes that shrink to nothing at the coast, which the grid's estimate misses: refused
  // at once (they kept the size cache refining towards the coast without end).
  for (const auto& [extra, message] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"--size-expr", "c"}, "--size-expr 'c' gives 0.000000 at ("},
           {{"--size-expr", "max(c, 1)", "--max-quads", "100000"},
            "(at least that along the boundary; 8665.1 km2, sizes from 1 m), over the limit"}}) {
    std::vector<std::string> args{"fields", sample("corsica.geojson"), "-o", out};
    args.insert(args.end(), extra.begin(), extra.end());
    const CliResult r = run_cli(args, dir);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
  }
}

// The start of a check of a fields .vtu (argv[1]) meshed in Web Mercator: its points
// x, y and sizes h, and ct, the transform from lon/lat to Web Mercator.
constexpr const char* kSizesAndLonLatToWebMercator =
    "import sys, meshio, numpy as np\n"
    "from osgeo import osr\n"
    "m = meshio.read(sys.argv[1])\n"
    "x, y, h = m.points[:, 0], m.points[:, 1], m.point_data['size']\n"
    "src = osr.SpatialReference(); src.ImportFromEPSG(4326)\n"
    "dst = osr.SpatialReference(); dst.ImportFromEPSG(3857)\n"
    "for s in (src, dst): s.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)\n"
    "ct = osr.CoordinateTransformation(src, dst)\n";

// --refine: a square of lon/lat on the equator meshed in Web Mercator (so that the
// features' rectangle stays a rectangle) at 3 km, with a rectangle asking for 600 m and
// a point asking for 400 m. At every background vertex the size is at most each
// feature's size plus the gradation times the distance to it (0 inside the rectangle),
// equals 600 well inside the rectangle and 3 km far from both. A size attribute that is
// missing or not positive stops the run, naming it.
TEST(CliFields, RefineFeaturesSetTheSizesAroundThem) {
  TempDir dir;
  const std::string domain = dir.file("square.geojson");
  write_file(domain, geojson_polygons({"[[[0,0],[0.5,0],[0.5,0.5],[0,0.5],[0,0]]]"}));
  const std::string refine = dir.file("refine.geojson");
  write_file(
      refine,
      R"({"type":"FeatureCollection","features":[)"
      R"({"type":"Feature","properties":{"size":600},"geometry":{"type":"Polygon",)"
      R"("coordinates":[[[0.05,0.05],[0.15,0.05],[0.15,0.12],[0.05,0.12],[0.05,0.05]]]}},)"
      R"({"type":"Feature","properties":{"size":400},"geometry":{"type":"Point","coordinates":[0.4,0.3]}}]})");
  const std::string vtu = dir.file("f.vtu");
  CliResult r = run_cli(
      {"fields", domain, "--dst-crs", "EPSG:3857", "--size", "3000", "--refine", refine, "-o", vtu},
      dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("features " + refine + " (2, 400 to 600 m)"), std::string::npos) << r.err;
  python_check(
      dir,
      std::string(kSizesAndLonLatToWebMercator) +
          "x0, y0, _ = ct.TransformPoint(0.05, 0.05); x1, y1, _ = ct.TransformPoint(0.15, 0.12)\n"
          "px, py, _ = ct.TransformPoint(0.4, 0.3)\n"
          "d_rect = np.hypot(np.maximum.reduce([x0 - x, 0 * x, x - x1]), np.maximum.reduce([y0 - "
          "y, 0 "
          "* y, y - y1]))\n"
          "d_pt = np.hypot(x - px, y - py)\n"
          "bound = np.minimum.reduce([3000 + 0 * x, 600 + 0.2 * d_rect, 400 + 0.2 * d_pt])\n"
          "assert (h <= bound * (1 + 1e-9)).all(), (h - bound).max()\n"
          "inner = (x > x0 + 2000) & (x < x1 - 2000) & (y > y0 + 2000) & (y < y1 - 2000)\n"
          "assert inner.sum() > 20 and np.allclose(h[inner], 600), h[inner].max()\n"
          "far = (d_rect > 15000) & (d_pt > 15000)\n"
          "assert far.sum() > 20 and np.allclose(h[far], 3000)\n"
          "near = d_pt < 100\n"
          "assert near.sum() >= 1 and h[near].max() < 430, h[near]\n",
      {vtu});
  // Bad sizes.
  write_file(dir.file("bad.geojson"),
             R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"size":0},)"
             R"("geometry":{"type":"Point","coordinates":[0.1,0.1]}}]})");
  r = run_cli({"fields", domain, "--size", "3000", "--refine", dir.file("bad.geojson"), "-o", vtu,
               "--overwrite"},
              dir);
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.err.find("feature 0 has size '0'"), std::string::npos) << r.err;
  r = run_cli({"fields", domain, "--size", "3000", "--refine", refine, "--refine-field", "h", "-o",
               vtu, "--overwrite"},
              dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no attribute 'h' for the sizes (attributes: size)"), std::string::npos)
      << r.err;
}

// --refine-width-field: a point asking for 400 m within 5 km of it (a width of 10 km),
// growing by the gradation beyond; the option needs --refine.
TEST(CliFields, ARefineWidthHoldsTheSizeRoundTheFeature) {
  TempDir dir;
  const std::string domain = dir.file("square.geojson");
  write_file(domain, geojson_polygons({"[[[0,0],[0.5,0],[0.5,0.5],[0,0.5],[0,0]]]"}));
  const std::string refine = dir.file("refine.geojson");
  write_file(refine,
             R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":)"
             R"({"size":400,"w":10000},"geometry":{"type":"Point","coordinates":[0.25,0.25]}}]})");
  const std::string vtu = dir.file("f.vtu");
  CliResult r = run_cli({"fields", domain, "--dst-crs", "EPSG:3857", "--size", "3000", "--refine",
                         refine, "--refine-width-field", "w", "-o", vtu},
                        dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("features " + refine + " (1, 400 m, up to 10000 m wide)"), std::string::npos)
      << r.err;
  python_check(dir,
               std::string(kSizesAndLonLatToWebMercator) +
                   "px, py, _ = ct.TransformPoint(0.25, 0.25)\n"
                   "d = np.hypot(x - px, y - py)\n"
                   "bound = np.minimum(3000, 400 + 0.2 * np.maximum(d - 5000, 0))\n"
                   "assert (h <= bound * (1 + 1e-9)).all(), (h - bound).max()\n"
                   "band = d < 4900\n"
                   "assert band.sum() > 100 and np.allclose(h[band], 400), h[band].max()\n"
                   "ring = (d > 6000) & (d < 9000)\n"
                   "assert ring.sum() > 20 and (h[ring] > 400).all()\n",
               {vtu});
  r = run_cli(
      {"fields", domain, "--size", "3000", "--refine-width-field", "w", "-o", vtu, "--overwrite"},
      dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--refine-width-field needs --refine"), std::string::npos) << r.err;
}
