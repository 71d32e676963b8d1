// Per-triangle quantities that every tiling step reads, and the relocation of
// generators to tile centroids (paper, section 2.3).
#pragma once

#include <cstdint>
#include <vector>

#include "core/geometry.h"
#include "fields/cross_field.h"
#include "fields/sizing_field.h"
#include "mesh/background_mesh.h"
#include "tiling/tiling.h"

namespace isoquad {

struct TriangleGeometry {
  std::vector<double> cx, cy;     // #F centroid, metres
  // #F. Also the relocation weight of 2.3, rho * area with rho = 1. The paper's rho = h^-4
  // sizes the tiles of its plain L-infinity flood; ours measures distances in units of
  // h (flood_tiling.h), which sizes tiles by h already, and h^-4 on top of it pulled
  // generators into small-h regions twice: on France with automatic sizing, coastal
  // quads came out at 0.6 h and 8 points fewer angles in [75,105] degrees.
  std::vector<double> area_m2;
  std::vector<double> size_m;  // #F h at the centroid (mean of the vertex sizes)
  // area / (2h)^2: the share of one ideally sized tile (tiles are 2h wide). Computed when
  // read, not held: an array over the triangles fewer at the tiling's peak.
  double mass(int f) const { return area_m2[f] / (4.0 * size_m[f] * size_m[f]); }
  // #F bit i set: no flood or merge crosses the edge opposite triangles[f][i]
  // (corner_barriers.h). Empty when there are no barriers.
  std::vector<std::uint8_t> barrier;
  bool crosses_barrier(int f, int i) const { return !barrier.empty() && ((barrier[f] >> i) & 1u); }
  int num_triangles() const { return static_cast<int>(cx.size()); }
};

TriangleGeometry triangle_geometry(const BackgroundMesh& mesh, const SizingField& size);

// The cross angle at the centroid of triangle f.
double frame_angle_at(const BackgroundMesh& mesh, const CrossField& cross, int f);

// Per tile, the weighted centroid of its triangle centroids and the total weight.
// sum_j w_j |c_j - x|^2 = W |x - C|^2 + const, so the triangle minimising the paper's
// f(t) is the one whose centroid is nearest C.
struct TileCentroids {
  std::vector<double> x, y;    // #T
  std::vector<double> weight;  // #T
};
TileCentroids tile_centroids(const TriangleGeometry& geom, const std::vector<int>& label,
                             int num_tiles);

// Per tile t with selected[t] (all when selected is empty), the triangle of tile t whose
// centroid is nearest target (x[t], y[t]); -1 for an empty tile or one not selected.
// Ties go to the lowest triangle id.
std::vector<int> nearest_triangles_in_tiles(const TriangleGeometry& geom,
                                            const std::vector<int>& label,
                                            const std::vector<double>& x,
                                            const std::vector<double>& y,
                                            const std::vector<char>& selected = {});

// Relocation: per tile, the triangle nearest its weighted centroid (the paper's Gamma).
std::vector<int> relocated_generators(const TriangleGeometry& geom, const std::vector<int>& label,
                                      int num_tiles);

// The discrete energy H of 2.3: sum over triangles of rho area d_inf(c(t), c(g)), with
// the L-infinity distance in the cross frame of the tile's generator (rho = 1: m^3).
double tiling_energy(const BackgroundMesh& mesh, const TriangleGeometry& geom,
                     const CrossField& cross, const Tiling& tiling);
// The same of labels and generators held apart.
double tiling_energy(const BackgroundMesh& mesh, const TriangleGeometry& geom,
                     const CrossField& cross, const std::vector<int>& label,
                     const std::vector<int>& generator);

// Replaces missing (-1), out-of-tile and duplicate generators by the relocated triangle
// of their tile, so that every tile owns its generator and no two tiles share one.
// Returns the number replaced.
int fix_generators(const TriangleGeometry& geom, Tiling& tiling);

}  // namespace isoquad
