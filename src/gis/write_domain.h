// Writes the cleaned planar domain as a layer of polygons: a GeoPackage, a FlatGeobuf
// (in the domain's CRS) or a GeoJSON (in longitudes and latitudes, RFC 7946), by the
// path's extension.
#pragma once

#include <string>
#include <vector>

#include "core/geometry.h"

namespace isoquad {

struct WriteDomainParams {
  std::string path;  // .gpkg, .fgb, .geojson or .json
  // The driver is chosen by this name's extension (path may be a temporary file's).
  std::string final_path;
  std::string layer = "domain";
  bool overwrite = false;
  // The boundary's open parts (FrontEndResult::open_boundary_parts), written in a
  // GeoPackage as the layer `open_boundary` (lines: id, length_m) when not empty.
  const std::vector<std::vector<Point2>>* open_parts = nullptr;
};

// Whether the path names a format write_domain writes (.gpkg, .fgb, .geojson, .json).
bool is_domain_output(const std::string& path);

// One feature per component: polygon with holes, fields component, area_m2,
// perimeter_m, num_holes, num_vertices (measured in the domain's CRS); in a GeoPackage
// also the open parts. Written
// atomically. Throws Error(output), Error(crs) when a vertex has no longitude and
// latitude for a GeoJSON.
void write_domain(const Domain& domain, const WriteDomainParams& params);

}  // namespace isoquad
