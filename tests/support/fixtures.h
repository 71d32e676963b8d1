// Small input files, good and bad, written into a temporary directory. Shared by the
// reader's unit tests and the CLI tests.
#pragma once

#include <string>

#include "support/test_support.h"

namespace isoquad::test {

// Two lon/lat squares in the Bay of Biscay area, valid.
inline std::string good_geojson(const TempDir& d) {
  const std::string path = d.file("good.geojson");
  write_file(path, geojson_polygons({"[[[-3,47],[-2,47],[-2,48],[-3,48],[-3,47]]]",
                                     "[[[-1,47],[0,47],[0,48],[-1,48],[-1,47]]]"}));
  return path;
}

inline std::string bowtie_geojson(const TempDir& d) {
  const std::string path = d.file("bowtie.geojson");
  write_file(path, geojson_polygons({"[[[-3,47],[-2,48.5],[-2,47],[-3,48],[-3,47]]]"}));
  return path;
}

inline std::string unclosed_geojson(const TempDir& d) {
  const std::string path = d.file("unclosed.geojson");
  write_file(path, geojson_polygons({"[[[-3,47],[-2,47],[-2,48],[-3,48]]]"}));
  return path;
}

inline std::string out_of_range_geojson(const TempDir& d) {
  const std::string path = d.file("latitude120.geojson");
  write_file(path, geojson_polygons({"[[[-3,117],[-2,117],[-2,120],[-3,120],[-3,117]]]"}));
  return path;
}

// Lon/lat numbers labelled as Lambert-93 metres: far outside that CRS's area of use.
inline std::string wrong_crs_geojson(const TempDir& d) {
  const std::string path = d.file("wrong_crs.geojson");
  write_file(path, geojson_polygons({"[[[-3,47],[-2,47],[-2,48],[-3,48],[-3,47]]]"},
                                    "\"crs\":{\"type\":\"name\",\"properties\":{\"name\":"
                                    "\"urn:ogc:def:crs:EPSG::2154\"}},"));
  return path;
}

inline std::string points_geojson(const TempDir& d) {
  const std::string path = d.file("points.geojson");
  write_file(path,
             "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\","
             "\"properties\":{},\"geometry\":{\"type\":\"Point\",\"coordinates\":[1,2]}}]}");
  return path;
}

// A CSV with a WKT column: OGR reads it, and it has no CRS.
inline std::string no_crs_csv(const TempDir& d) {
  const std::string path = d.file("no_crs.csv");
  write_file(path,
             "WKT,id\n\"POLYGON ((700000 6600000,701000 6600000,701000 6601000,"
             "700000 6601000,700000 6600000))\",1\n");
  return path;
}

inline std::string corrupt_shapefile(const TempDir& d) {
  const std::string path = d.file("corrupt.shp");
  write_file(path, std::string("this is not a shapefile\0\x01\x02\x03", 28));
  return path;
}

inline std::string empty_file(const TempDir& d) {
  const std::string path = d.file("empty.geojson");
  write_file(path, "");
  return path;
}

// A polygon with a NaN (or infinite) coordinate. OGR's GeoJSON reader accepts the
// NaN and Infinity literals, as some writers produce them.
inline std::string non_finite_geojson(const TempDir& d, bool infinite = false) {
  const std::string path = d.file(infinite ? "infinite.geojson" : "nan.geojson");
  const std::string bad = infinite ? "Infinity" : "NaN";
  write_file(path, geojson_polygons({"[[[-3,47],[-2,47],[" + bad + ",48],[-3,48],[-3,47]]]"}));
  return path;
}

}  // namespace isoquad::test
