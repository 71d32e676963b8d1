#include "mesh/boundary_corners.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace isoquad {

namespace {

// Signed sum of turning angles of the chain vertices within arc distance `half` of
// vertex k (k included). Closed chain: arc distances wrap.
double windowed_turning(const BoundaryChain& chain, int k, double half) {
  const int n = static_cast<int>(chain.vertices.size());
  const double length = chain.length_m;
  double sum = chain.turning_angle_deg[k];
  for (int dir : {1, -1}) {
    for (int step = 1; step < n; ++step) {
      const int j = ((k + dir * step) % n + n) % n;
      double d = dir > 0 ? chain.arc_length_m[j] - chain.arc_length_m[k]
                         : chain.arc_length_m[k] - chain.arc_length_m[j];
      if (d < 0) d += length;
      if (d > half || 2 * d > length) break;
      sum += chain.turning_angle_deg[j];
    }
  }
  return sum;
}

double arc_distance(const BoundaryChain& chain, int a, int b) {
  const double d = std::abs(chain.arc_length_m[a] - chain.arc_length_m[b]);
  return std::min(d, chain.length_m - d);
}

}  // namespace

void tag_corners(BackgroundMesh& mesh, const SizingField& size, const CornerParams& params) {
  const double threshold = params.corner_angle_deg;
  for (BoundaryChain& chain : mesh.chains) {
    const int n = static_cast<int>(chain.vertices.size());
    chain.is_corner.assign(n, 0);
    chain.corner_turning_deg.assign(n, 0.0);
    std::vector<double> window(n, 0.0), half(n, 0.0);
    std::vector<int> candidates;
    for (int k = 0; k < n; ++k) {
      if (!chain.is_input_vertex[k] || std::abs(chain.turning_angle_deg[k]) < 0.5 * threshold)
        continue;
      half[k] = params.window_h * size.size_m[chain.vertices[k]];
      window[k] = windowed_turning(chain, k, half[k]);
      // The corner must turn the same way locally: a locally convex vertex where the
      // boundary turns reflex overall would not need a second tile, and vice versa.
      if (std::abs(window[k]) > threshold && window[k] * chain.turning_angle_deg[k] > 0)
        candidates.push_back(k);
    }
    std::sort(candidates.begin(), candidates.end(), [&](int a, int b) {
      if (std::abs(window[a]) != std::abs(window[b])) return std::abs(window[a]) > std::abs(window[b]);
      const double ta = std::abs(chain.turning_angle_deg[a]), tb = std::abs(chain.turning_angle_deg[b]);
      if (ta != tb) return ta > tb;
      return a < b;
    });
    std::vector<int> accepted;
    for (int k : candidates) {
      bool near = false;
      for (int a : accepted)
        if (arc_distance(chain, a, k) < std::max(half[a], half[k])) {
          near = true;
          break;
        }
      if (near) continue;
      accepted.push_back(k);
      chain.is_corner[k] = 1;
      chain.corner_turning_deg[k] = window[k];
    }
  }
}

}  // namespace isoquad
