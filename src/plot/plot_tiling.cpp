#include "plot/plot_tiling.h"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "plot/canvas.h"

namespace isoquad {

namespace {

// A pale colour per tile, from a hash of its id (neighbours rarely look alike).
Rgb tile_colour(int tile) {
  unsigned h = static_cast<unsigned>(tile) * 2654435761u;
  const double hue = (h % 360) / 360.0;
  const double r = 0.5 + 0.5 * std::cos(2 * M_PI * hue), g = 0.5 + 0.5 * std::cos(2 * M_PI * (hue - 1.0 / 3)),
               b = 0.5 + 0.5 * std::cos(2 * M_PI * (hue - 2.0 / 3));
  return {0.55 + 0.4 * r, 0.55 + 0.4 * g, 0.55 + 0.4 * b};
}

}  // namespace

void plot_tiling(const BackgroundMesh& mesh, const Tiling& tiling, const MetaGraph& graph,
                 const PlotTilingParams& params) {
  std::array<double, 4> box{1e300, 1e300, -1e300, -1e300};
  for (const Point2& p : mesh.points)
    box[0] = std::min(box[0], p.x), box[1] = std::min(box[1], p.y), box[2] = std::max(box[2], p.x),
    box[3] = std::max(box[3], p.y);
  Canvas canvas(box, params.width_px, 40);
  cairo_t* cr = canvas.cr();
  cairo_set_antialias(cr, CAIRO_ANTIALIAS_NONE);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    const Point2 pts[3] = {mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]};
    canvas.polygon_path(pts, 3);
    canvas.set_colour(tile_colour(tiling.label[f]));
    cairo_fill_preserve(cr);
    cairo_set_line_width(cr, 0.6);
    cairo_stroke(cr);
  }
  cairo_set_antialias(cr, CAIRO_ANTIALIAS_DEFAULT);
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  cairo_set_line_width(cr, 1.0);
  for (const MetaEdge& e : graph.edges) {
    for (std::size_t i = 0; i < e.path.size(); ++i) {
      const Point2 p = canvas.to_pixel(mesh.points[e.path[i]]);
      if (i == 0)
        cairo_move_to(cr, p.x, p.y);
      else
        cairo_line_to(cr, p.x, p.y);
    }
    cairo_stroke(cr);
  }
  int num3 = 0, num5 = 0;
  for (std::size_t m = 0; m < graph.vertices.size(); ++m) {
    if (graph.vertex_on_boundary[m]) continue;
    const int d = graph.vertex_num_tiles[m];
    if (d == 4) continue;
    const Point2 p = canvas.to_pixel(mesh.points[graph.vertices[m]]);
    cairo_arc(cr, p.x, p.y, 3, 0, 2 * M_PI);
    if (d <= 3) {
      cairo_set_source_rgb(cr, 0.1, 0.25, 0.95);
      ++num3;
    } else {
      cairo_set_source_rgb(cr, 0.9, 0.1, 0.1);
      ++num5;
    }
    cairo_fill(cr);
  }
  const TilingStats st = tiling_stats(graph);
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "%d tiles, %.1f%% with 4 meta-vertices; interior meta-vertices: %d of degree 3 "
                "(blue), %d of degree 5+ (red)",
                st.num_tiles, 100 * st.share_quads, num3, num5);
  canvas.text(10, canvas.map_height() + 24, buf, 14);
  canvas.write_png(params.path, params.overwrite);
}

}  // namespace isoquad
