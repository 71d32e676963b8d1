#include "mesh/locate.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace isoquad {

std::array<double, 3> barycentric(const Point2& a, const Point2& b, const Point2& c,
                                  const Point2& p) {
  const double d = (b.y - c.y) * (a.x - c.x) + (c.x - b.x) * (a.y - c.y);
  const double l0 = ((b.y - c.y) * (p.x - c.x) + (c.x - b.x) * (p.y - c.y)) / d;
  const double l1 = ((c.y - a.y) * (p.x - c.x) + (a.x - c.x) * (p.y - c.y)) / d;
  return {l0, l1, 1.0 - l0 - l1};
}

TriangleLocator::TriangleLocator(const BackgroundMesh& mesh) : mesh_(&mesh) {
  double xmin = 1e300, ymin = 1e300, xmax = -1e300, ymax = -1e300;
  for (const Point2& p : mesh.points)
    xmin = std::min(xmin, p.x), ymin = std::min(ymin, p.y), xmax = std::max(xmax, p.x),
    ymax = std::max(ymax, p.y);
  const std::size_t nf = mesh.triangles.size();
  // About two triangles per cell where there are triangles: cells sized by the
  // triangles' own area, not the bounding box's (islands far apart leave it mostly
  // empty), but no more than 16 cells per triangle in all.
  double covered = 0.0;
  for (const auto& t : mesh.triangles) {
    const Point2 &a = mesh.points[t[0]], &b = mesh.points[t[1]], &c = mesh.points[t[2]];
    covered += std::abs(signed_area(a, b, c));
  }
  const double box = std::max((xmax - xmin) * (ymax - ymin), 1e-300);
  const double n = static_cast<double>(std::max<std::size_t>(nf, 1));
  cell_ = std::max({std::sqrt(2.0 * covered / n), std::sqrt(box / (16.0 * n)), 1e-12});
  x0_ = xmin;
  y0_ = ymin;
  nx_ = std::max(1, static_cast<int>(std::ceil((xmax - xmin) / cell_)) + 1);
  ny_ = std::max(1, static_cast<int>(std::ceil((ymax - ymin) / cell_)) + 1);
  std::vector<int> count(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
  auto for_cells = [&](std::size_t f, auto&& fn) {
    const auto& t = mesh.triangles[f];
    double bx0 = 1e300, by0 = 1e300, bx1 = -1e300, by1 = -1e300;
    for (int v : t)
      bx0 = std::min(bx0, mesh.points[v].x), by0 = std::min(by0, mesh.points[v].y),
      bx1 = std::max(bx1, mesh.points[v].x), by1 = std::max(by1, mesh.points[v].y);
    const int i0 = static_cast<int>((bx0 - x0_) / cell_), i1 = static_cast<int>((bx1 - x0_) / cell_);
    const int j0 = static_cast<int>((by0 - y0_) / cell_), j1 = static_cast<int>((by1 - y0_) / cell_);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) fn(static_cast<std::size_t>(j) * nx_ + i);
  };
  for (std::size_t f = 0; f < nf; ++f) for_cells(f, [&](std::size_t c) { ++count[c + 1]; });
  for (std::size_t c = 0; c + 1 < count.size(); ++c) count[c + 1] += count[c];
  start_ = count;
  items_.resize(start_.back());
  std::vector<int> fill(start_.begin(), start_.end() - 1);
  for (std::size_t f = 0; f < nf; ++f)
    for_cells(f, [&](std::size_t c) { items_[fill[c]++] = static_cast<int>(f); });
}

Location TriangleLocator::locate(const Point2& p) const {
  return search(p, true);
}

Location TriangleLocator::search(const Point2& p, bool skip_empty_rings) const {
  const BackgroundMesh& m = *mesh_;
  const int ci = std::clamp(static_cast<int>((p.x - x0_) / cell_), 0, nx_ - 1);
  const int cj = std::clamp(static_cast<int>((p.y - y0_) / cell_), 0, ny_ - 1);
  Location best;
  double best_violation = std::numeric_limits<double>::infinity();
  // A point on an edge or a vertex can come out of the barycentric computation a
  // rounding error outside both triangles: that is inside.
  constexpr double kOnEdge = 1e-12;
  auto visit = [&](int i, int j) {
    if (i < 0 || j < 0 || i >= nx_ || j >= ny_) return;
    const std::size_t c = static_cast<std::size_t>(j) * nx_ + i;
    for (int k = start_[c]; k < start_[c + 1]; ++k) {
      const int f = items_[k];
      const auto& t = m.triangles[f];
      const auto b = barycentric(m.points[t[0]], m.points[t[1]], m.points[t[2]], p);
      const double violation = std::max({0.0, -b[0], -b[1], -b[2]});
      // The least violation, then the lowest id: the order of the visits does not matter.
      if (violation < best_violation || (violation == best_violation && f < best.triangle)) {
        best_violation = violation;
        best.triangle = f;
        best.bary = b;
      }
    }
  };
  // Search rings of cells until a containing triangle is found, or the nearest one
  // once a ring adds nothing better. Rings known to be empty are skipped: they would
  // change nothing.
  const int last_ring = std::max(nx_, ny_);
  for (int ring = 0; ring < last_ring; ++ring) {
    if (skip_empty_rings && ring == 2 && best.triangle < 0) {
      std::call_once(empty_rings_once_, [this] { find_empty_rings(); });
      ring = std::max(ring, empty_rings_[static_cast<std::size_t>(cj) * nx_ + ci]);
      if (ring >= last_ring) break;
    }
    if (ring == 0) {
      visit(ci, cj);
    } else {
      for (int i = ci - ring; i <= ci + ring; ++i) visit(i, cj - ring), visit(i, cj + ring);
      for (int j = cj - ring + 1; j <= cj + ring - 1; ++j) visit(ci - ring, j), visit(ci + ring, j);
    }
    if (best_violation <= kOnEdge) break;
    if (best.triangle >= 0 && ring >= 1) break;
  }
  best.inside = best.triangle >= 0 && best_violation <= kOnEdge;
  if (best.triangle >= 0 && best_violation > 0) {
    for (double& w : best.bary) w = std::max(0.0, w);
    const double s = best.bary[0] + best.bary[1] + best.bary[2];
    for (double& w : best.bary) w /= s;
  }
  return best;
}

// A chessboard distance transform of the cells that hold triangles: two raster passes,
// each cell taking one more than the least of its already visited neighbours.
void TriangleLocator::find_empty_rings() const {
  const int big = nx_ + ny_;
  std::vector<int>& d = empty_rings_;
  d.assign(static_cast<std::size_t>(nx_) * ny_, big);
  auto at = [&](int i, int j) -> int& { return d[static_cast<std::size_t>(j) * nx_ + i]; };
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i) {
      const std::size_t c = static_cast<std::size_t>(j) * nx_ + i;
      if (start_[c + 1] > start_[c]) {
        at(i, j) = 0;
        continue;
      }
      int v = at(i, j);
      if (i > 0) v = std::min(v, at(i - 1, j) + 1);
      if (j > 0) {
        v = std::min(v, at(i, j - 1) + 1);
        if (i > 0) v = std::min(v, at(i - 1, j - 1) + 1);
        if (i + 1 < nx_) v = std::min(v, at(i + 1, j - 1) + 1);
      }
      at(i, j) = v;
    }
  for (int j = ny_ - 1; j >= 0; --j)
    for (int i = nx_ - 1; i >= 0; --i) {
      int v = at(i, j);
      if (i + 1 < nx_) v = std::min(v, at(i + 1, j) + 1);
      if (j + 1 < ny_) {
        v = std::min(v, at(i, j + 1) + 1);
        if (i + 1 < nx_) v = std::min(v, at(i + 1, j + 1) + 1);
        if (i > 0) v = std::min(v, at(i - 1, j + 1) + 1);
      }
      at(i, j) = v;
    }
}

Location TriangleLocator::locate(const Point2& p, int hint) const {
  if (hint >= 0) {
    const auto& t = mesh_->triangles[hint];
    const auto b = barycentric(mesh_->points[t[0]], mesh_->points[t[1]], mesh_->points[t[2]], p);
    if (b[0] > 1e-9 && b[1] > 1e-9 && b[2] > 1e-9) {
      Location inside;
      inside.triangle = hint;
      inside.bary = b;
      inside.inside = true;
      return inside;
    }
  }
  return locate(p);
}

}  // namespace isoquad
