// Zones of a quad mesh (app/quad_zones.h): the first polygon holding each quad's centroid,
// holes left out; the file's values checked.
#include "app/quad_zones.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/error.h"
#include "support/test_support.h"

using namespace isoquad;
using namespace isoquad::test;

namespace {

// 10 x 5 quads of 100 m from (500000, 5000000), in UTM 31N.
QuadMesh grid() {
  QuadMesh m;
  for (int j = 0; j <= 5; ++j)
    for (int i = 0; i <= 10; ++i) m.points.push_back({500000 + 100.0 * i, 5000000 + 100.0 * j});
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 10; ++i) {
      const int a = j * 11 + i;
      m.quads.push_back({a, a + 1, a + 12, a + 11});
    }
  return m;
}

// A GeoJSON in UTM 31N of features {geometry, properties} given as raw JSON.
std::string zones_file(const TempDir& dir, const std::vector<std::string>& features) {
  std::string s =
      std::string("{\"type\":\"FeatureCollection\",") + kUtm31nCrsMember + "\"features\":[";
  for (std::size_t i = 0; i < features.size(); ++i)
    s += (i ? "," : "") + std::string("{\"type\":\"Feature\",") + features[i] + "}";
  write_file(dir.file("zones.geojson"), s + "]}");
  return dir.file("zones.geojson");
}

std::string box(double x0, double y0, double x1, double y1) {
  auto pt = [](double x, double y) {
    return "[" + std::to_string(500000 + x) + "," + std::to_string(5000000 + y) + "]";
  };
  return "[" + pt(x0, y0) + "," + pt(x1, y0) + "," + pt(x1, y1) + "," + pt(x0, y1) + "," +
         pt(x0, y0) + "]";
}

}  // namespace

TEST(QuadZones, TheFirstPolygonHoldingTheCentroidGivesTheZone) {
  TempDir dir;
  ZonesSource source;
  // Zone 2 over the west half with a hole of 2 x 2 quads, then zone 5 over the east half
  // and one column of the west: that column stays in zone 2, the first in the file.
  source.path = zones_file(
      dir, {"\"properties\":{\"zone\":2},\"geometry\":{\"type\":\"Polygon\",\"coordinates\":[" +
                box(0, 0, 500, 500) + "," + box(100, 100, 300, 300) + "]}",
            "\"properties\":{\"zone\":5},\"geometry\":{\"type\":\"Polygon\",\"coordinates\":[" +
                box(400, -10, 1010, 510) + "]}"});
  const QuadMesh m = grid();
  const QuadZones z = quad_zones(source, parse_crs("EPSG:32631", "t"), m);
  ASSERT_EQ(z.zone.size(), m.quads.size());
  EXPECT_EQ(z.num_polygons, 2u);
  for (std::size_t q = 0; q < m.quads.size(); ++q) {
    const int column = static_cast<int>(q % 10), row = static_cast<int>(q / 10);
    const bool hole = column >= 1 && column <= 2 && row >= 1 && row <= 2;
    EXPECT_EQ(z.zone[q], column < 5 ? (hole ? 0 : 2) : 5) << column << " " << row;
  }
  EXPECT_EQ(z.counts.at(0), 4u);
  EXPECT_EQ(z.counts.at(2), 21u);
  EXPECT_EQ(z.counts.at(5), 25u);
  // The mesh in another CRS (Web Mercator): the polygons follow it, the same zones.
  QuadMesh mercator = m;
  const CrsInfo utm = parse_crs("EPSG:32631", "t"), web = parse_crs("EPSG:3857", "t");
  ASSERT_LT(CrsTransform(utm, web).transform(mercator.points), 0);
  EXPECT_EQ(quad_zones(source, web, mercator).zone, z.zone);
}

TEST(QuadZones, ZonesAreWholeNumbersOnPolygons) {
  const QuadMesh m = grid();
  const std::string polygon =
      ",\"geometry\":{\"type\":\"Polygon\",\"coordinates\":[" + box(0, 0, 500, 500) + "]}";
  for (const auto& [feature, expected] : std::vector<std::pair<std::string, std::string>>{
           {"\"properties\":{\"zone\":0}" + polygon, "zones are whole numbers, 1 or more"},
           {"\"properties\":{\"zone\":1.5}" + polygon, "zones are whole numbers, 1 or more"},
           {"\"properties\":{\"zone\":\"a\"}" + polygon, "zones are whole numbers, 1 or more"},
           {"\"properties\":{\"zone\":1},\"geometry\":{\"type\":\"LineString\","
            "\"coordinates\":[[500000,5000000],[500100,5000100]]}",
            "zones are polygons"},
           {"\"properties\":{\"class\":1}" + polygon, "has no attribute 'zone' for the zones"}}) {
    TempDir dir;
    ZonesSource source;
    source.path = zones_file(dir, {feature});
    try {
      quad_zones(source, parse_crs("EPSG:32631", "t"), m);
      ADD_FAILURE() << "no error for " << feature;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("--zones"), std::string::npos) << e.what();
    }
  }
}
