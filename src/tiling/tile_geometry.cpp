#include "tiling/tile_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace isoquad {

TriangleGeometry triangle_geometry(const BackgroundMesh& mesh, const SizingField& size) {
  const int num_faces = static_cast<int>(mesh.triangles.size());
  TriangleGeometry g;
  g.cx.resize(num_faces);
  g.cy.resize(num_faces);
  g.area_m2.resize(num_faces);
  g.size_m.resize(num_faces);
  for (int f = 0; f < num_faces; ++f) {
    const auto& t = mesh.triangles[f];
    const Point2 &a = mesh.points[t[0]], &b = mesh.points[t[1]], &c = mesh.points[t[2]];
    g.cx[f] = (a.x + b.x + c.x) / 3.0;
    g.cy[f] = (a.y + b.y + c.y) / 3.0;
    g.area_m2[f] = signed_area(a, b, c);
    g.size_m[f] = (size.size_m[t[0]] + size.size_m[t[1]] + size.size_m[t[2]]) / 3.0;
  }
  return g;
}

double frame_angle_at(const BackgroundMesh& mesh, const CrossField& cross, int f) {
  return cross_angle_at(mesh, cross, f, {1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0});
}

TileCentroids tile_centroids(const TriangleGeometry& geom, const std::vector<int>& label,
                             int num_tiles) {
  TileCentroids c;
  c.x.assign(num_tiles, 0.0);
  c.y.assign(num_tiles, 0.0);
  c.weight.assign(num_tiles, 0.0);
  const int num_faces = geom.num_triangles();
  for (int f = 0; f < num_faces; ++f) {
    const int t = label[f];
    const double w = geom.area_m2[f];
    c.x[t] += w * geom.cx[f];
    c.y[t] += w * geom.cy[f];
    c.weight[t] += w;
  }
  for (int t = 0; t < num_tiles; ++t) {
    if (c.weight[t] > 0.0) {
      c.x[t] /= c.weight[t];
      c.y[t] /= c.weight[t];
    }
  }
  return c;
}

std::vector<int> nearest_triangles_in_tiles(const TriangleGeometry& geom,
                                            const std::vector<int>& label,
                                            const std::vector<double>& x,
                                            const std::vector<double>& y,
                                            const std::vector<char>& selected) {
  const int num_tiles = static_cast<int>(x.size());
  std::vector<int> best(num_tiles, -1);
  std::vector<double> best_d2(num_tiles, std::numeric_limits<double>::infinity());
  const int num_faces = geom.num_triangles();
  const bool all = selected.empty();
  for (int f = 0; f < num_faces; ++f) {
    const int t = label[f];
    if (!all && !selected[t]) continue;
    const double dx = geom.cx[f] - x[t], dy = geom.cy[f] - y[t];
    const double d2 = dx * dx + dy * dy;
    if (d2 < best_d2[t]) {
      best_d2[t] = d2;
      best[t] = f;
    }
  }
  return best;
}

std::vector<int> relocated_generators(const TriangleGeometry& geom, const std::vector<int>& label,
                                      int num_tiles) {
  const TileCentroids c = tile_centroids(geom, label, num_tiles);
  return nearest_triangles_in_tiles(geom, label, c.x, c.y);
}

double tiling_energy(const BackgroundMesh& mesh, const TriangleGeometry& geom,
                     const CrossField& cross, const Tiling& tiling) {
  return tiling_energy(mesh, geom, cross, tiling.label, tiling.generator);
}

double tiling_energy(const BackgroundMesh& mesh, const TriangleGeometry& geom,
                     const CrossField& cross, const std::vector<int>& label,
                     const std::vector<int>& generator) {
  const int num_tiles = static_cast<int>(generator.size());
  std::vector<double> gx(num_tiles, 0.0), gy(num_tiles, 0.0), cu(num_tiles, 1.0),
      su(num_tiles, 0.0);
  for (int t = 0; t < num_tiles; ++t) {
    const int g = generator[t];
    if (g < 0) continue;
    gx[t] = geom.cx[g];
    gy[t] = geom.cy[g];
    const double a = frame_angle_at(mesh, cross, g);
    cu[t] = std::cos(a);
    su[t] = std::sin(a);
  }
  double h = 0.0;
  for (int f = 0; f < geom.num_triangles(); ++f) {
    const int t = label[f];
    if (generator[t] < 0) continue;
    const double dx = geom.cx[f] - gx[t], dy = geom.cy[f] - gy[t];
    const double d = std::max(std::abs(dx * cu[t] + dy * su[t]), std::abs(dy * cu[t] - dx * su[t]));
    h += geom.area_m2[f] * d;
  }
  return h;
}

int fix_generators(const TriangleGeometry& geom, Tiling& tiling) {
  const int num_tiles = tiling.num_tiles();
  const int num_faces = geom.num_triangles();
  std::vector<char> redo(num_tiles, 0), used(num_faces, 0);
  int num_redo = 0;
  for (int t = 0; t < num_tiles; ++t) {
    const int g = tiling.generator[t];
    if (g < 0 || g >= num_faces || tiling.label[g] != t || used[g]) {
      redo[t] = 1;
      ++num_redo;
    } else {
      used[g] = 1;
    }
  }
  if (num_redo == 0) return 0;
  const TileCentroids c = tile_centroids(geom, tiling.label, num_tiles);
  const std::vector<int> nearest = nearest_triangles_in_tiles(geom, tiling.label, c.x, c.y, redo);
  for (int t = 0; t < num_tiles; ++t)
    if (redo[t]) tiling.generator[t] = nearest[t];
  return num_redo;
}

}  // namespace isoquad
