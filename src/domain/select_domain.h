// From the polygons read to one planar domain: validity (repair or report), union,
// land, water or sea selection within the bbox.
#pragma once

#include <string>
#include <vector>

#include "core/geometry.h"
#include "gis/read_polygons.h"

namespace isoquad {

// land: the inside of the polygons (clipped to the bbox or area); water: the bbox (or
// area) minus the polygons; sea: the inside of the polygons as land, the polygons being
// water (sea areas, an ocean layer, a model's domain), so that the bbox's (or area's)
// sides that cut them are open boundary, as a water domain's are.
enum class DomainKind { land, water, sea };

// "water", "land" or "sea", as --domain names them.
const char* domain_kind_name(DomainKind kind);

struct SelectParams {
  DomainKind kind = DomainKind::land;
  bool repair = false;   // fix invalid polygons with GEOS MakeValid instead of failing
  std::string source_name;  // the input file, for messages
};

struct SelectResult {
  std::vector<Polygon> polygons;  // source CRS, oriented, sorted by decreasing area
  std::size_t num_repaired = 0;   // input polygons fixed by MakeValid
  // Repairs that changed the area the polygon's rings enclose, one line each.
  std::vector<std::string> repair_notes;
};

// Throws Error(input) for an invalid polygon (without repair) or an empty domain,
// Error(usage) for a water domain without a bbox.
SelectResult select_domain(const SourceData& source, const SelectParams& params);

}  // namespace isoquad
