#include "gis/write_domain.h"

#include <filesystem>

#include "core/error.h"
#include "core/text.h"
#include "gis/crs.h"
#include "gis/vector_writer.h"

namespace isoquad {

namespace {

// The OGR driver for the path's extension; empty for another.
std::string domain_driver(const std::string& path) {
  const std::string ext = lower_case(std::filesystem::path(path).extension().string());
  if (ext == ".gpkg") return "GPKG";
  if (ext == ".fgb") return "FlatGeobuf";
  if (ext == ".geojson" || ext == ".json") return "GeoJSON";
  return "";
}

}  // namespace

bool is_domain_output(const std::string& path) {
  return !domain_driver(path).empty();
}

void write_domain(const Domain& domain, const WriteDomainParams& params) {
  const std::string driver =
      domain_driver(params.final_path.empty() ? params.path : params.final_path);
  if (driver.empty())
    throw Error(ErrorClass::usage, "options",
                "'" + params.final_path + "': the domain is written as .gpkg, .fgb or .geojson");
  const bool lonlat = driver == "GeoJSON";
  const CrsInfo wgs84 = parse_crs("EPSG:4326", "GeoJSON");
  std::vector<std::string> options;
  if (lonlat) options.push_back("RFC7946=YES");
  VectorWriter w(params.path, params.overwrite, lonlat ? wgs84.wkt : domain.crs_wkt, driver,
                 options);
  std::unique_ptr<CrsTransform> to_lonlat;
  if (lonlat)
    to_lonlat = std::make_unique<CrsTransform>(CrsInfo{domain.crs_wkt, domain.crs_name}, wgs84);
  w.begin_layer(params.layer, GeometryKind::polygon,
                {{"component", FieldType::integer},
                 {"area_m2", FieldType::real},
                 {"perimeter_m", FieldType::real},
                 {"num_holes", FieldType::integer},
                 {"num_vertices", FieldType::integer}});
  for (std::size_t i = 0; i < domain.polygons.size(); ++i) {
    const Polygon& p = domain.polygons[i];
    Polygon shown = p;
    if (to_lonlat) {
      auto transform = [&](Ring& ring, const Ring& original) {
        const long bad = to_lonlat->transform(ring);
        if (bad >= 0)
          throw Error(ErrorClass::crs, "write",
                      "'" + params.final_path + "': vertex " + format_point(original[bad]) +
                          " of the domain has no longitude and latitude");
      };
      transform(shown.outer, p.outer);
      for (std::size_t h = 0; h < shown.holes.size(); ++h) transform(shown.holes[h], p.holes[h]);
    }
    w.add_polygon(shown, {FieldValue::integer(static_cast<long long>(i)), FieldValue::real(area(p)),
                          FieldValue::real(perimeter(p)),
                          FieldValue::integer(static_cast<long long>(p.holes.size())),
                          FieldValue::integer(static_cast<long long>(num_vertices(p)))});
  }
  if (driver == "GPKG" && params.open_parts && !params.open_parts->empty()) {
    w.begin_layer("open_boundary", GeometryKind::line,
                  {{"id", FieldType::integer}, {"length_m", FieldType::real}});
    for (std::size_t k = 0; k < params.open_parts->size(); ++k) {
      const std::vector<Point2>& line = (*params.open_parts)[k];
      w.add_line(line, {FieldValue::integer(static_cast<long long>(k)),
                        FieldValue::real(polyline_length(line))});
    }
  }
  w.commit();
}

}  // namespace isoquad
