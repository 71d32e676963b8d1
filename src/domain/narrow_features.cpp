#include "domain/narrow_features.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "core/text.h"
#include "domain/geos_ops.h"

namespace isoquad {

namespace {

// Components and holes: what the domain's topology is, for the comparison below. Parts
// and holes smaller than min_area are not counted.
std::pair<std::size_t, std::size_t> topology(const std::vector<Polygon>& polygons,
                                             double min_area = 0.0) {
  std::size_t parts = 0, holes = 0;
  for (const Polygon& p : polygons) {
    if (std::abs(signed_area(p.outer)) < min_area) continue;
    ++parts;
    for (const Ring& h : p.holes) holes += std::abs(signed_area(h)) >= min_area;
  }
  return {parts, holes};
}

// The same in a window of the domain (x0, y0, x1, y1): a part that reaches the window's
// edge (within `margin`) is a piece of a larger one and counts whatever its area.
std::pair<std::size_t, std::size_t> topology_in_window(const std::vector<Polygon>& polygons,
                                                       double min_area,
                                                       const std::array<double, 4>& window,
                                                       double margin) {
  std::size_t parts = 0, holes = 0;
  for (const Polygon& p : polygons) {
    bool at_edge = false;
    for (const Point2& q : p.outer)
      at_edge = at_edge || q.x <= window[0] + margin || q.y <= window[1] + margin ||
                q.x >= window[2] - margin || q.y >= window[3] - margin;
    if (!at_edge && std::abs(signed_area(p.outer)) < min_area) continue;
    ++parts;
    for (const Ring& h : p.holes) holes += std::abs(signed_area(h)) >= min_area;
  }
  return {parts, holes};
}

// An opening then a closing of `x` by a disc of radius r (mitred offsets).
GeosGeometry open_then_close(GeosContext& g, const GeosGeometry& x, double r, double mitre) {
  const GeosGeometry opened = g.buffer_mitre(g.buffer_mitre(x, -r, mitre), r, mitre);
  return g.buffer_mitre(g.buffer_mitre(opened, r, mitre), -r, mitre);
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

NarrowPlace place_of(const Polygon& p) {
  NarrowPlace out;
  double perimeter = 0;
  for (std::size_t i = 0; i < p.outer.size(); ++i) {
    const Point2& a = p.outer[i];
    const Point2& b = p.outer[(i + 1) % p.outer.size()];
    perimeter += std::hypot(b.x - a.x, b.y - a.y);
    out.at.x += a.x / static_cast<double>(p.outer.size());
    out.at.y += a.y / static_cast<double>(p.outer.size());
  }
  out.width_m = perimeter > 0 ? 2 * std::abs(signed_area(p.outer)) / perimeter : 0.0;
  return out;
}

namespace {

// Counts a piece left as it was.
void note_kept(NarrowResult& result, const Polygon& p, bool cut) {
  result.kept.push_back({p, cut});
  ++result.num_pieces_kept;
}

// Counts a piece applied, keeping the largest (pieces come largest first).
void note_changed(NarrowResult& result, const Polygon& p) {
  if (result.num_pieces == 0) result.largest_changed = place_of(p);
  ++result.num_pieces;
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
  const GeosGeometry original = geos.domain_multipolygon(domain);
  // GEOS's overlays refuse an invalid domain (a ring touching itself where the
  // simplification brought a vertex onto another edge): nothing is changed then.
  if (!geos.validity(original).valid) return result;
  GeosGeometry closed = open_then_close(geos, original, r, params.mitre_limit);
  // The mitred offsets may cross themselves by a rounding error where a spike's mitre
  // meets another edge (Brazil at 1:10m: GEOS's overlays then refused it as input).
  if (!geos.validity(closed).valid) closed = geos.make_valid(closed);

  // The two differences at once (on large domains each takes a second or more); the
  // second works on copies in a context of its own.
  std::vector<Polygon> removed, added;
  {
    GeosContext other;
    const GeosGeometry original_copy = other.clone(original), closed_copy = other.clone(closed);
    run_in_parallel(
        [&] { removed = pieces(geos, geos.difference(original, closed), negligible); },
        [&] { added = pieces(other, other.difference(closed_copy, original_copy), negligible); });
  }
  if (removed.empty() && added.empty()) return result;

  std::vector<Polygon> polygons = geos.polygons(closed);
  if (polygons.empty())
    throw Error(ErrorClass::input, "narrow features",
                printf_string("every part of the domain is narrower than --min-width, %.6g m; "
                              "nothing is left to mesh: give a smaller --min-width (its default "
                              "is a quarter of the size)",
                              params.min_width_m));
  const auto original_topology = topology(domain.polygons);
  if (topology(polygons) == original_topology) {
    for (const Polygon& p : removed) result.area_removed_m2 += std::abs(signed_area(p.outer));
    for (const Polygon& p : added) result.area_added_m2 += std::abs(signed_area(p.outer));
    result.largest_changed = place_of(!removed.empty() ? removed[0] : added[0]);
    result.num_pieces = removed.size() + added.size();
  } else if (removed.size() + added.size() <= params.max_sequential_pieces) {
    // Some piece would cut an isthmus, join components or open or close a hole (in a
    // water domain: flood a narrow land bridge); those are left out, so the domain keeps
    // its components and holes: connections are the user's to change (--min-width 0
    // turns this off). Few pieces: applied one by one, each checked on the whole domain.
    GeosGeometry current = geos.domain_multipolygon(domain);
    auto apply = [&](const std::vector<Polygon>& list, bool add, double& area) {
      for (const Polygon& p : list) {
        const GeosGeometry piece = geos.polygon_with_holes(p);
        std::optional<GeosGeometry> next;
        try {  // an overlay GEOS fails on (a non-noded intersection): the piece is kept
          next = add ? geos.union_of(current, piece) : geos.difference(current, piece);
        } catch (const Error&) {
        }
        if (!next || topology(geos.polygons(*next)) != original_topology) {
          note_kept(result, p, !add);
          continue;
        }
        current = std::move(*next);
        area += std::abs(signed_area(p.outer));
        note_changed(result, p);
      }
    };
    apply(removed, false, result.area_removed_m2);
    apply(added, true, result.area_added_m2);
    if (result.num_pieces == 0) return result;
    // A piece's sides lie on the original boundary up to rounding, so the overlays can
    // leave slivers and zero-width spikes or cracks along them: an opening then a
    // closing far below the width removes those.
    current = open_then_close(geos, current, 1e-3 * params.min_width_m, params.mitre_limit);
    polygons = geos.polygons(current);
  } else {
    // Many pieces (the whole-domain checks above would cost pieces x domain size: 33 s
    // on Canada at 1:10m): a piece without holes is a disk (one with holes is kept);
    // joined to the domain along k separate arcs it changes the Euler characteristic
    // (components - holes) by 1 - k, and along one arc it changes nothing (the union
    // retracts onto the domain). So a piece keeps the topology when it touches the rest
    // of the domain in exactly one place: counted locally, in a thin band round the
    // piece clipped to its box.
    const double eps = 1e-3 * params.min_width_m;
    auto contacts = [&](const GeosGeometry& piece, const Polygon& p, bool removed_piece) {
      double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
      for (const Point2& q : p.outer)
        x0 = std::min(x0, q.x), y0 = std::min(y0, q.y), x1 = std::max(x1, q.x), y1 = std::max(y1, q.y);
      const double m = 4 * eps;
      GeosGeometry near = geos.clip_valid(original, x0 - m, y0 - m, x1 + m, y1 + m);
      if (removed_piece) near = geos.difference(near, piece);
      const GeosGeometry band = geos.buffer_mitre(piece, eps, params.mitre_limit);
      // An inward offset far below the band's width drops the zero-width slivers the
      // difference leaves along the piece's sides, which would join separate contacts.
      const GeosGeometry touching = geos.unary_union(geos.intersection(band, near));
      const std::vector<Polygon> found =
          geos.polygons(geos.buffer_mitre(touching, -0.25 * eps, params.mitre_limit));
      // A contact all round (a ring: the piece is an island of land filled in or a
      // patch cut out of the middle) closes or opens a hole: not one arc.
      for (const Polygon& c : found)
        if (!c.holes.empty()) return found.size() + 1;
      return found.size();
    };
    struct Piece {
      const Polygon* polygon;
      double x0, y0, x1, y1;  // box, grown by the band's width
      double area;
      bool cut;  // removed from the domain (else filled in)
    };
    std::vector<Piece> accepted;
    auto sort_out = [&](const std::vector<Polygon>& list, bool removed_piece) {
      for (const Polygon& p : list) {
        if (!p.holes.empty() || contacts(geos.polygon_with_holes(p), p, removed_piece) != 1) {
          note_kept(result, p, removed_piece);
          continue;
        }
        Piece a{&p, 1e300, 1e300, -1e300, -1e300, std::abs(signed_area(p.outer)),
                removed_piece};
        for (const Point2& q : p.outer)
          a.x0 = std::min(a.x0, q.x - 4 * eps), a.y0 = std::min(a.y0, q.y - 4 * eps),
          a.x1 = std::max(a.x1, q.x + 4 * eps), a.y1 = std::max(a.y1, q.y + 4 * eps);
        accepted.push_back(std::move(a));
      }
    };
    sort_out(removed, true);
    sort_out(added, false);
    if (accepted.empty()) return result;
    // A piece's sides lie on the original boundary up to rounding, so the overlays can
    // leave slivers and near-zero-width spikes or cracks along them: an opening then a
    // closing far below the width removes those, component by component (a closing of
    // the whole would join components a few eps apart).
    // (In the context given: two of these run at once below.)
    auto cleaned_in = [&](GeosContext& g, const GeosGeometry& current) {
      std::vector<Polygon> out;
      for (const Polygon& part : g.polygons(current)) {
        const GeosGeometry c =
            open_then_close(g, g.polygon_with_holes(part), eps, params.mitre_limit);
        for (Polygon& q : g.polygons(c)) out.push_back(std::move(q));
      }
      return out;
    };
    auto cleaned = [&](const GeosGeometry& current) { return cleaned_in(geos, current); };
    // The domain with the chosen pieces cut out or filled in.
    auto overlay_in = [&](GeosContext& g, const std::vector<bool>& chosen) {
      std::vector<GeosGeometry> cut, fill;
      for (std::size_t i = 0; i < accepted.size(); ++i) {
        if (!chosen[i]) continue;
        (accepted[i].cut ? cut : fill).push_back(g.polygon_with_holes(*accepted[i].polygon));
      }
      GeosGeometry current = g.domain_multipolygon(domain);
      if (!cut.empty()) current = g.difference(current, g.unary_union(g.multipolygon(std::move(cut))));
      if (!fill.empty()) current = g.union_of(current, g.unary_union(g.multipolygon(std::move(fill))));
      return cleaned_in(g, current);
    };
    auto overlay = [&](const std::vector<bool>& chosen) { return overlay_in(geos, chosen); };
    // Pieces next to each other could still change it together. Fragments and holes
    // smaller than a square of the width are not counted: cuts next to each other can
    // leave slivers of land or water that the contacts saw as one (Canada at 1:10m: 13
    // fragments of 0.006 to 1.2 km2 among 351 pieces at a width of 1.7 km); the cleaning
    // drops them with the other islands and holes smaller than --min-island-area. When
    // the topology still changes, only the pieces whose boxes meet no other piece's are
    // applied (each alone keeps it, by its contacts, but for the slivers below), less
    // those that still change it, and when even that changes it, nothing is.
    const double tiny = params.min_width_m * params.min_width_m;
    // The domain with the pieces in `ids`, when that keeps the reference topology (an
    // overlay GEOS fails on, at a non-noded intersection, counts as a change).
    std::pair<std::size_t, std::size_t> reference;
    auto keeps = [&](const std::vector<std::size_t>& ids, std::vector<Polygon>* out) {
      std::vector<bool> some(accepted.size(), false);
      for (std::size_t i : ids) some[i] = true;
      ++result.num_domain_checks;
      try {
        std::vector<Polygon> result_polygons = overlay(some);
        if (topology(result_polygons, tiny) != reference) return false;
        if (out) *out = std::move(result_polygons);
        return true;
      } catch (const Error&) {
        return false;
      }
    };
    // The reference is the domain through the same overlay and cleaning with no piece:
    // the cleaning alone may change it (a hole touching the outer ring at a point would
    // open there, and every piece be refused for that). It and the domain with every
    // piece (most often the answer) are computed at once.
    result.num_domain_checks += 2;
    bool reference_failed = false;
    std::optional<std::vector<Polygon>> with_all;
    {
      GeosContext other;
      run_in_parallel(
          [&] {
            try {
              reference = topology(overlay(std::vector<bool>(accepted.size(), false)), tiny);
            } catch (const Error&) {
              reference_failed = true;
            }
          },
          [&] {
            try {
              with_all = overlay_in(other, std::vector<bool>(accepted.size(), true));
            } catch (const Error&) {  // an overlay GEOS fails on: a change, as in keeps
            }
          });
    }
    if (reference_failed) {
      for (const Piece& a : accepted) note_kept(result, *a.polygon, a.cut);
      return result;
    }
    std::vector<std::size_t> ids(accepted.size());
    for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = i;
    if (with_all && topology(*with_all, tiny) == reference) {
      polygons = std::move(*with_all);
    } else {
      // Only the pieces whose boxes meet no other piece's.
      std::vector<bool> isolated(accepted.size(), true);
      std::vector<std::size_t> order = ids;
      std::sort(order.begin(), order.end(),
                [&](std::size_t a, std::size_t b) { return accepted[a].x0 < accepted[b].x0; });
      for (std::size_t k = 0; k < order.size(); ++k) {
        const Piece& a = accepted[order[k]];
        for (std::size_t l = k + 1; l < order.size() && accepted[order[l]].x0 <= a.x1; ++l) {
          const Piece& b = accepted[order[l]];
          if (b.y0 <= a.y1 && a.y0 <= b.y1) isolated[order[k]] = isolated[order[l]] = false;
        }
      }
      ids.clear();
      for (std::size_t i = 0; i < accepted.size(); ++i)
        if (isolated[i]) ids.push_back(i);
      // The domain of the last set found to keep the topology (each check is an overlay
      // of the whole domain: not done twice).
      std::vector<Polygon> kept_polygons;
      bool ok = keeps(ids, &kept_polygons);
      if (!ok) {
        // Most often a few pieces change it alone. Each is checked first on the domain
        // round it (clipped to the piece's box grown by its size each way), with the same
        // overlay, cleaning and count; the set without those that change it there is
        // then checked on the whole domain. (The halving below checks each set on the
        // whole domain: the Arctic Ocean at 1:10m took 18 such checks of 0.6 s to find
        // the one piece of 323 that changed it.)
        std::vector<std::size_t> alone;
        for (std::size_t i : ids) {
          const Piece& a = accepted[i];
          const double grow = std::max(a.x1 - a.x0, a.y1 - a.y0);
          const std::array<double, 4> window{a.x0 - grow, a.y0 - grow, a.x1 + grow, a.y1 + grow};
          bool changes = true;
          try {
            const GeosGeometry near =
                geos.clip_valid(original, window[0], window[1], window[2], window[3]);
            const GeosGeometry piece = geos.polygon_with_holes(*a.polygon);
            const GeosGeometry with = a.cut ? geos.difference(near, piece) : geos.union_of(near, piece);
            // The cleaning moves the window's edges by rounding only; 4 eps is ample.
            changes = topology_in_window(cleaned(near), tiny, window, 4 * eps) !=
                      topology_in_window(cleaned(with), tiny, window, 4 * eps);
          } catch (const Error&) {
          }
          if (!changes) alone.push_back(i);
        }
        if (!alone.empty() && alone.size() < ids.size() && keeps(alone, &kept_polygons)) {
          ids = std::move(alone);
          ok = true;
        }
      }
      if (!ok) {
        // Some piece changes it even alone: a fill the closing's mitred corner makes,
        // touching the domain at that corner only, is joined to it by a sliver that the
        // cleaning drops (Indonesia at 1:10m, --min-width 1000: a 2.6 km2 triangle among
        // 115 pieces, and none was applied). Halving finds the pieces that change it, or the sets that
        // change it only together.
        std::vector<bool> dropped(accepted.size(), false);
        std::function<void(const std::vector<std::size_t>&)> drop =
            [&](const std::vector<std::size_t>& set) {
              if (set.size() == 1) {
                dropped[set[0]] = true;
                return;
              }
              const std::vector<std::size_t> a(set.begin(), set.begin() + set.size() / 2),
                  b(set.begin() + set.size() / 2, set.end());
              const bool bad_a = !keeps(a, nullptr), bad_b = !keeps(b, nullptr);
              if (bad_a) drop(a);
              if (bad_b) drop(b);
              if (!bad_a && !bad_b)
                for (std::size_t i : set) dropped[i] = true;
            };
        // Sets that keep it one by one may change it together: again on what is left,
        // a few times (each round drops at least one piece).
        for (int round = 0; round < 8 && !ids.empty(); ++round) {
          drop(ids);
          ids.erase(std::remove_if(ids.begin(), ids.end(), [&](std::size_t i) { return dropped[i]; }),
                    ids.end());
          if ((ok = keeps(ids, &kept_polygons))) break;
        }
      }
      if (ids.empty() || !ok) ids.clear();
      else polygons = std::move(kept_polygons);
    }
    std::vector<bool> chosen(accepted.size(), false);
    for (std::size_t i : ids) chosen[i] = true;
    for (std::size_t i = 0; i < accepted.size(); ++i) {
      if (!chosen[i]) {
        note_kept(result, *accepted[i].polygon, accepted[i].cut);
        continue;
      }
      note_changed(result, *accepted[i].polygon);
      (accepted[i].cut ? result.area_removed_m2 : result.area_added_m2) += accepted[i].area;
    }
    if (result.num_pieces == 0) return result;
  }
  for (Polygon& p : polygons) orient_polygon(p);
  sort_by_area(polygons);
  domain.polygons = std::move(polygons);
  result.num_components_after = domain.polygons.size();
  result.changed = true;
  return result;
}

NarrowResult close_hairlines(Domain& domain, const NarrowParams& params,
                             const std::vector<NarrowResult::Kept>& kept) {
  NarrowResult result;
  result.num_components_before = result.num_components_after = domain.polygons.size();
  if (!(params.min_width_m > 0) || domain.polygons.empty() || kept.empty()) return result;
  const double r = 0.5 * params.min_width_m;
  const double negligible = 1e-4 * params.min_width_m * params.min_width_m;
  GeosContext geos;
  GeosGeometry current = geos.domain_multipolygon(domain);
  if (!geos.validity(current).valid) return result;
  GeosGeometry closed = open_then_close(geos, current, r, params.mitre_limit);
  if (!geos.validity(closed).valid) closed = geos.make_valid(closed);
  std::vector<GeosGeometry> kept_geometry;
  for (const NarrowResult::Kept& k : kept)
    kept_geometry.push_back(geos.polygon_with_holes(k.piece));
  // A piece counts where it meets a kept piece and changes the topology: anything else
  // the opening and closing at this width move (the tips of sharp corners) is the
  // narrow features' to change, or to leave.
  auto apply = [&](const std::vector<Polygon>& list, bool add, double& area) {
    for (const Polygon& p : list) {
      const GeosGeometry piece = geos.polygon_with_holes(p);
      if (std::none_of(kept_geometry.begin(), kept_geometry.end(),
                       [&](const GeosGeometry& k) { return geos.intersects(piece, k); }))
        continue;
      std::optional<GeosGeometry> next;
      try {
        next = add ? geos.union_of(current, piece) : geos.difference(current, piece);
      } catch (const Error&) {
      }
      if (!next || topology(geos.polygons(*next)) == topology(geos.polygons(current))) continue;
      current = std::move(*next);
      area += std::abs(signed_area(p.outer));
      note_changed(result, p);
    }
  };
  apply(pieces(geos, geos.difference(current, closed), negligible), false, result.area_removed_m2);
  apply(pieces(geos, geos.difference(closed, current), negligible), true, result.area_added_m2);
  if (result.num_pieces == 0) return result;
  // The overlays' slivers along the pieces' sides, as in remove_narrow_features.
  current = open_then_close(geos, current, 1e-3 * params.min_width_m, params.mitre_limit);
  std::vector<Polygon> polygons = geos.polygons(current);
  if (polygons.empty()) return result;
  for (Polygon& p : polygons) orient_polygon(p);
  sort_by_area(polygons);
  domain.polygons = std::move(polygons);
  result.num_components_after = domain.polygons.size();
  result.num_hairline = result.num_pieces;
  result.changed = true;
  return result;
}

}  // namespace isoquad
