#include "tiling/seed_tiling.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "mesh/locate.h"
#include "tiling/flood_tiling.h"

namespace isoquad {

namespace {

struct Seed {
  Point2 p;
  double h;
  double c, s;  // the cross frame: u = (c, s), v = (-s, c)
  int triangle;
};

// Placed seeds with a uniform grid for the proximity test.
class SeedSet {
 public:
  SeedSet(const BackgroundMesh& mesh, const SizingField& size, const SeedParams& params)
      : min_gap_(params.min_gap) {
    double x1 = -1e300, y1 = -1e300;
    x0_ = y0_ = 1e300;
    for (const Point2& p : mesh.points) {
      x0_ = std::min(x0_, p.x), y0_ = std::min(y0_, p.y);
      x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
    }
    hmax_ = 0;
    double hmin = 1e300;
    for (double h : size.size_m) hmin = std::min(hmin, h), hmax_ = std::max(hmax_, h);
    // Cells of one small tile, but never more than about a million of them.
    cell_ = std::max(2 * hmin, std::sqrt((x1 - x0_) * (y1 - y0_) / 1e6));
    nx_ = static_cast<int>((x1 - x0_) / cell_) + 1;
    ny_ = static_cast<int>((y1 - y0_) / cell_) + 1;
    cells_.resize(static_cast<std::size_t>(nx_) * ny_);
  }

  // Whether no placed seed is within min_gap (h + h_j) of `q` in q's frame.
  bool has_room(const Seed& q) const {
    const double reach = std::sqrt(2.0) * min_gap_ * (q.h + hmax_);
    const int i0 = cell_x(q.p.x - reach), i1 = cell_x(q.p.x + reach);
    const int j0 = cell_y(q.p.y - reach), j1 = cell_y(q.p.y + reach);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i)
        for (int k : cells_[static_cast<std::size_t>(j) * nx_ + i]) {
          const Seed& o = seeds[k];
          const double dx = o.p.x - q.p.x, dy = o.p.y - q.p.y;
          const double d = std::max(std::abs(dx * q.c + dy * q.s), std::abs(dy * q.c - dx * q.s));
          if (d < min_gap_ * (q.h + o.h)) return false;
        }
    return true;
  }

  void add(const Seed& q) {
    cells_[static_cast<std::size_t>(cell_y(q.p.y)) * nx_ + cell_x(q.p.x)].push_back(
        static_cast<int>(seeds.size()));
    seeds.push_back(q);
  }

  std::vector<Seed> seeds;

 private:
  int cell_x(double x) const { return std::clamp(static_cast<int>((x - x0_) / cell_), 0, nx_ - 1); }
  int cell_y(double y) const { return std::clamp(static_cast<int>((y - y0_) / cell_), 0, ny_ - 1); }

  double min_gap_;
  double x0_, y0_, cell_, hmax_;
  int nx_, ny_;
  std::vector<std::vector<int>> cells_;
};

// A boundary chain parameterised by tile count: u grows by ds / 2h along the chain.
class ChainWalk {
 public:
  ChainWalk(const BackgroundMesh& mesh, const SizingField& size, const BoundaryChain& chain)
      : mesh_(mesh), chain_(chain) {
    const int n = static_cast<int>(chain.vertices.size());
    u_.assign(n + 1, 0.0);
    for (int i = 0; i < n; ++i) {
      const int a = chain.vertices[i], b = chain.vertices[(i + 1) % n];
      const double len = std::hypot(mesh.points[b].x - mesh.points[a].x,
                                    mesh.points[b].y - mesh.points[a].y);
      u_[i + 1] = u_[i] + len / (size.size_m[a] + size.size_m[b]);
    }
    h_.resize(n);
    for (int i = 0; i < n; ++i) h_[i] = size.size_m[chain.vertices[i]];
  }

  double total() const { return u_.back(); }
  double u_at_vertex(int i) const { return u_[i]; }

  // Position and h at parameter u (taken modulo the chain's total).
  Point2 point(double u, double* h = nullptr) const {
    const int n = static_cast<int>(chain_.vertices.size());
    u = std::fmod(u, total());
    if (u < 0) u += total();
    const int i = std::clamp(
        static_cast<int>(std::upper_bound(u_.begin(), u_.end(), u) - u_.begin()) - 1, 0, n - 1);
    const double span = u_[i + 1] - u_[i];
    const double t = span > 0 ? (u - u_[i]) / span : 0.0;
    const Point2& a = mesh_.points[chain_.vertices[i]];
    const Point2& b = mesh_.points[chain_.vertices[(i + 1) % n]];
    if (h) *h = (1 - t) * h_[i] + t * h_[(i + 1) % n];
    return {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)};
  }

 private:
  const BackgroundMesh& mesh_;
  const BoundaryChain& chain_;
  std::vector<double> u_, h_;
};

}  // namespace

Tiling seed_tiling(const BackgroundMesh& mesh, const TriangleGeometry& geom,
                   const SizingField& size, const CrossField& cross, const SeedParams& params,
                   SeedStats* stats) {
  SeedStats local;
  SeedStats& st = stats ? *stats : local;
  st = SeedStats{};
  const TriangleLocator locator(mesh);
  SeedSet set(mesh, size, params);

  auto inside = [&](const Point2& p) { return locator.locate(p).inside; };
  // Places a seed at q when it is inside, clear of the boundary by `clearance` h along
  // its frame axes, and has room.
  auto try_add = [&](const Point2& q, double clearance) {
    const Location loc = locator.locate(q);
    if (!loc.inside) return false;
    const double a = cross_angle_at(mesh, cross, loc.triangle, loc.bary);
    Seed s{q, size.at(mesh, loc.triangle, loc.bary), std::cos(a), std::sin(a), loc.triangle};
    if (clearance > 0) {
      const double r = clearance * s.h;
      if (!inside({q.x + r * s.c, q.y + r * s.s}) || !inside({q.x - r * s.c, q.y - r * s.s}) ||
          !inside({q.x - r * s.s, q.y + r * s.c}) || !inside({q.x + r * s.s, q.y - r * s.c}))
        return false;
    }
    if (!set.has_room(s)) return false;
    set.add(s);
    return true;
  };

  // Boundary rows: between consecutive corners a whole number of tiles, centred at h
  // inside (the domain is on the left of a chain).
  for (const BoundaryChain& chain : mesh.chains) {
    const ChainWalk walk(mesh, size, chain);
    const int n = static_cast<int>(chain.vertices.size());
    if (n < 3 || !(walk.total() > 0)) continue;
    std::vector<double> corners;
    for (int i = 0; i < n; ++i)
      if (chain.is_corner[i]) corners.push_back(walk.u_at_vertex(i));
    const bool closed_side = corners.empty();
    if (closed_side) corners.push_back(0.0);
    for (std::size_t k = 0; k < corners.size(); ++k) {
      const double ua = corners[k];
      const double ub = k + 1 < corners.size() ? corners[k + 1] : corners[0] + walk.total();
      const int tiles = std::max(1, static_cast<int>(std::lround(ub - ua)));
      for (int i = 0; i < tiles; ++i) {
        const double u = ua + (closed_side ? i : i + 0.5) * (ub - ua) / tiles;
        double h = 0;
        const Point2 b = walk.point(u, &h);
        const Point2 before = walk.point(u - 0.25), after = walk.point(u + 0.25);
        double tx = after.x - before.x, ty = after.y - before.y;
        const double len = std::hypot(tx, ty);
        if (!(len > 0)) continue;
        tx /= len, ty /= len;
        for (double depth : {1.0, 0.5}) {
          if (try_add({b.x - depth * h * ty, b.y + depth * h * tx}, 0.0)) {
            ++st.num_boundary;
            break;
          }
        }
      }
    }
  }

  // The lines' rows: along each line, a generator every tile (2h), where there is room.
  for (const std::vector<Point2>& line : params.lines) {
    double to_next = 0.0;  // tiles until the next generator
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
      const Point2 a = line[i], b = line[i + 1];
      const double length = distance(a, b);
      // Walked in steps of at most a quarter of h, counting tiles as ds / 2h.
      for (double t = 0.0; t < length;) {
        const Point2 p{a.x + (b.x - a.x) * t / length, a.y + (b.y - a.y) * t / length};
        const Location loc = locator.locate(p);
        const double h = loc.triangle >= 0 ? size.at(mesh, loc.triangle, loc.bary) : 0.0;
        if (!(h > 0)) break;
        if (to_next <= 0.0) {
          if (try_add(p, params.clearance)) ++st.num_lines;
          to_next += 1.0;
        }
        const double step = std::min(0.25 * h, length - t);
        to_next -= step / (2.0 * h);
        t += step;
      }
    }
  }

  // Fronts: breadth first from the boundary and lines' rows, one tile along each cross
  // direction.
  for (std::size_t k = 0; k < set.seeds.size(); ++k) {
    const Seed s = set.seeds[k];
    for (int dir = 0; dir < 4; ++dir) {
      const double dx = dir == 0 ? s.c : dir == 1 ? -s.s : dir == 2 ? -s.c : s.s;
      const double dy = dir == 0 ? s.s : dir == 1 ? s.c : dir == 2 ? -s.s : -s.c;
      // The step is 2h at the midpoint, so that spacing follows a graded size.
      const Location mid = locator.locate({s.p.x + s.h * dx, s.p.y + s.h * dy});
      const double h = mid.inside ? size.at(mesh, mid.triangle, mid.bary) : s.h;
      if (try_add({s.p.x + 2 * h * dx, s.p.y + 2 * h * dy}, params.clearance)) ++st.num_interior;
    }
  }

  // Generators: one per distinct seed triangle, then one more in the first triangle
  // each flood leaves unreached (a component whose seeds were all dropped).
  Tiling tiling;
  std::vector<char> used(geom.num_triangles(), 0);
  for (const Seed& s : set.seeds)
    if (!used[s.triangle]) used[s.triangle] = 1, tiling.generator.push_back(s.triangle);
  LinfFlood flood(mesh, geom, cross);
  for (;;) {
    flood.flood(tiling.generator, tiling.label);
    const auto missing = std::find(tiling.label.begin(), tiling.label.end(), -1);
    if (missing == tiling.label.end()) break;
    tiling.generator.push_back(static_cast<int>(missing - tiling.label.begin()));
    ++st.num_filled;
  }
  return tiling;
}

}  // namespace isoquad
