#include "gis/write_domain.h"

#include <cmath>
#include <filesystem>

#include "core/error.h"
#include "core/text.h"
#include "gis/crs.h"
#include "gis/layer_styles.h"
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

// A polygon in longitudes that crosses the antimeridian (an edge over 180 degrees of
// longitude long) with its longitudes in [0, 360) instead, continuous, for RFC 7946's
// writer to cut at 180 degrees (as the mesh's GeoJSON is); one round a pole stays.
void unwrap_longitudes(Polygon& polygon) {
  auto jumps = [](const Polygon& p) {
    auto ring_jumps = [](const Ring& r) {
      for (std::size_t i = 0; i < r.size(); ++i)
        if (std::abs(r[i].x - r[(i + 1) % r.size()].x) > 180.0) return true;
      return false;
    };
    if (ring_jumps(p.outer)) return true;
    for (const Ring& h : p.holes)
      if (ring_jumps(h)) return true;
    return false;
  };
  if (!jumps(polygon)) return;
  Polygon shifted = polygon;
  auto shift = [](Ring& r) {
    for (Point2& q : r)
      if (q.x < 0) q.x += 360.0;
  };
  shift(shifted.outer);
  for (Ring& h : shifted.holes) shift(h);
  if (!jumps(shifted)) polygon = std::move(shifted);
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
                 {"num_vertices", FieldType::integer}},
                {"isoquad domain: " + params.layer,
                 "The domain to mesh, in components (area and perimeter in metres in the "
                 "meshing CRS)."});
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
      unwrap_longitudes(shown);
    }
    w.add_polygon(shown, {FieldValue::integer(static_cast<long long>(i)), FieldValue::real(area(p)),
                          FieldValue::real(perimeter(p)),
                          FieldValue::integer(static_cast<long long>(p.holes.size())),
                          FieldValue::integer(static_cast<long long>(num_vertices(p)))});
  }
  if (driver == "GPKG" && params.open_parts && !params.open_parts->empty()) {
    w.begin_layer("open_boundary", GeometryKind::line,
                  {{"id", FieldType::integer}, {"length_m", FieldType::real}},
                  {"isoquad domain: open boundary",
                   "The runs of the domain's boundary that are open (sea), the rest land."});
    for (std::size_t k = 0; k < params.open_parts->size(); ++k) {
      const std::vector<Point2>& line = (*params.open_parts)[k];
      w.add_line(line, {FieldValue::integer(static_cast<long long>(k)),
                        FieldValue::real(polyline_length(line))});
    }
  }
  if (driver == "GPKG") {
    std::vector<const LayerStyle*> styles;
    for (const LayerStyle& s : domain_styles())
      if (std::string(s.layer) == params.layer ||
          (std::string(s.layer) == "open_boundary" && params.open_parts &&
           !params.open_parts->empty()))
        styles.push_back(&s);
    write_layer_styles(w, styles);
  }
  w.commit();
}

}  // namespace isoquad
