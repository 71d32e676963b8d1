#include "app/vertex_depths.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

#include "core/error.h"
#include "fields/sizing_field.h"
#include "gis/map_scale.h"

namespace isoquad {

VertexDepths vertex_depths(const RasterStack& rasters, const QuadMesh& mesh,
                           std::optional<double> min_depth_m, bool average) {
  const std::size_t n = mesh.points.size();
  VertexDepths out;
  out.depth.assign(n, 0.0);
  out.averaged = average;
  // Half the mean length of the quads' sides at each vertex (each quad's two counted).
  std::vector<double> half_side(n, 0.0);
  if (average) {
    std::vector<int> sides(n, 0);
    for (const auto& q : mesh.quads)
      for (int i = 0; i < 4; ++i) {
        const double l = distance(mesh.points[q[i]], mesh.points[q[(i + 1) % 4]]);
        for (int v : {q[i], q[(i + 1) % 4]}) half_side[v] += 0.5 * l, ++sides[v];
      }
    for (std::size_t v = 0; v < n; ++v)
      if (sides[v] > 0) half_side[v] /= sides[v];
  }
  // Dijkstra from every vertex with a value, over the quads' sides: a vertex without one
  // takes the depth of the first vertex with one to reach it (ties to the lower id).
  std::vector<double> reach(n, INFINITY);
  using Entry = std::pair<double, std::size_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  for (std::size_t v = 0; v < n; ++v) {
    const double d = rasters.mean_over(mesh.points[v], half_side[v]);
    if (std::isnan(d)) continue;
    out.depth[v] = d;
    reach[v] = 0.0;
    queue.push({0.0, v});
  }
  if (queue.empty())
    throw Error(ErrorClass::input, "bathymetry",
                rasters.paths_text() +
                    ": no vertex of the mesh lies where it has a depth (check its extent, its CRS "
                    "and its nodata value)" +
                    rasters.crs_hints());
  if (queue.size() < n) {
    std::vector<std::size_t> start(n + 1, 0);
    for (const auto& q : mesh.quads)
      for (int v : q) start[v + 1] += 2;
    for (std::size_t v = 0; v < n; ++v) start[v + 1] += start[v];
    std::vector<int> next(start.back());
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (const auto& q : mesh.quads)
      for (int i = 0; i < 4; ++i) {
        const int a = q[i], b = q[(i + 1) % 4];
        next[fill[a]++] = b;
        next[fill[b]++] = a;
      }
    auto spread = [&] {
      while (!queue.empty()) {
        const auto [d, v] = queue.top();
        queue.pop();
        if (d > reach[v]) continue;
        for (std::size_t k = start[v]; k < start[v + 1]; ++k) {
          const std::size_t w = static_cast<std::size_t>(next[k]);
          const double dw = d + distance(mesh.points[v], mesh.points[w]);
          if (dw < reach[w]) {
            reach[w] = dw;
            out.depth[w] = out.depth[v];
            queue.push({dw, w});
          }
        }
      }
    };
    spread();
    // A part of the mesh that no vertex with a depth reaches (an island's own mesh off
    // the rasters): from the vertex with a depth nearest its first vertex.
    for (std::size_t v = 0; v < n; ++v) {
      if (reach[v] < INFINITY) continue;
      std::size_t nearest = n;
      double best = INFINITY;
      for (std::size_t w = 0; w < n; ++w)
        if (reach[w] == 0.0 && distance(mesh.points[v], mesh.points[w]) < best)
          best = distance(mesh.points[v], mesh.points[w]), nearest = w;
      reach[v] = best;
      out.depth[v] = out.depth[nearest];
      queue.push({best, v});
      spread();
    }
    for (std::size_t v = 0; v < n; ++v)
      if (reach[v] > 0.0) {
        ++out.num_filled;
        out.max_fill_distance_m = std::max(out.max_fill_distance_m, reach[v]);
      }
  }
  out.num_dry = static_cast<std::size_t>(
      std::count_if(out.depth.begin(), out.depth.end(), [](double d) { return d <= 0; }));
  if (min_depth_m)
    for (double& d : out.depth)
      if (d < *min_depth_m) d = *min_depth_m, ++out.num_raised;
  const auto [lo, hi] = std::minmax_element(out.depth.begin(), out.depth.end());
  out.min_m = *lo;
  out.max_m = *hi;
  return out;
}

TimeSteps courant_time_steps(const QuadMesh& mesh, const std::vector<double>& depth, double courant,
                             double target_s, const MapScale* scale) {
  TimeSteps out;
  out.courant = courant;
  out.per_quad_s.assign(mesh.quads.size(), std::numeric_limits<double>::quiet_NaN());
  std::vector<double> wet;
  for (std::size_t q = 0; q < mesh.quads.size(); ++q) {
    const auto& c = mesh.quads[q];
    auto mid = [&](int i) {
      const Point2 &a = mesh.points[c[i]], &b = mesh.points[c[(i + 1) % 4]];
      return Point2{(a.x + b.x) / 2, (a.y + b.y) / 2};
    };
    double width = std::min(distance(mid(0), mid(2)), distance(mid(1), mid(3)));
    if (scale) width /= scale->at(quad_centroid(mesh, static_cast<int>(q)));
    double deepest = depth[c[0]];
    for (int v : c) deepest = std::max(deepest, depth[v]);
    if (!(deepest > 0)) continue;
    const double dt = courant * width / std::sqrt(kGravity * deepest);
    out.per_quad_s[q] = dt;
    wet.push_back(dt);
    if (dt < target_s) ++out.num_under_target;
    if (out.limiting_quad < 0 || dt < out.min_s) {
      out.min_s = dt;
      out.limiting_quad = static_cast<int>(q);
      out.width_m = width;
      out.depth_m = deepest;
    }
  }
  out.num_wet = wet.size();
  if (!wet.empty()) {
    std::nth_element(wet.begin(), wet.begin() + wet.size() / 2, wet.end());
    out.median_s = wet[wet.size() / 2];
  }
  return out;
}

}  // namespace isoquad
