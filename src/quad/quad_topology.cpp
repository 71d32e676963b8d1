#include "quad/quad_topology.h"

#include <algorithm>
#include <cmath>

namespace isoquad {

QuadTopology quad_topology(const QuadMesh& m) {
  QuadTopology t;
  rebuild_quad_topology(m, t);
  return t;
}

void rebuild_quad_topology(const QuadMesh& m, QuadTopology& t) {
  const std::size_t n = m.points.size();
  t.quad_start.assign(n + 1, 0);
  for (const auto& q : m.quads)
    for (int v : q) ++t.quad_start[v + 1];
  for (std::size_t i = 0; i < n; ++i) t.quad_start[i + 1] += t.quad_start[i];
  t.quad_items.resize(t.quad_start[n]);
  std::vector<int> fill(t.quad_start.begin(), t.quad_start.end() - 1);
  for (std::size_t q = 0; q < m.quads.size(); ++q)
    for (int v : m.quads[q]) t.quad_items[fill[v]++] = static_cast<int>(q);
  // A vertex's edge neighbours from its quads (each quad gives the corners before and
  // after it); an edge used by one quad only is a boundary edge. Boundary neighbours in
  // increasing order (the second slot keeps the last when there are more than two).
  t.neighbours.resize(n);
  for (auto& nb : t.neighbours) nb.clear();  // (their memory kept for the next rebuild)
  t.boundary_neighbours.assign(n, {-1, -1});
  std::vector<int> around;
  for (std::size_t v = 0; v < n; ++v) {
    around.clear();
    for (int k = t.quad_start[v]; k < t.quad_start[v + 1]; ++k) {
      const auto& q = m.quads[t.quad_items[k]];
      const int i =
          static_cast<int>(std::find(q.begin(), q.end(), static_cast<int>(v)) - q.begin());
      around.push_back(q[(i + 1) % 4]);
      around.push_back(q[(i + 3) % 4]);
    }
    std::sort(around.begin(), around.end());
    auto& nb = t.neighbours[v];
    auto& bn = t.boundary_neighbours[v];
    for (std::size_t i = 0; i < around.size();) {
      std::size_t j = i;
      while (j < around.size() && around[j] == around[i]) ++j;
      nb.push_back(around[i]);
      if (j - i == 1) (bn[0] < 0 ? bn[0] : bn[1]) = around[i];
      i = j;
    }
  }
}

bool point_less(const Point2& a, const Point2& b) {
  return a.x < b.x || (a.x == b.x && a.y < b.y);
}

double worst_convexity(const QuadMesh& m, const QuadTopology& t, int v) {
  double worst = 1.0;
  for (int k = t.quad_start[v]; k < t.quad_start[v + 1]; ++k)
    worst = std::min(worst, quad_convexity(m, t.quad_items[k]));
  return worst;
}

int count_nonconvex(const QuadMesh& m, double min_convexity) {
  int n = 0;
  for (int q = 0; q < static_cast<int>(m.quads.size()); ++q)
    n += quad_convexity(m, q) <= min_convexity;
  return n;
}

// Signed arc distance from a to b along a closed chain of length len, in (-len/2, len/2].
double arc_delta(double a, double b, double len) {
  double d = std::fmod(b - a, len);
  if (d > 0.5 * len) d -= len;
  if (d <= -0.5 * len) d += len;
  return d;
}

// Whether boundary vertex v lies strictly between its two boundary neighbours along
// its chain (false when it has not two on its chain).
bool between_boundary_neighbours(const BackgroundMesh& bg, const QuadMesh& m, const QuadTopology& t,
                                 int v) {
  const auto& bn = t.boundary_neighbours[v];
  const int c = m.chain[v];
  if (c < 0 || bn[0] < 0 || bn[1] < 0 || m.chain[bn[0]] != c || m.chain[bn[1]] != c) return false;
  const double len = bg.chains[c].length_m;
  const double d0 = arc_delta(m.arc_m[v], m.arc_m[bn[0]], len);
  return d0 * arc_delta(m.arc_m[v], m.arc_m[bn[1]], len) < 0;
}

// Tries to move vertex v to `target` (and arc `arc` on the boundary): kept only if the
// incident quads stay at least as convex as required (or as they were).
bool try_move(QuadMesh& m, const QuadTopology& t, int v, const Point2& target, double arc,
              double min_convexity) {
  const double before = worst_convexity(m, t, v);
  const Point2 old = m.points[v];
  const double old_arc = m.arc_m[v];
  m.points[v] = target;
  m.arc_m[v] = arc;
  const double after = worst_convexity(m, t, v);
  if (after > min_convexity || after >= before) return true;
  m.points[v] = old;
  m.arc_m[v] = old_arc;
  return false;
}

// The boundary target of v: the arc-length midpoint of its two boundary neighbours.
bool boundary_target(const BackgroundMesh& bg, const QuadMesh& m, const QuadTopology& t, int v,
                     Point2& target, double& arc) {
  const auto& bn = t.boundary_neighbours[v];
  if (bn[0] < 0 || bn[1] < 0) return false;
  const int c = m.chain[v];
  if (m.chain[bn[0]] != c || m.chain[bn[1]] != c) return false;
  const double len = bg.chains[c].length_m;
  const double d0 = arc_delta(m.arc_m[v], m.arc_m[bn[0]], len);
  const double d1 = arc_delta(m.arc_m[v], m.arc_m[bn[1]], len);
  if (d0 * d1 >= 0) return false;  // neighbours must lie on both sides
  arc = m.arc_m[v] + 0.5 * (d0 + d1);
  target = chain_point(bg, bg.chains[c], arc);
  return true;
}

}  // namespace isoquad
