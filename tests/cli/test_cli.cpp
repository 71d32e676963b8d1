// The isoquad binary as a user meets it: exit codes, one-line messages naming the file
// and the problem, and no output file after any failure.
#include <gtest/gtest.h>

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <tuple>

#include "gis/gdal_env.h"
#include "support/fixtures.h"

using namespace isoquad::test;

namespace {

struct BadCase {
  std::string name;
  std::string input;              // path of the bad input
  std::vector<std::string> extra;  // further arguments
  int exit_code;
  std::string problem;  // words the message must contain
};

void expect_clean_failure(const BadCase& c, const TempDir& dir) {
  const std::string out = dir.file("out.gpkg");
  std::vector<std::string> args{"domain", c.input, "-o", out};
  args.insert(args.end(), c.extra.begin(), c.extra.end());
  const auto before = dir.entries();
  const CliResult r = run_cli(args, dir);
  EXPECT_EQ(r.exit_code, c.exit_code) << c.name << ": " << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << c.name << ": " << r.err;
  EXPECT_EQ(r.err.rfind("isoquad: ", 0), 0u) << c.name << ": " << r.err;
  EXPECT_NE(r.err.find(c.input), std::string::npos) << c.name << ": " << r.err;
  EXPECT_NE(r.err.find(c.problem), std::string::npos) << c.name << ": " << r.err;
  EXPECT_FALSE(std::filesystem::exists(out)) << c.name;
  EXPECT_EQ(dir.entries(), before) << c.name << ": files left behind";
}

// The domain layer of a GeoPackage `isoquad domain` wrote: its features' area_m2 summed
// (-1 when it cannot be read), and whether every geometry is valid.
struct DomainLayer {
  double area_m2 = -1;
  bool valid = true;
};

DomainLayer read_domain_layer(const std::string& gpkg) {
  isoquad::ensure_gdal_registered();
  DomainLayer out;
  GDALDataset* ds = static_cast<GDALDataset*>(
      GDALOpenEx(gpkg.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr));
  if (!ds) return out;
  if (OGRLayer* layer = ds->GetLayerByName("domain")) {
    out.area_m2 = 0;
    for (auto& f : *layer) {
      out.valid = out.valid && f->GetGeometryRef() && f->GetGeometryRef()->IsValid();
      out.area_m2 += f->GetFieldAsDouble("area_m2");
    }
  }
  GDALClose(ds);
  return out;
}

}  // namespace

TEST(Cli, BadInputsFailCleanly) {
  TempDir dir;
  // Coordinates in degrees without a CRS: the message suggests EPSG:4326 (and only then).
  const std::string lonlat_csv = dir.file("lonlat.csv");
  write_file(lonlat_csv, "WKT,id\n\"POLYGON ((2 47,2.5 47,2.5 47.5,2 47.5,2 47))\",1\n");
  const std::vector<BadCase> cases = {
      {"missing file", dir.file("missing.shp"), {}, 3, "no such file"},
      {"corrupt file", corrupt_shapefile(dir), {}, 3, "cannot read"},
      {"empty file", empty_file(dir), {}, 3, "empty"},
      {"no polygons", points_geojson(dir), {}, 3, "has no polygons"},
      {"empty selection",
       good_geojson(dir),
       {"--where", "name = 'atlantis'"},
       3,
       "matched no feature"},
      {"no CRS",
       no_crs_csv(dir),
       {},
       4,
       "has no CRS; give the CRS of the coordinates with --src-crs\n"},
      {"no CRS, degrees", lonlat_csv, {}, 4, "(they lie within longitudes' and latitudes' range"},
      {"self-intersection", bowtie_geojson(dir), {}, 3, "Self-intersection"},
      {"unclosed ring", unclosed_geojson(dir), {}, 3, "not closed"},
      {"NaN", non_finite_geojson(dir), {}, 3, "not finite"},
      {"infinity", non_finite_geojson(dir, true), {}, 3, "not finite"},
      {"latitude 120", out_of_range_geojson(dir), {}, 4, "outside the valid range"},
      {"wrong CRS", wrong_crs_geojson(dir), {}, 4, "area of use"},
      {"bbox misses", good_geojson(dir), {"--bbox", "100,10,101,11"}, 3, "misses the data"},
      {"water covered",
       good_geojson(dir),
       {"--domain", "water", "--bbox", "-2.9,47.1,-2.1,47.9"},
       3,
       "empty"},
  };
  for (const BadCase& c : cases) expect_clean_failure(c, dir);
}

TEST(Cli, ExistingOutputIsNeverReplacedWithoutOverwrite) {
  TempDir dir;
  const std::string input = good_geojson(dir);
  const std::string out = dir.file("out.gpkg");
  write_file(out, "precious");
  CliResult r = run_cli({"domain", input, "-o", out}, dir);
  EXPECT_EQ(r.exit_code, 6) << r.err;
  EXPECT_NE(r.err.find(out), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("already exists"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(out), "precious");
  r = run_cli({"domain", input, "-o", out, "--overwrite", "-q"}, dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(read_file(out), "precious");
  EXPECT_EQ(r.out, "");
}

// No output replaces a file the run reads, even with --overwrite: INPUT as -o or
// --report fails before any work, a file read later (--exclude) when the outputs are
// moved into place; either way nothing is written and the input is as it was.
TEST(Cli, AnOutputNeverReplacesAnInput) {
  TempDir dir;
  const std::string input = good_geojson(dir);
  const std::string original = read_file(input);
  const std::string exclude = dir.file("exclude.geojson");
  write_file(exclude,
             R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},)"
             R"("geometry":{"type":"Polygon","coordinates":[[[-2.6,47.4],[-2.5,47.4],)"
             R"([-2.5,47.5],[-2.6,47.5],[-2.6,47.4]]]}}]})");
  const std::string exclude_text = read_file(exclude);
  const std::string out = dir.file("out.gpkg");
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"domain", input, "-o", input, "--overwrite"},
           {"domain", input, "-o", out, "--report", dir.path() + "/./good.geojson", "--overwrite"},
           {"domain", input, "-o", out, "--exclude", exclude, "--report", exclude,
            "--overwrite"}}) {
    const CliResult r = run_cli(args, dir);
    EXPECT_EQ(r.exit_code, 6) << r.err;
    EXPECT_NE(r.err.find("is an input of this run"), std::string::npos) << r.err;
    EXPECT_EQ(read_file(input), original);
    EXPECT_EQ(read_file(exclude), exclude_text);
    EXPECT_FALSE(std::filesystem::exists(out));
  }
}

TEST(Cli, UsageErrorsExitWithTwo) {
  TempDir dir;
  const std::string input = good_geojson(dir);
  const std::string out = dir.file("out.gpkg");
  for (const auto& args :
       std::vector<std::vector<std::string>>{{"domain", input, "-o", out, "--no-such-option"},
                                             {"domain", input, "-o", out, "--bbox", "1,2,3"},
                                             {"domain", input, "-o", out, "--bbox", "1,2,x,4"},
                                             {"domain", input, "-o", out, "--bbox", "1,2,3,4,x"},
                                             {"domain", input, "-o", out, "--domain", "ocean"},
                                             {"domain", input, "-o", out, "--simplify", "-5"},
                                             {"domain", input, "-o", dir.file("out.shp")},
                                             {"domain", input},
                                             {}}) {
    const CliResult r = run_cli(args, dir);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("isoquad: "), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
  // Numbers out of range or not numbers: one short line naming the option and the value.
  for (const auto& [option, value, message] : std::vector<std::array<std::string, 3>>{
           {"--hmax", "0", "--hmax: must be more than 0, not 0"},
           {"--hmax", "abc", "--hmax: 'abc' is not a number"},
           {"--hmax", "5000x", "--hmax: '5000x' is not a number"},
           {"--max-quads", "-1", "--max-quads: must be 0 or more, not -1"},
           // Range checks let NaN through, and a constant field of inf degrees hung the
           // tiling: every number option takes finite decimal numbers only.
           {"--cross-conformal", "nan", "--cross-conformal: 'nan' is not a number"},
           {"--cross-angle", "nan", "--cross-angle: 'nan' is not a number"},
           {"--hmin", "inf", "--hmin: 'inf' is not a number"},
           {"--cross-angle", "1e308", "--cross-angle: Value 1e308 not in range"},
           {"--corner-angle", "-nan", "--corner-angle: '-nan' is not a number"},
           {"--hmax", "0x4e20", "--hmax: '0x4e20' is not a number"},
           {"--cells-across", "4.9e-324", "--cells-across: '4.9e-324' is too small a number"},
           // A length whose square overflows said "inf km2" of --min-island-area.
           {"--hmax", "1e308",
            "--hmax: 1e308 m is longer than 100,000 km, more than twice round the Earth"},
           {"--simplify", "2e8", "--simplify: 2e8 m is longer than 100,000 km"},
           // An empty value (an unset shell variable) is not the option left out.
           {"--open-boundary", "",
            "--open-boundary: an empty value (give one, or leave the "
            "option out)"},
           {"--where", "", "--where: an empty value"},
           {"--report", "", "--report: an empty value"}}) {
    const CliResult r = run_cli({"mesh", input, "-o", out, option, value}, dir);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("isoquad: usage: " + message), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(" (isoquad mesh --help lists the options)\n"), std::string::npos) << r.err;
    EXPECT_LT(r.err.size(), 200u) << r.err;
  }
}

// A misspelt option: the nearest the subcommand has.
TEST(Cli, AMisspeltOptionGetsTheNearestName) {
  TempDir dir;
  const std::string input = good_geojson(dir);
  CliResult r = run_cli({"mesh", input, "--domian", "water", "-o", dir.file("m.gpkg")}, dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err,
            "isoquad: usage: unknown option --domian; did you mean --domain? (isoquad mesh --help "
            "lists the options)\n");
  // An option given twice, a value of the wrong kind: said in the project's words.
  r = run_cli({"mesh", input, "--hmax", "4000", "--hmax", "5000", "-o", dir.file("m.gpkg")}, dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("usage: --hmax is given 2 times; give it once"), std::string::npos) << r.err;
  r = run_cli({"mesh", input, "--jobs", "1.5", "-o", dir.file("m.gpkg")}, dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("usage: --jobs: '1.5' is not a whole number"), std::string::npos) << r.err;
  r = run_cli({"mesh", input, "--hmax", "abc", "-o", dir.file("m.gpkg")}, dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("usage: --hmax: 'abc' is not a number"), std::string::npos) << r.err;
  r = run_cli({"domain", input, "--hmax=5", "-o", dir.file("d.gpkg")}, dir);  // mesh's only
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("usage: --hmax is an option of fields, mesh, quality, not of domain"),
            std::string::npos)
      << r.err;
}

// Outputs that would not be what they are named, options that contradict each other:
// refused before any work, nothing written.
TEST(Cli, ContradictoryOutputsAndSizesAreRefusedBeforeMeshing) {
  TempDir dir;
  const std::string input = good_geojson(dir);
  std::filesystem::create_directory(dir.file("folder.gpkg"));
  for (const auto& [args, code, message] :
       std::vector<std::tuple<std::vector<std::string>, int, std::string>>{
           {{"-o", dir.file("m.gpkg"), "--output-format", "gr3"},
            2,
            "--output-format gr3 under a name of format .gpkg; name it .gr3"},
           {{"-o", "-"}, 2, "-o -: the mesh outputs are files"},
           {{"-o", dir.file("m.gpkg"), "--plot", dir.file("m.pdf")}, 2, "the plot is a PNG image"},
           {{"-o", dir.file("m.gpkg"), "--size", "3000", "--hmin", "5000"},
            2,
            "--size 3000 is under --hmin 5000"},
           {{"-o", dir.file("m.gpkg"), "--size", "3000", "--hmax", "2000"},
            2,
            "--size 3000 is over --hmax 2000"},
           {{"-o", dir.file("folder.gpkg")}, 6, "folder.gpkg' is a directory"},
           {{"-o", dir.file("folder.gpkg"), "--overwrite"}, 6, "folder.gpkg' is a directory"},
           // Geocentric X, Y, Z in a file of two coordinates (it wrote X and Y).
           {{"-o", dir.file("m.gpkg"), "--output-crs", "EPSG:4978"},
            4,
            "--output-crs 'EPSG:4978' (WGS 84) is neither geographic nor projected"}}) {
    std::vector<std::string> all{"mesh", input};
    all.insert(all.end(), args.begin(), args.end());
    const CliResult r = run_cli(all, dir);
    EXPECT_EQ(r.exit_code, code) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("m.gpkg")));
    EXPECT_FALSE(std::filesystem::exists(dir.file("m.pdf")));
    EXPECT_FALSE(std::filesystem::exists(dir.file("-")));
  }
}

TEST(Cli, HelpListsExitCodes) {
  TempDir dir;
  CliResult r = run_cli({"--help"}, dir);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("Exit codes"), std::string::npos);
  r = run_cli({"domain", "--help"}, dir);
  EXPECT_EQ(r.exit_code, 0);
  for (const char* opt : {"--bbox", "--where", "--layer", "--dst-crs", "--src-crs", "--simplify",
                          "--min-island-area", "--repair", "--overwrite", "--quiet", "--largest"})
    EXPECT_NE(r.out.find(opt), std::string::npos) << opt;
}

TEST(Cli, VersionNamesTheLibrariesThatDecideTheOutput) {
  // The libraries as the process loads them: GDAL's and GEOS's versions as this test
  // process sees them (the same shared libraries).
  TempDir dir;
  const CliResult r = run_cli({"--version"}, dir);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out.rfind("isoquad " ISOQUAD_VERSION "\nlibraries: CGAL ", 0), 0u) << r.out;
  EXPECT_NE(r.out.find(std::string("GDAL ") + GDALVersionInfo("RELEASE_NAME") + ","),
            std::string::npos)
      << r.out;
  for (const char* name :
       {"Eigen 3.", "GEOS 3.", "PROJ 9.", "GeographicLib 2.", "netCDF 4.", "SLEEF 3."})
    EXPECT_NE(r.out.find(std::string(", ") + name), std::string::npos) << name << ": " << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 2) << r.out;
}

TEST(Cli, DomainWritesAGeoPackageInTheMeshingCrs) {
  TempDir dir;
  const std::string out = dir.file("france.gpkg");
  const CliResult r =
      run_cli({"domain", sample("france.shp"), "-o", out, "--simplify", "1000"}, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // France's 3,094 points, and one where an edge's image strays from its chord by over
  // 1e-5 of the domain's diagonal (follow_curved_edges).
  EXPECT_NE(r.err.find("vertices:     3095 before simplification"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("automatic"), std::string::npos) << r.err;
  isoquad::ensure_gdal_registered();
  GDALDataset* ds = static_cast<GDALDataset*>(
      GDALOpenEx(out.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr));
  ASSERT_NE(ds, nullptr);
  OGRLayer* layer = ds->GetLayerByName("domain");
  ASSERT_NE(layer, nullptr);
  EXPECT_EQ(layer->GetFeatureCount(), 1);
  ASSERT_NE(layer->GetSpatialRef(), nullptr);
  EXPECT_TRUE(layer->GetSpatialRef()->IsProjected());
  auto f = std::unique_ptr<OGRFeature>(layer->GetNextFeature());
  const OGRPolygon* poly = f->GetGeometryRef()->toPolygon();
  EXPECT_EQ(poly->getNumInteriorRings(), 1);
  EXPECT_NEAR(poly->get_Area() / 538e9, 1.0, 0.01);
  EXPECT_NEAR(f->GetFieldAsDouble("area_m2"), poly->get_Area(), 1e-6 * poly->get_Area());
  GDALClose(ds);
}

// A D-Flow FM .pol of land and a lake, and its open boundary as a .pli, both without a
// CRS: --src-crs gives it to both; the summary says what the lines made.
TEST(Cli, AModelsLineFilesMeshWithTheirOpenBoundary) {
  TempDir dir;
  write_file(dir.file("bay.pol"),
             "* land with a lake, metres in UTM 30N\nbay\n 4 2\n500000 5000000\n540000 5000000\n"
             "540000 5030000\n500000 5030000\nlake\n 5 2\n510000 5010000\n510000 5020000\n"
             "520000 5020000\n520000 5010000\n510000 5010000\n");
  write_file(dir.file("sea.pli"), "sea\n 2 2\n540000 5000000\n540000 5030000\n");
  const CliResult r = run_cli({"mesh", dir.file("bay.pol"), "--src-crs", "EPSG:32630",
                               "--open-boundary", dir.file("sea.pli"), "--size", "2000", "-o",
                               dir.file("bay.gr3"), "--report", dir.file("bay.json")},
                              dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("lines:        2 feature(s) of lines made 2 ring(s), 1 polygon(s)"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("domain:       1 component(s), 2 ring(s), 1 hole(s)"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("open lines:   " + dir.file("sea.pli") + ": 1 line(s)"), std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("boundary:     0 open edges"), std::string::npos) << r.err;
  EXPECT_NE(read_file(dir.file("bay.json")).find("\"num_rings_from_lines\": 2"), std::string::npos);
}

// A mesh given as INPUT (an ocean model's hgrid.gr3, an SMS .2dm): its outline is the
// domain, and a .gr3's open boundaries stay open in the new mesh.
TEST(Cli, AMeshFileIsMeshedAgainWithinItsOutline) {
  TempDir dir;
  write_file(dir.file("bay.pol"),
             "bay\n 4 2\n500000 5000000\n540000 5000000\n540000 5030000\n500000 5030000\n"
             "lake\n 4 2\n510000 5010000\n510000 5020000\n520000 5020000\n520000 5010000\n");
  write_file(dir.file("sea.pli"), "sea\n 2 2\n540000 5000000\n540000 5030000\n");
  const std::vector<std::string> utm = {"--src-crs", "EPSG:32630", "--dst-crs", "EPSG:32630"};
  std::vector<std::string> args = {"mesh",
                                   dir.file("bay.pol"),
                                   "--open-boundary",
                                   dir.file("sea.pli"),
                                   "--size",
                                   "2000",
                                   "-o",
                                   dir.file("bay.gr3"),
                                   "-o",
                                   dir.file("bay.2dm")};
  args.insert(args.end(), utm.begin(), utm.end());
  CliResult r = run_cli(args, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;

  args = {"mesh", dir.file("bay.gr3"), "--size", "3000", "-o", dir.file("again.gr3")};
  args.insert(args.end(), utm.begin(), utm.end());
  r = run_cli(args, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("(layer 'its outline', 2 feature(s), 1 polygon(s), CRS WGS 84 / UTM zone "
                       "30N)"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("domain:       1 component(s), 2 ring(s), 1 hole(s)"), std::string::npos)
      << r.err;
  EXPECT_NE(
      r.err.find("open lines:   " + dir.file("bay.gr3") + " (its open boundaries): 1 line(s)"),
      std::string::npos)
      << r.err;
  // The 30 km of open sea in edges of about 3 km.
  const std::size_t at = r.err.find("boundary:     ");
  ASSERT_NE(at, std::string::npos) << r.err;
  const int open_edges = std::stoi(r.err.substr(at + 14));
  EXPECT_GE(open_edges, 8) << r.err;
  EXPECT_LE(open_edges, 13) << r.err;
  EXPECT_NE(read_file(dir.file("again.gr3")).find("1 = Number of open boundaries"),
            std::string::npos);

  // Without --dst-crs the grid is meshed in its own CRS, where a depth source without
  // one (the .gr3 itself, depths (x - 500 km) / 1000 written in) is read.
  {
    std::istringstream in(read_file(dir.file("bay.gr3")));
    std::string line, text;
    std::getline(in, line);
    text += line + "\n";
    std::getline(in, line);
    text += line + "\n";
    std::size_t ne = 0, np = 0;
    std::istringstream(line) >> ne >> np;
    for (std::size_t i = 0; i < np && std::getline(in, line); ++i) {
      long id;
      double x, y;
      std::istringstream(line) >> id >> x >> y;
      text += std::to_string(id) + " " + std::to_string(x) + " " + std::to_string(y) + " " +
              std::to_string((x - 500000) / 1000) + "\n";
    }
    while (std::getline(in, line)) text += line + "\n";
    write_file(dir.file("deep.gr3"), text);
  }
  r = run_cli({"mesh", dir.file("deep.gr3"), "--src-crs", "EPSG:32630", "--bathymetry",
               dir.file("deep.gr3"), "--size", "3000", "-o", dir.file("deep_again.gr3")},
              dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("meshing CRS:  WGS 84 / UTM zone 30N\n"), std::string::npos) << r.err;
  {
    std::istringstream in(read_file(dir.file("deep_again.gr3")));
    std::string line;
    std::getline(in, line);
    std::size_t ne = 0, np = 0;
    in >> ne >> np;
    ASSERT_GT(np, 50u);
    for (std::size_t i = 0; i < np; ++i) {
      long id;
      double x, y, depth;
      in >> id >> x >> y >> depth;
      EXPECT_NEAR(depth, (x - 500000) / 1000, 0.01) << id;
    }
  }

  // --size-mesh: the old grid's resolution (2 km) again, in about as many quads.
  r = run_cli({"mesh", dir.file("bay.gr3"), "--src-crs", "EPSG:32630", "--size-mesh",
               dir.file("bay.gr3"), "-o", dir.file("same.gr3"), "--report", dir.file("same.json")},
              dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("sizing:       mesh " + dir.file("bay.gr3") + " (its elements' sides)"),
            std::string::npos)
      << r.err;
  {
    std::istringstream gr3(read_file(dir.file("bay.gr3")));
    std::string title;
    std::getline(gr3, title);
    double old_quads = 0;
    gr3 >> old_quads;
    ASSERT_GT(old_quads, 100);
    const double quads = report_number(read_file(dir.file("same.json")), "num_quads");
    EXPECT_GT(quads, 0.8 * old_quads);
    EXPECT_LT(quads, 1.25 * old_quads);
  }

  // An SMS .2dm's outline as a domain: 40 x 30 km less the 10 x 10 km lake.
  r = run_cli({"domain", dir.file("bay.2dm"), "--src-crs", "EPSG:32630", "--dst-crs", "EPSG:32630",
               "-o", dir.file("d.gpkg"), "--report", dir.file("d.json")},
              dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NEAR(report_number(read_file(dir.file("d.json")), "area_m2"), 1.1e9, 1e3);

  // isoquad's .gr3 names its CRS in its title line: meshed again without --src-crs.
  r = run_cli({"mesh", dir.file("bay.gr3"), "--size", "3000", "-o", dir.file("named.gr3")}, dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("CRS WGS 84 / UTM zone 30N)"), std::string::npos) << r.err;
  // Another mesher's does not (the same grid, its title line without the CRS).
  std::string other = read_file(dir.file("bay.gr3"));
  other.replace(0, other.find('\n'), "bay, from another mesher");
  write_file(dir.file("other.gr3"), other);
  write_file(dir.file("other.ll"), read_file(dir.file("bay.ll")));
  r = run_cli({"mesh", dir.file("other.gr3"), "--size", "3000", "-o", dir.file("x.gr3")}, dir);
  EXPECT_EQ(r.exit_code, 4);
  EXPECT_NE(r.err.find("does not say its CRS: its outline is the domain, so give the CRS of its "
                       "coordinates with --src-crs"),
            std::string::npos)
      << r.err;
  // The .ll beside it (written with it) has one.
  EXPECT_NE(r.err.find("or give '" + dir.file("other.ll") + "' instead"), std::string::npos)
      << r.err;
  r = run_cli({"mesh", dir.file("bay.gr3"), "--src-crs", "EPSG:32630", "--where", "id = 1",
               "--size", "3000", "-o", dir.file("x.gr3")},
              dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("is a mesh, whose outline is the domain: --where selects"),
            std::string::npos)
      << r.err;
  r = run_cli({"mesh", dir.file("bay.gr3"), "--src-crs", "EPSG:32630", "--each", "name", "--size",
               "3000", "-o", dir.file("{}.gr3")},
              dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("is a mesh, whose outline is the domain: --each selects"), std::string::npos)
      << r.err;
}

TEST(Cli, WaterDomainAndRepairFromTheCommandLine) {
  TempDir dir;
  CliResult r = run_cli({"domain", sample("brittany_land.geojson"), "-o", dir.file("sea.gpkg"),
                         "--domain", "water", "--bbox", "-5.3,46.8,-1.95,49.35", "--size", "2000"},
                        dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("1 component(s), 5 ring(s), 4 hole(s)"), std::string::npos) << r.err;
  r = run_cli({"domain", bowtie_geojson(dir), "-o", dir.file("fixed.gpkg"), "--repair"}, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("1 invalid polygon(s) fixed"), std::string::npos) << r.err;
}

// --repair of rings that do not nest: a 10 km square whose 4 km "shell" lies inside its
// "hole" (rings wound the other way) is the annulus between them, not nothing; a hole
// drawn outside its shell is land of its own. Both said.
TEST(Cli, RepairKeepsWhatTheRingsEncloseAndSaysSo) {
  TempDir dir;
  const std::string big =
      "[500000,5000000],[510000,5000000],[510000,5010000],[500000,5010000],"
      "[500000,5000000]";
  const std::string small =
      "[503000,5003000],[507000,5003000],[507000,5007000],"
      "[503000,5007000],[503000,5003000]";
  const std::string apart =
      "[520000,5000000],[524000,5000000],[524000,5004000],"
      "[520000,5004000],[520000,5000000]";
  write_file(dir.file("inside_out.geojson"),
             geojson_polygons({"[[" + small + "],[" + big + "]]"}, kUtm31nCrsMember));
  CliResult r = run_cli({"domain", dir.file("inside_out.geojson"), "-o", dir.file("a.gpkg"),
                         "--repair", "--size", "1000"},
                        dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("area:         84 km2"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("feature 0: its rings do not nest as shell and holes"), std::string::npos)
      << r.err;
  write_file(dir.file("hole_apart.geojson"),
             geojson_polygons({"[[" + big + "],[" + apart + "]]"}, kUtm31nCrsMember));
  r = run_cli({"domain", dir.file("hole_apart.geojson"), "-o", dir.file("b.gpkg"), "--repair",
               "--size", "1000"},
              dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("area:         116 km2"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("feature 0: a hole lies outside its shell, at or near ("), std::string::npos)
      << r.err;
}

// A layer of polygons with a point and a closed line among them: those are ignored, and
// the summary says so.
TEST(Cli, PointsAndLinesAmongPolygonsAreIgnoredAndSaid) {
  TempDir dir;
  std::string json = geojson_polygons({"[[[500000,5000000],[510000,5000000],[510000,5010000],"
                                       "[500000,5010000],[500000,5000000]]]"},
                                      kUtm31nCrsMember);
  json.insert(json.size() - 2,
              R"(,{"type":"Feature","properties":{},"geometry":{"type":"Point",)"
              R"("coordinates":[520000,5000000]}},{"type":"Feature","properties":{},)"
              R"("geometry":{"type":"LineString","coordinates":[[520000,5000000],)"
              R"([530000,5000000],[530000,5010000],[520000,5000000]]}})");
  write_file(dir.file("mixed.geojson"), json);
  const CliResult r = run_cli({"domain", dir.file("mixed.geojson"), "-o", dir.file("d.gpkg")}, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: 2 feature(s) of points or lines in layer 'mixed' ignored"),
            std::string::npos)
      << r.err;
}

// Two squares that should share a side but miss by a tenth of a millimetre at one corner:
// their union has a slit 10 km long whose sides touch where cuts cannot part them (the
// run stopped: "rings still touch after cutting them apart"). The slit is closed.
TEST(Cli, PolygonsThatMissByAHairAreJoined) {
  TempDir dir;
  write_file(dir.file("two.geojson"),
             geojson_polygons({"[[[500000,5000000],[510000,5000000],[510000,5010000],"
                               "[500000,5010000],[500000,5000000]]]",
                               "[[[510000.0001,5000000],[520000,5000000],[520000,5010000],"
                               "[510000,5010000],[510000.0001,5000000]]]"},
                              kUtm31nCrsMember));
  const CliResult r = run_cli({"domain", dir.file("two.geojson"), "-o", dir.file("d.gpkg")}, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("domain:       1 component(s), 1 ring(s), 0 hole(s)"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("where rings touched (polygons that miss each other by a hair) were "
                       "closed"),
            std::string::npos)
      << r.err;
}

// The Arctic Ocean's side of Europe and Asia from Natural Earth's land at 1:110m (the
// seven parts of `world-atlas` land-110m.json that reach 64 N between 1 W and 91 E): with
// no simplification, cutting the rings apart where they touched left two of the pieces,
// slivers between the coast and the bbox edge at 66 N, touching at a point, and the
// domain command stopped ("rings still touch after cutting them apart"); those were cut
// apart in turn. Since the coast's edges follow their images once projected (as the
// bbox's always did), the slivers between their chords and the bbox edge are gone, and
// the two boundaries that met there are merged instead.
TEST(Cli, TheArcticWaterOfEuropeAndAsiaAt110mIsOneValidDomain) {
  TempDir dir;
  const std::string out = dir.file("arctic.gpkg");
  const CliResult r = run_cli({"domain", source_dir() + "/tests/data/arctic_110m.geojson", "-o", out,
                               "--bbox", "0,66,90,90", "--domain", "water", "--repair"},
                              dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("boundaries that coincide once projected were merged"), std::string::npos)
      << r.err;
  const DomainLayer d = read_domain_layer(out);
  EXPECT_TRUE(d.valid);
  // The sea north of 66 N between 0 and 90 E (the Barents and Kara seas, the White Sea,
  // part of the Norwegian and Greenland seas): 3.95 million km2.
  EXPECT_NEAR(d.area_m2 / 3.95e12, 1.0, 0.02);
}

TEST(Cli, ASharpTipIsCutBackToTheMinimumWidth) {
  // A square 1 km wide with a spike 600 m long and 40 m wide at its base (a tip of 3.8
  // degrees), in metres, cleaned as the mesh command does (simplification and minimum
  // width equal): the opening bevels the tip where it is 10 m wide, the simplification
  // that follows (10 m) takes the bevel's two corners back to a sharp tip, and the tip is
  // cut at last, less than the 750 m2 triangle the spike's last 150 m make. With
  // --min-width 0 nothing is cut.
  TempDir dir;
  const std::string input = dir.file("spike.geojson");
  write_file(input, geojson_polygons({"[[[0,0],[1000,0],[1000,480],[1600,500],[1000,520],"
                                      "[1000,1000],[0,1000],[0,0]]]"}));
  auto run = [&](const std::string& width) {
    const CliResult r = run_cli({"domain", input, "--src-crs", "EPSG:3857", "--dst-crs", "EPSG:3857",
                                 "--simplify", "10", "--min-width", width, "-o", dir.file("d.gpkg"),
                                 "--overwrite", "--report", dir.file("r.json")},
                                dir);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return std::make_pair(r.err, read_file(dir.file("r.json")));
  };
  const auto [out, report] = run("10");
  EXPECT_NE(out.find("spikes:       1 tip(s) sharper than 15 deg cut back to 10 m wide"),
            std::string::npos) << out;
  EXPECT_NE(report.find("\"spikes_num_cut\": 1"), std::string::npos) << report;
  const std::size_t at = report.find("\"spikes_area_removed_m2\": ");
  ASSERT_NE(at, std::string::npos) << report;
  const double removed = std::stod(report.substr(at + 26));
  EXPECT_GT(removed, 100.0);
  EXPECT_LT(removed, 750.0);
  const auto [out_off, report_off] = run("0");
  EXPECT_EQ(out_off.find("spikes:"), std::string::npos) << out_off;
  EXPECT_NE(report_off.find("\"spikes_num_cut\": 0"), std::string::npos) << report_off;
}

TEST(Cli, WaterOfOpenSeaIsTheWholeBbox) {
  // Off Brittany, no land in the bbox: the water domain is the bbox (with a warning);
  // the land domain there is still an error, and so is a --where matching nothing.
  TempDir dir;
  const std::string out = dir.file("sea.gpkg");
  CliResult r = run_cli({"domain", sample("brittany_land.geojson"), "-o", out, "--domain", "water",
                         "--bbox", "-5.3,46.9,-4.7,47.3", "--size", "2000"},
                        dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("the water domain is the whole bbox"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("1 component(s), 1 ring(s), 0 hole(s)"), std::string::npos) << r.err;
  // 0.6 by 0.4 degrees at 47.1 N: about 45.5 by 44.5 km.
  EXPECT_NEAR(read_domain_layer(out).area_m2 / 2.0255e9, 1.0, 0.01);
  r = run_cli({"domain", sample("brittany_land.geojson"), "-o", dir.file("land.gpkg"), "--domain",
               "land", "--bbox", "-5.3,46.9,-4.7,47.3"},
              dir);
  EXPECT_EQ(r.exit_code, 3) << r.err;
  r = run_cli({"domain", sample("brittany_land.geojson"), "-o", dir.file("where.gpkg"), "--domain",
               "water", "--bbox", "-5.3,46.9,-4.7,47.3", "--where", "name = 'nothing'"},
              dir);
  EXPECT_EQ(r.exit_code, 3) << r.err;
}

TEST(Cli, ALandmassRoundThePoleIsMeshableLand) {
  // As world-atlas's Antarctica at 1:50m: a coast round the south pole at 70 S (a bay of
  // 10 by 5 degrees), drawn from -180 to 179 and closed by the short edge across the
  // antimeridian, with a ring round the pole itself at 89.999 S as a hole. Closed through
  // the pole, it projects (centred on the pole) to one ring that goes down the 180th
  // meridian to the pole and back, a spike removed; with simplification the domain
  // command stopped with the rings still touching there.
  TempDir dir;
  std::string coast = "[";
  for (int lon = -180; lon < 0; lon += 10) coast += "[" + std::to_string(lon) + ",-70],";
  coast += "[0,-70],[0,-75],[10,-75],[10,-70],";
  for (int lon = 20; lon <= 170; lon += 10) coast += "[" + std::to_string(lon) + ",-70],";
  coast += "[179,-70],[-180,-70]]";
  std::string pole = "[";
  for (int lon = 150; lon >= -180; lon -= 30) pole += "[" + std::to_string(lon) + ",-89.999],";
  pole += "[150,-89.999]]";
  const std::string input = dir.file("antarctica.geojson");
  write_file(input, geojson_polygons({"[" + coast + "," + pole + "]"}));
  const std::string out = dir.file("antarctica.gpkg");
  // --repair: the ring round the pole, straight in lon/lat, is degenerate (dropped).
  const CliResult r = run_cli({"domain", input, "-o", out, "--bbox", "-180,-90,180,-60",
                               "--simplify", "1000", "--repair"},
                              dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("+lat_0=-90"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("1 component(s), 1 ring(s), 0 hole(s)"), std::string::npos) << r.err;
  // South of 70 S less the bay, on a sphere of the authalic radius: 15.06 million km2.
  const double R = 6371007.2, deg = M_PI / 180.0;
  const double expected = 2 * M_PI * R * R * (1 - std::sin(70 * deg)) -
                          R * R * 10 * deg * (std::sin(75 * deg) - std::sin(70 * deg));
  EXPECT_NEAR(read_domain_layer(out).area_m2 / expected, 1.0, 0.01);
  // A bbox near the pole, which the coast as drawn (70 S) does not reach: all land (OGR's
  // own filter, testing the polygon as drawn, used to drop it: no feature matched).
  const std::string near_pole = dir.file("near_pole.gpkg");
  const CliResult p = run_cli({"domain", input, "-o", near_pole, "--bbox", "-40,-90,-10,-80",
                               "--repair"},
                              dir);
  ASSERT_EQ(p.exit_code, 0) << p.err;
  const double box = R * R * 30 * deg * (1 - std::sin(80 * deg));
  EXPECT_NEAR(read_domain_layer(near_pole).area_m2 / box, 1.0, 0.01);
}

TEST(Cli, SameInputGivesByteIdenticalOutput) {
  TempDir dir;
  for (const char* name : {"a.gpkg", "b.gpkg"}) {
    const CliResult r =
        run_cli({"domain", sample("france.shp"), "-o", dir.file(name), "--simplify", "500"}, dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  EXPECT_EQ(read_file(dir.file("a.gpkg")), read_file(dir.file("b.gpkg")));
}

// An island across the antimeridian, drawn as two parts split at 180 degrees (as
// Natural Earth draws Fiji's, with a vertex of its boundary on 180 degrees): its domain
// as GeoJSON is cut at 180 degrees again (RFC 7946), each part within a degree of
// longitude, not a band round the globe.
TEST(Cli, DomainAcrossTheAntimeridianAsGeoJson) {
  TempDir dir;
  const std::string island = dir.file("island.geojson");
  write_file(island,
             R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},)"
             R"("geometry":{"type":"MultiPolygon","coordinates":[)"
             R"([[[179.9,-17],[180,-16.96],[180,-16.78],[179.93,-16.88],[179.9,-17]]],)"
             R"([[[-180,-16.96],[-179.97,-16.93],[-179.87,-16.85],[-179.86,-16.69],[-180,-16.78],)"
             R"([-180,-16.96]]]]}}]})");
  const CliResult r =
      run_cli({"domain", island, "-o", dir.file("d.geojson"), "--size", "500", "-q"}, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  isoquad::ensure_gdal_registered();
  GDALDataset* ds = static_cast<GDALDataset*>(
      GDALOpenEx(dir.file("d.geojson").c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr));
  ASSERT_NE(ds, nullptr);
  OGRLayer* layer = ds->GetLayer(0);
  ASSERT_EQ(layer->GetFeatureCount(), 1);  // one component
  for (auto& f : *layer) {
    const OGRGeometry* g = f->GetGeometryRef();
    ASSERT_EQ(wkbFlatten(g->getGeometryType()), wkbMultiPolygon) << g->exportToWkt();
    const OGRMultiPolygon* parts = g->toMultiPolygon();
    ASSERT_EQ(parts->getNumGeometries(), 2);
    for (const OGRPolygon* part : *parts) {
      OGREnvelope e;
      part->getEnvelope(&e);
      EXPECT_LT(e.MaxX - e.MinX, 0.2);
      EXPECT_TRUE(e.MinX >= 179.8 || e.MaxX <= -179.8) << e.MinX << " " << e.MaxX;
    }
  }
  GDALClose(ds);
}

// The domain as FlatGeobuf (its CRS) and GeoJSON (longitudes and latitudes): the same
// components, holes and areas as the GeoPackage's, valid, the GeoJSON within the bbox.
TEST(Cli, DomainAsFlatGeobufAndGeoJson) {
  TempDir dir;
  for (const char* name : {"sea.gpkg", "sea.fgb", "sea.geojson"}) {
    const CliResult r =
        run_cli({"domain", sample("brittany_land.geojson"), "-o", dir.file(name), "--domain",
                 "water", "--bbox", "-5.3,46.8,-1.95,49.35", "--size", "2000", "-q"},
                dir);
    ASSERT_EQ(r.exit_code, 0) << name << ": " << r.err;
  }
  const DomainLayer gpkg = read_domain_layer(dir.file("sea.gpkg"));
  ASSERT_GT(gpkg.area_m2, 1e10);
  // The GeoPackage's open parts: the bbox's sides where they cross water, three runs
  // between the coast's ends on the sides (the bbox is 250 by 284 km).
  {
    GDALDataset* ds = static_cast<GDALDataset*>(
        GDALOpenEx(dir.file("sea.gpkg").c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr));
    ASSERT_NE(ds, nullptr);
    OGRLayer* open = ds->GetLayerByName("open_boundary");
    ASSERT_NE(open, nullptr);
    EXPECT_EQ(open->GetFeatureCount(), 3);
    double length = 0;
    for (auto& f : *open) {
      const double l = f->GetFieldAsDouble("length_m");
      EXPECT_NEAR(f->GetGeometryRef()->toLineString()->get_Length(), l, 1e-6 * l);
      length += l;
    }
    EXPECT_GT(length, 500e3);
    EXPECT_LT(length, 1070e3);
    GDALClose(ds);
    // The summary's count and length of them.
    const CliResult r =
        run_cli({"domain", sample("brittany_land.geojson"), "-o", dir.file("sea2.gpkg"), "--domain",
                 "water", "--bbox", "-5.3,46.8,-1.95,49.35", "--size", "2000", "--report",
                 dir.file("sea.json")},
                dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("open parts:   3 run(s) of the boundary"), std::string::npos) << r.err;
    const std::string report = read_file(dir.file("sea.json"));
    EXPECT_EQ(report_number(report, "num_open_parts"), 3);
    EXPECT_NEAR(report_number(report, "open_parts_length_m"), length, 1e-6 * length);
  }
  for (const char* name : {"sea.fgb", "sea.geojson"}) {
    SCOPED_TRACE(name);
    const DomainLayer d = read_domain_layer(dir.file(name));
    EXPECT_TRUE(d.valid);
    EXPECT_DOUBLE_EQ(d.area_m2, gpkg.area_m2);
    GDALDataset* ds = static_cast<GDALDataset*>(
        GDALOpenEx(dir.file(name).c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr));
    ASSERT_NE(ds, nullptr);
    OGRLayer* layer = ds->GetLayerByName("domain");
    ASSERT_NE(layer, nullptr);
    ASSERT_NE(layer->GetSpatialRef(), nullptr);
    const bool geojson = std::string(name) == "sea.geojson";
    EXPECT_EQ(layer->GetSpatialRef()->IsGeographic(), geojson);
    OGREnvelope e;
    ASSERT_EQ(layer->GetExtent(&e), OGRERR_NONE);
    if (geojson) {
      EXPECT_NEAR(e.MinX, -5.3, 1e-6);
      EXPECT_NEAR(e.MaxX, -1.95, 1e-6);
      EXPECT_NEAR(e.MinY, 46.8, 1e-6);
      EXPECT_NEAR(e.MaxY, 49.35, 1e-6);
    }
    int holes = 0;
    for (auto& f : *layer) holes += f->GetFieldAsInteger("num_holes");
    EXPECT_GT(holes, 0);
    GDALClose(ds);
  }
  const CliResult r = run_cli({"domain", sample("corsica.shp"), "-o", dir.file("c.shp")}, dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(".gpkg"), std::string::npos) << r.err;
}

// Over a domain where the map's scale strays from 1 (80 x 80 degrees of sea, k from 0.90
// to 1.17), islands are kept or dropped by their area on the ground: of two of about 4.0e10
// m2 on the ground (0.83 --size squared), at the centre and at 35 N 35 E (drawn 36%
// larger in the CRS there), both go, a large one stays; `domain --size` cleans as `mesh
// --size` does.
TEST(Cli, IslandsAreMeasuredOnTheGroundAsTheSizesAre) {
  TempDir dir;
  write_file(dir.file("islands.geojson"),
             geojson_polygons({"[[[-0.9,-0.9],[0.9,-0.9],[0.9,0.9],[-0.9,0.9],[-0.9,-0.9]]]",
                               "[[[34,34],[36.2,34],[36.2,35.8],[34,35.8],[34,34]]]",
                               "[[[-20,10],[-16,10],[-16,14],[-20,14],[-20,10]]]"}));
  const std::vector<std::string> common = {dir.file("islands.geojson"),
                                           "--domain",
                                           "water",
                                           "--bbox",
                                           "-40,-40,40,40",
                                           "--size",
                                           "220000"};
  for (const char* command : {"domain", "mesh"}) {
    std::vector<std::string> args = {command};
    args.insert(args.end(), common.begin(), common.end());
    const std::string out = dir.file(std::string(command) + ".gpkg");
    const std::string report = dir.file(std::string(command) + ".json");
    args.insert(args.end(), {"-o", out, "--report", report});
    const CliResult r = run_cli(args, dir);
    ASSERT_EQ(r.exit_code, 0) << command << r.err;
    const std::string json = read_file(report);
    EXPECT_EQ(report_number(json, "num_holes"), 1) << command;
    EXPECT_EQ(report_number(json, "num_holes_dropped"), 2) << command;
  }
}
