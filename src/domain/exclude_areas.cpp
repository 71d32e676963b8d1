#include "domain/exclude_areas.h"

#include <array>

#include "core/error.h"
#include "domain/geos_ops.h"

namespace isoquad {

ExcludeResult exclude_areas(Domain& domain, const std::vector<SourcePolygon>& areas,
                            const ExcludeParams& params) {
  ExcludeResult result;
  if (areas.empty()) return result;
  GeosContext geos;
  GeosGeometry whole = geos.domain_multipolygon(domain);
  const double area_before = area(domain);
  std::vector<GeosGeometry> parts;
  for (const SourcePolygon& sp : areas) {
    GeosGeometry g = geos.polygon(sp.rings);
    const GeosValidity v = geos.validity(g);
    if (!v.valid) {
      if (!params.repair) {
        const Point2 at = params.to_file ? params.to_file(v.location) : v.location;
        throw Error(ErrorClass::input, "domain",
                    params.what + ": feature " + std::to_string(sp.fid) +
                        (sp.part ? " part " + std::to_string(sp.part) : std::string()) +
                        " is invalid: " + v.reason + " at or near " + format_point(at) +
                        "; use --repair to fix it");
      }
      g = geos.make_valid(g);
      ++result.num_repaired;
    }
    // Only those that reach the domain are removed and counted (a file of a whole
    // coast's structures serves many regions).
    if (geos.is_empty(g) || !geos.intersects(g, whole)) continue;
    parts.push_back(std::move(g));
  }
  result.num_polygons = parts.size();
  if (parts.empty()) return result;
  GeosGeometry removed = geos.unary_union(geos.collection(std::move(parts)));
  GeosGeometry left = geos.difference(whole, removed);
  result.removed = geos.polygons(geos.intersection(removed, whole));
  std::vector<Polygon> polygons = geos.polygons(left);
  normalize_polygons(polygons);
  if (polygons.empty())
    throw Error(ErrorClass::input, "domain",
                params.what + ": its polygons cover the whole domain; nothing is left to mesh");
  domain.polygons = std::move(polygons);
  result.area_removed_m2 = area_before - area(domain);
  return result;
}

ExcludedMeshed excluded_area_meshed(const Domain& domain, const std::vector<Polygon>& removed) {
  ExcludedMeshed out;
  out.num_areas = removed.size();
  if (removed.empty() || domain.polygons.empty()) return out;
  GeosContext geos;
  std::vector<GeosGeometry> parts;
  for (const Polygon& p : removed) parts.push_back(geos.polygon_with_holes(p));
  // One overlay for all, then each area against what came back (little, usually).
  GeosGeometry back =
      geos.intersection(geos.domain_multipolygon(domain), geos.multipolygon(std::move(parts)));
  out.area_m2 = geos.area(back);
  if (!(out.area_m2 > 0.0)) return out;
  for (const Polygon& p : removed) {
    const std::array<double, 4> box = bounding_box(p.outer);
    GeosGeometry near = geos.clip_by_rect(back, box[0], box[1], box[2], box[3]);
    if (geos.is_empty(near)) continue;
    if (geos.area(geos.intersection(near, geos.polygon_with_holes(p))) > 0.5 * area(p))
      ++out.num_mostly;
  }
  return out;
}

}  // namespace isoquad
