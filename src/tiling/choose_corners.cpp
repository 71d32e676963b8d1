#include "tiling/choose_corners.h"

#include <algorithm>
#include <cmath>

namespace isoquad {

namespace {

double projected_m(const Point2& from, const Point2& to, double dx, double dy) {
  return std::abs((to.x - from.x) * dx + (to.y - from.y) * dy);
}

}  // namespace

CornerChoice choose_corners_and_axes(const std::vector<Point2>& p, double frame_angle_rad) {
  const int n = static_cast<int>(p.size());
  CornerChoice best;
  if (n < 4) {
    for (int i = 0; i < n; ++i) best.corners[i] = i;
    return best;
  }
  const double ux = std::cos(frame_angle_rad), uy = std::sin(frame_angle_rad);
  const double dir[2][2] = {{ux, uy}, {-uy, ux}};  // u, v
  best.energy_m = -1.0;
  // f[k][r]: the best min over the first k sides when corner k+1 sits at r (positions
  // counted from the first corner); from[k][r] the previous corner.
  std::vector<double> f2(n), f3(n), f4(n);
  std::vector<int> from3(n), from4(n);
  for (int axis = 0; axis < 2; ++axis) {
    const double* d0 = dir[axis];
    const double* d1 = dir[1 - axis];
    for (int s = 0; s < n; ++s) {
      auto at = [&](int r) -> const Point2& { return p[(s + r) % n]; };
      for (int r = 1; r <= n - 3; ++r) f2[r] = projected_m(at(0), at(r), d0[0], d0[1]);
      for (int r = 2; r <= n - 2; ++r) {
        f3[r] = -1.0;
        for (int q = 1; q < r; ++q) {
          const double e = std::min(f2[q], projected_m(at(q), at(r), d1[0], d1[1]));
          if (e > f3[r]) f3[r] = e, from3[r] = q;
        }
      }
      for (int r = 3; r <= n - 1; ++r) {
        f4[r] = -1.0;
        for (int q = 2; q < r; ++q) {
          const double e = std::min(f3[q], projected_m(at(q), at(r), d0[0], d0[1]));
          if (e > f4[r]) f4[r] = e, from4[r] = q;
        }
      }
      for (int r = 3; r <= n - 1; ++r) {
        const double e = std::min(f4[r], projected_m(at(r), at(0), d1[0], d1[1]));
        if (e > best.energy_m) {
          best.energy_m = e;
          const int r3 = from4[r], r2 = from3[r3];
          best.corners = {s, (s + r2) % n, (s + r3) % n, (s + r) % n};
          best.first_side_along_v = axis == 1;
        }
      }
    }
  }
  // Report the corners in increasing index order; the side starting at the smallest
  // index is side k of the choice above, so its axis flips with k.
  const auto smallest = std::min_element(best.corners.begin(), best.corners.end());
  const int k = static_cast<int>(smallest - best.corners.begin());
  std::rotate(best.corners.begin(), best.corners.begin() + k, best.corners.end());
  if (k % 2 == 1) best.first_side_along_v = !best.first_side_along_v;
  return best;
}

std::array<int, 4> choose_corners(const std::vector<Point2>& meta_vertex_positions,
                                  double frame_angle_rad) {
  return choose_corners_and_axes(meta_vertex_positions, frame_angle_rad).corners;
}

}  // namespace isoquad
