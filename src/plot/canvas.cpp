#include "plot/canvas.h"

#include <cairo.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "gis/atomic_output.h"

namespace isoquad {

Rgb ramp_viridis(double t) {
  static const Rgb stops[] = {{0.267, 0.005, 0.329}, {0.283, 0.141, 0.458}, {0.254, 0.265, 0.530},
                              {0.207, 0.372, 0.553}, {0.164, 0.471, 0.558}, {0.128, 0.567, 0.551},
                              {0.135, 0.659, 0.518}, {0.267, 0.749, 0.441}, {0.478, 0.821, 0.318},
                              {0.741, 0.873, 0.150}, {0.993, 0.906, 0.144}};
  const int n = sizeof stops / sizeof stops[0];
  t = std::clamp(t, 0.0, 1.0) * (n - 1);
  const int i = std::min(n - 2, static_cast<int>(t));
  const double f = t - i;
  return {stops[i].r + f * (stops[i + 1].r - stops[i].r), stops[i].g + f * (stops[i + 1].g - stops[i].g),
          stops[i].b + f * (stops[i + 1].b - stops[i].b)};
}

Rgb ramp_white_to(const Rgb& to, double t) {
  t = std::clamp(t, 0.0, 1.0);
  return {1 + t * (to.r - 1), 1 + t * (to.g - 1), 1 + t * (to.b - 1)};
}

Canvas::Canvas(const std::array<double, 4>& box, int width_px, int legend_px) : box_(box) {
  const double w = std::max(box[2] - box[0], 1e-12), h = std::max(box[3] - box[1], 1e-12);
  width_ = width_px;
  scale_ = (width_px - 2 * margin_) / w;
  map_height_ = static_cast<int>(std::ceil(h * scale_ + 2 * margin_));
  height_ = map_height_ + legend_px;
  offset_x_ = margin_;
  offset_y_ = map_height_ - margin_;
  surface_ = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width_, height_);
  cr_ = cairo_create(surface_);
  cairo_set_source_rgb(cr_, 1, 1, 1);
  cairo_paint(cr_);
}

Canvas::Canvas(int width_px, int height_px) {
  width_ = width_px;
  height_ = height_px;
  map_height_ = height_px;
  surface_ = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width_, height_);
  cr_ = cairo_create(surface_);
  cairo_set_source_rgb(cr_, 1, 1, 1);
  cairo_paint(cr_);
}

void Canvas::set_view(const std::array<double, 4>& box, double x, double y, double w, double h) {
  box_ = box;
  const double bw = std::max(box[2] - box[0], 1e-12), bh = std::max(box[3] - box[1], 1e-12);
  scale_ = std::min(w / bw, h / bh);
  // Centre the box in the rectangle; y grows downwards in pixels.
  offset_x_ = x + 0.5 * (w - bw * scale_);
  offset_y_ = y + h - 0.5 * (h - bh * scale_);
}

void Canvas::histogram(double x, double y, double w, double h, const std::vector<int>& counts,
                       const std::string& title, const std::string& left, const std::string& right,
                       const Rgb& colour) {
  int top = 1;
  for (int c : counts) top = std::max(top, c);
  const double bar = w / std::max<std::size_t>(counts.size(), 1);
  set_colour(colour);
  for (std::size_t i = 0; i < counts.size(); ++i) {
    const double bh = (h - 20) * counts[i] / top;
    cairo_rectangle(cr_, x + i * bar, y + h - bh, std::max(bar - 1, 0.5), bh);
  }
  cairo_fill(cr_);
  cairo_set_source_rgb(cr_, 0, 0, 0);
  cairo_set_line_width(cr_, 1);
  cairo_move_to(cr_, x, y + h);
  cairo_line_to(cr_, x + w, y + h);
  cairo_stroke(cr_);
  text(x, y + 12, title, 13);
  text(x, y + h + 14, left, 12);
  cairo_text_extents_t ext;
  cairo_text_extents(cr_, right.c_str(), &ext);
  text(x + w - ext.width, y + h + 14, right, 12);
}

Canvas::~Canvas() {
  cairo_destroy(cr_);
  cairo_surface_destroy(surface_);
}

Point2 Canvas::to_pixel(const Point2& p) const {
  return {offset_x_ + (p.x - box_[0]) * scale_, offset_y_ - (p.y - box_[1]) * scale_};
}

void Canvas::polygon_path(const Point2* pts, int n) {
  for (int i = 0; i < n; ++i) {
    const Point2 q = to_pixel(pts[i]);
    if (i == 0)
      cairo_move_to(cr_, q.x, q.y);
    else
      cairo_line_to(cr_, q.x, q.y);
  }
  cairo_close_path(cr_);
}

void Canvas::set_colour(const Rgb& c, double alpha) {
  cairo_set_source_rgba(cr_, c.r, c.g, c.b, alpha);
}

void Canvas::text(double x, double y, const std::string& s, double size_px) {
  cairo_select_font_face(cr_, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr_, size_px);
  cairo_set_source_rgb(cr_, 0, 0, 0);
  cairo_move_to(cr_, x, y);
  cairo_show_text(cr_, s.c_str());
}

void Canvas::colour_bar(double x, double y, double w, double h, Rgb (*ramp)(double),
                        const std::string& left, const std::string& right) {
  const int steps = 64;
  for (int i = 0; i < steps; ++i) {
    set_colour(ramp((i + 0.5) / steps));
    cairo_rectangle(cr_, x + w * i / steps, y, w / steps + 0.5, h);
    cairo_fill(cr_);
  }
  cairo_set_source_rgb(cr_, 0, 0, 0);
  cairo_set_line_width(cr_, 1);
  cairo_rectangle(cr_, x, y, w, h);
  cairo_stroke(cr_);
  text(x, y + h + 14, left, 12);
  cairo_text_extents_t ext;
  cairo_text_extents(cr_, right.c_str(), &ext);
  text(x + w - ext.width, y + h + 14, right, 12);
}

void Canvas::write_png(const std::string& path, bool overwrite) {
  AtomicOutput out(path, overwrite);
  cairo_surface_flush(surface_);
  if (cairo_surface_write_to_png(surface_, out.temp_path().c_str()) != CAIRO_STATUS_SUCCESS)
    throw Error(ErrorClass::output, "plot", "'" + path + "': cannot write the PNG");
  out.commit();
}

}  // namespace isoquad
