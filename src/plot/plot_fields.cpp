#include "plot/plot_fields.h"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "plot/canvas.h"

namespace isoquad {

namespace {

std::string metres(double v) {
  char buf[32];
  if (v >= 1000)
    std::snprintf(buf, sizeof buf, "%.3g km", v / 1000);
  else
    std::snprintf(buf, sizeof buf, "%.3g m", v);
  return buf;
}

}  // namespace

void plot_fields(const BackgroundMesh& mesh, const SizingField& size, const CrossField& cross,
                 const std::vector<Singularity>& singularities, const PlotFieldsParams& params) {
  std::array<double, 4> box{1e300, 1e300, -1e300, -1e300};
  for (const Point2& p : mesh.points) {
    box[0] = std::min(box[0], p.x), box[1] = std::min(box[1], p.y);
    box[2] = std::max(box[2], p.x), box[3] = std::max(box[3], p.y);
  }
  Canvas canvas(box, params.width_px, 60);
  cairo_t* cr = canvas.cr();

  // Sizes on a log scale: they typically span orders of magnitude.
  const auto [lo_it, hi_it] = std::minmax_element(size.size_m.begin(), size.size_m.end());
  const double lo = *lo_it, hi = std::max(*hi_it, *lo_it * (1 + 1e-9));
  const double log_span = std::log(hi / lo);
  cairo_set_antialias(cr, CAIRO_ANTIALIAS_NONE);
  for (const auto& t : mesh.triangles) {
    const Point2 pts[3] = {mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]};
    const double h = (size.size_m[t[0]] + size.size_m[t[1]] + size.size_m[t[2]]) / 3;
    canvas.polygon_path(pts, 3);
    canvas.set_colour(ramp_viridis(log_span > 0 ? std::log(h / lo) / log_span : 0.5));
    cairo_fill_preserve(cr);
    cairo_set_line_width(cr, 0.6);
    cairo_stroke(cr);
  }
  cairo_set_antialias(cr, CAIRO_ANTIALIAS_DEFAULT);

  // One cross per grid cell: the triangle whose centroid is nearest the cell centre.
  const double cell = (box[2] - box[0]) / params.crosses_across;
  const int nx = params.crosses_across + 1;
  const int ny = static_cast<int>((box[3] - box[1]) / cell) + 1;
  std::vector<int> best(static_cast<std::size_t>(nx) * ny, -1);
  std::vector<double> best_d(best.size(), std::numeric_limits<double>::infinity());
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    const Point2 c{(mesh.points[t[0]].x + mesh.points[t[1]].x + mesh.points[t[2]].x) / 3,
                   (mesh.points[t[0]].y + mesh.points[t[1]].y + mesh.points[t[2]].y) / 3};
    const int i = std::min(nx - 1, static_cast<int>((c.x - box[0]) / cell));
    const int j = std::min(ny - 1, static_cast<int>((c.y - box[1]) / cell));
    const double d = std::hypot(c.x - (box[0] + (i + 0.5) * cell), c.y - (box[1] + (j + 0.5) * cell));
    const std::size_t k = static_cast<std::size_t>(j) * nx + i;
    if (d < best_d[k]) best_d[k] = d, best[k] = static_cast<int>(f);
  }
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_set_line_width(cr, 1.4);
  const double arm = 0.33 * cell * canvas.scale();
  for (int f : best) {
    if (f < 0 || best_d.empty()) continue;
    const auto& t = mesh.triangles[f];
    const Point2 c{(mesh.points[t[0]].x + mesh.points[t[1]].x + mesh.points[t[2]].x) / 3,
                   (mesh.points[t[0]].y + mesh.points[t[1]].y + mesh.points[t[2]].y) / 3};
    const double a = cross_angle_at(mesh, cross, f, {1.0 / 3, 1.0 / 3, 1.0 / 3});
    const Point2 q = canvas.to_pixel(c);
    for (double d : {a, a + M_PI / 2}) {
      // Pixel y grows downwards.
      const double dx = arm * std::cos(d), dy = -arm * std::sin(d);
      cairo_move_to(cr, q.x - dx, q.y - dy);
      cairo_line_to(cr, q.x + dx, q.y + dy);
    }
  }
  cairo_stroke(cr);

  // Boundary.
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 1.5);
  for (const BoundaryChain& ch : mesh.chains) {
    std::vector<Point2> pts;
    for (int v : ch.vertices) pts.push_back(mesh.points[v]);
    canvas.polygon_path(pts.data(), static_cast<int>(pts.size()));
    cairo_stroke(cr);
  }
  // Singularities: red for index +1/4 (degree-3-like), blue for negative.
  for (const Singularity& s : singularities) {
    const Point2 q = canvas.to_pixel(s.position);
    cairo_arc(cr, q.x, q.y, 5, 0, 2 * M_PI);
    if (s.index_quarters > 0)
      cairo_set_source_rgb(cr, 0.85, 0.1, 0.1);
    else
      cairo_set_source_rgb(cr, 0.1, 0.2, 0.9);
    cairo_fill(cr);
  }

  const double y = canvas.map_height() + 8;
  canvas.text(10, y + 12, "size h (log scale)", 13);
  canvas.colour_bar(150, y, 300, 14, ramp_viridis, metres(lo), metres(hi));
  char buf[160];
  std::snprintf(buf, sizeof buf, "crosses: white ticks; %zu singularities (red +1/4, blue -1/4); %zu triangles",
                singularities.size(), mesh.triangles.size());
  canvas.text(480, y + 12, buf, 13);
  canvas.write_png(params.path, params.overwrite);
}

}  // namespace isoquad
