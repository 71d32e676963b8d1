#include "domain/spike_tips.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "core/error.h"
#include "domain/geos_ops.h"

namespace isoquad {

namespace {

std::pair<std::size_t, std::size_t> topology(const std::vector<Polygon>& polygons) {
  std::size_t holes = 0;
  for (const Polygon& p : polygons) holes += p.holes.size();
  return {polygons.size(), holes};
}

// A tip to cut: its vertex, the unit bisector into the spike, its interior angle, and
// where it is: polygon, ring (0 the outer, k the hole k - 1) and vertex.
struct Tip {
  Point2 v, b;
  double angle = 0.0;
  std::size_t polygon = 0, ring = 0, vertex = 0;
};

Ring& ring_of(Domain& domain, std::size_t polygon, std::size_t ring) {
  Polygon& p = domain.polygons[polygon];
  return ring == 0 ? p.outer : p.holes[ring - 1];
}

std::vector<Tip> sharp_tips(const Domain& domain, double max_angle_rad) {
  std::vector<Tip> tips;
  for (std::size_t pi = 0; pi < domain.polygons.size(); ++pi) {
    const Polygon& p = domain.polygons[pi];
    std::vector<const Ring*> rings{&p.outer};
    for (const Ring& h : p.holes) rings.push_back(&h);
    for (std::size_t ri = 0; ri < rings.size(); ++ri) {
      const Ring* r = rings[ri];
      const std::size_t n = r->size();
      if (n < 3) continue;
      // The domain is left of its rings once oriented (outer counter-clockwise): a convex
      // corner turns left.
      const double side = (signed_area(*r) > 0) == (r == &p.outer) ? 1.0 : -1.0;
      for (std::size_t i = 0; i < n; ++i) {
        const Point2& prev = (*r)[(i + n - 1) % n];
        const Point2& v = (*r)[i];
        const Point2& next = (*r)[(i + 1) % n];
        const double l1 = std::hypot(prev.x - v.x, prev.y - v.y);
        const double l2 = std::hypot(next.x - v.x, next.y - v.y);
        if (l1 == 0 || l2 == 0) continue;
        const Point2 u1{(prev.x - v.x) / l1, (prev.y - v.y) / l1};
        const Point2 u2{(next.x - v.x) / l2, (next.y - v.y) / l2};
        const double turn = side * ((v.x - prev.x) * (next.y - v.y) - (v.y - prev.y) * (next.x - v.x));
        if (turn <= 0) continue;  // reflex or straight
        const double angle = std::acos(std::clamp(u1.x * u2.x + u1.y * u2.y, -1.0, 1.0));
        if (angle >= max_angle_rad || angle <= 0) continue;
        const double bx = u1.x + u2.x, by = u1.y + u2.y, bl = std::hypot(bx, by);
        tips.push_back({v, {bx / bl, by / bl}, angle, pi, ri, i});
      }
    }
  }
  return tips;
}

// The tips cut square across their bisectors where they are w wide, all at once where
// that keeps the topology, else one at a time.
void cut_tips_square(Domain& domain, const std::vector<Tip>& tips, double w, GeosContext& geos,
                     SpikeResult& result) {
  const GeosGeometry whole = geos.domain_multipolygon(domain);
  const auto reference = topology(domain.polygons);
  // Each tip's piece: the part of the domain in the box from just beyond the tip to the
  // cut, 2 w each side of the bisector, that holds the tip. It must lie within the box's
  // sides (else the cut would make new corners on the spike's sides) and hold no more
  // than the tip's triangle could, with a margin.
  std::vector<GeosGeometry> pieces;
  std::vector<double> areas;
  for (const Tip& t : tips) {
    const double d = w / (2.0 * std::tan(0.5 * t.angle));  // the cut's distance from the tip
    const double m = 0.01 * w, half = 2.0 * w;
    const Point2 n{-t.b.y, t.b.x};
    auto at = [&](double s, double u) { return Point2{t.v.x + s * t.b.x + u * n.x, t.v.y + s * t.b.y + u * n.y}; };
    const GeosGeometry box = geos.polygon({{at(-m, -half), at(d, -half), at(d, half), at(-m, half)}});
    GeosGeometry near;
    try {
      near = geos.intersection(whole, box);
    } catch (const Error&) {
      continue;
    }
    const Polygon* tip_piece = nullptr;
    std::vector<Polygon> found = geos.polygons(near);
    for (const Polygon& p : found)
      for (const Point2& q : p.outer)
        if (std::hypot(q.x - t.v.x, q.y - t.v.y) <= 1e-9 * d) tip_piece = &p;
    if (!tip_piece || !tip_piece->holes.empty()) continue;
    bool inside = true;
    for (const Point2& q : tip_piece->outer)
      inside = inside && std::abs((q.x - t.v.x) * n.x + (q.y - t.v.y) * n.y) < 0.99 * half;
    const double a = std::abs(signed_area(tip_piece->outer));
    if (!inside || a > 0.75 * w * d || a <= 0) continue;
    // What is cut: the piece grown a little, within the box, so that no sliver is left
    // along the spike's sides (the piece's corners on the cut line are rounded off its
    // sides), and the new end is the box's straight side.
    try {
      pieces.push_back(geos.intersection(
          box, geos.buffer_mitre(geos.polygon_with_holes(*tip_piece), 1e-3 * w, 5.0)));
    } catch (const Error&) {
      continue;
    }
    areas.push_back(a);
  }
  if (pieces.empty()) return;

  // All tips at once; when that changes the topology (two tips' pieces meeting, a cut
  // across a thin neck), one at a time, each kept only if the topology stays.
  auto apply = [&](const GeosGeometry& from, std::vector<GeosGeometry> cut) -> std::vector<Polygon> {
    try {
      const GeosGeometry out = geos.difference(from, geos.unary_union(geos.multipolygon(std::move(cut))));
      if (!geos.validity(out).valid) return {};
      return geos.polygons(out);
    } catch (const Error&) {
      return {};
    }
  };
  // (unary_union of one piece: a copy, as the pieces are kept for the second pass.)
  std::vector<GeosGeometry> all;
  for (const GeosGeometry& p : pieces) all.push_back(geos.unary_union(p));
  std::vector<Polygon> polygons = apply(whole, std::move(all));
  if (!polygons.empty() && topology(polygons) == reference) {
    result.num_cut = pieces.size();
    for (double a : areas) result.area_removed_m2 += a;
  } else {
    GeosGeometry current = geos.domain_multipolygon(domain);
    polygons.clear();
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      std::vector<GeosGeometry> one;
      one.push_back(geos.unary_union(pieces[i]));
      std::vector<Polygon> next = apply(current, std::move(one));
      if (next.empty() || topology(next) != reference) continue;
      Domain d;
      d.polygons = next;
      current = geos.domain_multipolygon(d);
      polygons = std::move(next);
      ++result.num_cut;
      result.area_removed_m2 += areas[i];
    }
    if (result.num_cut == 0) return;
  }
  for (Polygon& p : polygons) orient_polygon(p);
  sort_by_area(polygons);
  domain.polygons = std::move(polygons);
}

// A tip whose square cut is not made because its spike ends before the cut (a spit
// narrower than w at its base, where the coast turns away: the Nile delta's sand spits
// at 1:10m, whose 9-degree tips were the sharpest corners left in the countries' meshes)
// is cut square where the nearer of its two neighbours is, or at the square cut's
// distance if that is nearer: the tip vertex is replaced by the cut's ends. Each cut is
// kept when the domain stays valid with the same topology and the cut end is at least a
// quarter of w wide (narrower, the cut would only move the sharp corner to a shorter
// edge).
void cut_tips_at_base(Domain& domain, const std::vector<Tip>& tips, double w, GeosContext& geos,
                      SpikeResult& result) {
  const auto reference = topology(domain.polygons);
  // From the last tip back, so that a cut's new vertex leaves the indices of the tips
  // before it on its ring as they were.
  for (auto it = tips.rbegin(); it != tips.rend(); ++it) {
    const Tip& t = *it;
    Ring& ring = ring_of(domain, t.polygon, t.ring);
    const std::size_t n = ring.size();
    const Point2 prev = ring[(t.vertex + n - 1) % n], next = ring[(t.vertex + 1) % n];
    auto along = [&](const Point2& q) { return (q.x - t.v.x) * t.b.x + (q.y - t.v.y) * t.b.y; };
    const double s_prev = along(prev), s_next = along(next);
    const double s = std::min({s_prev, s_next, w / (2.0 * std::tan(0.5 * t.angle))});
    if (!(s > 0)) continue;
    auto toward = [&](const Point2& q, double sq) {
      return s == sq ? q : Point2{t.v.x + (q.x - t.v.x) * s / sq, t.v.y + (q.y - t.v.y) * s / sq};
    };
    const Point2 a = toward(prev, s_prev), b = toward(next, s_next);
    if (std::hypot(a.x - b.x, a.y - b.y) < 0.25 * w) continue;
    Ring cut;
    cut.reserve(n + 1);
    for (std::size_t i = 0; i < n; ++i) {
      if (i != t.vertex) {
        cut.push_back(ring[i]);
        continue;
      }
      if (s != s_prev) cut.push_back(a);
      if (s != s_next) cut.push_back(b);
    }
    Domain trial = domain;
    ring_of(trial, t.polygon, t.ring) = cut;
    try {
      if (!geos.validity(geos.domain_multipolygon(trial)).valid) continue;
    } catch (const Error&) {
      continue;
    }
    if (topology(trial.polygons) != reference) continue;
    const double removed = area(domain) - area(trial);
    if (!(removed > 0)) continue;
    ring = std::move(cut);  // (the tip moved inward: the ring's orientation stays)
    ++result.num_cut_at_base;
    result.area_removed_m2 += removed;
  }
}

}  // namespace

SpikeResult cut_spike_tips(Domain& domain, const SpikeParams& params) {
  SpikeResult result;
  const double w = params.min_width_m;
  if (!(w > 0) || domain.polygons.empty()) return result;
  const double max_angle = params.max_angle_deg * M_PI / 180.0;
  const std::vector<Tip> tips = sharp_tips(domain, max_angle);
  if (tips.empty()) return result;
  GeosContext geos;
  if (!geos.validity(geos.domain_multipolygon(domain)).valid) return result;
  cut_tips_square(domain, tips, w, geos, result);
  // The tips left sharp: those the square cut could not take.
  cut_tips_at_base(domain, sharp_tips(domain, max_angle), w, geos, result);
  if (result.num_cut_at_base > 0) sort_by_area(domain.polygons);  // (areas changed)
  return result;
}

}  // namespace isoquad
