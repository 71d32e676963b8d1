#include "domain/project_domain.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <sstream>

#include "core/error.h"
#include "core/text.h"
#include "gis/map_scale.h"

namespace isoquad {

namespace {

// Applies `t` to every ring; returns false at the first point that fails.
bool transform_all(const CrsTransform& t, std::vector<Polygon>& polys, Point2* failed) {
  for (Polygon& p : polys) {
    std::vector<Ring*> rings{&p.outer};
    for (Ring& h : p.holes) rings.push_back(&h);
    for (Ring* r : rings) {
      Ring original = *r;
      const long bad = t.transform(*r);
      if (bad >= 0) {
        *failed = original[bad];
        return false;
      }
    }
  }
  return true;
}

// A projected source CRS in metres is kept as the meshing CRS where, over the domain, it
// is conformal (squares stay squares: both steps scaled alike within 0.1%, at right
// angles within 0.1 degree) and true to the ground's scale within 1% (the automatic
// projection's error at 2,000 km from its centre). UTM within its zone strays by 0.04 to
// 0.1%, Lambert-93 over France by 0.3%; Web Mercator at 48 N by 49%, and an equal-area or
// equidistant CRS is not conformal away from its centre: those domains get the local
// projection, and the summary says why.
constexpr double kKeptScaleError = 0.01, kKeptAnisotropy = 1e-3, kKeptSkewDeg = 0.1;

// How far an edge's image may stray from its chord, as a share of the domain's diagonal
// (France: 11 m; a harbour 10 km across: 0.14 m).
constexpr double kCurvedEdgeTolerance = 1e-5;

// Empty when `crs` can serve as the meshing CRS over `points`, else why not.
std::string why_not_kept(const CrsInfo& crs, const std::vector<Point2>& points) {
  if (!crs.projected) return "";
  if (std::abs(crs.linear_unit_m - 1.0) > 1e-12) return "it is not in metres";
  const CrsDistortion d = crs_distortion(crs, points);
  if (!d.measured) return "its points cannot be converted to longitude and latitude";
  std::string why;
  if (d.max_scale_error > kKeptScaleError)
    why = printf_string("its scale strays by up to %.2g%% from the ground's over the domain",
                        100.0 * d.max_scale_error);
  if (d.max_anisotropy > kKeptAnisotropy || d.max_skew_deg > kKeptSkewDeg)
    why += printf_string(
        "%s (lengths along x and y differ by up to %.2g%%, their angle departs from 90 "
        "degrees by up to %.2g)",
        why.empty() ? "it is not conformal over the domain" : ", and it is not conformal",
        100.0 * d.max_anisotropy, d.max_skew_deg);
  return why;
}

// Longitude 180 read as -180 where the two are one point in `t`'s CRS (bit for bit the
// same point then, so that a ring closed through a pole by select_domain, which goes down
// the 180th meridian and comes back up at -180, comes back along exactly the same points:
// a spike, removed later). Not where they are the map's two edges, 40,000 km apart, as in
// a cylindrical CRS centred on Greenwich (EPSG:3857): a domain that ends at 180 would be
// torn across the map.
void read_antimeridian_as_west(const CrsTransform& t, std::vector<Polygon>& polys) {
  auto one_point = [&t](double lat) {
    std::vector<Point2> p{{180.0, lat}, {-180.0, lat}};
    return t.transform(p) < 0 && std::hypot(p[0].x - p[1].x, p[0].y - p[1].y) < 1.0;
  };
  auto west = [&](Ring& r) {
    for (Point2& q : r)
      if (q.x == 180.0 && one_point(q.y)) q.x = -180.0;
  };
  for (Polygon& p : polys) {
    west(p.outer);
    for (Ring& h : p.holes) west(h);
  }
}

// Error(crs) when an edge of `lonlat` (longitudes and latitudes, degrees) is torn across
// the map `t` projects it to (`projected`: the same rings, point for point): its image
// over 100 km long, and over 10 times what the CRS's larger scale at its two ends makes
// it (a scale that grows along an edge grows towards one of its ends, in the CRSs in
// use). So is a domain across the antimeridian (drawn from 177 to 183 degrees) in a CRS
// whose map ends there (EPSG:3857): the points beyond 180 land on the map's other edge.
void check_not_torn(const std::vector<Polygon>& lonlat, const std::vector<Polygon>& projected,
                    const CrsTransform& t, const CrsInfo& target) {
  constexpr double kRadius = 6371008.8, kDeg = M_PI / 180.0;
  auto ground = [](const Point2& a, const Point2& b) {
    const double dlat = (b.y - a.y) * kDeg,
                 dlon = (b.x - a.x) * kDeg * std::cos(0.5 * (a.y + b.y) * kDeg);
    return kRadius * std::hypot(dlat, dlon);
  };
  // Each edge's ends and images, and a point about 100 m from each end towards the other.
  std::vector<std::array<Point2, 4>> edges;
  std::vector<Point2> steps;
  auto add = [&](const Ring& r, const Ring& q) {
    for (std::size_t i = 0; i < r.size(); ++i) {
      const std::size_t j = (i + 1) % r.size();
      const double degrees = std::hypot(r[j].x - r[i].x, r[j].y - r[i].y);
      if (!(degrees > 0.0)) continue;
      const double f = std::min(0.5, 1e-3 / degrees);
      edges.push_back({r[i], r[j], q[i], q[j]});
      steps.push_back({r[i].x + f * (r[j].x - r[i].x), r[i].y + f * (r[j].y - r[i].y)});
      steps.push_back({r[j].x + f * (r[i].x - r[j].x), r[j].y + f * (r[i].y - r[j].y)});
    }
  };
  for (std::size_t k = 0; k < lonlat.size(); ++k) {
    add(lonlat[k].outer, projected[k].outer);
    for (std::size_t h = 0; h < lonlat[k].holes.size(); ++h)
      add(lonlat[k].holes[h], projected[k].holes[h]);
  }
  std::vector<Point2> images = steps;
  if (t.transform(images) >= 0) return;  // the transform above succeeded at the ends
  auto distance = [](const Point2& a, const Point2& b) { return std::hypot(b.x - a.x, b.y - a.y); };
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const auto& [a, b, pa, pb] = edges[e];
    const double scale = std::max(distance(pa, images[2 * e]) / ground(a, steps[2 * e]),
                                  distance(pb, images[2 * e + 1]) / ground(b, steps[2 * e + 1]));
    const double length = distance(pa, pb);
    if (length > 10.0 * scale * ground(a, b) && length > 100e3)
      throw Error(ErrorClass::crs, "crs",
                  printf_string("the domain does not fit whole in the map of '%s': its edge "
                                "from %s to %s, %.3g km long, is %.3g km long once projected "
                                "(the map ends between them: across the antimeridian?); "
                                "give a CRS centred on the domain, --dst-crs utm or local, "
                                "or no --dst-crs",
                                target.name.c_str(), format_point(a).c_str(),
                                format_point(b).c_str(), ground(a, b) / 1e3, length / 1e3));
  }
}

// Edges are straight in the source's coordinates (a parallel in longitude and latitude,
// a line in Web Mercator), and most are curves in the meshing CRS: a box drawn from 2 to
// 4 E at 50 N has its northern side 480 m from the chord between its corners in a
// stereographic projection centred on it. Each edge of `projected` (the images of
// `source`'s points, one for one) gets the images of points along it, halving it until
// the image of each half's midpoint lies within `tolerance` of its chord (a few levels
// at most), as --bbox and --clip are densified. An edge over 180 degrees of longitude
// (one that crosses the antimeridian, its image the short way) keeps its chord.
void follow_curved_edges(const std::vector<Polygon>& source, std::vector<Polygon>& projected,
                         const CrsTransform& t, bool geographic, double tolerance) {
  constexpr int kMaxLevels = 10;  // up to 1,023 points an edge
  std::function<void(const Point2&, const Point2&, const Point2&, const Point2&, int, Ring&)>
      refine = [&](const Point2& a, const Point2& pa, const Point2& b, const Point2& pb, int levels,
                   Ring& out) {
        const Point2 m{0.5 * (a.x + b.x), 0.5 * (a.y + b.y)};
        Point2 pm = m;
        if (!t.transform(pm) || distance_to_segment(pm, pa, pb) <= tolerance) return;
        if (levels > 1) refine(a, pa, m, pm, levels - 1, out);
        out.push_back(pm);
        if (levels > 1) refine(m, pm, b, pb, levels - 1, out);
      };
  auto follow = [&](const Ring& r, Ring& q) {
    Ring out;
    out.reserve(q.size());
    for (std::size_t i = 0; i < r.size(); ++i) {
      const std::size_t j = (i + 1) % r.size();
      out.push_back(q[i]);
      if (geographic && std::abs(r[j].x - r[i].x) > 180.0) continue;
      refine(r[i], q[i], r[j], q[j], kMaxLevels, out);
    }
    q = std::move(out);
  };
  for (std::size_t k = 0; k < source.size(); ++k) {
    follow(source[k].outer, projected[k].outer);
    for (std::size_t h = 0; h < source[k].holes.size(); ++h)
      follow(source[k].holes[h], projected[k].holes[h]);
  }
}

}  // namespace

ProjectResult project_domain(const std::vector<Polygon>& polygons, const CrsInfo& source_crs,
                             const ProjectParams& params) {
  ProjectResult result;
  CrsInfo target;
  std::vector<Point2> outer_points;
  for (const Polygon& p : polygons)
    outer_points.insert(outer_points.end(), p.outer.begin(), p.outer.end());
  if (params.dst_crs.empty() && source_crs.projected) {
    result.source_not_kept = why_not_kept(source_crs, outer_points);
    result.source_kept = result.source_not_kept.empty();
  }
  // The domain in the source's own geographic CRS `geog`, for the automatic projections
  // (only they need one: an explicit --dst-crs asks nothing of the source's base).
  auto lonlat_points = [&](const CrsInfo& geog) {
    std::vector<Point2> lonlat = outer_points;
    if (CrsTransform(source_crs, geog).transform(lonlat) >= 0)
      throw Error(ErrorClass::crs, "crs", "cannot convert the domain to longitude and latitude");
    return lonlat;
  };
  if (result.source_kept) {
    target = source_crs;
  } else if (params.dst_crs == "utm") {
    // The zone of the domain's centre (as the local projection finds it: across the
    // antimeridian, round a pole), on WGS 84.
    const CrsInfo geog = geographic_base(source_crs);
    const LocalProjection centre = choose_local_projection(geog, lonlat_points(geog));
    if (centre.lat0_deg > 84.0 || centre.lat0_deg < -80.0)
      throw Error(ErrorClass::crs, "crs",
                  printf_string("--dst-crs utm: the domain's centre lies at %.4g degrees of "
                                "latitude, beyond UTM's 80 S to 84 N; give a polar CRS "
                                "(EPSG:3413, EPSG:3031) or --dst-crs local",
                                centre.lat0_deg));
    const int zone =
        std::clamp(static_cast<int>(std::floor((centre.lon0_deg + 180.0) / 6.0)) + 1, 1, 60);
    target = parse_crs("EPSG:" + std::to_string((centre.lat0_deg >= 0.0 ? 32600 : 32700) + zone),
                       "--dst-crs utm");
  } else if (!params.dst_crs.empty() && params.dst_crs != "local") {
    target = parse_crs(params.dst_crs, "--dst-crs");
    if (!target.projected)
      throw Error(ErrorClass::crs, "crs",
                  "--dst-crs '" + params.dst_crs + "' (" + target.name +
                      ") is not a projected CRS; meshing needs planar coordinates in metres");
    if (std::abs(target.linear_unit_m - 1.0) > 1e-12)
      throw Error(ErrorClass::crs, "crs",
                  "--dst-crs '" + params.dst_crs + "' (" + target.name +
                      ") is not in metres; choose a projected CRS in metres");
    // A zone mistyped (UTM 10N for Corsica) meshes in a map stretched by a fifth: said.
    double aou[4];
    if (crs_area_of_use(target, aou)) {
      const CrsInfo geog = geographic_base(source_crs);
      constexpr double kMarginDeg = 10.0;  // as for the input's own CRS
      for (const Point2& q : lonlat_points(geog))
        if (q.x < aou[0] - kMarginDeg || q.x > aou[2] + kMarginDeg || q.y < aou[1] - kMarginDeg ||
            q.y > aou[3] + kMarginDeg) {
          result.warning = printf_string(
              "--dst-crs '%s' (%s): the domain reaches lon %.4g, lat %.4g, far outside the "
              "CRS's area of use (lon %.4g to %.4g, lat %.4g to %.4g); the map strays from "
              "the ground there: check the CRS, or --dst-crs local",
              params.dst_crs.c_str(), target.name.c_str(), q.x, q.y, aou[0], aou[2], aou[1],
              aou[3]);
          break;
        }
    }
  } else {
    // Centred on the domain.
    const CrsInfo geog = geographic_base(source_crs);
    result.local = choose_local_projection(geog, lonlat_points(geog));
    target = result.local->crs;
  }

  std::vector<Polygon> source = polygons;
  CrsTransform t(source_crs, target);
  if (source_crs.geographic) read_antimeridian_as_west(t, source);
  std::vector<Polygon> projected = source;
  Point2 failed;
  if (!transform_all(t, projected, &failed))
    throw Error(ErrorClass::crs, "crs",
                "point " + format_point(failed) + " cannot be transformed from '" + source_crs.name +
                    "' to '" + target.name + "'");
  // The local projection's map ends only at the domain's antipode.
  if (source_crs.geographic && !result.local) check_not_torn(polygons, projected, t, target);
  if (!result.source_kept) {
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (const Polygon& p : projected)
      for (const Point2& q : p.outer)
        x0 = std::min(x0, q.x), y0 = std::min(y0, q.y), x1 = std::max(x1, q.x),
        y1 = std::max(y1, q.y);
    follow_curved_edges(source, projected, t, source_crs.geographic,
                        kCurvedEdgeTolerance * std::hypot(x1 - x0, y1 - y0));
  }
  // Points that are one once projected (every point at a pole; see above for the
  // antimeridian) leave duplicates and spikes.
  remove_duplicates_and_spikes(projected);
  if (params.dst_crs == "utm") {
    std::vector<Point2> points;
    for (const Polygon& p : projected) points.insert(points.end(), p.outer.begin(), p.outer.end());
    const CrsDistortion d = crs_distortion(target, points);
    if (d.max_scale_error > kKeptScaleError)
      result.warning = printf_string(
          "--dst-crs utm (%s): the domain reaches where that zone's scale strays by up to "
          "%.2g%% from the ground's; consider --dst-crs local",
          target.name.c_str(), 100.0 * d.max_scale_error);
  }
  for (Polygon& p : projected) orient_polygon(p);
  sort_by_area(projected);
  result.domain.polygons = std::move(projected);
  result.domain.crs_wkt = target.wkt;
  result.domain.crs_name = target.name;
  return result;
}

}  // namespace isoquad
