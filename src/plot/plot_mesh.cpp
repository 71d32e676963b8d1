#include "plot/plot_mesh.h"

#include <cairo.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "plot/canvas.h"

namespace isoquad {

namespace {

Rgb size_colour(double ratio) {
  // A factor of 2 either way saturates the ramp.
  const double t = std::clamp(std::log2(std::max(ratio, 1e-9)), -1.0, 1.0);
  return t < 0 ? ramp_white_to({0.15, 0.3, 0.85}, -t) : ramp_white_to({0.85, 0.15, 0.15}, t);
}

void draw_quads(Canvas& c, const QuadMesh& m, const std::vector<Rgb>& fill, bool irregular,
                const QuadMetrics& q) {
  cairo_t* cr = c.cr();
  const double line = std::clamp(0.6 * std::sqrt(c.scale()), 0.2, 1.0);
  for (std::size_t i = 0; i < m.quads.size(); ++i) {
    const auto& t = m.quads[i];
    const Point2 pts[4] = {m.points[t[0]], m.points[t[1]], m.points[t[2]], m.points[t[3]]};
    c.polygon_path(pts, 4);
    c.set_colour(fill[i]);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.25, 0.25, 0.25);
    cairo_set_line_width(cr, line);
    cairo_stroke(cr);
  }
  if (!irregular) return;
  for (std::size_t v = 0; v < m.points.size(); ++v) {
    const int d = q.degree[v], ideal = q.ideal_degree[v];
    if (d == 0 || d == ideal) continue;
    const Point2 p = c.to_pixel(m.points[v]);
    cairo_arc(cr, p.x, p.y, 2.5, 0, 2 * M_PI);
    if (d > ideal)
      cairo_set_source_rgb(cr, 0.9, 0.1, 0.1);
    else
      cairo_set_source_rgb(cr, 0.1, 0.25, 0.95);
    cairo_fill(cr);
  }
}

// The lines in a colour, clipped to the panel at (x, y) of w x h pixels.
void draw_lines(Canvas& c, const std::vector<std::vector<Point2>>& lines, double x, double y,
                double w, double h, const std::array<double, 3>& rgb, double width) {
  if (lines.empty()) return;
  cairo_t* cr = c.cr();
  cairo_save(cr);
  cairo_rectangle(cr, x, y, w, h);
  cairo_clip(cr);
  for (const auto& line : lines) {
    for (std::size_t i = 0; i < line.size(); ++i) {
      const Point2 p = c.to_pixel(line[i]);
      if (i == 0)
        cairo_move_to(cr, p.x, p.y);
      else
        cairo_line_to(cr, p.x, p.y);
    }
  }
  cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
  cairo_set_line_width(cr, width);
  cairo_stroke(cr);
  cairo_restore(cr);
}

std::array<double, 4> box_of(const QuadMesh& m) {
  std::array<double, 4> b{1e300, 1e300, -1e300, -1e300};
  for (const Point2& p : m.points)
    b[0] = std::min(b[0], p.x), b[1] = std::min(b[1], p.y), b[2] = std::max(b[2], p.x),
    b[3] = std::max(b[3], p.y);
  return b;
}

}  // namespace

void plot_mesh(const QuadMesh& m, const QuadMetrics& q, const QualitySummary& s,
               const PlotMeshParams& params) {
  const std::array<double, 4> box = box_of(m);
  const double aspect = (box[3] - box[1]) / std::max(box[2] - box[0], 1e-12);
  const double w = params.panel_px;
  const double map_h = std::clamp(w * aspect, 200.0, 2.0 * w);
  const double hist_h = 180;
  Canvas c(static_cast<int>(3 * w + 40), static_cast<int>(map_h + hist_h + 90));

  std::vector<Rgb> plain(m.quads.size(), Rgb{0.97, 0.97, 0.97}), by_size, by_orientation;
  for (std::size_t i = 0; i < m.quads.size(); ++i) {
    by_size.push_back(size_colour(q.size_ratio[i]));
    by_orientation.push_back(ramp_white_to({0.45, 0.45, 0.45}, q.orientation_deg[i] / 45.0));
  }
  const char* titles[3] = {"mesh (red: degree excess, blue: deficit)",
                           "size sqrt(area)/h (blue smaller, red larger)",
                           "orientation deviation (white 0, grey 45 deg)"};
  const std::vector<Rgb>* fills[3] = {&plain, &by_size, &by_orientation};
  for (int k = 0; k < 3; ++k) {
    c.text(10 + k * (w + 10), 18, titles[k], 14);
    c.set_view(box, 10 + k * (w + 10), 28, w, map_h);
    draw_quads(c, m, *fills[k], k == 0, q);
    draw_lines(c, params.lines, 10 + k * (w + 10), 28, w, map_h, {0.0, 0.45, 0.2}, 2.0);
    draw_lines(c, params.embedded, 10 + k * (w + 10), 28, w, map_h, {0.8, 0.0, 0.6}, 1.0);
  }

  char buf[200];
  const double y = map_h + 50;
  std::snprintf(buf, sizeof buf, "angles: %.1f%% in [75,105]", 100 * s.share_angles_75_105);
  c.histogram(10, y, w, hist_h, s.angle_histogram, buf, "0", "180 deg", {0.2, 0.45, 0.75});
  std::snprintf(buf, sizeof buf, "size ratio: median %.2f, %.1f%% in [0.8,1.25]", s.size_ratio_median,
                100 * s.share_size_08_125);
  c.histogram(20 + w, y, w, hist_h, s.size_ratio_histogram, buf, "0.25", "1.75", {0.75, 0.3, 0.3});
  std::snprintf(buf, sizeof buf, "orientation: mean %.1f, p90 %.1f deg", s.orientation_mean_deg,
                s.orientation_p90_deg);
  c.histogram(30 + 2 * w, y, w, hist_h, s.orientation_histogram, buf, "0", "45 deg", {0.4, 0.4, 0.4});
  std::snprintf(buf, sizeof buf,
                "%zu quads, %zu vertices; regular: %.1f%% interior, %.1f%% boundary; "
                "min angle %.1f, max %.1f deg",
                s.num_quads, s.num_vertices, 100 * s.share_regular_interior,
                100 * s.share_regular_boundary, s.min_angle_deg, s.max_angle_deg);
  c.text(10, y + hist_h + 34, buf, 13);
  c.write_png(params.path, params.overwrite);
}

}  // namespace isoquad
