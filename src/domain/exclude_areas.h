// Areas not to mesh (--exclude): polygons of another file removed from the domain, their
// edges becoming land boundary. Breakwaters, piers and jetties drawn apart from the
// coastline, the islands of a lake kept in another layer, a basin left to another model.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "core/geometry.h"
#include "gis/read_polygons.h"

namespace isoquad {

struct ExcludeParams {
  bool repair = false;  // fix invalid polygons (GEOS MakeValid) instead of failing
  std::string what;     // how messages name the file: "--exclude 'piers.gpkg'"
  // Maps a point of the domain's CRS to the file's, so that a message says where a
  // polygon is invalid in the coordinates the user drew it in.
  std::function<Point2(const Point2&)> to_file;
};

struct ExcludeResult {
  std::size_t num_polygons = 0;  // polygons removed: those that reach the domain
  std::size_t num_repaired = 0;  // of the file's polygons, fixed with repair
  double area_removed_m2 = 0.0;
  // The area removed, as polygons (the polygons' union within the domain's box).
  std::vector<Polygon> removed;
};

// Removes `areas` (polygons in the domain's CRS) from `domain`; the result is oriented,
// its rings start at their lowest vertex and its polygons are sorted by area, as
// select_domain leaves them. Throws Error(input) for an invalid polygon without repair
// (its feature and where), or when nothing of the domain is left.
ExcludeResult exclude_areas(Domain& domain, const std::vector<SourcePolygon>& areas,
                            const ExcludeParams& params);

// What `domain` holds again of the areas removed (ExcludeResult::removed) once it has
// been cleaned and simplified: holes under the least area dropped, pieces narrower than
// min_width filled in, chords across small bends.
struct ExcludedMeshed {
  std::size_t num_areas = 0;   // the removed polygons
  std::size_t num_mostly = 0;  // of which more than half lies in the domain again
  double area_m2 = 0.0;        // of the removed polygons, in the domain again
};
ExcludedMeshed excluded_area_meshed(const Domain& domain, const std::vector<Polygon>& removed);

}  // namespace isoquad
