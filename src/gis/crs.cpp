#include "gis/crs.h"

#include <GeographicLib/Geodesic.hpp>
#include <cpl_conv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "core/error.h"
#include "core/text.h"
#include "gis/gdal_env.h"

namespace isoquad {

namespace {

std::string to_wkt2(const OGRSpatialReference& srs) {
  char* wkt = nullptr;
  const char* options[] = {"FORMAT=WKT2_2019", nullptr};
  srs.exportToWkt(&wkt, options);
  std::string out = wkt ? wkt : "";
  CPLFree(wkt);
  return out;
}

std::unique_ptr<OGRSpatialReference> make_srs(const CrsInfo& crs) {
  auto srs = std::make_unique<OGRSpatialReference>();
  srs->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  if (srs->importFromWkt(crs.wkt.c_str()) != OGRERR_NONE)
    throw Error(ErrorClass::internal, "crs", "cannot re-read a CRS: " + crs.name);
  return srs;
}

}  // namespace

CrsInfo crs_from_srs(const OGRSpatialReference& srs) {
  CrsInfo info;
  info.wkt = to_wkt2(srs);
  const char* name = srs.GetName();
  info.name = name ? name : "unnamed CRS";
  info.geographic = srs.IsGeographic();
  info.projected = srs.IsProjected();
  if (info.projected) info.linear_unit_m = srs.GetLinearUnits();
  return info;
}

CrsInfo parse_crs(const std::string& text, const std::string& what) {
  ensure_gdal_registered();
  if (text.empty()) throw Error(ErrorClass::crs, "crs", what + ": empty CRS");
  OGRSpatialReference srs;
  GdalErrorCapture capture;
  if (srs.SetFromUserInput(text.c_str()) != OGRERR_NONE) {
    std::string detail = capture.last_message();
    throw Error(ErrorClass::crs, "crs",
                what + ": cannot understand CRS '" + text + "'" +
                    (detail.empty() ? "" : " (" + detail + ")") +
                    "; give EPSG:n, WKT, a PROJ string or PROJJSON");
  }
  CrsInfo crs = crs_from_srs(srs);
  // A PROJ string names no CRS (nor a WKT made from one): messages and summaries show
  // the PROJ string instead.
  if (crs.name.empty() || crs.name == "unknown") {
    const std::string proj = crs_proj_string(crs);
    const std::string& shown = proj.empty() ? text : proj;
    crs.name = shown.size() <= 100 ? shown : shown.substr(0, 97) + "...";
  }
  return crs;
}

std::string format_meshing_place(const Point2& p, const std::string& crs_wkt) {
  std::string text = format_point(p) + " in the meshing CRS";
  try {
    const CrsInfo crs = parse_crs(crs_wkt, "the meshing CRS");
    Point2 lonlat = p;
    if (!crs.geographic && !CrsTransform(crs, geographic_base(crs)).transform(lonlat)) return text;
    text += printf_string(", %.5f %c %.5f %c", std::abs(lonlat.y), lonlat.y < 0 ? 'S' : 'N',
                          std::abs(lonlat.x), lonlat.x < 0 ? 'W' : 'E');
  } catch (const Error&) {
  }
  return text;
}

CrsInfo geographic_base(const CrsInfo& crs) {
  auto srs = make_srs(crs);
  std::unique_ptr<OGRSpatialReference> geog(srs->CloneGeogCS());
  if (!geog) throw Error(ErrorClass::crs, "crs", "CRS '" + crs.name + "' has no geographic base");
  geog->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  return crs_from_srs(*geog);
}

std::string crs_proj_string(const CrsInfo& crs) {
  auto srs = make_srs(crs);
  char* proj = nullptr;
  GdalErrorCapture capture;  // some CRSs have no PROJ string form; that is fine
  srs->exportToProj4(&proj);
  std::string out = proj ? proj : "";
  CPLFree(proj);
  return out;
}

std::string crs_esri_wkt(const CrsInfo& crs) {
  const auto srs = make_srs(crs);
  char* wkt = nullptr;
  const char* options[] = {"FORMAT=WKT1_ESRI", nullptr};
  const OGRErr err = srs->exportToWkt(&wkt, options);
  std::string out = wkt ? wkt : "";
  CPLFree(wkt);
  if (err != OGRERR_NONE || out.empty())
    throw Error(ErrorClass::crs, "crs", crs.name + " has no ESRI WKT form");
  return out;
}

bool crs_is_wgs84_lonlat(const CrsInfo& crs) {
  if (!crs.geographic) return false;
  const auto srs = make_srs(crs);
  OGRSpatialReference wgs84;
  wgs84.importFromEPSG(4326);
  const char* options[] = {"CRITERION=EQUIVALENT_EXCEPT_AXIS_ORDER_GEOGCRS",
                           "IGNORE_DATA_AXIS_TO_SRS_AXIS_MAPPING=YES", nullptr};
  return srs->IsSame(&wgs84, options);
}

LocalProjection choose_local_projection(const CrsInfo& geographic,
                                        const std::vector<Point2>& lonlat) {
  if (lonlat.empty()) throw Error(ErrorClass::internal, "crs", "no points to centre a projection");
  // Longitudes may straddle the antimeridian: then work in [0, 360).
  double lo = 1e300, hi = -1e300;
  for (const Point2& p : lonlat) lo = std::min(lo, p.x), hi = std::max(hi, p.x);
  const bool wrap = hi - lo > 180.0;
  double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
  for (const Point2& p : lonlat) {
    const double x = (wrap && p.x < 0) ? p.x + 360.0 : p.x;
    xmin = std::min(xmin, x), xmax = std::max(xmax, x);
    ymin = std::min(ymin, p.y), ymax = std::max(ymax, p.y);
  }
  LocalProjection lp;
  // Rounded so that the CRS text stays short and stable.
  auto round_to = [](double v, double step) { return std::round(v / step) * step; };
  lp.lon0_deg = round_to(0.5 * (xmin + xmax), 1e-4);
  if (lp.lon0_deg > 180.0) lp.lon0_deg -= 360.0;
  lp.lat0_deg = round_to(0.5 * (ymin + ymax), 1e-4);
  // A domain round a pole: the middle of its lon/lat box is no centre (Antarctica's
  // would be at 75 S on the antimeridian). Every longitude: the pole on the side of its
  // middle latitude (a polar cap, a band of latitudes round the globe); a pole but not
  // every longitude (a wedge of the Southern Ocean): the direction of the mean of its
  // points on the sphere.
  constexpr double kDeg = M_PI / 180.0;
  if (xmax - xmin > 180.0) {
    lp.lat0_deg = ymin + ymax >= 0.0 ? 90.0 : -90.0;
    lp.lon0_deg = 0.0;
  } else if (ymax >= 90.0 - 1e-9 || ymin <= -90.0 + 1e-9) {
    double sx = 0.0, sy = 0.0, sz = 0.0;
    for (const Point2& p : lonlat) {
      sx += std::cos(p.y * kDeg) * std::cos(p.x * kDeg);
      sy += std::cos(p.y * kDeg) * std::sin(p.x * kDeg);
      sz += std::sin(p.y * kDeg);
    }
    lp.lat0_deg = round_to(std::atan2(sz, std::hypot(sx, sy)) / kDeg, 1e-4);
    lp.lon0_deg = std::abs(lp.lat0_deg) >= 90.0 ? 0.0 : round_to(std::atan2(sy, sx) / kDeg, 1e-4);
  }

  const GeographicLib::Geodesic& geod = GeographicLib::Geodesic::WGS84();
  double smax = 0.0;
  for (const Point2& p : lonlat) {
    double s12 = 0.0;
    geod.Inverse(lp.lat0_deg, lp.lon0_deg, p.y, p.x, s12);
    smax = std::max(smax, s12);
  }
  lp.max_distance_km = smax / 1000.0;
  // Stereographic scale grows as k0 (1 + c^2/4) with angular distance c; balancing the
  // centre against the farthest point halves the worst length error.
  const double c = smax / 6371008.8;
  lp.scale_factor = round_to(1.0 / (1.0 + c * c / 8.0), 1e-7);

  auto srs = make_srs(geographic);
  // Named with its centre, so that the CRSs of several regions (--each) tell apart in a
  // GIS's list: "isoquad local oblique stereographic 48.0750N 3.6250W".
  srs->SetProjCS(printf_string("isoquad local oblique stereographic %.4f%c %.4f%c",
                               std::abs(lp.lat0_deg), lp.lat0_deg < 0 ? 'S' : 'N',
                               std::abs(lp.lon0_deg), lp.lon0_deg < 0 ? 'W' : 'E')
                     .c_str());
  srs->SetOS(lp.lat0_deg, lp.lon0_deg, lp.scale_factor, 0.0, 0.0);
  srs->SetLinearUnits(SRS_UL_METER, 1.0);
  lp.crs = crs_from_srs(*srs);
  return lp;
}

CrsTransform::CrsTransform(const CrsInfo& from, const CrsInfo& to) {
  ensure_gdal_registered();
  if (from.wkt == to.wkt) {
    identity_ = true;
    return;
  }
  auto a = make_srs(from);
  auto b = make_srs(to);
  // The same CRS written differently (a file's WKT and --dst-crs EPSG:xxxx): no
  // transformation, so that the coordinates stay bit for bit what they were.
  if (a->IsSame(b.get())) {
    identity_ = true;
    return;
  }
  GdalErrorCapture capture;
  ct_.reset(OGRCreateCoordinateTransformation(a.get(), b.get()));
  if (!ct_)
    throw Error(ErrorClass::crs, "crs",
                "no transformation from '" + from.name + "' to '" + to.name + "'" +
                    (capture.last_message().empty() ? "" : ": " + capture.last_message()));
}

CrsTransform::~CrsTransform() = default;

long CrsTransform::transform(std::vector<Point2>& points) const {
  if (!identity_ && !points.empty()) {
    std::vector<double> xs(points.size()), ys(points.size());
    std::vector<int> ok(points.size(), 0);
    for (std::size_t i = 0; i < points.size(); ++i) xs[i] = points[i].x, ys[i] = points[i].y;
    GdalErrorCapture capture;  // failures are reported per point below
    ct_->Transform(points.size(), xs.data(), ys.data(), nullptr, ok.data());
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (!ok[i] || !std::isfinite(xs[i]) || !std::isfinite(ys[i])) return static_cast<long>(i);
      points[i] = {xs[i], ys[i]};
    }
  }
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!std::isfinite(points[i].x) || !std::isfinite(points[i].y)) return static_cast<long>(i);
  return -1;
}

bool CrsTransform::transform(Point2& p) const {
  std::vector<Point2> v{p};
  if (transform(v) >= 0) return false;
  p = v[0];
  return true;
}

bool crs_area_of_use(const CrsInfo& crs, double bounds[4]) {
  auto srs = make_srs(crs);
  const char* name = nullptr;
  return srs->GetAreaOfUse(&bounds[0], &bounds[1], &bounds[2], &bounds[3], &name) &&
         bounds[0] > -1000.0;
}

int epsg_code(const std::string& wkt) {
  OGRSpatialReference srs;
  if (wkt.empty() || srs.importFromWkt(wkt.c_str()) != OGRERR_NONE) return 0;
  const char* authority = srs.GetAuthorityName(nullptr);
  const char* code = srs.GetAuthorityCode(nullptr);
  if (!authority || !code || std::strcmp(authority, "EPSG") != 0) return 0;
  return std::atoi(code);
}

}  // namespace isoquad
