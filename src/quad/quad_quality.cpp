#include "quad/quad_quality.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "mesh/locate.h"

namespace isoquad {

namespace {

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  const std::size_t k = std::min(v.size() - 1, static_cast<std::size_t>(p * (v.size() - 1) + 0.5));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

void add_to_histogram(std::vector<int>& h, double value, double lo, double width) {
  const int n = static_cast<int>(h.size());
  const int bin = std::clamp(static_cast<int>(std::floor((value - lo) / width)), 0, n - 1);
  ++h[bin];
}

// The departures of the domain's boundary from the mesh's (QualitySummary): per boundary
// edge, in sizes h; the largest in metres and where, into s.
std::vector<double> boundary_departures(const QuadMesh& m, const BackgroundMesh& bg,
                                        const SizingField& size,
                                        const std::vector<std::array<int, 2>>& edges,
                                        QualitySummary& s) {
  std::vector<double> in_h;
  const std::vector<char> back = boundary_backtracks(m, bg, edges);
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const std::array<int, 2>& e = edges[i];
    in_h.push_back(0.0);
    s.num_boundary_backtracks += back[i];
    const ChordDeparture d =
        back[i] ? chord_departure(m, bg, e[1], e[0]) : chord_departure(m, bg, e[0], e[1]);
    if (d.vertex < 0) continue;
    const double h = size.size_m[d.vertex];
    if (h > 0) in_h.back() = d.distance_m / h;
    if (d.distance_m > s.boundary_departure_max_m) {
      s.boundary_departure_max_m = d.distance_m;
      s.boundary_departure_where = bg.points[d.vertex];
    }
  }
  return in_h;
}

// `c` when it lies inside or on the counter-clockwise polygon `corners`, else the point
// where the segment from `mean` (inside) to it leaves the polygon (D-Flow FM keeps a
// cell's centre inside it).
Point2 inside_cell(const std::vector<Point2>& corners, const Point2& mean, const Point2& c) {
  const std::size_t n = corners.size();
  bool inside = true;
  for (std::size_t i = 0; i < n && inside; ++i) {
    const Point2 &a = corners[i], &b = corners[(i + 1) % n];
    inside = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x) >= 0;
  }
  if (inside) return c;
  for (std::size_t i = 0; i < n; ++i) {
    const Point2 &a = corners[i], &b = corners[(i + 1) % n];
    const double dx = c.x - mean.x, dy = c.y - mean.y, ex = b.x - a.x, ey = b.y - a.y;
    const double den = dx * ey - dy * ex;
    if (den == 0) continue;
    const double s = ((a.x - mean.x) * ey - (a.y - mean.y) * ex) / den;  // along mean -> c
    const double u = ((a.x - mean.x) * dy - (a.y - mean.y) * dx) / den;  // along a -> b
    if (s >= 0 && s <= 1 && u >= 0 && u <= 1) return {mean.x + s * dx, mean.y + s * dy};
  }
  return mean;
}

// For each cell (the quads, then the triangles), the cell across each side (side i from
// corner i; -1 on the boundary; a triangle's fourth -1).
std::vector<std::array<int, 4>> cells_across(const QuadMesh& m,
                                             const std::vector<std::array<int, 3>>& triangles) {
  const int nq = static_cast<int>(m.quads.size());
  const int nc = nq + static_cast<int>(triangles.size());
  // (edge, cell, side) sorted by edge: an edge of two cells comes twice in a row.
  std::vector<std::tuple<std::array<int, 2>, int, int>> sides;
  for (int c = 0; c < nc; ++c) {
    const int n = c < nq ? 4 : 3;
    for (int i = 0; i < n; ++i) {
      const int v = c < nq ? m.quads[c][i] : triangles[c - nq][i];
      const int w = c < nq ? m.quads[c][(i + 1) % 4] : triangles[c - nq][(i + 1) % 3];
      sides.push_back({{std::min(v, w), std::max(v, w)}, c, i});
    }
  }
  std::sort(sides.begin(), sides.end());
  std::vector<std::array<int, 4>> across(nc, {-1, -1, -1, -1});
  for (std::size_t k = 0; k + 1 < sides.size(); ++k)
    if (std::get<0>(sides[k]) == std::get<0>(sides[k + 1])) {
      across[std::get<1>(sides[k])][std::get<2>(sides[k])] = std::get<1>(sides[k + 1]);
      across[std::get<1>(sides[k + 1])][std::get<2>(sides[k + 1])] = std::get<1>(sides[k]);
    }
  return across;
}

}  // namespace

Point2 dflowfm_centre(const QuadMesh& m, int q, const std::array<bool, 4>& shared) {
  const auto& t = m.quads[q];
  Point2 mean{0, 0};
  for (int v : t) mean.x += 0.25 * m.points[v].x, mean.y += 0.25 * m.points[v].y;
  if (std::count(shared.begin(), shared.end(), true) < 2) return mean;
  Point2 c = mean;
  for (int sweep = 0; sweep < 100; ++sweep) {
    const Point2 before = c;
    for (int i = 0; i < 4; ++i) {
      if (!shared[i]) continue;
      const Point2 &a = m.points[t[i]], &b = m.points[t[(i + 1) % 4]];
      const double len = distance(a, b);
      if (len <= 0) continue;
      const double ux = (b.x - a.x) / len, uy = (b.y - a.y) / len;  // along the edge
      const double along = (c.x - 0.5 * (a.x + b.x)) * ux + (c.y - 0.5 * (a.y + b.y)) * uy;
      c.x -= 0.1 * along * ux;
      c.y -= 0.1 * along * uy;
    }
    if (sweep > 0 && std::abs(c.x - before.x) < 1e-3 && std::abs(c.y - before.y) < 1e-3) break;
  }
  return inside_cell({m.points[t[0]], m.points[t[1]], m.points[t[2]], m.points[t[3]]}, mean, c);
}

double link_orthogonality(const Point2& a, const Point2& b, const Point2& ca, const Point2& cb) {
  const double ex = b.x - a.x, ey = b.y - a.y, fx = cb.x - ca.x, fy = cb.y - ca.y;
  const double norms = std::hypot(ex, ey) * std::hypot(fx, fy);
  return norms > 0 ? std::abs(ex * fx + ey * fy) / norms : 1.0;
}

std::vector<std::array<int, 4>> quads_across(const QuadMesh& m) {
  return cells_across(m, {});
}

DflowfmLinks dflowfm_links(const QuadMesh& m) {
  return dflowfm_links(m, {});
}

DflowfmLinks dflowfm_links(const QuadMesh& m, const std::vector<std::array<int, 3>>& triangles) {
  const int nq = static_cast<int>(m.quads.size());
  const int nc = nq + static_cast<int>(triangles.size());
  auto corners = [&](int c) { return c < nq ? 4 : 3; };
  auto corner = [&](int c, int i) { return c < nq ? m.quads[c][i] : triangles[c - nq][i]; };
  const std::vector<std::array<int, 4>> across = cells_across(m, triangles);
  std::vector<Point2> centre(nc);
  std::vector<double> area(nc);
  for (int c = 0; c < nc; ++c) {
    const auto& a = across[c];
    if (c < nq) {
      centre[c] = dflowfm_centre(m, c, {a[0] >= 0, a[1] >= 0, a[2] >= 0, a[3] >= 0});
      area[c] = std::abs(quad_area(m, c));
      continue;
    }
    const Point2 &p = m.points[corner(c, 0)], &q = m.points[corner(c, 1)],
                 &r = m.points[corner(c, 2)];
    area[c] = std::abs(signed_area(p, q, r));
    // The circumcentre, from p.
    const double bx = q.x - p.x, by = q.y - p.y, cx = r.x - p.x, cy = r.y - p.y;
    const double d = 2 * (bx * cy - by * cx);
    const double b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
    const Point2 mean{(p.x + q.x + r.x) / 3, (p.y + q.y + r.y) / 3};
    if (d == 0) {
      centre[c] = mean;
      continue;
    }
    const Point2 circumcentre{p.x + (cy * b2 - by * c2) / d, p.y + (bx * c2 - cx * b2) / d};
    centre[c] = d > 0 ? inside_cell({p, q, r}, mean, circumcentre)
                      : inside_cell({r, q, p}, mean, circumcentre);
  }
  DflowfmLinks out;
  for (int a = 0; a < nc; ++a)
    for (int i = 0; i < corners(a); ++i) {
      const int b = across[a][i];
      if (b < a) continue;  // each link once, from its lower cell
      const int v = corner(a, i), w = corner(a, (i + 1) % corners(a));
      out.edge.push_back({std::min(v, w), std::max(v, w)});
      out.quads.push_back({a, b});
      out.orthogonality.push_back(
          link_orthogonality(m.points[v], m.points[w], centre[a], centre[b]));
      const double lo = std::min(area[a], area[b]), hi = std::max(area[a], area[b]);
      out.smoothness.push_back(lo > 0 ? hi / lo : std::numeric_limits<double>::infinity());
    }
  return out;
}

void summarize_dflowfm(const DflowfmLinks& links, QualitySummary& s,
                       std::vector<double>* per_quad) {
  std::size_t ortho_ok = 0, smooth_ok = 0;
  double ortho_sum = 0;
  s.dflowfm_orthogonality_max = s.dflowfm_orthogonality_mean = 0;
  s.dflowfm_orthogonality_violations = 0;
  s.dflowfm_share_orthogonality_002 = s.dflowfm_smoothness_max = s.dflowfm_share_smoothness_12 = 0;
  for (std::size_t k = 0; k < links.edge.size(); ++k) {
    const double o = links.orthogonality[k], r = links.smoothness[k];
    if (per_quad)
      for (int q : links.quads[k])
        if (q < static_cast<int>(per_quad->size())) (*per_quad)[q] = std::max((*per_quad)[q], o);
    s.dflowfm_orthogonality_max = std::max(s.dflowfm_orthogonality_max, o);
    ortho_sum += o;
    s.dflowfm_orthogonality_violations += o > 0.5;
    ortho_ok += o <= 0.02;
    s.dflowfm_smoothness_max = std::max(s.dflowfm_smoothness_max, r);
    smooth_ok += r <= 1.2;
  }
  if (!links.edge.empty()) {
    const double n = static_cast<double>(links.edge.size());
    s.dflowfm_orthogonality_mean = ortho_sum / n;
    s.dflowfm_share_orthogonality_002 = ortho_ok / n;
    s.dflowfm_share_smoothness_12 = smooth_ok / n;
  }
}

QualitySummary measure_quality(const QuadMesh& m, const BackgroundMesh& bg, const SizingField& size,
                               const CrossField& cross, QuadMetrics* out) {
  QualitySummary s;
  QuadMetrics local;
  QuadMetrics& qm = out ? *out : local;
  const int nq = static_cast<int>(m.quads.size());
  const int np = static_cast<int>(m.points.size());
  s.num_quads = nq;
  s.num_vertices = np;
  s.num_boundary_crossings = count_boundary_crossings(m);
  qm = QuadMetrics{};
  qm.min_angle_deg.resize(nq);
  qm.max_angle_deg.resize(nq);
  qm.aspect_ratio.resize(nq);
  qm.size_ratio.resize(nq);
  qm.orientation_deg.resize(nq);
  qm.eta.resize(nq);
  s.angle_histogram.assign(36, 0);
  s.size_ratio_histogram.assign(30, 0);
  s.orientation_histogram.assign(45, 0);
  const TriangleLocator locator(bg);
  std::size_t in_range = 0, angles = 0;
  s.min_angle_deg = 360;
  s.max_angle_deg = 0;
  s.eta_min = 1;
  double eta_sum = 0, orient_sum = 0;
  for (int q = 0; q < nq; ++q) {
    if (quad_convexity(m, q) <= 0) ++s.num_nonconvex;
    const auto a = quad_angles_deg(m, q);
    double amin = 360, amax = 0, worst = 0;
    for (double x : a) {
      amin = std::min(amin, x), amax = std::max(amax, x);
      worst = std::max(worst, std::abs(90 - x));
      in_range += x >= 75 && x <= 105;
      ++angles;
      add_to_histogram(s.angle_histogram, x, 0, 5);
    }
    qm.min_angle_deg[q] = amin;
    qm.max_angle_deg[q] = amax;
    qm.eta[q] = 1 - worst / 90;
    s.min_angle_deg = std::min(s.min_angle_deg, amin);
    s.max_angle_deg = std::max(s.max_angle_deg, amax);
    eta_sum += qm.eta[q];
    s.eta_min = std::min(s.eta_min, qm.eta[q]);
    // A quad with a corner of 180 degrees or more (not convex, or clockwise: every corner
    // 270) fails too: SCHISM stops on it, whatever the ratio of its angles.
    const bool bad_ratio = fails_schism_angle_ratio(a) || amax >= 180.0;
    if (bad_ratio) ++s.schism_angle_ratio_violations;

    const auto& t = m.quads[q];
    Point2 c{0, 0};
    for (int i = 0; i < 4; ++i) c.x += 0.25 * m.points[t[i]].x, c.y += 0.25 * m.points[t[i]].y;
    const double aspect = quad_aspect(m, q);
    qm.aspect_ratio[q] = aspect;
    // A side of length 0 (an infinite ratio) fails too.
    const bool bad_aspect = fails_schism_aspect_ratio(aspect) || std::isinf(aspect);
    if (bad_aspect) ++s.schism_aspect_violations;
    if (bad_ratio || bad_aspect) ++s.schism_failures;
    const Location loc = locator.locate(c);
    const double h = loc.triangle >= 0 ? size.at(bg, loc.triangle, loc.bary) : 0.0;
    qm.size_ratio[q] = h > 0 ? std::sqrt(std::max(0.0, quad_area(m, q))) / h : 0.0;
    add_to_histogram(s.size_ratio_histogram, qm.size_ratio[q], 0.25, 0.05);
    const double theta = loc.triangle >= 0 ? cross_angle_at(bg, cross, loc.triangle, loc.bary) : 0.0;
    double dev = 0;
    for (int i = 0; i < 4; ++i) {
      const Point2 &p = m.points[t[i]], &r = m.points[t[(i + 1) % 4]];
      const double phi = std::atan2(r.y - p.y, r.x - p.x);
      dev += std::abs(cross_rotation_rad(theta, phi)) * 180.0 / M_PI;
    }
    qm.orientation_deg[q] = dev / 4;
    orient_sum += qm.orientation_deg[q];
    add_to_histogram(s.orientation_histogram, qm.orientation_deg[q], 0, 1);
  }
  s.share_angles_75_105 = angles ? static_cast<double>(in_range) / angles : 0;
  s.eta_mean = nq ? eta_sum / nq : 0;
  s.orientation_mean_deg = nq ? orient_sum / nq : 0;
  s.orientation_p90_deg = percentile(qm.orientation_deg, 0.9);
  s.size_ratio_median = percentile(qm.size_ratio, 0.5);
  std::size_t size_ok = 0;
  for (double r : qm.size_ratio) size_ok += r >= 0.8 && r <= 1.25;
  s.share_size_08_125 = nq ? static_cast<double>(size_ok) / nq : 0;

  // Degrees; boundary vertices from edges used by one quad, with the boundary angle
  // (sum of the incident quads' angles) giving the ideal degree.
  qm.degree.assign(np, 0);
  qm.boundary.assign(np, 0);
  qm.ideal_degree.assign(np, 4);
  std::vector<double> angle_sum(np, 0.0);
  std::vector<std::pair<std::pair<int, int>, int>> edges;
  for (int q = 0; q < nq; ++q) {
    const auto a = quad_angles_deg(m, q);
    for (int i = 0; i < 4; ++i) {
      const int v = m.quads[q][i], w = m.quads[q][(i + 1) % 4];
      ++qm.degree[v];
      angle_sum[v] += a[i];
      edges.push_back({{std::min(v, w), std::max(v, w)}, q});
    }
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j].first == edges[i].first) ++j;
    if (j - i == 1) qm.boundary[edges[i].first.first] = qm.boundary[edges[i].first.second] = 1;
    i = j;
  }
  std::size_t interior = 0, interior_regular = 0, boundary = 0, boundary_regular = 0;
  s.interior_degree_histogram.assign(9, 0);
  for (int v = 0; v < np; ++v) {
    if (qm.degree[v] == 0) continue;
    if (qm.boundary[v]) {
      qm.ideal_degree[v] = std::max(1, static_cast<int>(std::lround(angle_sum[v] / 90.0)));
      ++boundary;
      boundary_regular += qm.degree[v] == qm.ideal_degree[v];
    } else {
      ++interior;
      interior_regular += qm.degree[v] == 4;
      ++s.interior_degree_histogram[std::min(qm.degree[v], 8)];
    }
  }
  qm.irregular_corners.assign(nq, 0.0);
  for (int q = 0; q < nq; ++q)
    for (int v : m.quads[q]) qm.irregular_corners[q] += qm.degree[v] != qm.ideal_degree[v];
  s.num_boundary_vertices = boundary;
  s.share_regular_interior = interior ? static_cast<double>(interior_regular) / interior : 0;
  s.share_regular_boundary = boundary ? static_cast<double>(boundary_regular) / boundary : 0;
  s.share_regular_all =
      interior + boundary ? static_cast<double>(interior_regular + boundary_regular) / (interior + boundary) : 0;

  qm.orthogonality.assign(nq, 0.0);
  summarize_dflowfm(dflowfm_links(m), s, &qm.orthogonality);

  for (int q = 0; q < nq; ++q) s.mesh_area_m2 += quad_area(m, q);
  s.domain_area_m2 = area(bg);
  measure_coast(m, bg, size, boundary_edges(m), s);
  return s;
}

void measure_coast(const QuadMesh& mesh, const BackgroundMesh& background, const SizingField& size,
                   const std::vector<std::array<int, 2>>& edges, QualitySummary& summary) {
  const std::vector<double> departures =
      boundary_departures(mesh, background, size, edges, summary);
  if (!departures.empty()) {
    summary.boundary_departure_max_h = *std::max_element(departures.begin(), departures.end());
    summary.boundary_departure_p95_h = percentile(departures, 0.95);
  }
}

void measure_line_following(const QuadMesh& mesh, const std::vector<std::vector<Point2>>& lines,
                            QualitySummary& summary) {
  summary.align_num_quads = 0;
  summary.align_deviation_mean_deg = 0;
  const PolylineIndex index(lines);
  double sum = 0;
  for (int q = 0; q < static_cast<int>(mesh.quads.size()); ++q) {
    const auto& t = mesh.quads[q];
    Point2 c{0, 0};
    for (int i = 0; i < 4; ++i)
      c.x += 0.25 * mesh.points[t[i]].x, c.y += 0.25 * mesh.points[t[i]].y;
    Point2 a, b;
    if (!index.nearest_segment(c, 0.5 * std::sqrt(std::max(0.0, quad_area(mesh, q))), a, b))
      continue;
    const double line = std::atan2(b.y - a.y, b.x - a.x);
    for (int i = 0; i < 4; ++i) {
      const Point2 &p = mesh.points[t[i]], &r = mesh.points[t[(i + 1) % 4]];
      sum += std::abs(cross_rotation_rad(line, std::atan2(r.y - p.y, r.x - p.x))) * 45.0 / M_PI;
    }
    ++summary.align_num_quads;
  }
  if (summary.align_num_quads > 0) summary.align_deviation_mean_deg = sum / summary.align_num_quads;
}

}  // namespace isoquad
