#include "gis/read_lines.h"

#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogrsf_frmts.h>

#include "core/error.h"
#include "gis/gdal_env.h"
#include "support/fixtures.h"

using namespace isoquad;
using namespace isoquad::test;

namespace {

std::string feature(const std::string& geometry) {
  return R"({"type":"Feature","properties":{},"geometry":)" + geometry + "}";
}

std::string collection(const std::vector<std::string>& geometries) {
  std::string s = R"({"type":"FeatureCollection","features":[)";
  for (std::size_t i = 0; i < geometries.size(); ++i) s += (i ? "," : "") + feature(geometries[i]);
  return s + "]}";
}

void expect_error(const std::string& path, ErrorClass cls, const std::string& words) {
  try {
    read_lines(path, "", "open boundary");
    ADD_FAILURE() << "no error for " << path;
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), cls) << e.what();
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("open boundary"), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(ReadLines, LinesMultiLinesAndPolygonRings) {
  // A line with a repeated point, a multi-line of two parts, a polygon with a hole and
  // a feature without geometry: five polylines, the rings closed (first point repeated).
  TempDir dir;
  const std::string path = dir.file("lines.geojson");
  write_file(
      path,
      collection({R"({"type":"LineString","coordinates":[[0,0],[1,0],[1,0],[1,1]]})",
                  R"({"type":"MultiLineString","coordinates":[[[2,0],[3,0]],[[4,0],[4,1],[5,1]]]})",
                  R"({"type":"Polygon","coordinates":[[[0,2],[3,2],[3,5],[0,5],[0,2]],)"
                  R"([[1,3],[1,4],[2,4],[1,3]]]})",
                  "null"}));
  const SourceLines s = read_lines(path, "", "open boundary");
  EXPECT_TRUE(s.crs.geographic);
  EXPECT_EQ(s.num_features, 3u);
  ASSERT_EQ(s.lines.size(), 5u);
  EXPECT_EQ(s.lines[0].size(), 3u);  // the repeated point dropped
  EXPECT_EQ(s.lines[1].size(), 2u);
  EXPECT_EQ(s.lines[2].size(), 3u);
  EXPECT_EQ(s.lines[3].size(), 5u);
  EXPECT_EQ(s.lines[4].size(), 4u);
  EXPECT_DOUBLE_EQ(s.lines[3].front().x, s.lines[3].back().x);
  EXPECT_DOUBLE_EQ(s.lines[3].front().y, s.lines[3].back().y);
  EXPECT_DOUBLE_EQ(s.lines[2][2].x, 5.0);
}

TEST(ReadLines, TheFirstLayerOfLinesUnlessOneIsNamed) {
  // A project's GeoPackage: the domain's polygon first, the open boundary's line second.
  TempDir dir;
  const std::string path = dir.file("project.gpkg");
  ensure_gdal_registered();
  {
    GDALDataset* ds = GetGDALDriverManager()->GetDriverByName("GPKG")->Create(path.c_str(), 0, 0, 0,
                                                                              GDT_Unknown, nullptr);
    ASSERT_NE(ds, nullptr);
    OGRSpatialReference srs;
    srs.importFromEPSG(32631);
    const std::pair<const char*, const char*> layers[] = {
        {"domain", "POLYGON ((0 0,10 0,10 10,0 10,0 0))"}, {"open", "LINESTRING (0 0,10 0)"}};
    for (const auto& [name, wkt] : layers) {
      OGRGeometry* g = nullptr;
      OGRGeometryFactory::createFromWkt(wkt, nullptr, &g);
      OGRLayer* l = ds->CreateLayer(name, &srs, wkbFlatten(g->getGeometryType()), nullptr);
      OGRFeature f(l->GetLayerDefn());
      f.SetGeometryDirectly(g);
      ASSERT_EQ(l->CreateFeature(&f), OGRERR_NONE);
    }
    GDALClose(ds);
  }
  SourceLines s = read_lines(path, "", "open boundary");
  EXPECT_EQ(s.layer_name, "open");
  ASSERT_EQ(s.lines.size(), 1u);
  EXPECT_EQ(s.lines[0].size(), 2u);
  EXPECT_TRUE(s.crs.projected);
  s = read_lines(path, "domain", "open boundary");
  ASSERT_EQ(s.lines.size(), 1u);
  EXPECT_EQ(s.lines[0].size(), 5u);  // the ring, closed
  try {
    read_lines(path, "nope", "open boundary");
    ADD_FAILURE() << "no error for a missing layer";
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), ErrorClass::usage);
    EXPECT_NE(std::string(e.what()).find("layers: domain, open"), std::string::npos) << e.what();
  }
}

TEST(ReadLines, SegmentsAcrossTheAntimeridianGoTheShortWay) {
  TempDir dir;
  const std::string path = dir.file("fiji.geojson");
  write_file(
      path,
      collection(
          {R"({"type":"LineString","coordinates":[[179.5,-17],[-179.5,-17],[-179,-18],[179,-18]]})"}));
  const SourceLines s = read_lines(path, "", "open boundary");
  ASSERT_EQ(s.lines.size(), 1u);
  ASSERT_EQ(s.lines[0].size(), 4u);
  EXPECT_DOUBLE_EQ(s.lines[0][1].x, 180.5);
  EXPECT_DOUBLE_EQ(s.lines[0][2].x, 181.0);
  EXPECT_DOUBLE_EQ(s.lines[0][3].x, 179.0);
}

TEST(ReadLines, BadInputsNameTheFileAndTheProblem) {
  TempDir dir;
  expect_error(dir.file("missing.geojson"), ErrorClass::input, "no such file");
  expect_error(points_geojson(dir), ErrorClass::input, "is a Point");
  expect_error(no_crs_csv(dir), ErrorClass::crs, "has no CRS");
  const std::string empty = dir.file("empty_geometry.geojson");
  write_file(empty, collection({"null"}));
  expect_error(empty, ErrorClass::input, "has no line or polygon");
}

// A D-Flow FM .pli has no CRS: it takes the domain's when given, and only then.
TEST(ReadLines, AModellingPackagesLineFileTakesTheDomainsCrs) {
  TempDir dir;
  const std::string path = dir.file("sea.pli");
  write_file(
      path,
      "* the open boundary\nsea\n    3    2\n540000 5000000\n540000 5015000\n540000 5030000\n");
  const CrsInfo utm = parse_crs("EPSG:32630", "--src-crs");
  const SourceLines lines = read_lines(path, "", "open boundary", &utm);
  EXPECT_EQ(lines.layer_name, "sea");
  ASSERT_EQ(lines.lines.size(), 1u);
  EXPECT_EQ(lines.lines[0].size(), 3u);
  EXPECT_EQ(lines.crs.wkt, utm.wkt);
  expect_error(path, ErrorClass::crs, "has no CRS");
}
