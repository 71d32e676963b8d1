#include "domain/separate_rings.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "domain/geos_ops.h"

namespace isoquad {

namespace {

std::vector<Point2> pinch_points(const Domain& domain) {
  std::vector<std::pair<double, double>> points;
  for (const Polygon& p : domain.polygons) {
    for (const Point2& q : p.outer) points.push_back({q.x, q.y});
    for (const Ring& h : p.holes)
      for (const Point2& q : h) points.push_back({q.x, q.y});
  }
  std::sort(points.begin(), points.end());
  std::vector<Point2> out;
  for (std::size_t i = 1; i < points.size(); ++i)
    if (points[i] == points[i - 1] && (i < 2 || points[i - 1] != points[i - 2]))
      out.push_back({points[i].first, points[i].second});
  return out;
}

}  // namespace

std::size_t count_pinch_points(const Domain& domain) { return pinch_points(domain).size(); }

void separate_rings(Domain& domain, double r_m) {
  const std::vector<Point2> pinches = pinch_points(domain);
  if (pinches.empty()) return;
  GeosContext geos;
  std::vector<GeosGeometry> parts;
  for (const Polygon& p : domain.polygons) {
    std::vector<Ring> rings{p.outer};
    rings.insert(rings.end(), p.holes.begin(), p.holes.end());
    parts.push_back(geos.polygon(rings));
  }
  // Octagons of radius r around the pinch points, cut out of the domain.
  std::vector<GeosGeometry> cuts;
  for (const Point2& c : pinches) {
    Ring octagon;
    for (int k = 0; k < 8; ++k) {
      const double a = (k + 0.5) * M_PI / 4;
      octagon.push_back({c.x + r_m * std::cos(a), c.y + r_m * std::sin(a)});
    }
    cuts.push_back(geos.polygon({octagon}));
  }
  const GeosGeometry cut = geos.difference(geos.multipolygon(std::move(parts)),
                                           geos.unary_union(geos.multipolygon(std::move(cuts))));
  std::vector<Polygon> polygons = geos.polygons(cut);
  if (polygons.empty())
    throw Error(ErrorClass::input, "simplify", "nothing is left after separating touching rings");
  for (Polygon& p : polygons) orient_polygon(p);
  sort_by_area(polygons);
  domain.polygons = std::move(polygons);
}

}  // namespace isoquad
