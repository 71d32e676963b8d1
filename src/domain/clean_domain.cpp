#include "domain/clean_domain.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace isoquad {

CleanResult clean_domain(Domain& domain, const CleanParams& params) {
  CleanResult result;
  if (params.largest && domain.polygons.size() > 1) {
    result.num_components_dropped = domain.polygons.size() - 1;
    domain.polygons.resize(1);
  }
  auto& polys = domain.polygons;
  const std::size_t before = polys.size();
  polys.erase(std::remove_if(polys.begin(), polys.end(),
                             [&](const Polygon& p) {
                               return std::abs(signed_area(p.outer)) < params.min_island_area_m2;
                             }),
              polys.end());
  result.num_islands_dropped = before - polys.size();
  for (Polygon& p : polys) {
    const std::size_t nh = p.holes.size();
    p.holes.erase(std::remove_if(p.holes.begin(), p.holes.end(),
                                 [&](const Ring& h) {
                                   return std::abs(signed_area(h)) < params.min_hole_area_m2;
                                 }),
                  p.holes.end());
    result.num_holes_dropped += nh - p.holes.size();
  }
  if (polys.empty())
    throw Error(ErrorClass::input, "domain",
                "every component is smaller than --min-island-area; nothing is left to mesh");
  return result;
}

}  // namespace isoquad
