#include "domain/exclude_areas.h"

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
  std::vector<Polygon> polygons = geos.polygons(left);
  remove_duplicates_and_spikes(polygons);
  if (polygons.empty())
    throw Error(ErrorClass::input, "domain",
                params.what + ": its polygons cover the whole domain; nothing is left to mesh");
  for (Polygon& p : polygons) {
    orient_polygon(p);
    start_at_lowest_vertex(p.outer);
    for (Ring& h : p.holes) start_at_lowest_vertex(h);
  }
  sort_by_area(polygons);
  domain.polygons = std::move(polygons);
  result.area_removed_m2 = area_before - area(domain);
  return result;
}

}  // namespace isoquad
