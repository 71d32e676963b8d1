// Coordinate reference systems: parsing user text, the automatic local metric
// projection, and point transformation (PROJ, through OGR).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/geometry.h"

class OGRSpatialReference;
class OGRCoordinateTransformation;

namespace isoquad {

// A CRS held as WKT2 text; cheap to copy, plain to pass between stages.
struct CrsInfo {
  std::string wkt;
  std::string name;
  bool geographic = false;
  bool projected = false;
  double linear_unit_m = 1.0;  // metres per unit of a projected CRS
};

// Parses any CRS text GDAL/PROJ accept (EPSG:n, WKT, PROJ string, PROJJSON).
// `what` names the option or file in the error message. Throws Error(crs).
CrsInfo parse_crs(const std::string& text, const std::string& what);
// The CRS given as OGR's WKT (e.g. from a layer).
CrsInfo crs_from_srs(const OGRSpatialReference& srs);
// The geographic (lon/lat) CRS a CRS is based on.
CrsInfo geographic_base(const CrsInfo& crs);
// A proj4-style one-line description, for summaries.
std::string crs_proj_string(const CrsInfo& crs);
// The CRS as ESRI's WKT 1 (one line, as .prj files and DHI's MIKE files hold it).
// Error(crs) when it has none.
std::string crs_esri_wkt(const CrsInfo& crs);
// Longitudes and latitudes on WGS 84 (EPSG:4326, either axis order).
bool crs_is_wgs84_lonlat(const CrsInfo& crs);
// The EPSG code of a CRS (its WKT) that names one, else 0.
int epsg_code(const std::string& wkt);

// The automatic meshing CRS: an oblique stereographic projection (conformal, so
// squares stay squares) centred on the domain, with its scale factor chosen so that
// the scale error is balanced between the centre and the farthest point. `lonlat`
// are the domain's points in `geographic` (degrees, lon first).
struct LocalProjection {
  CrsInfo crs;
  double lon0_deg = 0.0;
  double lat0_deg = 0.0;
  double scale_factor = 1.0;
  double max_distance_km = 0.0;  // farthest point from the centre
};
LocalProjection choose_local_projection(const CrsInfo& geographic,
                                        const std::vector<Point2>& lonlat);

// Transforms points between two CRSs, x = easting / longitude (GIS axis order).
class CrsTransform {
 public:
  CrsTransform(const CrsInfo& from, const CrsInfo& to);
  ~CrsTransform();
  CrsTransform(const CrsTransform&) = delete;
  CrsTransform& operator=(const CrsTransform&) = delete;

  // Transforms in place. Returns the index of the first point that failed (not
  // transformable or not finite), or -1 when all succeeded.
  long transform(std::vector<Point2>& points) const;
  // Transforms one point; false when it fails.
  bool transform(Point2& p) const;

 private:
  std::unique_ptr<OGRCoordinateTransformation> ct_;
  bool identity_ = false;
};

// A place in a message: "(x, y) in the meshing CRS, 52.36710 N 4.88120 E", the point in
// `crs_wkt` (the meshing CRS's WKT) and its latitude and longitude, which a user finds on
// a map; the latter left out where the CRS has none.
std::string format_meshing_place(const Point2& p, const std::string& crs_wkt);

// The CRS's area of use in degrees (west, south, east, north); false when unknown.
bool crs_area_of_use(const CrsInfo& crs, double bounds[4]);

}  // namespace isoquad
