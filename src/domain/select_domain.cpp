#include "domain/select_domain.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <sstream>

#include "core/error.h"
#include "domain/geos_ops.h"

namespace isoquad {

namespace {

// Whether moving the negative longitudes of these rings by 360 degrees keeps them
// whole: no edge crosses the prime meridian (from a negative longitude to one >= 0,
// less than 180 degrees apart), which the move would stretch around the globe. An
// island whose ring crosses the antimeridian (179.9 then -179.9) moves whole and joins;
// a landmass across Greenwich (Natural Earth's Eurasia, which also reaches +-180) does
// not move.
bool shifts_whole(const std::vector<Ring>& rings) {
  bool negative = false;
  for (const Ring& r : rings)
    for (std::size_t i = 0; i < r.size(); ++i) {
      const Point2 &a = r[i], &b = r[(i + 1) % r.size()];
      negative = negative || a.x < 0.0;
      if ((a.x < 0.0) != (b.x < 0.0) && std::abs(b.x - a.x) < 180.0) return false;
    }
  return negative;
}

// Whether a geographic source is better read with longitudes in [0, 360): it straddles
// the antimeridian (its longitudes span more than 180 degrees, as
// choose_local_projection decides) and moving the polygons that shift whole narrows it.
bool unwrap_narrows(const SourceData& source) {
  double lo = 1e300, hi = -1e300, shifted_lo = 1e300, shifted_hi = -1e300;
  for (const SourcePolygon& sp : source.polygons) {
    const double shift = shifts_whole(sp.rings) ? 360.0 : 0.0;
    for (const Ring& r : sp.rings)
      for (const Point2& p : r) {
        lo = std::min(lo, p.x), hi = std::max(hi, p.x);
        const double x = p.x < 0.0 ? p.x + shift : p.x;
        shifted_lo = std::min(shifted_lo, x), shifted_hi = std::max(shifted_hi, x);
      }
  }
  return hi - lo > 180.0 && shifted_hi - shifted_lo < hi - lo - 1e-9;
}

// Whether a ring of these crosses the antimeridian as written: an edge more than 180
// degrees long (179.9 then -179.9), which is meant the short way round. An edge along a
// pole (both ends at 90 degrees of latitude, -180 then 180: a polygon of the world's sea
// drawn up to the top of the map) is a point on the globe, and crosses nothing.
bool crosses_antimeridian(const std::vector<Ring>& rings) {
  auto at_pole = [](const Point2& p) { return std::abs(p.y) >= 90.0; };
  for (const Ring& r : rings)
    for (std::size_t i = 0; i < r.size(); ++i) {
      const Point2 &a = r[i], &b = r[(i + 1) % r.size()];
      if (std::abs(b.x - a.x) > 180.0 && !(at_pole(a) && at_pole(b))) return true;
    }
  return false;
}

void shift_negative(Ring& r) {
  for (Point2& p : r)
    if (p.x < 0.0) p.x += 360.0;
}

// Longitudes moved into [0, 360) where that keeps a polygon whole: a ring that crosses
// the antimeridian (179.9 then -179.9) is then valid, and the parts of an island cut
// there join.
void unwrap_antimeridian(SourceData& source) {
  for (SourcePolygon& sp : source.polygons)
    if (shifts_whole(sp.rings))
      for (Ring& r : sp.rings) shift_negative(r);
  if (source.bbox_ring && shifts_whole({*source.bbox_ring})) shift_negative(*source.bbox_ring);
}

// The rings of a polygon drawn across the antimeridian made continuous: after an edge
// more than 180 degrees long (meant the short way, across it), the following longitudes
// move by 360; then each ring moves by whole turns so that it starts at or east of -180
// (holes: of the outer ring's west end). False for a ring around a pole (the moves do
// not cancel), which is left as drawn.
// The turns (multiples of 360 degrees) that make a ring's longitudes continuous: after
// an edge more than 180 degrees long, the following vertices move by 360. Applied in one
// addition per vertex, so that a vertex that ends where it was keeps its exact
// coordinate. The closing edge, from the last vertex back to the first, undoes them
// unless the ring winds round a pole.
struct RingTurns {
  std::vector<double> turn;  // added to each vertex
  double closing = 0.0;      // the closing edge's
  bool winds() const { return std::abs(turn.back() + closing) > 1.0; }
};

RingTurns ring_turns(const Ring& r) {
  RingTurns t;
  t.turn.assign(r.size(), 0.0);
  for (std::size_t i = 1; i < r.size(); ++i) {
    t.turn[i] = t.turn[i - 1];
    if (r[i].x - r[i - 1].x > 180.0) t.turn[i] -= 360.0;
    if (r[i - 1].x - r[i].x > 180.0) t.turn[i] += 360.0;
  }
  if (r.front().x - r.back().x > 180.0) t.closing = -360.0;
  if (r.back().x - r.front().x > 180.0) t.closing = 360.0;
  return t;
}

// The ring's longitudes with `turn` added, moved by whole turns to start at or east of
// `west`; returns its west end.
double move_east_of(Ring& r, const std::vector<double>& turn, double west) {
  double lo = 1e300;
  for (std::size_t i = 0; i < r.size(); ++i) lo = std::min(lo, r[i].x + turn[i]);
  const double whole = 360.0 * std::ceil((west - lo) / 360.0 - 1e-12);
  for (std::size_t i = 0; i < r.size(); ++i) r[i].x += turn[i] + whole;
  return lo + whole;
}

bool unwrap_continuously(std::vector<Ring>& rings) {
  double west = -180.0;
  for (std::size_t k = 0; k < rings.size(); ++k) {
    Ring& r = rings[k];
    if (r.empty()) continue;
    const RingTurns t = ring_turns(r);
    if (t.winds()) return false;
    const double lo = move_east_of(r, t.turn, west);
    if (k == 0) west = lo;
  }
  return true;
}

// The rings of a polygon drawn round a pole, as a spherical polygon (d3's TopoJSON,
// world-atlas's Antarctica): a ring whose longitudes wind once round the globe (the
// moves of unwrap_continuously do not cancel). Drawn so in lon/lat, it encloses the
// strip between itself and its closing edge; made continuous and closed through the
// pole on its side of the equator, it is the polygon meant. A hole that winds within a
// hundredth of a degree of the pole (a ring round the pole itself) is dropped. The rings
// then start at or east of -180, as unwrap_continuously leaves them. False when no ring
// winds, or a hole winds farther from the pole (left as drawn).
bool close_round_pole(std::vector<Ring>& rings) {
  bool winds = false;
  std::vector<Ring> out;
  for (std::size_t k = 0; k < rings.size(); ++k) {
    Ring r = rings[k];
    if (r.size() < 3) continue;
    const RingTurns t = ring_turns(r);
    if (!t.winds()) {
      out.push_back(std::move(r));
      continue;
    }
    double lat = 0.0;
    for (const Point2& p : r) lat += p.y / static_cast<double>(r.size());
    const double pole = lat < 0.0 ? -90.0 : 90.0;
    winds = true;
    if (k > 0) {
      if (!std::all_of(r.begin(), r.end(), [&](const Point2& p) { return std::abs(p.y - pole) < 0.01; }))
        return false;
      continue;
    }
    for (std::size_t i = 0; i < r.size(); ++i) r[i].x += t.turn[i];
    // One more step along the ring (its closing edge, the short way), then down to the
    // pole and back along it to where the ring starts.
    const double end_x = r.front().x + t.turn.back() + t.closing;
    const Point2 start = r.front();
    r.push_back({end_x, start.y});
    r.push_back({end_x, pole});
    r.push_back({start.x, pole});
    move_east_of(r, std::vector<double>(r.size(), 0.0), -180.0);
    out.push_back(std::move(r));
  }
  if (winds) rings = std::move(out);
  return winds;
}

using Rectangle = std::array<double, 4>;  // xmin, ymin, xmax, ymax

// Where a polygon's pieces are read: rectangles in the polygon's frame, and the shift in
// x that takes a piece from there to the frame of the bbox.
struct Window {
  Rectangle rect;
  double shift = 0.0;
};

// The windows of a polygon in a geographic source that stays in [-180, 180] (a world
// file): the bbox's rectangle, and the same 360 degrees west and east, so that a bbox
// across the antimeridian (176 to 182) reads the land drawn at -180..-178 too, and a
// polygon made continuous across it (Chukotka at 180..191) lands in a bbox at
// -180..-168. Without a bbox, a continuous polygon is cut at 180 and its part beyond
// moves back.
std::vector<Window> windows(const std::optional<Rectangle>& rect, bool continuous) {
  if (rect) {
    const Rectangle& r = *rect;
    return {{r, 0.0},
            {{r[0] - 360.0, r[1], r[2] - 360.0, r[3]}, 360.0},
            {{r[0] + 360.0, r[1], r[2] + 360.0, r[3]}, -360.0}};
  }
  if (continuous)
    return {{{-180.0, -90.0, 180.0, 90.0}, 0.0}, {{180.0, -90.0, 540.0, 90.0}, -360.0}};
  return {};
}

// The rectangle read within when there is a bbox: its ring's envelope widened by a
// hundredth, so that nothing cut along it reaches the bbox itself.
std::optional<Rectangle> read_rectangle(const SourceData& source) {
  if (!source.bbox_ring || source.bbox_ring->empty()) return std::nullopt;
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (const Point2& p : *source.bbox_ring)
    x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
  const double m = 0.01 * std::max(x1 - x0, y1 - y0);
  return Rectangle{x0 - m, y0 - m, x1 + m, y1 + m};
}

// The area an invalid polygon's rings enclose an odd number of times (even-odd, as a
// renderer fills them), each ring made valid alone.
GeosGeometry even_odd(GeosContext& geos, const GeosGeometry& g) {
  std::optional<GeosGeometry> filled;
  for (const Polygon& p : geos.polygons(g)) {
    std::vector<const Ring*> rings{&p.outer};
    for (const Ring& hole : p.holes) rings.push_back(&hole);
    for (const Ring* ring : rings) {
      if (ring->size() < 3) continue;
      GeosGeometry r = geos.make_valid(geos.polygon({*ring}));
      filled = filled ? geos.sym_difference(*filled, r) : std::move(r);
    }
  }
  return filled ? geos.make_valid(*filled) : geos.make_valid(g);
}

// An invalid polygon (`what`: which feature) made valid. MakeValid's structure method
// takes the first ring for the shell and cuts the others out of it: rings wound the
// other way (a shapefile's shell read inside its own "hole") would lose the whole
// polygon. So where that keeps less than half of what the rings enclose by even-odd,
// the even-odd area is taken; and a result more than 1% off that area is noted, as is a
// hole outside its shell (`v`: the validity check's finding), which becomes land.
GeosGeometry repaired(GeosContext& geos, const GeosGeometry& g, const std::string& what,
                      const GeosValidity& v, std::vector<std::string>& notes) {
  GeosGeometry fixed = geos.make_valid(g);
  std::optional<GeosGeometry> even;
  try {  // an overlay GEOS fails on (a non-noded intersection): MakeValid's result stands
    even = even_odd(geos, g);
  } catch (const Error&) {
    return fixed;
  }
  GeosGeometry drawn = std::move(*even);
  const double a_fixed = geos.area(fixed), a_drawn = geos.area(drawn);
  if (!(a_drawn > 0)) return fixed;
  if (a_fixed < 0.5 * a_drawn) {
    notes.push_back(what + ": its rings do not nest as shell and holes (wound the other way?); " +
                    "repaired as the area they enclose an odd number of times");
    return drawn;
  }
  const double change = (a_fixed - a_drawn) / a_drawn;
  if (std::abs(change) > 0.01) {
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  ": the repair %s %.3g%% of the area its rings enclose (a hole outside its "
                  "shell, or holes that overlap)",
                  change < 0 ? "left out" : "added", 100 * std::abs(change));
    notes.push_back(what + buf);
  } else if (v.reason == "Hole lies outside shell") {
    notes.push_back(what + ": a hole lies outside its shell, at or near " +
                    format_point(v.location) + ": it is land of its own");
  }
  return fixed;
}

}  // namespace

const char* domain_kind_name(DomainKind kind) {
  switch (kind) {
    case DomainKind::water:
      return "water";
    case DomainKind::sea:
      return "sea";
    case DomainKind::land:
      break;
  }
  return "land";
}

SelectResult select_domain(const SourceData& input, const SelectParams& params) {
  const std::string file = "'" + params.source_name + "'";
  SourceData unwrapped;
  const bool unwrap = input.crs.geographic && unwrap_narrows(input);
  if (unwrap) {
    unwrapped = input;
    unwrap_antimeridian(unwrapped);
  }
  const SourceData& source = unwrap ? unwrapped : input;
  if (params.kind == DomainKind::water && !source.bbox_ring)
    throw Error(ErrorClass::usage, "domain",
                "--domain water needs --bbox or --clip: the water domain is the bbox (or the "
                "area of --clip) minus the polygons");

  SelectResult result;
  GeosContext geos;
  std::vector<GeosGeometry> parts;
  // With a bbox, each polygon is first cut to the bbox's rectangle: only what lies
  // there is checked (an invalid ring far away does not matter) and repaired, and the
  // rest costs nothing more.
  const std::optional<Rectangle> rect = read_rectangle(source);
  const bool world = input.crs.geographic && !unwrap;
  for (const SourcePolygon& sp : source.polygons) {
    std::vector<Ring> continuous_rings;
    bool continuous = false;
    if (world && crosses_antimeridian(sp.rings)) {
      continuous_rings = sp.rings;
      continuous = unwrap_continuously(continuous_rings);
      if (!continuous) {
        continuous_rings = sp.rings;
        continuous = close_round_pole(continuous_rings);
      }
    }
    std::vector<Window> ws = windows(rect, continuous);
    if (!world && ws.size() > 1) ws.resize(1);
    GeosGeometry whole = geos.polygon(continuous ? continuous_rings : sp.rings);
    const bool clipped = !ws.empty();
    if (!clipped) ws.push_back({{}, 0.0});  // the whole polygon
    std::optional<bool> whole_valid;
    for (const Window& w : ws) {
      const Rectangle& r = w.rect;
      GeosGeometry g =
          clipped ? geos.clip_by_rect(whole, r[0], r[1], r[2], r[3]) : std::move(whole);
      if (geos.is_empty(g)) continue;
      GeosValidity v = geos.validity(g);
      if (!v.valid && clipped) {
        // The fast cut of a valid polygon can be invalid along the rectangle.
        if (!whole_valid) whole_valid = geos.validity(whole).valid;
        if (*whole_valid) {
          g = geos.intersection(
              whole, geos.polygon({{{r[0], r[1]}, {r[2], r[1]}, {r[2], r[3]}, {r[0], r[3]}}}));
          v = geos.validity(g);
        }
      }
      if (w.shift != 0.0) {
        g = geos.translated(g, w.shift);
        v.location.x += w.shift;
      }
      if (!v.valid) {
        if (!params.repair)
          throw Error(ErrorClass::input, "domain",
                      file + ": feature " + std::to_string(sp.fid) +
                          (sp.part ? " part " + std::to_string(sp.part) : std::string()) +
                          " is invalid: " + v.reason + " at or near " + format_point(v.location) +
                          "; use --repair to fix it");
        g = repaired(geos, g, file + ": feature " + std::to_string(sp.fid), v, result.repair_notes);
        ++result.num_repaired;
      }
      parts.push_back(std::move(g));
    }
  }

  GeosGeometry merged = geos.unary_union(geos.collection(std::move(parts)));
  GeosGeometry domain;
  if (source.bbox_ring) {
    GeosGeometry box = geos.polygon({*source.bbox_ring});
    domain = params.kind == DomainKind::water ? geos.difference(box, merged)
                                              : geos.intersection(merged, box);
  } else {
    domain = std::move(merged);
  }

  result.polygons = geos.polygons(domain);
  normalize_polygons(result.polygons);
  if (result.polygons.empty())
    throw Error(ErrorClass::input, "domain",
                file + ": the " + domain_kind_name(params.kind) + " domain is empty" +
                    (params.kind == DomainKind::water ? " (the area is covered by the polygons)"
                                                      : " (no polygon inside the area)"));
  return result;
}

}  // namespace isoquad
