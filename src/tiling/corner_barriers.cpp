#include "tiling/corner_barriers.h"

#include <cmath>
#include <utility>

namespace isoquad {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Triangles around every vertex, as compressed rows.
struct VertexFans {
  std::vector<int> begin, faces;
  explicit VertexFans(const BackgroundMesh& mesh) {
    begin.assign(mesh.points.size() + 1, 0);
    for (const auto& t : mesh.triangles)
      for (int v : t) ++begin[v + 1];
    for (std::size_t v = 0; v < mesh.points.size(); ++v) begin[v + 1] += begin[v];
    faces.resize(begin.back());
    std::vector<int> next(begin.begin(), begin.end() - 1);
    for (int f = 0; f < static_cast<int>(mesh.triangles.size()); ++f)
      for (int v : mesh.triangles[f]) faces[next[v]++] = f;
  }
};

// The chain vertex about `distance` metres from vertex k along the chain, forwards
// (step = +1) or backwards (step = -1), never further than half the chain.
int vertex_along(const BoundaryChain& chain, int k, int step, double distance) {
  const int n = static_cast<int>(chain.vertices.size());
  const double total = chain.length_m;
  int j = k;
  for (int steps = 1; steps < n / 2; ++steps) {
    j = ((j + step) % n + n) % n;
    double d = step > 0 ? chain.arc_length_m[j] - chain.arc_length_m[k]
                        : chain.arc_length_m[k] - chain.arc_length_m[j];
    if (d < 0.0) d += total;
    if (d >= distance) break;
  }
  return chain.vertices[j];
}

class BarrierBuilder {
 public:
  explicit BarrierBuilder(const BackgroundMesh& mesh)
      : mesh_(mesh), fans_(mesh), mask_(mesh.triangles.size(), 0),
        used_(mesh.points.size(), 0) {
    for (std::size_t v = 0; v < mesh.points.size(); ++v)
      if (mesh.boundary_chain_of_vertex[v] >= 0) used_[v] = 1;
  }

  // An edge path from corner v along direction (dx, dy), about `length` metres long.
  void trace(int v, double dx, double dy, double length) {
    const Point2 origin = mesh_.points[v];
    int u = v;
    double progress = 0.0;
    while (progress < length) {
      int best = -1;
      double best_score = -1e300, best_progress = 0.0;
      for (int k = fans_.begin[u]; k < fans_.begin[u + 1]; ++k)
        for (int w : mesh_.triangles[fans_.faces[k]]) {
          if (w == u || used_[w]) continue;
          const Point2& p = mesh_.points[w];
          const double along = (p.x - origin.x) * dx + (p.y - origin.y) * dy;
          const double across = std::abs((p.y - origin.y) * dx - (p.x - origin.x) * dy);
          if (along <= progress) continue;
          // Straight on: progress along the ray, penalised by the distance off it.
          const double score = along - progress - 1.5 * across;
          if (score > best_score || (score == best_score && w < best)) {
            best_score = score;
            best = w;
            best_progress = along;
          }
        }
      if (best < 0) break;
      mark_edge(u, best);
      used_[best] = 1;
      u = best;
      progress = best_progress;
    }
  }

  void mark_edge(int a, int b) {
    for (int k = fans_.begin[a]; k < fans_.begin[a + 1]; ++k) {
      const int f = fans_.faces[k];
      const auto& t = mesh_.triangles[f];
      for (int i = 0; i < 3; ++i) {
        const int p = t[(i + 1) % 3], q = t[(i + 2) % 3];
        if ((p == a && q == b) || (p == b && q == a)) mask_[f] |= static_cast<std::uint8_t>(1u << i);
      }
    }
  }

  std::vector<std::uint8_t> take() { return std::move(mask_); }

 private:
  const BackgroundMesh& mesh_;
  VertexFans fans_;
  std::vector<std::uint8_t> mask_;
  std::vector<char> used_;  // boundary vertices and barrier vertices
};

}  // namespace

std::vector<std::uint8_t> corner_barriers(const BackgroundMesh& mesh, const SizingField& size,
                                          const CornerBarrierParams& params) {
  BarrierBuilder builder(mesh);
  if (!(params.length_h > 0.0)) return builder.take();
  for (const BoundaryChain& chain : mesh.chains) {
    const int n = static_cast<int>(chain.vertices.size());
    for (int k = 0; k < n; ++k) {
      const double turning = chain.corner_turning_deg[k];
      if (!chain.is_corner[k] || !(turning < 0.0)) continue;
      const int v = chain.vertices[k];
      const double h = size.size_m[v];
      // The corner's two boundary directions over half a tile (tile-scale corners are
      // tagged from the turning within h, not at one vertex).
      const Point2& p = mesh.points[v];
      const Point2& back = mesh.points[vertex_along(chain, k, -1, 0.5 * h)];
      const Point2& ahead = mesh.points[vertex_along(chain, k, +1, 0.5 * h)];
      const double a_back = std::atan2(back.y - p.y, back.x - p.x);
      const double a_ahead = std::atan2(ahead.y - p.y, ahead.x - p.x);
      // The domain lies on the left of the chain: counter-clockwise from ahead to back.
      double interior = a_back - a_ahead;
      while (interior <= 0.0) interior += 2.0 * kPi;
      if (interior <= kPi) continue;  // not reflex at tile scale after all
      const int parts = turning < -params.sharp_reflex_deg ? 3 : 2;
      for (int j = 1; j < parts; ++j) {
        const double a = a_ahead + interior * j / parts;
        builder.trace(v, std::cos(a), std::sin(a), params.length_h * h);
      }
    }
  }
  return builder.take();
}

}  // namespace isoquad
