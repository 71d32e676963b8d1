#include "domain/narrow_features.h"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "domain/geos_ops.h"

namespace isoquad {

namespace {

GeosGeometry to_geos(GeosContext& geos, const Polygon& p) {
  std::vector<Ring> rings{p.outer};
  rings.insert(rings.end(), p.holes.begin(), p.holes.end());
  return geos.polygon(rings);
}

// Components and holes: what the domain's topology is, for the comparison below.
std::pair<std::size_t, std::size_t> topology(const std::vector<Polygon>& polygons) {
  std::size_t holes = 0;
  for (const Polygon& p : polygons) holes += p.holes.size();
  return {polygons.size(), holes};
}

// The pieces of `g` larger than min_area, largest first.
std::vector<Polygon> pieces(GeosContext& geos, const GeosGeometry& g, double min_area) {
  std::vector<Polygon> out;
  for (Polygon& p : geos.polygons(g))
    if (std::abs(signed_area(p.outer)) >= min_area) out.push_back(std::move(p));
  std::stable_sort(out.begin(), out.end(), [](const Polygon& a, const Polygon& b) {
    return std::abs(signed_area(a.outer)) > std::abs(signed_area(b.outer));
  });
  return out;
}

}  // namespace

NarrowResult remove_narrow_features(Domain& domain, const NarrowParams& params) {
  NarrowResult result;
  result.num_components_before = result.num_components_after = domain.polygons.size();
  if (!(params.min_width_m > 0) || domain.polygons.empty()) return result;
  const double r = 0.5 * params.min_width_m;
  // Offsetting moves vertices by rounding errors; pieces below this area are such noise.
  const double negligible = 1e-4 * params.min_width_m * params.min_width_m;

  GeosContext geos;
  std::vector<GeosGeometry> parts;
  for (const Polygon& p : domain.polygons) parts.push_back(to_geos(geos, p));
  const GeosGeometry original = geos.multipolygon(std::move(parts));
  const GeosGeometry opened = geos.buffer_mitre(
      geos.buffer_mitre(original, -r, params.mitre_limit), r, params.mitre_limit);
  const GeosGeometry closed = geos.buffer_mitre(
      geos.buffer_mitre(opened, r, params.mitre_limit), -r, params.mitre_limit);

  const std::vector<Polygon> removed = pieces(geos, geos.difference(original, closed), negligible);
  const std::vector<Polygon> added = pieces(geos, geos.difference(closed, original), negligible);
  if (removed.empty() && added.empty()) return result;

  std::vector<Polygon> polygons = geos.polygons(closed);
  if (polygons.empty())
    throw Error(ErrorClass::input, "narrow features",
                "every part of the domain is narrower than the minimum width " +
                    std::to_string(params.min_width_m) + " m; nothing is left to mesh");
  const auto original_topology = topology(domain.polygons);
  if (topology(polygons) == original_topology) {
    for (const Polygon& p : removed) result.area_removed_m2 += std::abs(signed_area(p.outer));
    for (const Polygon& p : added) result.area_added_m2 += std::abs(signed_area(p.outer));
    result.num_pieces = removed.size() + added.size();
  } else {
    // Some piece would cut an isthmus, join components or open or close a hole (in a
    // water domain: flood a narrow land bridge). The pieces are applied one by one and
    // those that change the topology are left out, so the domain keeps its components
    // and holes: connections are the user's to change (--min-width 0 turns this off).
    GeosGeometry current = geos.multipolygon({});
    {
      std::vector<GeosGeometry> again;
      for (const Polygon& p : domain.polygons) again.push_back(to_geos(geos, p));
      current = geos.multipolygon(std::move(again));
    }
    auto apply = [&](const std::vector<Polygon>& list, bool add, double& area) {
      for (const Polygon& p : list) {
        const GeosGeometry piece = to_geos(geos, p);
        GeosGeometry next = add ? geos.union_of(current, piece) : geos.difference(current, piece);
        if (topology(geos.polygons(next)) != original_topology) {
          ++result.num_pieces_kept;
          continue;
        }
        current = std::move(next);
        area += std::abs(signed_area(p.outer));
        ++result.num_pieces;
      }
    };
    apply(removed, false, result.area_removed_m2);
    apply(added, true, result.area_added_m2);
    if (result.num_pieces == 0) return result;
    // A piece's sides lie on the original boundary up to rounding, so the overlays can
    // leave slivers and zero-width spikes or cracks along them: an opening then a
    // closing far below the width removes those.
    const double eps = 1e-3 * params.min_width_m;
    current = geos.buffer_mitre(geos.buffer_mitre(current, -eps, params.mitre_limit), eps,
                                params.mitre_limit);
    current = geos.buffer_mitre(geos.buffer_mitre(current, eps, params.mitre_limit), -eps,
                                params.mitre_limit);
    polygons = geos.polygons(current);
  }
  for (Polygon& p : polygons) orient_polygon(p);
  sort_by_area(polygons);
  domain.polygons = std::move(polygons);
  result.num_components_after = domain.polygons.size();
  result.changed = true;
  return result;
}

}  // namespace isoquad
