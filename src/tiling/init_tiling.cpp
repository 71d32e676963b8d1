#include "tiling/init_tiling.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <queue>
#include <vector>

namespace isoquad {

namespace {

struct Adjacent {
  int tile;
  double length_m;  // shared boundary length
};

// A candidate merge a < b, pushed as the best merge of `owner` (a or b); valid while
// both tiles are alive and unchanged since it was pushed.
struct Candidate {
  double score;
  int a, b;
  std::uint32_t stamp_a, stamp_b;
  int owner;
};

// Highest score first; ties by the smaller pair, so the order is deterministic.
struct LowerPriority {
  bool operator()(const Candidate& x, const Candidate& y) const {
    if (x.score != y.score) return x.score < y.score;
    if (x.a != y.a) return x.a > y.a;
    return x.b > y.b;
  }
};

class Merger {
 public:
  Merger(const BackgroundMesh& mesh, const TriangleGeometry& geom) {
    const int n = geom.num_triangles();
    area_ = geom.area_m2;
    mass_.resize(n);
    for (int f = 0; f < n; ++f) mass_[f] = geom.mass(f);
    perimeter_.assign(n, 0.0);
    parent_.resize(n);
    alive_.assign(n, 1);
    stamp_.assign(n, 0);
    adjacent_.resize(n);
    num_alive_ = n;
    for (int f = 0; f < n; ++f) {
      parent_[f] = f;
      const auto& t = mesh.triangles[f];
      adjacent_[f].reserve(3);
      for (int i = 0; i < 3; ++i) {
        const Point2 &a = mesh.points[t[(i + 1) % 3]], &b = mesh.points[t[(i + 2) % 3]];
        const double len = std::hypot(b.x - a.x, b.y - a.y);
        perimeter_[f] += len;
        const int g = mesh.neighbours[f][i];
        if (g >= 0 && !geom.crosses_barrier(f, i)) adjacent_[f].push_back({g, len});
      }
    }
  }

  // Compactness of the union (2.2): area / perimeter^2.
  double compactness(int a, int b, double shared_m) const {
    const double p = perimeter_[a] + perimeter_[b] - 2.0 * shared_m;
    return (area_[a] + area_[b]) / (p * p);
  }

  // Merges phase: merges the pair of highest `score(a, b, shared)` among those
  // `allowed(a, b)`, again and again until `done()`. Returns the number of merges.
  //
  // The queue holds one entry per tile, its best merge when pushed, rather than one per
  // adjacent pair (a heap of all pairs took most of the time). A merge changes only the
  // pairs of the survivor r: r's best is pushed afresh, and a neighbour's pair with r when
  // it beats the score the neighbour last pushed. Every other entry stays an upper bound
  // of its owner's best; a stale one (its partner changed, or grew too heavy) is replaced
  // by the owner's recomputed best when it reaches the top. So each merge is still the
  // best pair overall, ties going to the smaller pair.
  template <class Score, class Allowed, class Done>
  int merge_all(Score score, Allowed allowed, Done done) {
    std::priority_queue<Candidate, std::vector<Candidate>, LowerPriority> queue;
    const LowerPriority lower;
    std::vector<double> pushed(alive_.size(), -std::numeric_limits<double>::infinity());
    auto candidate = [&](int owner, const Adjacent& adj) {
      const int lo = std::min(owner, adj.tile), hi = std::max(owner, adj.tile);
      return Candidate{score(owner, adj.tile, adj.length_m), lo, hi, stamp_[lo], stamp_[hi], owner};
    };
    auto push_best = [&](int t) {
      bool found = false;
      Candidate best{};
      for (const Adjacent& adj : adjacent_[t]) {
        if (!allowed(t, adj.tile)) continue;
        const Candidate c = candidate(t, adj);
        if (!found || lower(best, c)) best = c, found = true;
      }
      pushed[t] = found ? best.score : -std::numeric_limits<double>::infinity();
      if (found) queue.push(best);
    };
    for (int t = 0; t < static_cast<int>(alive_.size()); ++t)
      if (alive_[t]) push_best(t);
    int num_merges = 0;
    while (!queue.empty() && !done()) {
      const Candidate c = queue.top();
      queue.pop();
      const std::uint32_t owner_stamp = c.owner == c.a ? c.stamp_a : c.stamp_b;
      if (!alive_[c.owner] || stamp_[c.owner] != owner_stamp) continue;  // superseded
      if (!alive_[c.a] || !alive_[c.b] || stamp_[c.a] != c.stamp_a || stamp_[c.b] != c.stamp_b ||
          !allowed(c.a, c.b)) {
        push_best(c.owner);
        continue;
      }
      const int r = merge(c.a, c.b);
      ++num_merges;
      push_best(r);
      for (const Adjacent& adj : adjacent_[r]) {
        const int n = adj.tile;
        if (!allowed(n, r)) continue;
        const Candidate with_r = candidate(n, {r, adj.length_m});
        if (with_r.score >= pushed[n]) {
          pushed[n] = with_r.score;
          queue.push(with_r);
        }
      }
    }
    return num_merges;
  }

  // Merges the tile with the shorter adjacency list into the other; returns the survivor.
  int merge(int a, int b) {
    const int r = adjacent_[a].size() >= adjacent_[b].size() ? a : b;
    const int o = r == a ? b : a;
    double shared = 0.0;
    std::vector<Adjacent>& lr = adjacent_[r];
    for (const Adjacent& adj : adjacent_[o]) {
      const int n = adj.tile;
      if (n == r) {
        shared += adj.length_m;
        continue;
      }
      // n now borders r instead of o.
      std::vector<Adjacent>& ln = adjacent_[n];
      int io = -1, ir = -1;
      for (int k = 0; k < static_cast<int>(ln.size()); ++k) {
        if (ln[k].tile == o) io = k;
        else if (ln[k].tile == r) ir = k;
      }
      if (ir >= 0) {
        ln[ir].length_m += ln[io].length_m;
        ln[io] = ln.back();
        ln.pop_back();
      } else {
        ln[io].tile = r;
      }
      bool found = false;
      for (Adjacent& x : lr)
        if (x.tile == n) {
          x.length_m += adj.length_m;
          found = true;
          break;
        }
      if (!found) lr.push_back(adj);
    }
    for (std::size_t k = 0; k < lr.size(); ++k)
      if (lr[k].tile == o) {
        lr[k] = lr.back();
        lr.pop_back();
        break;
      }
    std::vector<Adjacent>().swap(adjacent_[o]);
    area_[r] += area_[o];
    mass_[r] += mass_[o];
    perimeter_[r] += perimeter_[o] - 2.0 * shared;
    alive_[o] = 0;
    ++stamp_[r];
    parent_[o] = r;
    --num_alive_;
    return r;
  }

  int find(int f) {
    int r = f;
    while (parent_[r] != r) r = parent_[r];
    while (parent_[f] != r) {
      const int next = parent_[f];
      parent_[f] = r;
      f = next;
    }
    return r;
  }

  int num_alive() const { return num_alive_; }
  double mass(int t) const { return mass_[t]; }

 private:
  std::vector<double> area_, perimeter_, mass_;
  std::vector<int> parent_;
  std::vector<char> alive_;
  std::vector<std::uint32_t> stamp_;
  std::vector<std::vector<Adjacent>> adjacent_;
  int num_alive_ = 0;
};

}  // namespace

Tiling init_tiling(const BackgroundMesh& mesh, const TriangleGeometry& geom,
                   const InitParams& params, InitStats* stats) {
  const int num_faces = geom.num_triangles();
  InitStats s;
  for (int f = 0; f < num_faces; ++f) s.total_mass += geom.mass(f);
  Merger merger(mesh, geom);

  // Compactness first (2.2): the most compact unions merge while they fit in one tile.
  s.num_compact_merges = merger.merge_all(
      [&](int a, int b, double shared) { return merger.compactness(a, b, shared); },
      [&](int a, int b) { return merger.mass(a) + merger.mass(b) <= params.max_mass; },
      [] { return false; });

  // Every tile now holds at most one tile's worth of area, most of them less: merge the
  // lightest pairs until the count matches, or the relaxation would keep too many tiles.
  if (params.match_count) {
    const int target = std::max(1, static_cast<int>(std::lround(s.total_mass)));
    s.num_count_merges = merger.merge_all(
        [&](int a, int b, double) { return -(merger.mass(a) + merger.mass(b)); },
        [](int, int) { return true; }, [&] { return merger.num_alive() <= target; });
  }

  Tiling tiling;
  tiling.label.assign(num_faces, -1);
  std::vector<int> id_of_root(num_faces, -1);
  int num_tiles = 0;
  for (int f = 0; f < num_faces; ++f) {
    const int r = merger.find(f);
    if (id_of_root[r] < 0) id_of_root[r] = num_tiles++;
    tiling.label[f] = id_of_root[r];
  }
  tiling.generator = relocated_generators(geom, tiling.label, num_tiles);
  if (stats) *stats = s;
  return tiling;
}

}  // namespace isoquad
