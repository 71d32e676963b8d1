#include "fields/align_lines.h"

#include <algorithm>
#include <cmath>
#include <functional>

namespace isoquad {

void walk_line(const BackgroundMesh& mesh, const TriangleLocator& locator,
               const std::vector<Point2>& line,
               const std::function<void(const Point2&, const Location&, double)>& visit) {
  int hint = -1;
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    const Point2 a = line[i], b = line[i + 1];
    const double length = distance(a, b);
    if (!(length > 0.0)) continue;
    const double phi = std::atan2(b.y - a.y, b.x - a.x);
    for (double t = 0.0;;) {
      const double s = std::min(t, length) / length;
      const Point2 p{a.x + s * (b.x - a.x), a.y + s * (b.y - a.y)};
      const Location at = hint >= 0 ? locator.locate(p, hint) : locator.locate(p);
      double step = length;  // no triangle (an empty mesh): the segment's end
      if (at.triangle >= 0) {
        hint = at.triangle;
        const auto& tri = mesh.triangles[at.triangle];
        double shortest = INFINITY;
        for (int k = 0; k < 3; ++k)
          shortest =
              std::min(shortest, distance(mesh.points[tri[k]], mesh.points[tri[(k + 1) % 3]]));
        step = 0.25 * shortest;
        if (!at.inside) {  // no part of the mesh is nearer than its nearest triangle
          Point2 q{0.0, 0.0};
          for (int k = 0; k < 3; ++k)
            q.x += at.bary[k] * mesh.points[tri[k]].x, q.y += at.bary[k] * mesh.points[tri[k]].y;
          step = std::max(step, 0.5 * distance(p, q));
        }
      }
      visit(p, at, phi);
      if (t >= length) break;
      t += std::max(step, 1e-9 * length);
    }
  }
}

LineCrosses line_crosses(const BackgroundMesh& mesh,
                         const std::vector<std::vector<Point2>>& lines) {
  const std::size_t num_vertices = mesh.points.size();
  std::vector<double> sc(num_vertices, 0.0), ss(num_vertices, 0.0);
  std::vector<char> reached(num_vertices, 0);
  LineCrosses out;
  out.line_inside.assign(lines.size(), 0);
  const TriangleLocator locator(mesh);
  for (std::size_t l = 0; l < lines.size(); ++l) {
    walk_line(mesh, locator, lines[l], [&](const Point2& p, const Location& at, double phi) {
      if (!at.inside) return;
      out.line_inside[l] = 1;
      const auto& tri = mesh.triangles[at.triangle];
      int nearest = tri[0];
      for (int k = 1; k < 3; ++k)
        if (distance(mesh.points[tri[k]], p) < distance(mesh.points[nearest], p)) nearest = tri[k];
      if (mesh.boundary_chain_of_vertex[nearest] < 0) {
        sc[nearest] += std::cos(4.0 * phi);
        ss[nearest] += std::sin(4.0 * phi);
        reached[nearest] = 1;
      }
    });
  }
  FixedCrosses& f = out.crosses;
  f.is_fixed.assign(num_vertices, 0);
  f.uc.assign(num_vertices, 0.0);
  f.us.assign(num_vertices, 0.0);
  for (std::size_t v = 0; v < num_vertices; ++v) {
    const double norm = std::hypot(sc[v], ss[v]);
    if (!reached[v] || norm < 1e-6) continue;
    f.is_fixed[v] = 1;
    f.uc[v] = sc[v] / norm;
    f.us[v] = ss[v] / norm;
    ++out.num_fixed;
  }
  return out;
}

}  // namespace isoquad
