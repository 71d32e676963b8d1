#include "domain/select_domain.h"

#include <algorithm>
#include <sstream>

#include "core/error.h"
#include "domain/geos_ops.h"

namespace isoquad {

namespace {

// Whether a geographic source straddles the antimeridian: its longitudes span more than
// 180 degrees, as choose_local_projection decides.
bool straddles_antimeridian(const SourceData& source) {
  double lo = 1e300, hi = -1e300;
  for (const SourcePolygon& sp : source.polygons)
    for (const Ring& r : sp.rings)
      for (const Point2& p : r) lo = std::min(lo, p.x), hi = std::max(hi, p.x);
  return hi - lo > 180.0;
}

// Its longitudes moved into [0, 360): a ring that crosses the antimeridian (179.9 then
// -179.9) is then valid, and the parts of an island cut there join.
void unwrap_antimeridian(SourceData& source) {
  auto shift = [](Ring& r) {
    for (Point2& p : r)
      if (p.x < 0.0) p.x += 360.0;
  };
  for (SourcePolygon& sp : source.polygons)
    for (Ring& r : sp.rings) shift(r);
  if (source.bbox_ring) shift(*source.bbox_ring);
}

}  // namespace

SelectResult select_domain(const SourceData& input, const SelectParams& params) {
  const std::string file = "'" + params.source_name + "'";
  SourceData unwrapped;
  const bool unwrap = input.crs.geographic && straddles_antimeridian(input);
  if (unwrap) {
    unwrapped = input;
    unwrap_antimeridian(unwrapped);
  }
  const SourceData& source = unwrap ? unwrapped : input;
  if (params.kind == DomainKind::water && !source.bbox_ring)
    throw Error(ErrorClass::usage, "domain",
                "--domain water needs --bbox: the water domain is the bbox minus the polygons");

  SelectResult result;
  GeosContext geos;
  std::vector<GeosGeometry> parts;
  for (const SourcePolygon& sp : source.polygons) {
    GeosGeometry g = geos.polygon(sp.rings);
    const GeosValidity v = geos.validity(g);
    if (!v.valid) {
      if (!params.repair)
        throw Error(ErrorClass::input, "domain",
                    file + ": feature " + std::to_string(sp.fid) +
                        (sp.part ? " part " + std::to_string(sp.part) : std::string()) +
                        " is invalid: " + v.reason + " at or near " + format_point(v.location) +
                        "; use --repair to fix it");
      g = geos.make_valid(g);
      ++result.num_repaired;
    }
    parts.push_back(std::move(g));
  }

  GeosGeometry merged = geos.unary_union(geos.multipolygon(std::move(parts)));
  GeosGeometry domain;
  if (source.bbox_ring) {
    GeosGeometry box = geos.polygon({*source.bbox_ring});
    domain = params.kind == DomainKind::water ? geos.difference(box, merged)
                                              : geos.intersection(merged, box);
  } else {
    domain = std::move(merged);
  }

  result.polygons = geos.polygons(domain);
  for (Polygon& p : result.polygons) {
    remove_duplicates_and_spikes(p.outer);
    for (Ring& h : p.holes) remove_duplicates_and_spikes(h);
    p.holes.erase(std::remove_if(p.holes.begin(), p.holes.end(),
                                 [](const Ring& h) { return h.size() < 3; }),
                  p.holes.end());
    orient_polygon(p);
  }
  result.polygons.erase(std::remove_if(result.polygons.begin(), result.polygons.end(),
                                       [](const Polygon& p) { return p.outer.size() < 3; }),
                        result.polygons.end());
  if (result.polygons.empty())
    throw Error(ErrorClass::input, "domain",
                file + ": the " + std::string(params.kind == DomainKind::water ? "water" : "land") +
                    " domain is empty" +
                    (params.kind == DomainKind::water ? " (the bbox is covered by the polygons)"
                                                      : " (no polygon inside the bbox)"));
  sort_by_area(result.polygons);
  return result;
}

}  // namespace isoquad
