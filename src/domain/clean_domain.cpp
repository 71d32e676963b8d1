#include "domain/clean_domain.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/text.h"

namespace isoquad {

CleanResult clean_domain(Domain& domain, const CleanParams& params) {
  CleanResult result;
  if (params.largest && domain.polygons.size() > 1) {
    result.num_components_dropped = domain.polygons.size() - 1;
    domain.polygons.resize(1);
  }
  auto measured = [&](const Ring& r) {
    const double a = std::abs(signed_area(r));
    if (!params.area_factor || r.empty()) return a;
    double x0 = r[0].x, x1 = r[0].x, y0 = r[0].y, y1 = r[0].y;
    for (const Point2& q : r)
      x0 = std::min(x0, q.x), x1 = std::max(x1, q.x), y0 = std::min(y0, q.y),
      y1 = std::max(y1, q.y);
    return a * params.area_factor({0.5 * (x0 + x1), 0.5 * (y0 + y1)});
  };
  auto& polys = domain.polygons;
  const std::size_t before = polys.size();
  double largest = 0.0;
  for (const Polygon& p : polys) largest = std::max(largest, measured(p.outer));
  polys.erase(std::remove_if(
                  polys.begin(), polys.end(),
                  [&](const Polygon& p) { return measured(p.outer) < params.min_island_area_m2; }),
              polys.end());
  result.num_islands_dropped = before - polys.size();
  for (Polygon& p : polys) {
    const std::size_t nh = p.holes.size();
    p.holes.erase(
        std::remove_if(p.holes.begin(), p.holes.end(),
                       [&](const Ring& h) { return measured(h) < params.min_hole_area_m2; }),
        p.holes.end());
    result.num_holes_dropped += nh - p.holes.size();
  }
  if (polys.empty())
    throw Error(ErrorClass::input, "domain",
                printf_string("every component is smaller than --min-island-area, %.4g km2 (the "
                              "largest: %.4g km2); nothing is left to mesh. %s",
                              params.min_island_area_m2 / 1e6, largest / 1e6,
                              params.min_island_area_given
                                  ? "Give a --min-island-area under the largest component's area"
                                  : "Its default is the square of the size (--size, or the "
                                    "automatic sizing's hmin): give a smaller size, or "
                                    "--min-island-area"));
  return result;
}

}  // namespace isoquad
