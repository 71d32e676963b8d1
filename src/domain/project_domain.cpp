#include "domain/project_domain.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.h"
#include "core/text.h"
#include "gis/map_scale.h"

namespace isoquad {

namespace {

// Applies `t` to every ring; returns false at the first point that fails.
bool transform_all(const CrsTransform& t, std::vector<Polygon>& polys, Point2* failed) {
  for (Polygon& p : polys) {
    std::vector<Ring*> rings{&p.outer};
    for (Ring& h : p.holes) rings.push_back(&h);
    for (Ring* r : rings) {
      Ring original = *r;
      const long bad = t.transform(*r);
      if (bad >= 0) {
        *failed = original[bad];
        return false;
      }
    }
  }
  return true;
}

// A projected source CRS in metres is kept as the meshing CRS where, over the domain, it
// is conformal (squares stay squares: both steps scaled alike within 0.1%, at right
// angles within 0.1 degree) and true to the ground's scale within 1% (the automatic
// projection's error at 2,000 km from its centre). UTM within its zone strays by 0.04 to
// 0.1%, Lambert-93 over France by 0.3%; Web Mercator at 48 N by 49%, and an equal-area or
// equidistant CRS is not conformal away from its centre: those domains get the local
// projection, and the summary says why.
constexpr double kKeptScaleError = 0.01, kKeptAnisotropy = 1e-3, kKeptSkewDeg = 0.1;

// Empty when `crs` can serve as the meshing CRS over `points`, else why not.
std::string why_not_kept(const CrsInfo& crs, const std::vector<Point2>& points) {
  if (!crs.projected) return "";
  if (std::abs(crs.linear_unit_m - 1.0) > 1e-12) return "it is not in metres";
  const CrsDistortion d = crs_distortion(crs, points);
  if (!d.measured) return "its points cannot be converted to longitude and latitude";
  std::string why;
  if (d.max_scale_error > kKeptScaleError)
    why = printf_string("its scale strays by up to %.2g%% from the ground's over the domain",
                        100.0 * d.max_scale_error);
  if (d.max_anisotropy > kKeptAnisotropy || d.max_skew_deg > kKeptSkewDeg)
    why += printf_string(
        "%s (lengths along x and y differ by up to %.2g%%, their angle departs from 90 "
        "degrees by up to %.2g)",
        why.empty() ? "it is not conformal over the domain" : ", and it is not conformal",
        100.0 * d.max_anisotropy, d.max_skew_deg);
  return why;
}

}  // namespace

ProjectResult project_domain(const std::vector<Polygon>& polygons, const CrsInfo& source_crs,
                             const ProjectParams& params) {
  ProjectResult result;
  CrsInfo target;
  std::vector<Point2> outer_points;
  for (const Polygon& p : polygons)
    outer_points.insert(outer_points.end(), p.outer.begin(), p.outer.end());
  if (params.dst_crs.empty() && source_crs.projected) {
    result.source_not_kept = why_not_kept(source_crs, outer_points);
    result.source_kept = result.source_not_kept.empty();
  }
  // The domain in the source's own geographic CRS `geog`, for the automatic projections
  // (only they need one: an explicit --dst-crs asks nothing of the source's base).
  auto lonlat_points = [&](const CrsInfo& geog) {
    std::vector<Point2> lonlat = outer_points;
    if (CrsTransform(source_crs, geog).transform(lonlat) >= 0)
      throw Error(ErrorClass::crs, "crs", "cannot convert the domain to longitude and latitude");
    return lonlat;
  };
  if (result.source_kept) {
    target = source_crs;
  } else if (params.dst_crs == "utm") {
    // The zone of the domain's centre (as the local projection finds it: across the
    // antimeridian, round a pole), on WGS 84.
    const CrsInfo geog = geographic_base(source_crs);
    const LocalProjection centre = choose_local_projection(geog, lonlat_points(geog));
    if (centre.lat0_deg > 84.0 || centre.lat0_deg < -80.0)
      throw Error(ErrorClass::crs, "crs",
                  printf_string("--dst-crs utm: the domain's centre lies at %.4g degrees of "
                                "latitude, beyond UTM's 80 S to 84 N; give a polar CRS "
                                "(EPSG:3413, EPSG:3031) or --dst-crs local",
                                centre.lat0_deg));
    const int zone =
        std::clamp(static_cast<int>(std::floor((centre.lon0_deg + 180.0) / 6.0)) + 1, 1, 60);
    target = parse_crs("EPSG:" + std::to_string((centre.lat0_deg >= 0.0 ? 32600 : 32700) + zone),
                       "--dst-crs utm");
  } else if (!params.dst_crs.empty() && params.dst_crs != "local") {
    target = parse_crs(params.dst_crs, "--dst-crs");
    if (!target.projected)
      throw Error(ErrorClass::crs, "crs",
                  "--dst-crs '" + params.dst_crs + "' (" + target.name +
                      ") is not a projected CRS; meshing needs planar coordinates in metres");
    if (std::abs(target.linear_unit_m - 1.0) > 1e-12)
      throw Error(ErrorClass::crs, "crs",
                  "--dst-crs '" + params.dst_crs + "' (" + target.name +
                      ") is not in metres; choose a projected CRS in metres");
  } else {
    // Centred on the domain.
    const CrsInfo geog = geographic_base(source_crs);
    result.local = choose_local_projection(geog, lonlat_points(geog));
    target = result.local->crs;
  }

  std::vector<Polygon> projected = polygons;
  // Longitude 180 read as -180: the same point once projected, bit for bit, so that a
  // ring closed through a pole (select_domain), which goes down the 180th meridian and
  // comes back up at -180, comes back along exactly the same points (a spike, removed
  // below).
  auto antimeridian_west = [](Ring& r) {
    for (Point2& q : r)
      if (q.x == 180.0) q.x = -180.0;
  };
  if (source_crs.geographic)
    for (Polygon& p : projected) {
      antimeridian_west(p.outer);
      for (Ring& h : p.holes) antimeridian_west(h);
    }
  CrsTransform t(source_crs, target);
  Point2 failed;
  if (!transform_all(t, projected, &failed))
    throw Error(ErrorClass::crs, "crs",
                "point " + format_point(failed) + " cannot be transformed from '" + source_crs.name +
                    "' to '" + target.name + "'");
  // Points that are one once projected (every point at a pole; see above for the
  // antimeridian) leave duplicates and spikes.
  remove_duplicates_and_spikes(projected);
  if (params.dst_crs == "utm") {
    std::vector<Point2> points;
    for (const Polygon& p : projected) points.insert(points.end(), p.outer.begin(), p.outer.end());
    const CrsDistortion d = crs_distortion(target, points);
    if (d.max_scale_error > kKeptScaleError)
      result.warning = printf_string(
          "--dst-crs utm (%s): the domain reaches where that zone's scale strays by up to "
          "%.2g%% from the ground's; consider --dst-crs local",
          target.name.c_str(), 100.0 * d.max_scale_error);
  }
  for (Polygon& p : projected) orient_polygon(p);
  sort_by_area(projected);
  result.domain.polygons = std::move(projected);
  result.domain.crs_wkt = target.wkt;
  result.domain.crs_name = target.name;
  return result;
}

}  // namespace isoquad
