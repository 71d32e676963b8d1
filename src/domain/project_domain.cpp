#include "domain/project_domain.h"

#include <sstream>

#include "core/error.h"

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

}  // namespace

ProjectResult project_domain(const std::vector<Polygon>& polygons, const CrsInfo& source_crs,
                             const ProjectParams& params) {
  ProjectResult result;
  CrsInfo target;
  if (!params.dst_crs.empty()) {
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
    // Centre the projection on the domain, in the source's own geographic CRS.
    const CrsInfo geog = geographic_base(source_crs);
    CrsTransform to_geog(source_crs, geog);
    std::vector<Point2> lonlat;
    for (const Polygon& p : polygons) lonlat.insert(lonlat.end(), p.outer.begin(), p.outer.end());
    if (to_geog.transform(lonlat) >= 0)
      throw Error(ErrorClass::crs, "crs", "cannot convert the domain to longitude and latitude");
    result.local = choose_local_projection(geog, lonlat);
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
  for (Polygon& p : projected) orient_polygon(p);
  sort_by_area(projected);
  result.domain.polygons = std::move(projected);
  result.domain.crs_wkt = target.wkt;
  result.domain.crs_name = target.name;
  return result;
}

}  // namespace isoquad
