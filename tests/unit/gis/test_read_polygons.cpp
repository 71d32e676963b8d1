#include "gis/read_polygons.h"

#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.h"
#include "gis/gdal_env.h"
#include "gis/where_hint.h"
#include "support/fixtures.h"
#include "support/write_archive.h"

using namespace isoquad;
using namespace isoquad::test;

namespace {

// Runs the reader and returns the error it throws; fails the test when it does not.
Error read_error(const ReadParams& p) {
  try {
    read_polygons(p);
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "no error for " << p.path;
  return Error(ErrorClass::internal, "", "");
}

void expect_error(const ReadParams& p, ErrorClass cls, const std::string& words) {
  const Error e = read_error(p);
  EXPECT_EQ(e.error_class(), cls) << e.what();
  EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find(p.path), std::string::npos) << e.what();
}

ReadParams params(const std::string& path) {
  ReadParams p;
  p.path = path;
  return p;
}

}  // namespace

TEST(ReadPolygons, ReadsTheFranceSample) {
  const SourceData d = read_polygons(params(sample("france.shp")));
  ASSERT_EQ(d.polygons.size(), 1u);
  EXPECT_EQ(d.polygons[0].rings.size(), 2u);  // mainland and the Llivia enclave
  EXPECT_TRUE(d.crs.geographic);
  EXPECT_EQ(d.layer_name, "france");
  std::size_t n = 0;
  for (const Ring& r : d.polygons[0].rings) n += r.size();
  EXPECT_GT(n, 3000u);
  // Rings are stored open.
  EXPECT_NE(d.polygons[0].rings[0].front(), d.polygons[0].rings[0].back());
}

TEST(ReadPolygons, WhereAndBboxSelectFeatures) {
  TempDir dir;
  ReadParams p = params(good_geojson(dir));
  p.where = "name = 'f1'";
  SourceData d = read_polygons(p);
  ASSERT_EQ(d.polygons.size(), 1u);
  EXPECT_DOUBLE_EQ(d.polygons[0].rings[0][0].x, -1.0);

  p = params(good_geojson(dir));
  p.bbox = std::array<double, 4>{-3.5, 46.5, -2.5, 48.5};
  d = read_polygons(p);
  ASSERT_EQ(d.polygons.size(), 1u);
  EXPECT_DOUBLE_EQ(d.polygons[0].rings[0][0].x, -3.0);
  ASSERT_TRUE(d.bbox_ring.has_value());
}

// Under a pool (--each) a file is opened once: later reads get the kept data set back with
// none of the earlier reads' filters, and two reads at once get a data set each.
TEST(ReadPolygons, APoolKeepsTheDataSetAndClearsItsFilters) {
  TempDir dir;
  const std::string path = good_geojson(dir);
  const VectorDatasetPool pool;
  GDALDataset* kept = nullptr;
  {
    const GdalDataset a = open_vector_dataset(path, "read");
    kept = a.get();
    const GdalDataset b = open_vector_dataset(path, "read");
    EXPECT_NE(b.get(), kept);  // in use: another data set
    const GdalDataset c = open_vector_dataset(path, "read", {"FLATTEN_NESTED_ATTRIBUTES=YES"});
    EXPECT_NE(c.get(), kept);  // other open options: another data set
    EXPECT_NE(c.get(), b.get());
  }
  EXPECT_EQ(open_vector_dataset(path, "read").get(), kept);

  ReadParams p = params(path);
  p.where = "name = 'f1'";
  ASSERT_EQ(read_polygons(p).polygons.size(), 1u);
  p = params(path);
  p.bbox = std::array<double, 4>{-3.5, 46.5, -2.5, 48.5};
  const SourceData d = read_polygons(p);
  ASSERT_EQ(d.polygons.size(), 1u);  // the where above is gone
  EXPECT_DOUBLE_EQ(d.polygons[0].rings[0][0].x, -3.0);
  EXPECT_EQ(read_polygons(params(path)).polygons.size(), 2u);  // and the bbox
  EXPECT_EQ(open_vector_dataset(path, "read").get(), kept);
}

// A geometry collection (as overlays and some GeoJSON give) is read for its polygons,
// its points and lines ignored with a warning; one without a polygon is not a polygon.
TEST(ReadPolygons, TheGeometryCollectionsPolygonsAreRead) {
  TempDir dir;
  const std::string path = dir.file("gc.geojson");
  write_file(
      path,
      R"({"type":"FeatureCollection","features":[)"
      R"({"type":"Feature","properties":{},"geometry":{"type":"Polygon","coordinates":)"
      R"([[[-3,47],[-2,47],[-2,48],[-3,48],[-3,47]]]}},)"
      R"({"type":"Feature","properties":{},"geometry":{"type":"GeometryCollection",)"
      R"("geometries":[{"type":"Point","coordinates":[0.5,47.5]},)"
      R"({"type":"Polygon","coordinates":[[[-1,47,3],[0,47,3],[0,48,3],[-1,48,3],[-1,47,3]]]},)"
      R"({"type":"LineString","coordinates":[[1,47],[2,48]]}]}}]})");
  const SourceData d = read_polygons(params(path));
  ASSERT_EQ(d.polygons.size(), 2u);
  EXPECT_DOUBLE_EQ(d.polygons[1].rings[0][0].x, -1.0);
  ASSERT_EQ(d.warnings.size(), 1u);
  EXPECT_NE(d.warnings[0].find("2 point or line part(s) of geometry collections ignored (the "
                               "first in feature 1)"),
            std::string::npos)
      << d.warnings[0];

  write_file(path, R"({"type":"FeatureCollection","features":[)"
                   R"({"type":"Feature","properties":{},"geometry":{"type":"GeometryCollection",)"
                   R"("geometries":[{"type":"Point","coordinates":[0.5,47.5]}]}}]})");
  expect_error(params(path), ErrorClass::input, "has no polygons");
}

// The other polygonal types of simple features: a triangle, a TIN (its triangles), a
// polyhedral surface and a curve polygon (its arcs made segments) are areas, not lines.
TEST(ReadPolygons, TrianglesTinsAndCurvePolygonsAreAreas) {
  ensure_gdal_registered();
  TempDir dir;
  const std::string path = dir.file("surfaces.gpkg");
  const char* wkts[] = {"TRIANGLE ((0 0,10 0,10 10,0 0))",
                        "TIN (((20 0,30 0,30 10,20 0)),((20 0,30 10,20 10,20 0)))",
                        "POLYHEDRALSURFACE (((40 0,50 0,50 10,40 10,40 0)))",
                        "CURVEPOLYGON (CIRCULARSTRING (60 0,70 0,60 0))"};
  {
    GDALDataset* ds = GetGDALDriverManager()->GetDriverByName("GPKG")->Create(path.c_str(), 0, 0, 0,
                                                                              GDT_Unknown, nullptr);
    ASSERT_NE(ds, nullptr);
    OGRSpatialReference srs;
    srs.importFromEPSG(32631);
    OGRLayer* l = ds->CreateLayer("surfaces", &srs, wkbUnknown, nullptr);
    for (const char* wkt : wkts) {
      OGRGeometry* g = nullptr;
      ASSERT_EQ(OGRGeometryFactory::createFromWkt(wkt, nullptr, &g), OGRERR_NONE) << wkt;
      OGRFeature f(l->GetLayerDefn());
      f.SetGeometryDirectly(g);
      ASSERT_EQ(l->CreateFeature(&f), OGRERR_NONE) << wkt;
    }
    GDALClose(ds);
  }
  const SourceData d = read_polygons(params(path));
  EXPECT_TRUE(d.warnings.empty()) << d.warnings.front();
  ASSERT_EQ(d.polygons.size(), 5u);  // the TIN's two triangles apart
  double area[4] = {0, 0, 0, 0};
  for (const auto& poly : d.polygons) {
    ASSERT_EQ(poly.rings.size(), 1u);
    const int k = static_cast<int>(poly.rings[0][0].x / 20.0);
    ASSERT_TRUE(k >= 0 && k < 4) << poly.rings[0][0].x;
    area[k] += std::abs(signed_area(poly.rings[0]));
  }
  EXPECT_DOUBLE_EQ(area[0], 50.0);
  EXPECT_DOUBLE_EQ(area[1], 100.0);
  EXPECT_DOUBLE_EQ(area[2], 100.0);
  EXPECT_NEAR(area[3], M_PI * 25.0, 0.02 * M_PI * 25.0);  // a circle of diameter 10
}

// A CRS the file declares but GDAL cannot use: GeoJSON's "crs" member naming an unknown
// CRS (GDAL reads the coordinates as WGS 84, metres as degrees where they fit), a
// shapefile's .prj that is not WKT. The error names the CRS or file; --src-crs overrides.
TEST(ReadPolygons, ADeclaredCrsGdalCannotUseIsAnError) {
  ensure_gdal_registered();
  TempDir dir;
  const std::string square = R"([[[1,1],[2,1],[2,2],[1,2],[1,1]]])";
  for (const std::string name : {"urn:ogc:def:crs:EPSG::999999", "foo"}) {
    const std::string path = dir.file("declared.geojson");
    write_file(path, R"({"type":"FeatureCollection","crs":{"type":"name","properties":)"
                     R"({"name":")" +
                         name +
                         R"("}},"features":[{"type":"Feature",)"
                         R"("properties":{"crs":"x"},"geometry":{"type":"Polygon","coordinates":)" +
                         square + "}}]}");
    SCOPED_TRACE(name);
    expect_error(params(path), ErrorClass::crs,
                 "its \"crs\" member names '" + name + "', a CRS GDAL and PROJ do not know");
    ReadParams p = params(path);
    p.src_crs = "EPSG:32631";
    EXPECT_EQ(read_polygons(p).polygons.size(), 1u);
  }
  // A known CRS named, and a property called "crs" in the features: no error.
  const std::string known = dir.file("known.geojson");
  write_file(known, R"({"type":"FeatureCollection","crs":{"properties":{"name":)"
                    R"("urn:ogc:def:crs:EPSG::32631"},"type":"name"},"features":[{"type":)"
                    R"("Feature","properties":{"crs":{"type":"name","properties":{"name":)"
                    R"("foo"}}},"geometry":{"type":"Polygon","coordinates":)" +
                        square + "}}]}");
  EXPECT_TRUE(read_polygons(params(known)).crs.projected);

  const std::string shp = dir.file("broken.shp");
  {
    GDALDataset* ds = GetGDALDriverManager()
                          ->GetDriverByName("ESRI Shapefile")
                          ->Create(shp.c_str(), 0, 0, 0, GDT_Unknown, nullptr);
    ASSERT_NE(ds, nullptr);
    OGRLayer* l = ds->CreateLayer("broken", nullptr, wkbPolygon, nullptr);
    OGRGeometry* g = nullptr;
    OGRGeometryFactory::createFromWkt("POLYGON ((1 1,2 1,2 2,1 2,1 1))", nullptr, &g);
    OGRFeature f(l->GetLayerDefn());
    f.SetGeometryDirectly(g);
    ASSERT_EQ(l->CreateFeature(&f), OGRERR_NONE);
    GDALClose(ds);
  }
  expect_error(params(shp), ErrorClass::crs, "layer 'broken' has no CRS");  // no .prj
  write_file(dir.file("broken.prj"), R"(GEOGCS["GCS_WGS_1984",DATUM[)");
  expect_error(params(shp), ErrorClass::crs,
               "its .prj file 'broken.prj' holds no CRS GDAL can read (");
}

// Data sources GDAL opens by name, not files: a driver's prefix, a database connection.
// A name that is neither a file nor a source says both.
TEST(ReadPolygons, DataSourcesAreOpenedByTheirNames) {
  TempDir dir;
  const std::string path = dir.file("box.geojson");
  write_file(path, R"({"type":"FeatureCollection","features":[{"type":"Feature",)"
                   R"("properties":{},"geometry":{"type":"Polygon","coordinates":)"
                   R"([[[1,1],[2,1],[2,2],[1,2],[1,1]]]}}]})");
  const SourceData d = read_polygons(params("GeoJSON:" + path));
  ASSERT_EQ(d.polygons.size(), 1u);
  EXPECT_DOUBLE_EQ(std::abs(signed_area(d.polygons[0].rings[0])), 1.0);
  expect_error(params("PG:host=/nonexistent-isoquad dbname=coast"), ErrorClass::input,
               "'PG:host=/nonexistent-isoquad dbname=coast': no such file, nor a data source "
               "GDAL opens");
  expect_error(params("C:/coast.shp"), ErrorClass::input, "no such file or directory");
  EXPECT_TRUE(is_data_source_name("WFS:https://host/wfs"));
  EXPECT_TRUE(is_data_source_name("https://host/coast.geojson"));
  EXPECT_FALSE(is_data_source_name("C:/coast.shp"));
  EXPECT_FALSE(is_data_source_name(path));
  EXPECT_FALSE(is_data_source_name("/vsizip/a.zip"));
}

TEST(ReadPolygons, BboxInAnotherCrs) {
  TempDir dir;
  ReadParams p = params(good_geojson(dir));
  // Around (-0.5, 47.5) in Lambert-93 metres: only the eastern square.
  p.bbox = std::array<double, 4>{380000, 6700000, 420000, 6740000};
  p.bbox_crs = "EPSG:2154";
  const SourceData d = read_polygons(p);
  ASSERT_EQ(d.polygons.size(), 1u);
  EXPECT_DOUBLE_EQ(d.polygons[0].rings[0][0].x, -1.0);
}

TEST(ReadPolygons, BadInputsAreReportedWithFileAndProblem) {
  TempDir dir;
  expect_error(params(dir.file("missing.shp")), ErrorClass::input, "no such file");
  expect_error(params(corrupt_shapefile(dir)), ErrorClass::input, "cannot read");
  expect_error(params(empty_file(dir)), ErrorClass::input, "empty");
  expect_error(params(points_geojson(dir)), ErrorClass::input, "1 with point or line geometry");
  // A feature whose geometry is empty (a tiny island quantized away: Natural Earth's
  // Vatican at 1:10m in world-atlas) is counted as such.
  const std::string empty_geometry = dir.file("empty_geometry.geojson");
  write_file(empty_geometry,
             "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\","
             "\"properties\":{},\"geometry\":{\"type\":\"Polygon\",\"coordinates\":[]}}]}");
  expect_error(params(empty_geometry), ErrorClass::input, "has no polygons (1 feature(s) read, "
                                                          "0 with point or line geometry, 1 with none or an empty one)");
  expect_error(params(no_crs_csv(dir)), ErrorClass::crs, "--src-crs");
  expect_error(params(unclosed_geojson(dir)), ErrorClass::input, "not closed");
  expect_error(params(non_finite_geojson(dir)), ErrorClass::input, "not finite");
  expect_error(params(non_finite_geojson(dir, true)), ErrorClass::input, "not finite");
  expect_error(params(out_of_range_geojson(dir)), ErrorClass::crs, "outside the valid range");
  expect_error(params(wrong_crs_geojson(dir)), ErrorClass::crs, "area of use");

  ReadParams p = params(good_geojson(dir));
  p.where = "name = 'nothing'";
  expect_error(p, ErrorClass::input, "matched no feature");
  p.where = "no_such_field = 1";
  expect_error(p, ErrorClass::usage, "--where");
  p = params(good_geojson(dir));
  p.bbox = std::array<double, 4>{100, 10, 101, 11};
  expect_error(p, ErrorClass::input, "misses the data");
  EXPECT_EQ(std::string(read_error(p).what()).find("look like longitudes"), std::string::npos);
  // Degrees given in a projected CRS.
  p.bbox = std::array<double, 4>{-3, 47, -2, 48};
  p.bbox_crs = "EPSG:2154";
  expect_error(p, ErrorClass::input,
               "its numbers look like longitudes and latitudes, and 'RGF93 v1 / Lambert-93' is "
               "projected: --bbox-crs EPSG:4326?");
  p.bbox_crs.clear();
  p.bbox = std::array<double, 4>{1, 10, 0, 11};
  expect_error(p, ErrorClass::usage, "XMIN < XMAX");
  p = params(good_geojson(dir));
  p.layer = "nope";
  expect_error(p, ErrorClass::usage, "no layer 'nope'");
}

// Without --layer, the first layer of polygons is read, also one whose type is not
// declared (a TopoJSON's object of polygons and multipolygons, as Natural Earth's
// countries in world-atlas, before its land); the other layers of polygons are named.
TEST(ReadPolygons, TheFirstLayerOfPolygonsIsReadWhetherItsTypeIsDeclaredOrNot) {
  TempDir dir;
  const std::string path = dir.file("world.topojson");
  write_file(
      path,
      R"({"type":"Topology","objects":{)"
      R"("stations":{"type":"GeometryCollection","geometries":[{"type":"Point",)"
      R"("coordinates":[-2.5,47.5]}]},)"
      R"("countries":{"type":"GeometryCollection","geometries":[)"
      R"({"type":"Polygon","arcs":[[0]],"properties":{"name":"a"}},)"
      R"({"type":"MultiPolygon","arcs":[[[1]]],"properties":{"name":"b"}}]},)"
      R"("land":{"type":"GeometryCollection","geometries":[{"type":"Polygon","arcs":[[1]]}]}},)"
      R"("arcs":[[[-3,47],[-2,47],[-2,48],[-3,48],[-3,47]],)"
      R"([[-1,47],[0,47],[0,48],[-1,48],[-1,47]]]})");
  ReadParams p = params(path);
  p.src_crs = "EPSG:4326";
  const SourceData d = read_polygons(p);
  EXPECT_EQ(d.layer_name, "countries");
  EXPECT_EQ(d.polygons.size(), 2u);
  EXPECT_EQ(d.other_polygon_layers, std::vector<std::string>{"land"});
  p.layer = "land";
  const SourceData land = read_polygons(p);
  EXPECT_EQ(land.polygons.size(), 1u);
  EXPECT_TRUE(land.other_polygon_layers.empty());
}

// An invalid filter lists the layer's attributes with their types, and says what OGR
// took for a missing attribute may be a misspelt one or a text value without quotes.
TEST(ReadPolygons, AnInvalidFilterListsTheAttributesAndWhatItMayHaveMeant) {
  TempDir dir;
  ReadParams p = params(good_geojson(dir));  // attributes id (0, 1) and name (f0, f1)
  p.where = "no_such_field = 1";
  expect_error(p, ErrorClass::usage, "(attributes: id (Integer), name (String))");
  p.where = "nme = 'f0'";
  expect_error(p, ErrorClass::usage, "'nme': did you mean 'name'?");
  p.where = "name = f0";
  expect_error(p, ErrorClass::usage, "a text value goes in single quotes: 'f0'");
  p.where = "name IN ('f1', f0)";
  expect_error(p, ErrorClass::usage, "a text value goes in single quotes: 'f0'");
  p.where = "f0 = name";  // a word before the comparison: maybe an attribute
  const std::string message = read_error(p).what();
  EXPECT_EQ(message.find("single quotes"), std::string::npos) << message;
}

// A filter that selects nothing says why, when a value it compares with is mistyped or
// lies outside the bbox.
TEST(ReadPolygons, AFilterThatSelectsNothingNamesTheNearestValues) {
  TempDir dir;
  ReadParams p = params(good_geojson(dir));  // features f0 (x -3 to -2) and f1 (x -1 to 0)
  p.where = "name = 'f7'";
  expect_error(p, ErrorClass::input, "no feature has name 'f7' (the nearest: 'f0', 'f1')");
  p.where = "'g1' = name";
  expect_error(p, ErrorClass::input, "no feature has name 'g1' (the nearest: 'f1')");
  p.where = "name IN ('f0', 'xyz')";  // f0 matches; xyz, a warning
  const SourceData some = read_polygons(p);
  EXPECT_EQ(some.polygons.size(), 1u);
  ASSERT_EQ(some.warnings.size(), 1u);
  EXPECT_EQ(some.warnings[0], "--where 'name IN ('f0', 'xyz')': no feature has name 'xyz'");
  p.hint_unmatched_values = false;  // --each's regions
  EXPECT_TRUE(read_polygons(p).warnings.empty());
  p.hint_unmatched_values = true;
  p.bbox = std::array<double, 4>{-1.5, 46.5, 0.5, 48.5};  // f1 only
  p.where = "name = 'f0'";
  expect_error(p, ErrorClass::input, "the features with name 'f0' lie outside the bbox");
  // A pattern, or a value that some feature holds, gets no hint.
  for (const char* where : {"name LIKE 'zz%'", "name = 'f1' AND id = 7"}) {
    p.where = where;
    const std::string message = read_error(p).what();
    EXPECT_NE(message.find("matched no feature"), std::string::npos) << message;
    EXPECT_EQ(message.find("no feature has"), std::string::npos) << message;
    EXPECT_EQ(message.find("lie outside"), std::string::npos) << message;
  }
}

TEST(WhereHint, NearestValuesAreCloseInSpellingOrHoldTheValue) {
  const std::vector<std::string> countries{"France",      "Greece",      "Ireland",       "Kenya",
                                           "North Korea", "South Korea", "Guinea-Bissau", "Guinea"};
  EXPECT_EQ(nearest_values("Frnce", countries), std::vector<std::string>{"France"});
  EXPECT_EQ(nearest_values("korea", countries),
            (std::vector<std::string>{"North Korea", "South Korea"}));
  EXPECT_EQ(nearest_values("Guinea Bisau", countries), std::vector<std::string>{"Guinea-Bissau"});
  EXPECT_TRUE(nearest_values("Atlantis", countries).empty());
  EXPECT_EQ(nearest_values("e", countries, 2).size(), 0u);  // a letter is near nothing
}

TEST(ReadPolygons, RepairClosesUnclosedRings) {
  TempDir dir;
  ReadParams p = params(unclosed_geojson(dir));
  p.repair = true;
  const SourceData d = read_polygons(p);
  ASSERT_EQ(d.polygons.size(), 1u);
  EXPECT_EQ(d.polygons[0].rings[0].size(), 4u);
  EXPECT_EQ(d.num_rings_closed, 1u);
}

TEST(ReadPolygons, SrcCrsGivesACrsToDataWithout) {
  TempDir dir;
  ReadParams p = params(no_crs_csv(dir));
  p.src_crs = "EPSG:2154";
  const SourceData d = read_polygons(p);
  ASSERT_EQ(d.polygons.size(), 1u);
  EXPECT_TRUE(d.crs.projected);
}

TEST(ReadPolygons, DensifiedBoxHasItsCornersInOrder) {
  const Ring r = densified_box({0, 0, 4, 2}, 4);
  ASSERT_EQ(r.size(), 16u);
  EXPECT_EQ(r[0], (Point2{0, 0}));
  EXPECT_EQ(r[4], (Point2{4, 0}));
  EXPECT_EQ(r[8], (Point2{4, 2}));
  EXPECT_EQ(r[12], (Point2{0, 2}));
  EXPECT_DOUBLE_EQ(signed_area(r), 8.0);
}

namespace {

// A GeoJSON file of one MultiPolygon feature (as a world land file) with these parts,
// each the coordinates of one polygon.
std::string multipolygon_file(const TempDir& dir, const std::vector<std::string>& parts) {
  std::string coords;
  for (const std::string& part : parts) coords += (coords.empty() ? "" : ",") + part;
  const std::string path = dir.file("world.geojson");
  write_file(path, R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},)"
                   R"("geometry":{"type":"MultiPolygon","coordinates":[)" +
                       coords + "]}}]}");
  return path;
}

}  // namespace

TEST(ReadPolygons, ABboxReadsOnlyThePartsOfAMultipolygonThatReachIt) {
  // A square near (-2.5, 47.5) and, far away, a degenerate part (three points on a line)
  // that would need --repair.
  TempDir dir;
  ReadParams p = params(multipolygon_file(dir, {"[[[-3,47],[-2,47],[-2,48],[-3,48],[-3,47]]]",
                                                "[[[100,10],[101,10],[102,10],[100,10]]]"}));
  expect_error(p, ErrorClass::input, "degenerate");
  p.bbox = std::array<double, 4>{-4, 46, -1, 49};
  const SourceData d = read_polygons(p);
  ASSERT_EQ(d.polygons.size(), 1u);
  EXPECT_EQ(d.polygons[0].part, 0);
  EXPECT_EQ(d.num_rings_dropped, 0u);
}

TEST(ReadPolygons, AnAreaThatHoldsNoPolygonIsAnErrorUnlessEmptyAreasAreAllowed) {
  // Polygons at 65 N; bboxes that miss them: beside their extent, within it but between
  // them, and north of 60 N, where every feature is read and its parts selected (a
  // polar bbox). With empty_area_ok (--exclude) each gives no polygons and no error.
  TempDir dir;
  const std::string path = dir.file("two.geojson");
  write_file(path, geojson_polygons({"[[[-20,65],[-19,65],[-19,66],[-20,66],[-20,65]]]",
                                     "[[[-10,65],[-9,65],[-9,66],[-10,66],[-10,65]]]"}));
  ReadParams p = params(path);
  for (const std::array<double, 4>& box :
       {std::array<double, 4>{0, 40, 1, 41}, std::array<double, 4>{-16, 50, -14, 52},
        std::array<double, 4>{-16, 65, -14, 66}}) {
    p.bbox = box;
    p.empty_area_ok = false;
    read_error(p);
    p.empty_area_ok = true;
    SourceData d;
    EXPECT_NO_THROW(d = read_polygons(p)) << box[0] << " " << box[1];
    EXPECT_TRUE(d.polygons.empty());
  }
  // A filter that matches features elsewhere gives none; one that matches nothing
  // anywhere is still an error.
  p.where = "id = 1";
  EXPECT_TRUE(read_polygons(p).polygons.empty());
  p.where = "id = 99";
  read_error(p);
}

TEST(ReadPolygons, ABboxAcrossTheAntimeridianReadsWhatLiesBeyondIt) {
  // Longitudes 176 to 182: the part drawn at -179.5 (181.5 the other way round) is read,
  // the one at -170 is not.
  TempDir dir;
  ReadParams p = params(
      multipolygon_file(dir, {"[[[177,-18],[178,-18],[178,-17],[177,-17],[177,-18]]]",
                              "[[[-179.5,-18],[-179,-18],[-179,-17],[-179.5,-17],[-179.5,-18]]]",
                              "[[[-170,-18],[-169,-18],[-169,-17],[-170,-17],[-170,-18]]]"}));
  p.bbox = std::array<double, 4>{176, -20, 182, -15};
  const SourceData d = read_polygons(p);
  ASSERT_EQ(d.polygons.size(), 2u);
  EXPECT_EQ(d.polygons[0].part, 0);
  EXPECT_EQ(d.polygons[1].part, 1);
  // A bbox wholly past 180 does not miss the data drawn at -180..-178.
  p.bbox = std::array<double, 4>{180.2, -20, 183, -15};
  const SourceData beyond = read_polygons(p);
  ASSERT_EQ(beyond.polygons.size(), 1u);
  EXPECT_EQ(beyond.polygons[0].part, 1);
}

// Downloads come zipped (Natural Earth's ne_10m_land.zip, a folder inside or not) or
// gzipped: read as they are, through GDAL's virtual file systems.
TEST(ReadPolygons, ReadsArchivesAsDownloaded) {
  TempDir dir;
  const std::string stem = sample("corsica.shp").substr(0, sample("corsica.shp").size() - 4);
  const SourceData plain = read_polygons(params(stem + ".shp"));
  auto expect_same = [&](const std::string& path, const SourceData& reference) {
    SCOPED_TRACE(path);
    const SourceData d = read_polygons(params(path));
    ASSERT_EQ(d.polygons.size(), reference.polygons.size());
    for (std::size_t i = 0; i < d.polygons.size(); ++i) {
      ASSERT_EQ(d.polygons[i].rings.size(), reference.polygons[i].rings.size());
      for (std::size_t k = 0; k < d.polygons[i].rings.size(); ++k)
        EXPECT_TRUE(d.polygons[i].rings[k] == reference.polygons[i].rings[k]);
    }
    EXPECT_EQ(d.crs.wkt, reference.crs.wkt);
  };
  // At the top level (GDAL reads it as a folder of shapefiles), and in a folder beside a
  // text file (the one shapefile inside).
  expect_same(write_zip(dir.file("top.zip"), shapefile_members(stem, "")), plain);
  auto in_folder = shapefile_members(stem, "ne_corsica/");
  in_folder.emplace_back("ne_corsica/README.txt", "Made with Natural Earth.");
  expect_same(write_zip(dir.file("Folder.ZIP"), in_folder), plain);
  expect_same(write_gzip(dir.file("corsica.geojson.gz"), read_file(sample("corsica.geojson"))),
              read_polygons(params(sample("corsica.geojson"))));

  // Two shapefiles in two folders: which one is for the user to say, and how.
  auto two = shapefile_members(stem, "a/");
  for (auto& m : shapefile_members(stem, "b/")) two.push_back(m);
  const std::string two_zip = write_zip(dir.file("two.zip"), two);
  expect_error(params(two_zip), ErrorClass::input,
               "the archive holds 2 vector files (a/corsica.shp, b/corsica.shp): name one, "
               "e.g. /vsizip/" +
                   two_zip + "/a/corsica.shp");
  const SourceData picked = read_polygons(params("/vsizip/" + two_zip + "/b/corsica.shp"));
  EXPECT_EQ(picked.polygons.size(), plain.polygons.size());
  // Nothing to read.
  expect_error(params(write_zip(dir.file("text.zip"), {{"README.txt", "no data"}})),
               ErrorClass::input,
               "the archive holds no vector file GDAL reads (it holds README.txt)");
}

namespace {

// The rings of `d` cut into lines of up to `per_line` segments, every other line
// reversed and the lines in reverse order, as a GeoJSON layer of LineStrings in lon/lat.
std::string rings_as_lines(const SourceData& d, std::size_t per_line, const std::string& path) {
  std::vector<std::vector<Point2>> lines;
  for (const SourcePolygon& p : d.polygons)
    for (Ring r : p.rings) {
      r.push_back(r.front());
      for (std::size_t k = 0; k + 1 < r.size(); k += per_line)
        lines.emplace_back(
            r.begin() + static_cast<std::ptrdiff_t>(k),
            r.begin() + static_cast<std::ptrdiff_t>(std::min(r.size(), k + per_line + 1)));
    }
  std::reverse(lines.begin(), lines.end());
  std::ostringstream os;
  os.precision(17);
  os << R"({"type":"FeatureCollection","features":[)";
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (i % 2) std::reverse(lines[i].begin(), lines[i].end());
    os << (i ? "," : "") << R"({"type":"Feature","properties":{"id":)" << i
       << R"(},"geometry":{"type":"LineString","coordinates":[)";
    for (std::size_t k = 0; k < lines[i].size(); ++k)
      os << (k ? "," : "") << "[" << lines[i][k].x << "," << lines[i][k].y << "]";
    os << "]}}";
  }
  os << "]}";
  write_file(path, os.str());
  return path;
}

std::vector<std::pair<double, double>> sorted_points(const Ring& r) {
  std::vector<std::pair<double, double>> v;
  for (const Point2& p : r) v.emplace_back(p.x, p.y);
  std::sort(v.begin(), v.end());
  return v;
}

}  // namespace

// A coastline drawn as lines (closed or in pieces, in any direction and order) is read
// as the polygons its rings make.
TEST(ReadPolygons, ReadsTheRingsOfALayerOfLines) {
  TempDir dir;
  const SourceData shape = read_polygons(params(sample("france.shp")));
  ASSERT_EQ(shape.polygons.size(), 1u);
  ASSERT_EQ(shape.polygons[0].rings.size(), 2u);  // the mainland and the Llivia enclave
  const std::string path = rings_as_lines(shape, 40, dir.file("france_lines.geojson"));
  const SourceData lines = read_polygons(params(path));
  EXPECT_GT(lines.num_line_features, 70u);
  EXPECT_EQ(lines.num_rings_from_lines, 2u);
  // The mainland in many lines; the enclave's ring, if under 40 segments, in one.
  EXPECT_GE(lines.num_rings_joined, 1u);
  EXPECT_EQ(lines.num_lines_joined + (2 - lines.num_rings_joined), lines.num_line_features);
  ASSERT_EQ(lines.polygons.size(), 1u);
  ASSERT_EQ(lines.polygons[0].rings.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    const Ring &a = shape.polygons[0].rings[k], &b = lines.polygons[0].rings[k];
    EXPECT_EQ(sorted_points(a), sorted_points(b));
    EXPECT_NEAR(std::abs(signed_area(a)), std::abs(signed_area(b)),
                1e-9 * std::abs(signed_area(a)));
  }
  // The bbox selects the polygons, not the lines: Brittany's bbox reaches only some of
  // the lines of France's ring, and still gives the whole ring.
  ReadParams p = params(path);
  p.bbox = std::array<double, 4>{-5.0, 47.5, -3.0, 48.5};
  const SourceData brittany = read_polygons(p);
  ASSERT_EQ(brittany.polygons.size(), 1u);
  EXPECT_EQ(sorted_points(brittany.polygons[0].rings[0]),
            sorted_points(shape.polygons[0].rings[0]));
  // Two squares drawn as lines, and a bbox between them.
  write_file(dir.file("squares.geojson"),
             R"({"type":"FeatureCollection","features":[)"
             R"({"type":"Feature","properties":{"name":"a"},"geometry":{"type":"LineString",)"
             R"("coordinates":[[-3,47],[-2,47],[-2,48],[-3,48],[-3,47]]}},)"
             R"({"type":"Feature","properties":{"name":"b"},"geometry":{"type":"LineString",)"
             R"("coordinates":[[-1,47],[0,47],[0,48],[-1,48],[-1,47]]}}]})");
  p = params(dir.file("squares.geojson"));
  EXPECT_EQ(read_polygons(p).polygons.size(), 2u);
  // --each's values are those of the lines that reach the bbox.
  p.bbox = std::array<double, 4>{-2.5, 47.2, -1.5, 47.8};
  const std::vector<SelectionValue> values = selection_values(p, "name");
  ASSERT_EQ(values.size(), 1u);
  EXPECT_EQ(values[0].text, "a");
  p.bbox = std::array<double, 4>{-1.8, 47.2, -1.2, 47.8};
  expect_error(p, ErrorClass::input,
               "the 2 ring(s) the lines of layer 'squares' make all miss the selection (--bbox)");
  // A line left out: the ring does not close, and the message says where.
  p = params(path);
  p.where = "id <> 3";
  expect_error(p, ErrorClass::input, "its lines do not close into rings: feature");
  expect_error(p, ErrorClass::input, "2 loose end(s) in all");
}

// --each fid: a region per feature, by the features' ids (a GeoPackage's FID column,
// OGR's FID of a GeoJSON file or a shapefile), each filter selecting that feature alone,
// where no attribute tells them apart (the parts of a multi-polygon split into features).
TEST(ReadPolygons, TheFeaturesIdsAreValuesOfEach) {
  TempDir dir;
  ensure_gdal_registered();
  const char* const squares[] = {"POLYGON ((0 0,1 0,1 1,0 1,0 0))",
                                 "POLYGON ((2 0,3 0,3 1,2 1,2 0))",
                                 "POLYGON ((4 0,6 0,6 2,4 2,4 0))"};
  const std::pair<const char*, const char*> files[] = {
      {"GPKG", "parts.gpkg"}, {"GeoJSON", "parts.geojson"}, {"ESRI Shapefile", "parts.shp"}};
  for (const auto& [driver, file] : files) {
    SCOPED_TRACE(driver);
    const std::string path = dir.file(file);
    {
      GDALDataset* ds = GetGDALDriverManager()->GetDriverByName(driver)->Create(
          path.c_str(), 0, 0, 0, GDT_Unknown, nullptr);
      ASSERT_NE(ds, nullptr);
      OGRSpatialReference srs;
      srs.importFromEPSG(32631);
      OGRLayer* l = ds->CreateLayer("parts", &srs, wkbPolygon, nullptr);
      OGRFieldDefn name("name", OFTString);
      ASSERT_EQ(l->CreateField(&name), OGRERR_NONE);
      for (const char* wkt : squares) {
        OGRGeometry* g = nullptr;
        OGRGeometryFactory::createFromWkt(wkt, nullptr, &g);
        OGRFeature f(l->GetLayerDefn());
        f.SetField("name", "island");
        f.SetGeometryDirectly(g);
        ASSERT_EQ(l->CreateFeature(&f), OGRERR_NONE);
      }
      GDALClose(ds);
    }
    ReadParams p = params(path);
    EXPECT_EQ(selection_values(p, "name").size(), 1u);  // one value for the three
    p.where = "name = 'island'";                        // --where and the ids together
    const std::vector<SelectionValue> ids = selection_values(p, "FID");
    ASSERT_EQ(ids.size(), 3u);
    const double areas[] = {1.0, 1.0, 4.0};
    for (std::size_t k = 0; k < ids.size(); ++k) {
      EXPECT_FALSE(ids[k].null);
      p.where = ids[k].filter;
      const SourceData d = read_polygons(p);
      ASSERT_EQ(d.polygons.size(), 1u) << ids[k].filter;
      EXPECT_DOUBLE_EQ(std::abs(signed_area(d.polygons[0].rings[0])), areas[k]) << ids[k].filter;
      EXPECT_DOUBLE_EQ(d.polygons[0].rings[0][0].x, 2.0 * k) << ids[k].filter;
    }
    // Named as the file names its ids (a GeoPackage's column "fid"), in any case.
    p.where.clear();
    EXPECT_EQ(selection_values(p, "fid").size(), 3u);
    // An attribute the layer lacks: its attributes, and what its ids are called.
    try {
      selection_values(p, "nmae");
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("(attributes: name; the features' ids: "),
                std::string::npos)
          << e.what();
    }
  }
}

// --each over a date: the values as ISO 8601 writes them (GDAL formats 2020/01/31), each
// filter still selecting its features, on a GeoPackage's date and a GeoJSON's detected one.
TEST(ReadPolygons, DatesAreValuesOfEachInIsoForm) {
  TempDir dir;
  ensure_gdal_registered();
  write_file(dir.file("surveys.geojson"),
             R"({"type":"FeatureCollection","features":[)"
             R"({"type":"Feature","properties":{"day":"2021-06-30"},"geometry":{"type":"Polygon",)"
             R"("coordinates":[[[0,0],[1,0],[1,1],[0,1],[0,0]]]}},)"
             R"({"type":"Feature","properties":{"day":"2020-01-31"},"geometry":{"type":"Polygon",)"
             R"("coordinates":[[[2,0],[4,0],[4,2],[2,2],[2,0]]]}}]})");
  const std::string gpkg = dir.file("surveys.gpkg");
  {
    GDALDataset* ds = GetGDALDriverManager()->GetDriverByName("GPKG")->Create(gpkg.c_str(), 0, 0, 0,
                                                                              GDT_Unknown, nullptr);
    ASSERT_NE(ds, nullptr);
    OGRSpatialReference srs;
    srs.importFromEPSG(4326);
    OGRLayer* l = ds->CreateLayer("surveys", &srs, wkbPolygon, nullptr);
    OGRFieldDefn day("day", OFTDate);
    ASSERT_EQ(l->CreateField(&day), OGRERR_NONE);
    OGRFieldDefn at("at", OFTDateTime);
    ASSERT_EQ(l->CreateField(&at), OGRERR_NONE);
    const std::pair<const char*, int> rows[] = {{"POLYGON ((0 0,1 0,1 1,0 1,0 0))", 2021},
                                                {"POLYGON ((2 0,4 0,4 2,2 2,2 0))", 2020}};
    for (const auto& [wkt, year] : rows) {
      OGRGeometry* g = nullptr;
      OGRGeometryFactory::createFromWkt(wkt, nullptr, &g);
      OGRFeature f(l->GetLayerDefn());
      f.SetField("day", year, year == 2020 ? 1 : 6, year == 2020 ? 31 : 30);
      f.SetField("at", year, 1, 31, 10, 20, 30.0f, 100);  // UTC
      f.SetGeometryDirectly(g);
      ASSERT_EQ(l->CreateFeature(&f), OGRERR_NONE);
    }
    GDALClose(ds);
  }
  for (const std::string& path : {dir.file("surveys.geojson"), gpkg}) {
    SCOPED_TRACE(path);
    ReadParams p = params(path);
    const std::vector<SelectionValue> values = selection_values(p, "day");
    ASSERT_EQ(values.size(), 2u);
    EXPECT_EQ(values[0].text, "2020-01-31");
    EXPECT_EQ(values[1].text, "2021-06-30");
    for (const bool by_id : {true, false}) {
      p.where = by_id ? values[0].id_filter : values[0].filter;
      const SourceData d = read_polygons(p);
      ASSERT_EQ(d.polygons.size(), 1u) << p.where;
      EXPECT_DOUBLE_EQ(std::abs(signed_area(d.polygons[0].rings[0])), 4.0) << p.where;
    }
  }
  const std::vector<SelectionValue> times = selection_values(params(gpkg), "at");
  ASSERT_EQ(times.size(), 2u);
  EXPECT_EQ(times[0].text, "2020-01-31T10:20:30Z");
}

// Delft3D / D-Flow FM Tekal files (.pol, .ldb, .pli) and Blue Kenue line sets (.i2s):
// lines without a CRS, read as a layer named after the file with the lines' names.
TEST(ReadPolygons, ReadsTheLineFilesOfModellingPackages) {
  TempDir dir;
  auto read = [&](const std::string& name, const std::string& text, const std::string& where = "") {
    write_file(dir.file(name), text);
    ReadParams p = params(dir.file(name));
    p.src_crs = "EPSG:32630";
    p.where = where;
    return read_polygons(p);
  };
  auto areas = [](const SourceData& d) {
    std::vector<double> a;
    for (const SourcePolygon& p : d.polygons)
      for (const Ring& r : p.rings) a.push_back(std::abs(signed_area(r)));
    return a;
  };
  // A .pol block is a closed ring whether or not it repeats its first point.
  const std::string pol =
      "* land and a lake\nland\n 5 2\n0 0\n1000 0\n1000 1000\n0 1000\n0 0\n"
      "lake\n 4 2\n400 400\n600 400\n600 600\n400 600\n";
  SourceData d = read("coast.pol", pol);
  EXPECT_EQ(d.layer_name, "coast");
  EXPECT_EQ(areas(d), (std::vector<double>{1e6, 4e4}));
  EXPECT_EQ(read("coast.pol", pol, "name = 'land'").polygons[0].rings.size(), 1u);
  // An .ldb's 999.999 999.999 ends a line within a block; its lines join into a ring.
  d = read("coast.ldb",
           "L001\n 7 2\n0 0\n1000 0\n1000 1000\n999.999 999.999\n1000 1000\n0 1000\n0 0\n");
  EXPECT_EQ(d.num_rings_joined, 1u);
  EXPECT_EQ(areas(d), (std::vector<double>{1e6}));
  // .i2s: a header, then lines of "count value" and their points.
  d = read(
      "coast.i2s",
      ":FileType i2s  ASCII  EnSim 1.0\n:EndHeader\n5 0\n0 0\n1000 0\n1000 1000\n0 1000\n0 0\n");
  EXPECT_EQ(areas(d), (std::vector<double>{1e6}));
  // Malformed: the line and what was expected.
  write_file(dir.file("bad.pol"), "land\n 5 2\n0 0\n1000 zero\n");
  expect_error(params(dir.file("bad.pol")), ErrorClass::input,
               "line 4: expected two numbers x y, found '1000 zero'");
  write_file(dir.file("bad.i2s"), "5 0\n0 0\n");
  expect_error(params(dir.file("bad.i2s")), ErrorClass::input, "no ':EndHeader' line");
  // Without --src-crs: the CRS is asked for.
  write_file(dir.file("nocrs.pol"), pol);
  expect_error(params(dir.file("nocrs.pol")), ErrorClass::crs, "give the CRS of the coordinates");
}

// A spherical polygon drawn round a pole (world-atlas's Antarctica at 1:50m): its outer
// ring runs along 89.999 S, a line in lon/lat, and the coast is its hole. With
// --repair the degenerate ring is dropped and the hole read as a polygon of its own,
// with a warning; it was once dropped with it, and the continent with it.
TEST(ReadPolygons, TheHolesOfAnOuterRingWithoutAreaArePolygonsOfTheirOwn) {
  TempDir dir;
  const std::string path = dir.file("pole.geojson");
  write_file(path, geojson_polygons({"[[[-180,-89.999],[0,-89.999],[179,-89.999],[-180,-89.999]],"
                                     "[[-60,-70],[-50,-70],[-50,-65],[-60,-65],[-60,-70]]]"}));
  expect_error(params(path), ErrorClass::input, "ring 0 is degenerate");
  ReadParams p = params(path);
  p.repair = true;
  const SourceData d = read_polygons(p);
  ASSERT_EQ(d.polygons.size(), 1u);
  ASSERT_EQ(d.polygons[0].rings.size(), 1u);
  EXPECT_DOUBLE_EQ(std::abs(signed_area(d.polygons[0].rings[0])), 50.0);
  EXPECT_EQ(d.num_rings_dropped, 1u);
  ASSERT_EQ(d.warnings.size(), 1u);
  EXPECT_NE(
      d.warnings[0].find("ring 0 has no area; its 1 hole(s) are read as polygons of their own"),
      std::string::npos)
      << d.warnings[0];
}

// "North of 66.5 N" drawn as the Arctic Circle: a ring along one parallel round every
// longitude is a line in longitude and latitude. Said as such (with or without --repair,
// which would only drop it), with the ring through the pole that means the cap; that
// ring reads as one polygon.
TEST(ReadPolygons, ARingAlongAParallelRoundTheGlobeIsSaidToEncloseNothing) {
  TempDir dir;
  std::string along = "[[";
  for (int lon = -180; lon < 180; lon += 10) along += "[" + std::to_string(lon) + ",66.5],";
  const std::string circle = dir.file("circle.geojson"), cap = dir.file("cap.geojson");
  write_file(circle, geojson_polygons({along + "[-180,66.5]]]"}));
  write_file(cap, geojson_polygons({along + "[180,66.5],[180,90],[-180,90],[-180,66.5]]]"}));
  ReadParams p = params(circle);
  for (const bool repair : {false, true}) {
    p.repair = repair;
    expect_error(p, ErrorClass::input, "runs along the parallel 66.5 N round every longitude");
    expect_error(p, ErrorClass::input, "add (180, 66.5), (180, 90) and (-180, 90)");
  }
  const SourceData d = read_polygons(params(cap));
  ASSERT_EQ(d.polygons.size(), 1u);
  EXPECT_EQ(d.polygons[0].rings.size(), 1u);
}
