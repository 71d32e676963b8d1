#include "quad/quad_mesh.h"

#include <algorithm>
#include <cmath>

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

double quad_convexity(const Point2& a, const Point2& b, const Point2& c, const Point2& d) {
  const Point2 v[4] = {a, b, c, d};
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

double quad_area(const QuadMesh& m, int q) {
  const auto& t = m.quads[q];
  const Point2 &a = m.points[t[0]], &b = m.points[t[1]], &c = m.points[t[2]], &d = m.points[t[3]];
  return 0.5 * ((c.x - a.x) * (d.y - b.y) - (d.x - b.x) * (c.y - a.y));
}

}  // namespace isoquad
