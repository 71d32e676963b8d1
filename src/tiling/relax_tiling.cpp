#include "tiling/relax_tiling.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include "core/error.h"
#include "tiling/choose_corners.h"
#include "tiling/flood_tiling.h"

namespace isoquad {

namespace {

std::uint64_t hash_of(const std::vector<int>& v) {
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a
  for (int x : v) {
    h ^= static_cast<std::uint32_t>(x);
    h *= 1099511628211ull;
  }
  return h;
}

// The generator sets met so far: discrete L-inf Lloyd iterations may cycle (2.3).
class GeneratorHistory {
 public:
  bool contains(const std::vector<int>& g) const {
    const std::uint64_t h = hash_of(g);
    for (std::size_t i = 0; i < hashes_.size(); ++i)
      if (hashes_[i] == h && sets_[i] == g) return true;
    return false;
  }
  void add(const std::vector<int>& g) {
    hashes_.push_back(hash_of(g));
    sets_.push_back(g);
  }

 private:
  std::vector<std::uint64_t> hashes_;
  std::vector<std::vector<int>> sets_;
};

// Whether generator triangle g is close enough to its tile's target (x, y) to stay.
bool settled(const TriangleGeometry& geom, int g, double x, double y, double settle_h) {
  const double r = settle_h * geom.size_m[g];
  const double dx = geom.cx[g] - x, dy = geom.cy[g] - y;
  return dx * dx + dy * dy <= r * r;
}

// Relocation of the tiles marked in `changed` (2.3): the triangle nearest the weighted
// centroid, found by a search of the tile from its generator (tiles of a flood are
// connected and own their generator). Other tiles keep their generator: an unchanged
// tile has the same centroid.
class Relocator {
 public:
  Relocator(const BackgroundMesh& mesh, const TriangleGeometry& geom, double settle_h)
      : mesh_(mesh), geom_(geom), settle_h_(settle_h), stamp_(geom.num_triangles(), 0) {}

  void relocate(const std::vector<int>& label, const std::vector<char>& changed,
                std::vector<int>& generator) {
    for (int t = 0; t < static_cast<int>(generator.size()); ++t) {
      if (!changed[t]) continue;
      ++current_;
      const int start = generator[t];
      stamp_[start] = current_;
      members_.assign(1, start);
      double w = 0.0, sx = 0.0, sy = 0.0;
      for (std::size_t k = 0; k < members_.size(); ++k) {
        const int f = members_[k];
        w += geom_.area_m2[f];
        sx += geom_.area_m2[f] * geom_.cx[f];
        sy += geom_.area_m2[f] * geom_.cy[f];
        for (int g : mesh_.neighbours[f])
          if (g >= 0 && label[g] == t && stamp_[g] != current_) {
            stamp_[g] = current_;
            members_.push_back(g);
          }
      }
      const double x = sx / w, y = sy / w;
      if (settled(geom_, start, x, y, settle_h_)) continue;
      int best = start;
      double best_d2 = std::numeric_limits<double>::infinity();
      for (int f : members_) {
        const double dx = geom_.cx[f] - x, dy = geom_.cy[f] - y;
        const double d2 = dx * dx + dy * dy;
        if (d2 < best_d2 || (d2 == best_d2 && f < best)) {
          best_d2 = d2;
          best = f;
        }
      }
      generator[t] = best;
    }
  }

 private:
  const BackgroundMesh& mesh_;
  const TriangleGeometry& geom_;
  double settle_h_;
  std::vector<int> stamp_;
  int current_ = 0;
  std::vector<int> members_;
};

// Whether the Lloyd iterations stop at the relocated generators `next` (nothing moved, or
// a generator set came back); otherwise records them.
bool stop_iterating(const std::vector<int>& next, const std::vector<int>& generator,
                    GeneratorHistory& history, RelaxResult& r) {
  if (next == generator) {
    r.converged = true;
    return true;
  }
  if (history.contains(next)) {
    r.cycled = true;
    return true;
  }
  history.add(next);
  return false;
}

// Shared boundary length between adjacent tiles, per tile.
using TileAdjacency = std::vector<std::vector<std::pair<int, double>>>;

void add_shared(TileAdjacency& adjacent, int a, int b, double len) {
  for (auto& [t, l] : adjacent[a])
    if (t == b) {
      l += len;
      return;
    }
  adjacent[a].push_back({b, len});
}

TileAdjacency adjacency_from_graph(const MetaGraph& graph, int num_tiles) {
  TileAdjacency adjacent(num_tiles);
  for (const MetaEdge& e : graph.edges) {
    if (e.on_boundary() || e.tile_left == e.tile_right) continue;
    add_shared(adjacent, e.tile_left, e.tile_right, e.length_m);
    add_shared(adjacent, e.tile_right, e.tile_left, e.length_m);
  }
  return adjacent;
}

// The same from the labels in one pass over the triangles, without a meta-graph.
TileAdjacency adjacency_from_labels(const BackgroundMesh& mesh, const std::vector<int>& label,
                                    int num_tiles) {
  TileAdjacency adjacent(num_tiles);
  for (int f = 0; f < static_cast<int>(mesh.triangles.size()); ++f)
    for (int i = 0; i < 3; ++i) {
      const int g = mesh.neighbours[f][i];
      if (g < 0 || label[g] == label[f]) continue;
      const Point2 &a = mesh.points[mesh.triangles[f][(i + 1) % 3]],
                   &b = mesh.points[mesh.triangles[f][(i + 2) % 3]];
      add_shared(adjacent, label[f], label[g], distance(a, b));
    }
  return adjacent;
}

// ConformShiftRule::lattice, one tile: its shift (dx, dy) from its centroid, from the tile
// centroids cx, cy of it and its neighbours.
struct LatticeShift {
  double dx = 0.0, dy = 0.0, length = 0.0;
};
LatticeShift lattice_shift(const BackgroundMesh& mesh, const CrossField& cross,
                           const std::vector<std::pair<int, double>>& adjacent, int t,
                           int relocated, const std::vector<double>& cx,
                           const std::vector<double>& cy, double pull) {
  const double theta = frame_angle_at(mesh, cross, relocated);
  const double ux = std::cos(theta), uy = std::sin(theta);
  // Per side (+u, -u, +v, -v): the neighbour sharing the most boundary, and its offset
  // across that side's axis.
  double best_len[4] = {0, 0, 0, 0}, across[4] = {0, 0, 0, 0};
  for (const auto& [j, len] : adjacent) {
    const double dx = cx[j] - cx[t], dy = cy[j] - cy[t];
    const double du = dx * ux + dy * uy, dv = dy * ux - dx * uy;
    const int side = std::abs(du) >= std::abs(dv) ? (du > 0 ? 0 : 1) : (dv > 0 ? 2 : 3);
    if (len > best_len[side]) {
      best_len[side] = len;
      across[side] = side < 2 ? dv : du;
    }
  }
  double move_u = 0.0, move_v = 0.0;
  int nu = 0, nv = 0;
  for (int side = 0; side < 4; ++side) {
    if (best_len[side] <= 0.0) continue;
    if (side < 2)
      move_v += across[side], ++nv;
    else
      move_u += across[side], ++nu;
  }
  if (nu > 0) move_u *= pull / nu;
  if (nv > 0) move_v *= pull / nv;
  return {move_u * ux - move_v * uy, move_u * uy + move_v * ux, std::hypot(move_u, move_v)};
}

// ConformShiftRule::lattice over every tile. out holds the tile centroids on entry.
void lattice_targets(const BackgroundMesh& mesh, const CrossField& cross,
                     const TileAdjacency& adjacent, const std::vector<int>& relocated,
                     double pull, ConformTargets& out) {
  const int num_tiles = static_cast<int>(relocated.size());
  const std::vector<double> cx = out.x, cy = out.y;
  for (int t = 0; t < num_tiles; ++t) {
    if (relocated[t] < 0) continue;
    const LatticeShift shift =
        lattice_shift(mesh, cross, adjacent[t], t, relocated[t], cx, cy, pull);
    out.x[t] += shift.dx;
    out.y[t] += shift.dy;
    out.shift_m[t] = shift.length;
  }
}

}  // namespace

RelaxResult relax_tiling(const BackgroundMesh& mesh, const TriangleGeometry& geom,
                         const CrossField& cross, Tiling& tiling, const RelaxParams& params,
                         const Progress& progress) {
  RelaxResult r;
  fix_generators(geom, tiling);
  const int num_tiles = tiling.num_tiles();
  LinfFlood flood(mesh, geom, cross);
  Relocator relocator(mesh, geom, params.settle_h);
  double best_energy = std::numeric_limits<double>::infinity();
  int since_best = 0;
  std::vector<int> generator = tiling.generator;
  std::vector<int> label;
  flood.flood(generator, label);
  r.num_flooded += flood.num_flooded();
  if (params.record_energy)
    r.energy_history.push_back(tiling_energy(mesh, geom, cross, label, generator));
  std::vector<char> changed(num_tiles, 1);
  GeneratorHistory history;
  history.add(generator);
  for (int it = 0; it < params.max_iters; ++it) {
    progress.report("relax", static_cast<double>(it) / params.max_iters);
    std::vector<int> next = generator;
    relocator.relocate(label, changed, next);
    ++r.iterations;
    if (stop_iterating(next, generator, history, r)) break;
    generator.swap(next);
    flood.reflood(generator, label, changed);
    r.num_flooded += flood.num_flooded();
    // The discrete iterations shuffle a few generators long after the energy stopped
    // falling: stop when it has not improved its best by energy_tol in `patience` floods.
    const double e = tiling_energy(mesh, geom, cross, label, generator);
    if (params.record_energy) r.energy_history.push_back(e);
    if (e < best_energy * (1.0 - params.energy_tol)) {
      best_energy = e;
      since_best = 0;
    } else if (++since_best >= params.patience) {
      r.converged = true;
      break;
    }
  }
  tiling.label.swap(label);
  tiling.generator.swap(generator);
  r.energy = tiling_energy(mesh, geom, cross, tiling);
  progress.report("relax", 1.0);
  return r;
}

namespace {

// conform_targets; `graph` may be null for the lattice rule, which then reads the tile
// adjacency from the labels.
ConformTargets targets_of(const BackgroundMesh& mesh, const TriangleGeometry& geom,
                          const CrossField& cross, const Tiling& tiling, const MetaGraph* graph,
                          const ConformParams& params) {
  const int num_tiles = tiling.num_tiles();
  const TileCentroids c = tile_centroids(geom, tiling.label, num_tiles);
  const std::vector<int> relocated = nearest_triangles_in_tiles(geom, tiling.label, c.x, c.y);
  ConformTargets out;
  out.x = c.x;
  out.y = c.y;
  out.shift_m.assign(num_tiles, 0.0);
  if (params.rule == ConformShiftRule::lattice) {
    const TileAdjacency adjacent = graph ? adjacency_from_graph(*graph, num_tiles)
                                         : adjacency_from_labels(mesh, tiling.label, num_tiles);
    lattice_targets(mesh, cross, adjacent, relocated, params.shift, out);
    return out;
  }
  std::vector<Point2> pos;
  std::vector<char> is_corner;
  std::vector<int> side_of;
  for (int t = 0; t < num_tiles; ++t) {
    const TileCycle& cycle = graph->tiles[t];
    const int p = static_cast<int>(cycle.vertices.size());
    // Quadrangles and triangles are not shifted (2.4).
    if (p <= 4 || relocated[t] < 0) continue;
    // The frame is the cross at the tile's relocated triangle (2.4).
    const double theta = frame_angle_at(mesh, cross, relocated[t]);
    pos.resize(p);
    for (int i = 0; i < p; ++i) pos[i] = mesh.points[graph->vertices[cycle.vertices[i]]];
    const CornerChoice choice = choose_corners_and_axes(pos, theta);
    is_corner.assign(p, 0);
    side_of.assign(p, 0);
    for (int k = 0; k < 4; ++k) {
      is_corner[choice.corners[k]] = 1;
      const int end = choice.corners[(k + 1) % 4];
      for (int i = choice.corners[k]; i != end; i = (i + 1) % p) side_of[i] = k;
    }
    const double ux = std::cos(theta), uy = std::sin(theta);
    // Meta-edge i runs from meta-vertex i to i+1; only those with exactly one corner end
    // carry a T-junction to close.
    int chosen = -1;
    double chosen_len = 0.0, ref_x = 0.0, ref_y = 0.0;
    const bool longest = params.rule != ConformShiftRule::close_shortest;
    for (int i = 0; i < p; ++i) {
      const int j = (i + 1) % p;
      if (is_corner[i] == is_corner[j]) continue;
      const bool along_v = (side_of[i] + (choice.first_side_along_v ? 1 : 0)) % 2 == 1;
      const double rx = along_v ? -uy : ux, ry = along_v ? ux : uy;
      const double len = std::abs((pos[j].x - pos[i].x) * rx + (pos[j].y - pos[i].y) * ry);
      if (chosen < 0 || (longest ? len > chosen_len : len < chosen_len)) {
        chosen = i;
        chosen_len = len;
        ref_x = rx;
        ref_y = ry;
      }
    }
    if (chosen < 0) continue;
    const int a = chosen, b = (chosen + 1) % p;
    const Point2& corner = is_corner[a] ? pos[a] : pos[b];
    const Point2& other = is_corner[a] ? pos[b] : pos[a];
    // Unit vector along the reference direction pointing from the other end to the corner.
    const double sign =
        (corner.x - other.x) * ref_x + (corner.y - other.y) * ref_y >= 0.0 ? 1.0 : -1.0;
    double towards = params.shift * chosen_len;
    if (params.rule != ConformShiftRule::longest_towards_corner) towards = -towards;
    out.x[t] += towards * sign * ref_x;
    out.y[t] += towards * sign * ref_y;
    out.shift_m[t] = std::abs(towards);
  }
  return out;
}

// One conforming iteration's relocated generators from every tile's target: the passes
// over the whole mesh (targets_of, nearest_triangles_in_tiles).
std::vector<int> relocate_all(const BackgroundMesh& mesh, const TriangleGeometry& geom,
                              const CrossField& cross, const Tiling& current,
                              const ConformParams& params) {
  // The lattice rule needs only the tile adjacency; the others the tiles' meta-vertices.
  MetaGraph graph;
  if (params.rule != ConformShiftRule::lattice)
    graph = build_meta_graph(mesh, current, params.graph);
  const ConformTargets targets =
      targets_of(mesh, geom, cross, current,
                 params.rule == ConformShiftRule::lattice ? nullptr : &graph, params);
  std::vector<int> next = nearest_triangles_in_tiles(geom, current.label, targets.x, targets.y);
  for (int t = 0; t < current.num_tiles(); ++t)
    if (settled(geom, current.generator[t], targets.x[t], targets.y[t], params.settle_h))
      next[t] = current.generator[t];
  return next;
}

// The lattice rule's relocations kept from one iteration to the next. A tile's target
// depends on its triangles, the labels of the triangles round it and its neighbours'
// centroids: it changes only where the flood changed the tile or a neighbour, and a
// tile whose target stands keeps its generator (the triangle nearest that target, or
// one within settle_h of it, since the iteration that moved it there). So only those
// tiles are computed again, each over its own triangles in ascending order: the sums
// and ties of relocate_all's passes over the mesh, and the same generators.
class LatticeRelocator {
 public:
  LatticeRelocator(const BackgroundMesh& mesh, const TriangleGeometry& geom,
                   const CrossField& cross, const ConformParams& params, int num_tiles)
      : mesh_(mesh),
        geom_(geom),
        cross_(cross),
        params_(params),
        cx_(num_tiles, 0.0),
        cy_(num_tiles, 0.0),
        relocated_(num_tiles, -1),
        adjacent_(num_tiles),
        seen_(geom.num_triangles(), 0) {}

  // changed: the tiles the last flood may have changed (all on the first call).
  std::vector<int> relocate(const Tiling& current, const std::vector<char>& changed) {
    const int num_tiles = current.num_tiles();
    // Tiles to compute again: the changed ones and their neighbours (by the adjacency of
    // before the flood: a label that changed next to a tile belonged to a changed tile).
    dirty_.clear();
    for (int t = 0; t < num_tiles; ++t) {
      bool dirty = changed[t] != 0;
      for (std::size_t k = 0; k < adjacent_[t].size() && !dirty; ++k)
        dirty = changed[adjacent_[t][k].first] != 0;
      if (dirty) dirty_.push_back(t);
    }
    // The changed tiles' centroids and nearest triangles (first: their neighbours'
    // targets read them).
    for (int t = 0; t < num_tiles; ++t) {
      if (!changed[t]) continue;
      collect(t, current);
      double w = 0.0, sx = 0.0, sy = 0.0;
      for (int f : members_) {
        const double a = geom_.area_m2[f];
        sx += a * geom_.cx[f];
        sy += a * geom_.cy[f];
        w += a;
      }
      cx_[t] = sx / w;
      cy_[t] = sy / w;
      relocated_[t] = nearest(cx_[t], cy_[t]);
    }
    // Every dirty tile's adjacency, as adjacency_from_labels lists it, its target and its
    // relocation; every other tile keeps its generator.
    std::vector<int> next = current.generator;
    for (int t : dirty_) {
      collect(t, current);
      adjacent_[t].clear();
      for (int f : members_)
        for (int i = 0; i < 3; ++i) {
          const int g = mesh_.neighbours[f][i];
          if (g < 0 || current.label[g] == t) continue;
          const Point2 &a = mesh_.points[mesh_.triangles[f][(i + 1) % 3]],
                       &b = mesh_.points[mesh_.triangles[f][(i + 2) % 3]];
          add_shared(adjacent_, t, current.label[g], distance(a, b));
        }
      const LatticeShift shift =
          lattice_shift(mesh_, cross_, adjacent_[t], t, relocated_[t], cx_, cy_, params_.shift);
      const double x = cx_[t] + shift.dx, y = cy_[t] + shift.dy;
      if (!settled(geom_, current.generator[t], x, y, params_.settle_h)) next[t] = nearest(x, y);
    }
    return next;
  }

 private:
  // Tile t's triangles into members_, ascending: a search from its generator (the tiles
  // of a flood are connected and own their generator), sorted.
  void collect(int t, const Tiling& current) {
    members_.assign(1, current.generator[t]);
    seen_[members_[0]] = 1;
    for (std::size_t k = 0; k < members_.size(); ++k)
      for (int h : mesh_.neighbours[members_[k]])
        if (h >= 0 && !seen_[h] && current.label[h] == t) {
          seen_[h] = 1;
          members_.push_back(h);
        }
    for (int f : members_) seen_[f] = 0;
    std::sort(members_.begin(), members_.end());
  }

  // The first of members_ nearest (x, y), as nearest_triangles_in_tiles finds it.
  int nearest(double x, double y) const {
    int best = -1;
    double best_d2 = std::numeric_limits<double>::infinity();
    for (int f : members_) {
      const double dx = geom_.cx[f] - x, dy = geom_.cy[f] - y;
      const double d2 = dx * dx + dy * dy;
      if (d2 < best_d2) {
        best_d2 = d2;
        best = f;
      }
    }
    return best;
  }

  const BackgroundMesh& mesh_;
  const TriangleGeometry& geom_;
  const CrossField& cross_;
  const ConformParams& params_;
  std::vector<double> cx_, cy_;  // #T centroids
  std::vector<int> relocated_;   // #T the triangle nearest the centroid
  TileAdjacency adjacent_;       // #T
  std::vector<int> dirty_, members_;
  std::vector<char> seen_;  // #F, 0 between searches
};

}  // namespace

ConformTargets conform_targets(const BackgroundMesh& mesh, const TriangleGeometry& geom,
                               const CrossField& cross, const Tiling& tiling,
                               const MetaGraph& graph, const ConformParams& params) {
  return targets_of(mesh, geom, cross, tiling, &graph, params);
}

RelaxResult conform_tiling(const BackgroundMesh& mesh, const TriangleGeometry& geom,
                           const CrossField& cross, Tiling& tiling, const ConformParams& params,
                           const Progress& progress) {
  RelaxResult r;
  fix_generators(geom, tiling);
  const int num_tiles = tiling.num_tiles();
  LinfFlood flood(mesh, geom, cross);
  Tiling current;
  current.generator = tiling.generator;
  flood.flood(current.generator, current.label);
  r.num_flooded += flood.num_flooded();
  if (params.record_energy) r.energy_history.push_back(tiling_energy(mesh, geom, cross, current));
  std::vector<char> changed(num_tiles, 1);
  GeneratorHistory history;
  history.add(current.generator);
  std::optional<LatticeRelocator> lattice;
  if (params.rule == ConformShiftRule::lattice)
    lattice.emplace(mesh, geom, cross, params, num_tiles);
  for (int it = 0; it < params.iters; ++it) {
    progress.report("conform", static_cast<double>(it) / params.iters);
    std::vector<int> next = lattice ? lattice->relocate(current, changed)
                                    : relocate_all(mesh, geom, cross, current, params);
    if (lattice && params.verify_relocations &&
        next != relocate_all(mesh, geom, cross, current, params))
      throw Error(ErrorClass::internal, "tiling",
                  "conforming iteration " + std::to_string(it) +
                      ": the lattice rule's relocations, kept from the iteration before, "
                      "differ from those computed over every tile");
    ++r.iterations;
    if (stop_iterating(next, current.generator, history, r)) break;
    current.generator.swap(next);
    flood.reflood(current.generator, current.label, changed);
    r.num_flooded += flood.num_flooded();
    if (params.record_energy)
      r.energy_history.push_back(tiling_energy(mesh, geom, cross, current));
  }
  tiling = std::move(current);
  r.energy = tiling_energy(mesh, geom, cross, tiling);
  progress.report("conform", 1.0);
  return r;
}

}  // namespace isoquad
