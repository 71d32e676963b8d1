#include "quad/quad_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>

namespace isoquad {

Point2 chain_point(const BackgroundMesh& mesh, const BoundaryChain& chain, double arc_m) {
  const double len = chain.length_m;
  double s = std::fmod(arc_m, len);
  if (s < 0) s += len;
  // arc_length_m is increasing from 0; the last segment closes the chain.
  const auto& arcs = chain.arc_length_m;
  const std::size_t n = arcs.size();
  std::size_t i = static_cast<std::size_t>(std::upper_bound(arcs.begin(), arcs.end(), s) - arcs.begin());
  i = i == 0 ? 0 : i - 1;
  const double a0 = arcs[i], a1 = i + 1 < n ? arcs[i + 1] : len;
  const Point2& p = mesh.points[chain.vertices[i]];
  const Point2& q = mesh.points[chain.vertices[(i + 1) % n]];
  const double t = a1 > a0 ? (s - a0) / (a1 - a0) : 0.0;
  return {p.x + t * (q.x - p.x), p.y + t * (q.y - p.y)};
}

namespace {

// How far ahead of arc `from` arc `to` lies along a closed chain of length `length`, in
// [0, length).
double arc_ahead(double from, double to, double length) {
  const double d = std::fmod(to - from, length);
  return d < 0 ? d + length : d;
}

}  // namespace

std::vector<char> boundary_backtracks(const QuadMesh& m, const BackgroundMesh& bg,
                                      const std::vector<std::array<int, 2>>& edges) {
  const std::size_t ne = edges.size();
  std::vector<char> back(ne, 0), seen(ne, 0);
  std::vector<int> out_edge(m.points.size(), -1);
  for (std::size_t i = 0; i < ne; ++i) out_edge[edges[i][0]] = static_cast<int>(i);
  std::vector<int> loop;
  for (std::size_t first = 0; first < ne; ++first) {
    if (seen[first]) continue;
    loop.clear();
    for (int e = static_cast<int>(first); e >= 0 && !seen[e]; e = out_edge[edges[e][1]]) {
      seen[e] = 1;
      loop.push_back(e);
    }
    const int c = m.chain[edges[first][0]];
    if (c < 0) continue;
    bool one_chain = true;
    for (int e : loop)
      one_chain = one_chain && m.chain[edges[e][0]] == c && m.chain[edges[e][1]] == c;
    const double length = bg.chains[c].length_m;
    if (!one_chain || !(length > 0)) continue;
    std::vector<std::pair<double, int>> spans;
    double total = 0;
    for (int e : loop) {
      const double d = arc_ahead(m.arc_m[edges[e][0]], m.arc_m[edges[e][1]], length);
      spans.push_back({d, e});
      total += d;
    }
    const long extra = std::lround(total / length) - 1;
    if (extra <= 0) continue;
    std::sort(spans.begin(), spans.end(), std::greater<>());
    for (long k = 0; k < extra && k < static_cast<long>(spans.size()); ++k)
      back[spans[k].second] = 1;
  }
  return back;
}

ChordDeparture chord_departure(const QuadMesh& m, const BackgroundMesh& bg, int a, int b) {
  ChordDeparture result;
  const int c = m.chain[a];
  if (c < 0 || m.chain[b] != c) return result;
  const BoundaryChain& chain = bg.chains[c];
  const double length = chain.length_m;
  if (!(length > 0)) return result;
  // The chain's stretch from a to b: the edge runs the chain's way (the mesh and the
  // domain are both on their left).
  const double from = m.arc_m[a], span = arc_ahead(from, m.arc_m[b], length);
  const auto& arcs = chain.arc_length_m;
  const std::size_t n = arcs.size();
  std::size_t k = static_cast<std::size_t>(
      std::upper_bound(arcs.begin(), arcs.end(), std::fmod(from, length)) - arcs.begin());
  const Point2 &p = m.points[a], &q = m.points[b];
  const double dx = q.x - p.x, dy = q.y - p.y, l2 = dx * dx + dy * dy;
  for (std::size_t step = 0; step < n; ++step, ++k) {
    const std::size_t i = k % n;
    const double along = arc_ahead(from, arcs[i], length);
    if (along <= 0 || along >= span) break;
    const Point2& v = bg.points[chain.vertices[i]];
    const double t = l2 > 0 ? std::clamp(((v.x - p.x) * dx + (v.y - p.y) * dy) / l2, 0.0, 1.0) : 0.0;
    const double d = std::hypot(v.x - (p.x + t * dx), v.y - (p.y + t * dy));
    if (d > result.distance_m) result = {d, chain.vertices[i]};
  }
  return result;
}

double quad_convexity(const Point2& a, const Point2& b, const Point2& c, const Point2& d) {
  const Point2 v[4] = {a, b, c, d};
  // A side shorter than kDegenerateSide times the longest is no side: its direction is
  // rounding noise, and the quad a triangle (the Baltic at 1:10m had one of 2e-9 m in a
  // quad 2.5 km long, which the turns alone counted convex).
  constexpr double kDegenerateSide = 1e-6;
  double shortest2 = std::numeric_limits<double>::infinity(), longest2 = 0.0;
  for (int i = 0; i < 4; ++i) {
    const double dx = v[(i + 1) % 4].x - v[i].x, dy = v[(i + 1) % 4].y - v[i].y;
    shortest2 = std::min(shortest2, dx * dx + dy * dy);
    longest2 = std::max(longest2, dx * dx + dy * dy);
  }
  if (shortest2 <= kDegenerateSide * kDegenerateSide * longest2) return -1.0;
  double worst = 1.0;
  for (int i = 0; i < 4; ++i) {
    const Point2& p = v[(i + 3) % 4];
    const Point2& q = v[i];
    const Point2& r = v[(i + 1) % 4];
    const double ux = q.x - p.x, uy = q.y - p.y, wx = r.x - q.x, wy = r.y - q.y;
    const double l2 = (ux * ux + uy * uy) * (wx * wx + wy * wy);
    if (l2 == 0) return -1.0;
    worst = std::min(worst, (ux * wy - uy * wx) / std::sqrt(l2));
  }
  return worst;
}

double quad_convexity(const QuadMesh& m, int q) {
  const auto& t = m.quads[q];
  return quad_convexity(m.points[t[0]], m.points[t[1]], m.points[t[2]], m.points[t[3]]);
}

Point2 quad_centroid(const QuadMesh& m, int q) {
  Point2 c{0, 0};
  for (int v : m.quads[q]) c.x += 0.25 * m.points[v].x, c.y += 0.25 * m.points[v].y;
  return c;
}

namespace {

// Sign of the turn a -> b -> c (0 when collinear).
int orientation(const Point2& a, const Point2& b, const Point2& c) {
  const double d = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  return (d > 0) - (d < 0);
}

bool on_segment(const Point2& a, const Point2& b, const Point2& p) {
  return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
         p.y <= std::max(a.y, b.y);
}

// Segments pq and rs meet (ends included).
bool segments_meet(const Point2& p, const Point2& q, const Point2& r, const Point2& s) {
  const int o1 = orientation(p, q, r), o2 = orientation(p, q, s);
  const int o3 = orientation(r, s, p), o4 = orientation(r, s, q);
  if (o1 != o2 && o3 != o4) return true;
  return (o1 == 0 && on_segment(p, q, r)) || (o2 == 0 && on_segment(p, q, s)) ||
         (o3 == 0 && on_segment(r, s, p)) || (o4 == 0 && on_segment(r, s, q));
}

}  // namespace

std::vector<std::array<int, 2>> boundary_edges(const QuadMesh& m) {
  // Directed quad edges whose reverse no quad has: each vertex's outgoing edges in a
  // compressed table, the reverse looked up among the few of its other end.
  const std::size_t n = m.points.size();
  std::vector<int> start(n + 1, 0);
  for (const auto& q : m.quads)
    for (int v : q) ++start[v + 1];
  for (std::size_t i = 0; i < n; ++i) start[i + 1] += start[i];
  std::vector<int> to(start[n]);
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (const auto& q : m.quads)
    for (int i = 0; i < 4; ++i) to[fill[q[i]]++] = q[(i + 1) % 4];
  std::vector<std::array<int, 2>> edges;
  for (const auto& q : m.quads)
    for (int i = 0; i < 4; ++i) {
      const int a = q[i], b = q[(i + 1) % 4];
      if (std::find(to.begin() + start[b], to.begin() + start[b + 1], a) == to.begin() + start[b + 1])
        edges.push_back({a, b});
    }
  return edges;
}

bool boundary_edges_meet(const QuadMesh& m, const std::array<int, 2>& e, const std::array<int, 2>& f) {
  const int shared = (e[0] == f[0]) + (e[0] == f[1]) + (e[1] == f[0]) + (e[1] == f[1]);
  const Point2 &p = m.points[e[0]], &q = m.points[e[1]], &r = m.points[f[0]], &s = m.points[f[1]];
  if (shared == 0) return segments_meet(p, q, r, s);
  if (shared != 1) return false;
  // Edges with a common end meet elsewhere only if they overlap along a line.
  const int o = e[0] == f[0] || e[0] == f[1] ? 0 : 1;  // e's shared end
  const Point2& common = o == 0 ? p : q;
  const Point2& e_other = o == 0 ? q : p;
  const Point2& f_other = (f[0] == e[o]) ? s : r;
  return orientation(common, e_other, f_other) == 0 &&
         (e_other.x - common.x) * (f_other.x - common.x) +
                 (e_other.y - common.y) * (f_other.y - common.y) > 0;
}

std::vector<std::array<int, 4>> boundary_crossings(const QuadMesh& m) {
  std::vector<std::array<int, 4>> out;
  const std::vector<std::array<int, 2>> edges = boundary_edges(m);
  if (edges.size() < 2) return out;
  // A uniform grid of cells about one mean edge long; a pair is tested in the first cell
  // both edges' boxes share.
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300, total = 0;
  for (const auto& e : edges) {
    const Point2 &a = m.points[e[0]], &b = m.points[e[1]];
    x0 = std::min({x0, a.x, b.x}), y0 = std::min({y0, a.y, b.y});
    x1 = std::max({x1, a.x, b.x}), y1 = std::max({y1, a.y, b.y});
    total += distance(a, b);
  }
  const double cell = std::max({total / edges.size(), (x1 - x0) / 4096, (y1 - y0) / 4096, 1e-9});
  const int nx = static_cast<int>((x1 - x0) / cell) + 1;
  auto box = [&](const std::array<int, 2>& e) {
    const Point2 &a = m.points[e[0]], &b = m.points[e[1]];
    return std::array<int, 4>{static_cast<int>((std::min(a.x, b.x) - x0) / cell),
                              static_cast<int>((std::min(a.y, b.y) - y0) / cell),
                              static_cast<int>((std::max(a.x, b.x) - x0) / cell),
                              static_cast<int>((std::max(a.y, b.y) - y0) / cell)};
  };
  // (cell, edge) for every cell an edge's box covers, sorted: the non-empty cells in
  // order, each with its edges in order (a dense grid of up to 4096 x 4096 cells would
  // cost more to allocate than the test itself on a large domain).
  std::vector<std::pair<std::int64_t, int>> items;
  for (int k = 0; k < static_cast<int>(edges.size()); ++k) {
    const auto bx = box(edges[k]);
    for (int j = bx[1]; j <= bx[3]; ++j)
      for (int i = bx[0]; i <= bx[2]; ++i) items.push_back({static_cast<std::int64_t>(j) * nx + i, k});
  }
  std::sort(items.begin(), items.end());
  for (std::size_t first = 0; first < items.size();) {
    std::size_t last = first;
    while (last < items.size() && items[last].first == items[first].first) ++last;
    const int ci = static_cast<int>(items[first].first % nx), cj = static_cast<int>(items[first].first / nx);
    for (std::size_t u = first; u < last; ++u)
      for (std::size_t w = u + 1; w < last; ++w) {
        const auto &e = edges[items[u].second], &f = edges[items[w].second];
        const auto be = box(e), bf = box(f);
        // Only in the first cell the two boxes share.
        if (std::max(be[0], bf[0]) != ci || std::max(be[1], bf[1]) != cj) continue;
        if (boundary_edges_meet(m, e, f)) out.push_back({e[0], e[1], f[0], f[1]});
      }
    first = last;
  }
  return out;
}

std::size_t count_boundary_crossings(const QuadMesh& m, Point2* where) {
  const auto crossings = boundary_crossings(m);
  if (!crossings.empty() && where) {
    const Point2 &p = m.points[crossings[0][0]], &q = m.points[crossings[0][1]];
    *where = {0.5 * (p.x + q.x), 0.5 * (p.y + q.y)};
  }
  return crossings.size();
}

double quad_aspect(const QuadMesh& m, int q) {
  double shortest = std::numeric_limits<double>::infinity(), longest = 0;
  for (int i = 0; i < 4; ++i) {
    const double l = distance(m.points[m.quads[q][i]], m.points[m.quads[q][(i + 1) % 4]]);
    shortest = std::min(shortest, l), longest = std::max(longest, l);
  }
  return shortest > 0 ? longest / shortest : std::numeric_limits<double>::infinity();
}

std::array<double, 4> quad_angles_deg(const QuadMesh& m, int q) {
  const auto& t = m.quads[q];
  std::array<double, 4> out{};
  for (int i = 0; i < 4; ++i) {
    const Point2& p = m.points[t[(i + 3) % 4]];
    const Point2& c = m.points[t[i]];
    const Point2& n = m.points[t[(i + 1) % 4]];
    const double ax = p.x - c.x, ay = p.y - c.y, bx = n.x - c.x, by = n.y - c.y;
    // Interior angle of a counter-clockwise polygon at c, in [0, 360).
    double a = std::atan2(ax * by - ay * bx, ax * bx + ay * by);
    a = -a;  // from the next edge to the previous one, counter-clockwise
    if (a < 0) a += 2 * M_PI;
    out[i] = a * 180.0 / M_PI;
  }
  return out;
}

bool fails_schism_angle_ratio(const std::array<double, 4>& a) {
  const double amin = std::min({a[0], a[1], a[2], a[3]}), amax = std::max({a[0], a[1], a[2], a[3]});
  return amax > 0 && amin < kSchismAngleRatio * amax;
}

bool fails_schism_aspect_ratio(double aspect) {
  return std::isfinite(aspect) && aspect > kSchismAspectRatio;
}

bool fails_schism_checks(const QuadMesh& m, int q) {
  return fails_schism_angle_ratio(quad_angles_deg(m, q)) ||
         fails_schism_aspect_ratio(quad_aspect(m, q));
}

double quad_area(const QuadMesh& m, int q) {
  const auto& t = m.quads[q];
  const Point2 &a = m.points[t[0]], &b = m.points[t[1]], &c = m.points[t[2]], &d = m.points[t[3]];
  return 0.5 * ((c.x - a.x) * (d.y - b.y) - (d.x - b.x) * (c.y - a.y));
}

}  // namespace isoquad
