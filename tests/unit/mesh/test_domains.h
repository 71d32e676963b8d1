// Small analytic domains and geometric checks shared by the mesh and field tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/geometry.h"
#include "mesh/background_mesh.h"

namespace isoquad::test {

constexpr double kPi = 3.14159265358979323846;

// Square [0, side_m]^2, counter-clockwise.
inline Domain square_domain(double side_m) {
  Domain d;
  d.polygons.push_back({{{0, 0}, {side_m, 0}, {side_m, side_m}, {0, side_m}}, {}});
  return d;
}

// Regular n-gon of radius r_m centred on the origin, counter-clockwise.
inline Ring circle_ring(double r_m, int n) {
  Ring ring;
  for (int k = 0; k < n; ++k)
    ring.push_back({r_m * std::cos(2 * kPi * k / n), r_m * std::sin(2 * kPi * k / n)});
  return ring;
}

inline Domain disk_domain(double r_m, int n) {
  Domain d;
  d.polygons.push_back({circle_ring(r_m, n), {}});
  return d;
}

// Outer ring r_outer_m (CCW), one hole r_inner_m (CW).
inline Domain annulus_domain(double r_outer_m, double r_inner_m, int n) {
  Domain d;
  Ring hole = circle_ring(r_inner_m, n);
  std::vector<Point2> reversed(hole.rbegin(), hole.rend());
  d.polygons.push_back({circle_ring(r_outer_m, n), {reversed}});
  return d;
}

// L-shape of side 2*arm_m with one reflex corner at (arm_m, arm_m).
inline Domain l_domain(double arm_m) {
  const double a = arm_m, b = 2 * arm_m;
  Domain d;
  d.polygons.push_back({{{0, 0}, {b, 0}, {b, a}, {a, a}, {a, b}, {0, b}}, {}});
  return d;
}

// Even-odd ray crossing test; points exactly on the ring are not expected.
inline bool inside_ring(const Ring& ring, const Point2& p) {
  bool inside = false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const Point2 &a = ring[i], &b = ring[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x)
      inside = !inside;
  }
  return inside;
}

inline bool inside_domain(const Domain& d, const Point2& p) {
  for (const Polygon& poly : d.polygons) {
    if (!inside_ring(poly.outer, p)) continue;
    bool in_hole = false;
    for (const Ring& h : poly.holes) in_hole = in_hole || inside_ring(h, p);
    if (!in_hole) return true;
  }
  return false;
}

inline Point2 centroid(const BackgroundMesh& m, int f) {
  const auto& t = m.triangles[f];
  return {(m.points[t[0]].x + m.points[t[1]].x + m.points[t[2]].x) / 3.0,
          (m.points[t[0]].y + m.points[t[1]].y + m.points[t[2]].y) / 3.0};
}

}  // namespace isoquad::test
