// A PNG canvas over a world bounding box (cairo), shared by the plots.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "core/geometry.h"

typedef struct _cairo cairo_t;
typedef struct _cairo_surface cairo_surface_t;

namespace isoquad {

struct Rgb {
  double r = 0, g = 0, b = 0;
};

// Perceptual colour ramp (viridis-like), t in [0,1].
Rgb ramp_viridis(double t);
// White to `to` (the paper's conformance ramps), t in [0,1].
Rgb ramp_white_to(const Rgb& to, double t);

class Canvas {
 public:
  // The world box [xmin, ymin, xmax, ymax] is fitted into width_px, keeping the aspect
  // ratio, with a margin; `legend_px` extra pixels below for text.
  Canvas(const std::array<double, 4>& world_box, int width_px, int legend_px = 40);
  // A blank canvas of the given size; set_view() places world boxes on it.
  Canvas(int width_px, int height_px);
  ~Canvas();
  // Maps `world_box` into the pixel rectangle (x, y, w, h), keeping the aspect ratio.
  void set_view(const std::array<double, 4>& world_box, double x_px, double y_px, double w_px,
                double h_px);
  // A histogram with bars of `colour`, its title and its axis range labels.
  void histogram(double x_px, double y_px, double w_px, double h_px, const std::vector<int>& counts,
                 const std::string& title, const std::string& left, const std::string& right,
                 const Rgb& colour);
  Canvas(const Canvas&) = delete;
  Canvas& operator=(const Canvas&) = delete;

  cairo_t* cr() const { return cr_; }
  Point2 to_pixel(const Point2& p) const;
  double scale() const { return scale_; }  // pixels per world unit
  int width() const { return width_; }
  int height() const { return height_; }
  int map_height() const { return map_height_; }

  void polygon_path(const Point2* pts, int n);
  void set_colour(const Rgb& c, double alpha = 1.0);
  void text(double x_px, double y_px, const std::string& s, double size_px = 13);
  // A horizontal colour bar with a label at each end.
  void colour_bar(double x_px, double y_px, double w_px, double h_px, Rgb (*ramp)(double),
                  const std::string& left, const std::string& right);

  // Writes the PNG atomically. Throws Error(output).
  void write_png(const std::string& path, bool overwrite);

 private:
  cairo_surface_t* surface_ = nullptr;
  cairo_t* cr_ = nullptr;
  std::array<double, 4> box_{};
  double scale_ = 1.0;
  double margin_ = 10.0;
  double offset_x_ = 0.0, offset_y_ = 0.0;  // pixel position of the view's lower-left corner
  int width_ = 0, height_ = 0, map_height_ = 0;
};

}  // namespace isoquad
