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

struct RingVertex {
  int ring = 0;
  int index = 0;
};

// A vertex touching another part of the rings: ring (outer rings and holes numbered
// polygon by polygon), its index there, where.
struct Touch {
  int ring = 0;
  int index = 0;
  Point2 p;
};

// Vertices that touch another part of the domain's rings: a vertex used twice (by two
// rings, or twice by one ring), or within 1e-9 of the domain's extent (a millimetre at
// 1000 km) of a segment it does not end: GEOS output often has such near-touches, off by
// rounding, which the triangulation takes as separate and between which CGAL's
// refinement can fail (Fiji's water had five, 1e-11 m apart). Real narrow gaps are the
// narrow-feature step's business. One point per place.
std::vector<Touch> touching_vertices(const Domain& domain, double* tol_out) {
  std::vector<const Ring*> rings;
  for (const Polygon& p : domain.polygons) {
    rings.push_back(&p.outer);
    for (const Ring& h : p.holes) rings.push_back(&h);
  }
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  std::size_t num_segments = 0;
  for (const Ring* r : rings) {
    num_segments += r->size();
    for (const Point2& q : *r)
      x0 = std::min(x0, q.x), y0 = std::min(y0, q.y), x1 = std::max(x1, q.x),
      y1 = std::max(y1, q.y);
  }
  if (num_segments == 0) return {};
  const double extent = std::max(x1 - x0, y1 - y0);
  const double tol = 1e-9 * extent;
  if (tol_out) *tol_out = tol;
  // Segments in a uniform grid of about one segment per cell, each in every cell its
  // box (widened by tol) meets.
  const int n = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(num_segments))));
  const double cell = std::max(extent / n, tol);
  const int nx = static_cast<int>((x1 - x0) / cell) + 1,
            ny = static_cast<int>((y1 - y0) / cell) + 1;
  auto cx = [&](double x) { return std::clamp(static_cast<int>((x - x0) / cell), 0, nx - 1); };
  auto cy = [&](double y) { return std::clamp(static_cast<int>((y - y0) / cell), 0, ny - 1); };
  std::vector<std::vector<RingVertex>> grid(static_cast<std::size_t>(nx) * ny);
  for (int ri = 0; ri < static_cast<int>(rings.size()); ++ri) {
    const Ring& r = *rings[ri];
    for (int i = 0; i < static_cast<int>(r.size()); ++i) {
      const Point2 &a = r[i], &b = r[(i + 1) % r.size()];
      for (int gx = cx(std::min(a.x, b.x) - tol); gx <= cx(std::max(a.x, b.x) + tol); ++gx)
        for (int gy = cy(std::min(a.y, b.y) - tol); gy <= cy(std::max(a.y, b.y) + tol); ++gy)
          grid[static_cast<std::size_t>(gy) * nx + gx].push_back({ri, i});
    }
  }
  std::vector<Touch> out;
  for (int ri = 0; ri < static_cast<int>(rings.size()); ++ri) {
    const Ring& r = *rings[ri];
    const int m = static_cast<int>(r.size());
    for (int i = 0; i < m; ++i) {
      const Point2& q = r[i];
      bool touches = false;
      for (const RingVertex& s : grid[static_cast<std::size_t>(cy(q.y)) * nx + cx(q.x)]) {
        // The two segments that end at q do not count.
        if (s.ring == ri && (s.index == i || s.index == (i + m - 1) % m)) continue;
        const Ring& sr = *rings[s.ring];
        const Point2 &a = sr[s.index], &b = sr[(s.index + 1) % sr.size()];
        const double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
        const double t =
            len2 > 0 ? std::clamp(((q.x - a.x) * dx + (q.y - a.y) * dy) / len2, 0.0, 1.0) : 0.0;
        if (std::hypot(q.x - a.x - t * dx, q.y - a.y - t * dy) <= tol) {
          touches = true;
          break;
        }
      }
      if (touches) out.push_back({ri, i, q});
    }
  }
  return out;
}

std::vector<GeosGeometry> geos_polygons(GeosContext& geos, const Domain& domain) {
  std::vector<GeosGeometry> parts;
  for (const Polygon& p : domain.polygons) parts.push_back(geos.polygon_with_holes(p));
  return parts;
}

void set_polygons(Domain& domain, std::vector<Polygon> polygons) {
  for (Polygon& p : polygons) orient_polygon(p);
  sort_by_area(polygons);
  domain.polygons = std::move(polygons);
}

}  // namespace

namespace {

// One point per place: the places are few.
std::vector<Point2> places(const std::vector<Touch>& touches, double tol) {
  std::vector<Point2> out;
  for (const Touch& t : touches) {
    bool known = false;
    for (const Point2& p : out) known = known || std::hypot(p.x - t.p.x, p.y - t.p.y) <= 2 * tol;
    if (!known) out.push_back(t.p);
  }
  return out;
}

}  // namespace

std::vector<Point2> pinch_points(const Domain& domain) {
  double tol = 0.0;
  const std::vector<Touch> touches = touching_vertices(domain, &tol);
  return places(touches, tol);
}

bool merge_shared_boundaries(Domain& domain) {
  // Two consecutive vertices of a ring both touching: the edge between them runs along
  // another ring or another part of its own, a contact GEOS may not see (rounding leaves
  // a gap or an overlap of a few nanometres: both sides were projected from longitudes
  // -180 and 180).
  double tol = 0.0;
  const std::vector<Touch> touches = touching_vertices(domain, &tol);
  bool edge_contact = false;
  for (std::size_t k = 1; k < touches.size() && !edge_contact; ++k)
    edge_contact = touches[k].ring == touches[k - 1].ring && touches[k].index == touches[k - 1].index + 1;
  GeosContext geos;
  // Each polygon valid on its own, as a multipolygon: invalid only where two of them
  // overlap or share boundary.
  std::vector<GeosGeometry> parts;
  for (GeosGeometry& g : geos_polygons(geos, domain)) {
    if (geos.validity(g).valid) {
      parts.push_back(std::move(g));
      continue;
    }
    for (const Polygon& p : geos.polygons(geos.make_valid(g))) {
      std::vector<Ring> rings{p.outer};
      rings.insert(rings.end(), p.holes.begin(), p.holes.end());
      parts.push_back(geos.polygon(rings));
    }
  }
  const GeosGeometry all = geos.multipolygon(std::move(parts));
  if (!edge_contact && geos.validity(all).valid) return false;
  // Snapped to a grid of 4 tol: vertices move by 2 tol at most (a millimetre at 500 km),
  // coinciding edges become one and the union dissolves them. Kept only when polygons
  // join or fewer places touch (two point contacts at consecutive vertices look like an
  // edge contact too).
  Domain merged;
  merged.polygons = geos.polygons(geos.snapped(geos.unary_union_snapped(all, 4.0 * tol), 4.0 * tol));
  if (merged.polygons.empty()) return false;
  // The snapping gives a coordinate that rounds to zero either sign, not always the same
  // from one run to the next: +0, so that the output is the same byte for byte.
  auto positive_zeros = [](Ring& r) {
    for (Point2& q : r) q.x += 0.0, q.y += 0.0;
  };
  for (Polygon& p : merged.polygons) {
    positive_zeros(p.outer);
    for (Ring& h : p.holes) positive_zeros(h);
  }
  if (merged.polygons.size() >= domain.polygons.size() &&
      pinch_points(merged).size() >= places(touches, tol).size())
    return false;
  set_polygons(domain, std::move(merged.polygons));
  return true;
}

void separate_rings(Domain& domain, double r_m) {
  const std::vector<Point2> pinches = pinch_points(domain);
  if (pinches.empty()) return;
  GeosContext geos;
  std::vector<GeosGeometry> parts = geos_polygons(geos, domain);
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
  // A ring touching itself is invalid for GEOS's overlays: made valid first (the touch
  // stays, and the octagon cuts it).
  GeosGeometry whole = geos.multipolygon(std::move(parts));
  if (!geos.validity(whole).valid) whole = geos.make_valid(whole);
  const GeosGeometry cut =
      geos.difference(whole, geos.unary_union(geos.multipolygon(std::move(cuts))));
  // The cut can leave slivers far smaller than itself (Kiribati at 1:10m: a triangle of
  // 1 m2 whose ends are 4 mm apart, a new pinch at every cut).
  const double sliver = r_m * r_m;
  std::vector<Polygon> polygons;
  for (Polygon& p : geos.polygons(cut)) {
    if (std::abs(signed_area(p.outer)) < sliver) continue;
    p.holes.erase(std::remove_if(p.holes.begin(), p.holes.end(),
                                 [&](const Ring& h) { return std::abs(signed_area(h)) < sliver; }),
                  p.holes.end());
    polygons.push_back(std::move(p));
  }
  if (polygons.empty())
    throw Error(ErrorClass::input, "simplify", "nothing is left after separating touching rings");
  set_polygons(domain, std::move(polygons));
}

void close_hairline_gaps(Domain& domain, double r_m) {
  if (!(r_m > 0) || domain.polygons.empty()) return;
  constexpr double kMitreLimit = 5.0;
  GeosContext geos;
  GeosGeometry whole = geos.multipolygon(geos_polygons(geos, domain));
  if (!geos.validity(whole).valid) whole = geos.make_valid(whole);
  GeosGeometry closed =
      geos.buffer_mitre(geos.buffer_mitre(whole, r_m, kMitreLimit), -r_m, kMitreLimit);
  if (!geos.validity(closed).valid) closed = geos.make_valid(closed);
  std::vector<Polygon> polygons = geos.polygons(closed);
  if (!polygons.empty()) set_polygons(domain, std::move(polygons));
}

}  // namespace isoquad
