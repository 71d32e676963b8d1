#include "tiling/butterflies.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <queue>
#include <set>
#include <tuple>
#include <unordered_set>
#include <utility>
#include <vector>

#include "tiling/mean_value.h"

namespace isoquad {

namespace {

// Rounds of candidate collection, one meta-graph build each. A removal creates no new
// butterfly (the region boundary keeps its tiles, the centre has 4), so later rounds
// only retry failed butterflies whose region changed since; two usually suffice.
constexpr int kMaxRounds = 8;
const char* const kStage = "tiling butterflies";
// Centre candidates tried, nearest to phi(v*) first, before giving a butterfly up.
constexpr int kMaxCentreCandidates = 8;

// A directed background edge out of a vertex with the tiles on its left and right
// (-1 outside the domain).
struct Spoke {
  int to = -1;
  int left = -1;
  int right = -1;
};

// The four tiles A, B, C, D around a short inner meta-edge V_B -> V_D (paper, 2.5 and
// Fig. 8). A is on the left of V_B -> V_D, C on its right, B the third tile at V_B and D
// the third tile at V_D: A, B, C, D run counter-clockwise around the region.
struct Butterfly {
  int inner_b = -1;                 // V_B (background vertex id)
  int inner_d = -1;                 // V_D
  std::array<int, 4> tiles{};       // A, B, C, D
  std::array<int, 4> interfaces{};  // V_AB, V_BC, V_CD, V_DA on the region boundary
  double length_m = 0.0;            // of the inner meta-edge
};

// A line fitted to segments by principal component analysis (uniform density along
// the segments, as CGAL's linear_least_squares_fitting_2 with dimension 1).
struct LineFit {
  Point2 direction;              // unit
  double relative_spread = 1.0;  // orthogonal over along-line variance, 0 = perfect line
};

std::optional<LineFit> fit_line(const std::array<std::pair<Point2, Point2>, 2>& segments) {
  double total = 0.0, mx = 0.0, my = 0.0;
  for (const auto& [a, b] : segments) {
    const double length = distance(a, b);
    total += length;
    mx += length * 0.5 * (a.x + b.x);
    my += length * 0.5 * (a.y + b.y);
  }
  if (!(total > 0.0)) return std::nullopt;
  mx /= total;
  my /= total;
  // Second moment of a segment about m: L ((c - m)(c - m)^T + d d^T / 12).
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (const auto& [a, b] : segments) {
    const double length = distance(a, b);
    const double cx = 0.5 * (a.x + b.x) - mx, cy = 0.5 * (a.y + b.y) - my;
    const double dx = b.x - a.x, dy = b.y - a.y;
    sxx += length * (cx * cx + dx * dx / 12.0);
    sxy += length * (cx * cy + dx * dy / 12.0);
    syy += length * (cy * cy + dy * dy / 12.0);
  }
  const double half_trace = 0.5 * (sxx + syy);
  const double radius = std::hypot(0.5 * (sxx - syy), sxy);
  const double major = half_trace + radius, minor = half_trace - radius;
  if (!(major > 0.0)) return std::nullopt;
  const double angle = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
  return LineFit{{std::cos(angle), std::sin(angle)}, std::max(0.0, minor) / major};
}

// The four corners of the butterfly region (paper, 2.5), one per tile arc: the DP of
// section 2.4 maximising E = min over the four sides of their projection on a, a^90,
// a, a^90, for a in {u, u^90}. candidates[k] are the positions allowed for the corner in
// the arc of tile k (sides run from arc k to arc k+1 across one interface vertex).
// Returns the chosen index in each candidate list, or nullopt when every choice has a
// side of zero projection.
std::optional<std::array<int, 4>> choose_arc_corners(
    const std::array<std::vector<Point2>, 4>& candidates, const Point2& u) {
  const Point2 u90{-u.y, u.x};
  double best_energy = 0.0;
  std::optional<std::array<int, 4>> best;
  for (const Point2& a : {u, u90}) {
    const Point2 a90{-a.y, a.x};
    const std::array<Point2, 4> axis{a, a90, a, a90};
    auto side = [&](int k, const Point2& from, const Point2& to) {
      return std::abs((to.x - from.x) * axis[k].x + (to.y - from.y) * axis[k].y);
    };
    for (int first = 0; first < static_cast<int>(candidates[0].size()); ++first) {
      // value[k][j]: best min over the sides so far, ending at candidate j of arc k.
      std::array<std::vector<double>, 4> value;
      std::array<std::vector<int>, 4> from;
      value[0].assign(candidates[0].size(), -1.0);
      value[0][first] = std::numeric_limits<double>::infinity();
      for (int k = 1; k < 4; ++k) {
        value[k].assign(candidates[k].size(), -1.0);
        from[k].assign(candidates[k].size(), -1);
        for (std::size_t j = 0; j < candidates[k].size(); ++j)
          for (std::size_t i = 0; i < candidates[k - 1].size(); ++i) {
            if (value[k - 1][i] < 0.0) continue;
            const double v =
                std::min(value[k - 1][i], side(k - 1, candidates[k - 1][i], candidates[k][j]));
            if (v > value[k][j]) {
              value[k][j] = v;
              from[k][j] = static_cast<int>(i);
            }
          }
      }
      for (std::size_t j = 0; j < candidates[3].size(); ++j) {
        if (value[3][j] < 0.0) continue;
        const double energy =
            std::min(value[3][j], side(3, candidates[3][j], candidates[0][first]));
        if (energy > best_energy) {
          best_energy = energy;
          std::array<int, 4> choice{};
          choice[3] = static_cast<int>(j);
          for (int k = 3; k > 0; --k) choice[k - 1] = k - 1 == 0 ? first : from[k][choice[k]];
          best = choice;
        }
      }
    }
  }
  return best;
}

int local_corner(const std::array<int, 3>& t, int v) {
  return t[0] == v ? 0 : t[1] == v ? 1 : 2;
}

std::uint64_t edge_key(int a, int b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) |
         static_cast<std::uint32_t>(std::max(a, b));
}

// The boundary of a set of triangles, when the set is a topological disk.
struct DiskBoundary {
  std::vector<int> vertices;        // background ids, counter-clockwise (region on the left)
  std::vector<int> inner_triangle;  // [i]: the region triangle along vertices[i] -> [i+1]
};

class ButterflyRemover {
 public:
  ButterflyRemover(const BackgroundMesh& mesh, const SizingField& size, Tiling& tiling,
                   const ButterflyParams& params)
      : mesh_(mesh),
        size_(size),
        tiling_(tiling),
        params_(params),
        fans_(vertex_triangles(mesh)),
        boundary_meta_(mesh.points.size(), 0),
        vertex_scratch_(mesh.points.size(), -1),
        local_of_(mesh.points.size(), -1),
        region_of_(mesh.triangles.size(), -1),
        face_mark_(mesh.triangles.size(), 0),
        vertex_mark_(mesh.points.size(), 0) {}

  ButterflyStats run(const Progress& progress);

 private:
  bool on_domain_boundary(int v) const { return mesh_.boundary_chain_of_vertex[v] >= 0; }
  const int* fan_begin(int v) const { return fans_.triangles.data() + fans_.offset[v]; }
  const int* fan_end(int v) const { return fans_.triangles.data() + fans_.offset[v + 1]; }
  int fan_size(int v) const { return fans_.offset[v + 1] - fans_.offset[v]; }

  std::vector<int> tiles_at(int v) const;
  void append_tiles_at(int v, std::vector<int>& out) const;
  int num_tiles_at(int v) const;
  bool is_meta(int v) const;
  std::vector<Spoke> spokes(int v) const;
  bool trace(int from, const Spoke& spoke, std::vector<int>& path) const;
  double path_length(const std::vector<int>& path) const;
  double size_at_midpoint(const std::vector<int>& path) const;
  std::optional<Butterfly> identify(int a, int b) const;
  std::vector<int> collect_region(const Butterfly& b) const;
  std::uint64_t signature(const std::vector<int>& region) const;
  std::optional<DiskBoundary> disk_boundary(const std::vector<int>& triangles,
                                            const std::function<bool(int)>& inside);
  int num_irregular(const std::vector<int>& vertices) const;
  bool reparameterize(const Butterfly& b, const std::vector<int>& region);

  const BackgroundMesh& mesh_;
  const SizingField& size_;
  Tiling& tiling_;
  const ButterflyParams& params_;
  VertexTriangles fans_;
  // Meta-vertex status of domain boundary vertices, from the last meta-graph. Such a
  // vertex is always on the boundary of a butterfly region, whose tiles around it
  // reparameterization keeps, so the status stays valid between rebuilds.
  std::vector<char> boundary_meta_;
  std::vector<int> vertex_scratch_;  // #V, -1 outside any call
  std::vector<int> local_of_;        // #V, -1 outside reparameterize
  std::vector<int> region_of_;       // #F, -1 outside reparameterize
  // Visit marks: an element is marked when its entry equals the current round.
  mutable std::vector<int> face_mark_;  // #F
  mutable std::vector<int> vertex_mark_;  // #V
  mutable int face_round_ = 0, vertex_round_ = 0;
};

std::vector<int> ButterflyRemover::tiles_at(int v) const {
  std::vector<int> tiles;
  append_tiles_at(v, tiles);
  return tiles;
}

// The tiles round v, sorted, appended to `out`.
void ButterflyRemover::append_tiles_at(int v, std::vector<int>& out) const {
  const std::size_t begin = out.size();
  for (const int* f = fan_begin(v); f != fan_end(v); ++f) out.push_back(tiling_.label[*f]);
  std::sort(out.begin() + begin, out.end());
  out.erase(std::unique(out.begin() + begin, out.end()), out.end());
}

// How many tiles meet at v, without listing them (the fans hold a few triangles).
int ButterflyRemover::num_tiles_at(int v) const {
  int count = 0;
  for (const int* f = fan_begin(v); f != fan_end(v); ++f) {
    const int label = tiling_.label[*f];
    const int* earlier = fan_begin(v);
    while (earlier != f && tiling_.label[*earlier] != label) ++earlier;
    if (earlier == f) ++count;
  }
  return count;
}

// Section 2.1: 3 or more tiles inside the domain; on the boundary, the meta-graph's call.
bool ButterflyRemover::is_meta(int v) const {
  if (on_domain_boundary(v)) return boundary_meta_[v] != 0;
  return num_tiles_at(v) >= 3;
}

// The background edges out of an interior vertex that separate two tiles.
std::vector<Spoke> ButterflyRemover::spokes(int v) const {
  std::vector<Spoke> out;
  for (const int* it = fan_begin(v); it != fan_end(v); ++it) {
    const int f = *it;
    const auto& t = mesh_.triangles[f];
    const int i = local_corner(t, v);
    // f is on the left of v -> t[i+1]; the triangle across that edge is on its right.
    const int across = mesh_.neighbours[f][(i + 2) % 3];
    const int right = across >= 0 ? tiling_.label[across] : -1;
    if (right != tiling_.label[f]) out.push_back({t[(i + 1) % 3], tiling_.label[f], right});
  }
  std::sort(out.begin(), out.end(), [](const Spoke& a, const Spoke& b) { return a.to < b.to; });
  return out;
}

// Follows the meta-edge that starts with `spoke` (same tiles on the same sides) up to the
// next meta-vertex. Fails on a vertex where the tiles do not continue unambiguously.
bool ButterflyRemover::trace(int from, const Spoke& spoke, std::vector<int>& path) const {
  path.assign({from, spoke.to});
  const std::size_t max_length = mesh_.points.size();
  while (!is_meta(path.back())) {
    const int current = path.back(), previous = path[path.size() - 2];
    if (on_domain_boundary(current) || path.size() > max_length) return false;
    int next = -1;
    for (const Spoke& s : spokes(current)) {
      if (s.to == previous || s.left != spoke.left || s.right != spoke.right) continue;
      if (next >= 0) return false;
      next = s.to;
    }
    if (next < 0) return false;
    path.push_back(next);
  }
  return true;
}

double ButterflyRemover::path_length(const std::vector<int>& path) const {
  double length = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i)
    length += distance(mesh_.points[path[i - 1]], mesh_.points[path[i]]);
  return length;
}

// h at the arc-length midpoint of a path (linear along the background edge).
double ButterflyRemover::size_at_midpoint(const std::vector<int>& path) const {
  const double half = 0.5 * path_length(path);
  double walked = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) {
    const int a = path[i - 1], b = path[i];
    const double length = distance(mesh_.points[a], mesh_.points[b]);
    if (walked + length >= half && length > 0.0) {
      const double t = (half - walked) / length;
      return (1.0 - t) * size_.size_m[a] + t * size_.size_m[b];
    }
    walked += length;
  }
  return size_.size_m[path.back()];
}

// The butterfly around the inner meta-edge between interior vertices a and b, read from
// the current labels: both are meta-vertices of exactly three tiles, each tile in one
// wedge around them, joined by a meta-edge shorter than max_length_ratio * h, and the
// four tiles are distinct.
std::optional<Butterfly> ButterflyRemover::identify(int a, int b) const {
  if (a == b || on_domain_boundary(a) || on_domain_boundary(b)) return std::nullopt;
  if (num_tiles_at(a) != 3 || num_tiles_at(b) != 3) return std::nullopt;
  const std::vector<Spoke> spokes_a = spokes(a), spokes_b = spokes(b);
  if (spokes_a.size() != 3 || spokes_b.size() != 3) return std::nullopt;  // a split wedge

  std::vector<int> path, inner;
  const Spoke* inner_spoke = nullptr;
  for (const Spoke& s : spokes_a) {
    if (!trace(a, s, path) || path.back() != b) continue;
    if (inner_spoke) return std::nullopt;  // two meta-edges between a and b
    inner_spoke = &s;
    inner = path;
  }
  if (!inner_spoke) return std::nullopt;
  const double length = path_length(inner);
  if (!(length < params_.max_length_ratio * size_at_midpoint(inner))) return std::nullopt;

  Butterfly bf;
  bf.inner_b = a;
  bf.inner_d = b;
  bf.length_m = length;
  const int tile_a = inner_spoke->left, tile_c = inner_spoke->right;
  auto third = [&](int v) {
    for (int t : tiles_at(v))
      if (t != tile_a && t != tile_c) return t;
    return -1;
  };
  const std::vector<int> at_b = tiles_at(b);
  if (!std::binary_search(at_b.begin(), at_b.end(), tile_a) ||
      !std::binary_search(at_b.begin(), at_b.end(), tile_c))
    return std::nullopt;
  const int tile_b = third(a), tile_d = third(b);
  if (tile_b < 0 || tile_d < 0 || tile_b == tile_d) return std::nullopt;
  bf.tiles = {tile_a, tile_b, tile_c, tile_d};

  // The four other meta-edges out of V_B and V_D end at the interface meta-vertices.
  auto interface = [&](int from, const std::vector<Spoke>& out, int t0, int t1) {
    for (const Spoke& s : out)
      if ((s.left == t0 && s.right == t1) || (s.left == t1 && s.right == t0))
        return trace(from, s, path) ? path.back() : -1;
    return -1;
  };
  bf.interfaces = {interface(a, spokes_a, tile_a, tile_b), interface(a, spokes_a, tile_b, tile_c),
                   interface(b, spokes_b, tile_c, tile_d), interface(b, spokes_b, tile_d, tile_a)};
  for (int i = 0; i < 4; ++i) {
    const int v = bf.interfaces[i];
    if (v < 0 || v == a || v == b) return std::nullopt;
    for (int j = 0; j < i; ++j)
      if (bf.interfaces[j] == v) return std::nullopt;
  }
  return bf;
}

// The triangles of the four tiles, flooded from the inner meta-vertices.
std::vector<int> ButterflyRemover::collect_region(const Butterfly& b) const {
  auto in_butterfly = [&](int f) {
    const int label = tiling_.label[f];
    return std::find(b.tiles.begin(), b.tiles.end(), label) != b.tiles.end();
  };
  std::vector<int> region;
  const int round = ++face_round_;
  auto add = [&](int f) {
    if (face_mark_[f] == round) return;
    face_mark_[f] = round;
    region.push_back(f);
  };
  for (int v : {b.inner_b, b.inner_d})
    for (const int* f = fan_begin(v); f != fan_end(v); ++f) add(*f);
  for (std::size_t k = 0; k < region.size(); ++k)
    for (int g : mesh_.neighbours[region[k]])
      if (g >= 0 && in_butterfly(g)) add(g);
  std::sort(region.begin(), region.end());
  return region;
}

// FNV-1a of the region's triangles and labels: a failed butterfly is retried only when
// its region changed since.
std::uint64_t ButterflyRemover::signature(const std::vector<int>& region) const {
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&h](std::uint64_t x) {
    for (int k = 0; k < 8; ++k) {
      h ^= (x >> (8 * k)) & 0xff;
      h *= 1099511628211ull;
    }
  };
  for (int f : region) {
    mix(static_cast<std::uint64_t>(f));
    mix(static_cast<std::uint64_t>(tiling_.label[f]));
  }
  return h;
}

// The boundary loop of `triangles` (all of which satisfy `inside`) when they form a
// topological disk: edge-connected, one boundary edge out of every boundary vertex (no
// pinch), a single loop and V - E + F = 1 (DESIGN.md, Tiling).
std::optional<DiskBoundary> ButterflyRemover::disk_boundary(
    const std::vector<int>& triangles, const std::function<bool(int)>& inside) {
  std::vector<int> touched;
  std::vector<std::array<int, 3>> edges;  // from, to, inner triangle
  bool manifold = true;
  for (int f : triangles) {
    const auto& t = mesh_.triangles[f];
    for (int i = 0; i < 3; ++i) {
      const int g = mesh_.neighbours[f][i];
      if (g >= 0 && inside(g)) continue;
      const int from = t[(i + 1) % 3], to = t[(i + 2) % 3];
      if (vertex_scratch_[from] >= 0) manifold = false;
      if (vertex_scratch_[from] < 0) touched.push_back(from);
      vertex_scratch_[from] = static_cast<int>(edges.size());
      edges.push_back({from, to, f});
    }
  }
  std::optional<DiskBoundary> result;
  if (manifold && !edges.empty()) {
    DiskBoundary loop;
    int e = 0;
    do {
      loop.vertices.push_back(edges[e][0]);
      loop.inner_triangle.push_back(edges[e][2]);
      e = vertex_scratch_[edges[e][1]];
    } while (e > 0 && loop.vertices.size() <= edges.size());
    if (e == 0 && loop.vertices.size() == edges.size()) result = std::move(loop);
  }
  for (int v : touched) vertex_scratch_[v] = -1;
  if (!result) return std::nullopt;

  // Edge-connected, and Euler characteristic 1.
  const int round = ++face_round_;
  std::vector<int> stack{triangles.front()};
  face_mark_[triangles.front()] = round;
  std::size_t reached = 1;
  while (!stack.empty()) {
    const int f = stack.back();
    stack.pop_back();
    for (int g : mesh_.neighbours[f])
      if (g >= 0 && face_mark_[g] != round && inside(g)) {
        face_mark_[g] = round;
        ++reached;
        stack.push_back(g);
      }
  }
  if (reached != triangles.size()) return std::nullopt;
  const int vround = ++vertex_round_;
  long num_vertices = 0;
  for (int f : triangles)
    for (int v : mesh_.triangles[f])
      if (vertex_mark_[v] != vround) vertex_mark_[v] = vround, ++num_vertices;
  const long num_faces = static_cast<long>(triangles.size());
  const long num_edges = (3 * num_faces + static_cast<long>(edges.size())) / 2;
  if (num_vertices - num_edges + num_faces != 1) return std::nullopt;
  return result;
}

// Interior meta-vertices among `vertices` whose number of tiles is not 4.
int ButterflyRemover::num_irregular(const std::vector<int>& vertices) const {
  int count = 0;
  for (int v : vertices) {
    if (on_domain_boundary(v)) continue;
    const int n = num_tiles_at(v);
    if (n >= 3 && n != 4) ++count;
  }
  return count;
}

// Section 2.5 on one butterfly: checks, corners, mean value map onto the unit square,
// centre, four edge paths, relabelling. Leaves the labels unchanged and returns false
// when any step fails.
bool ButterflyRemover::reparameterize(const Butterfly& b, const std::vector<int>& region) {
  const std::array<int, 4>& tiles = b.tiles;
  const std::array<int, 4>& interfaces = b.interfaces;

  // Region: a disk whose boundary meets V_AB, V_BC, V_CD, V_DA in this order, with the
  // arc between consecutive interfaces owned by one tile (A between V_DA and V_AB...).
  for (std::size_t k = 0; k < region.size(); ++k) region_of_[region[k]] = static_cast<int>(k);
  std::vector<int> local_vertices;
  auto cleanup = [&]() {
    for (int f : region) region_of_[f] = -1;
    for (int v : local_vertices) local_of_[v] = -1;
  };
  auto fail = [&]() {
    cleanup();
    return false;
  };
  const std::optional<DiskBoundary> boundary =
      disk_boundary(region, [&](int f) { return region_of_[f] >= 0; });
  if (!boundary) return fail();
  const std::vector<int>& loop = boundary->vertices;
  const int loop_size = static_cast<int>(loop.size());

  for (int f : region)
    for (int v : mesh_.triangles[f])
      if (local_of_[v] < 0) {
        local_of_[v] = static_cast<int>(local_vertices.size());
        local_vertices.push_back(v);
      }
  const int n = static_cast<int>(local_vertices.size());
  std::vector<char> on_loop(n, 0);
  std::vector<int> loop_index(n, -1);
  for (int i = 0; i < loop_size; ++i) {
    on_loop[local_of_[loop[i]]] = 1;
    loop_index[local_of_[loop[i]]] = i;
  }
  std::array<int, 4> at{};  // loop index of each interface
  for (int k = 0; k < 4; ++k) {
    at[k] = loop_index[local_of_[interfaces[k]]];
    if (at[k] < 0) return fail();
  }
  auto forward = [&](int from, int to) {
    return ((to - from) % loop_size + loop_size) % loop_size;
  };
  if (!(forward(at[0], at[1]) < forward(at[0], at[2]) &&
        forward(at[0], at[2]) < forward(at[0], at[3])))
    return fail();
  // arc_start[k]: loop index of the interface where the arc of tile k begins.
  std::array<int, 4> arc_start{at[3], at[0], at[1], at[2]};
  std::array<int, 4> arc_size{};
  for (int k = 0; k < 4; ++k) {
    arc_size[k] = forward(arc_start[k], at[k]);
    for (int j = 0; j < arc_size[k]; ++j)
      if (tiling_.label[boundary->inner_triangle[(arc_start[k] + j) % loop_size]] != tiles[k])
        return fail();
  }
  // No interior meta-vertex but V_B and V_D.
  for (int i = 0; i < n; ++i) {
    const int v = local_vertices[i];
    if (!on_loop[i] && v != b.inner_b && v != b.inner_d && is_meta(v)) return fail();
  }

  // Meta-vertices strictly inside each arc. Only the counts of A and C change: each loses
  // V_B and V_D and gains the centre. Removing the butterfly trades two irregular
  // meta-vertices for this; when A and C were both quadrangles it would only turn them
  // into triangles, so the butterfly is kept.
  std::array<std::vector<int>, 4> arc_meta;
  for (int k = 0; k < 4; ++k)
    for (int j = 1; j < arc_size[k]; ++j) {
      const int index = (arc_start[k] + j) % loop_size;
      if (is_meta(loop[index])) arc_meta[k].push_back(index);
    }
  auto not_quad = [](std::size_t num_meta) { return num_meta != 4 ? 1 : 0; };
  const int non_quads_before = not_quad(arc_meta[0].size() + 4) + not_quad(arc_meta[2].size() + 4);
  const int non_quads_after = not_quad(arc_meta[0].size() + 3) + not_quad(arc_meta[2].size() + 3);
  if (non_quads_after - non_quads_before >= 2) return fail();

  // Reference direction: PCA lines through ([V_AB, V_B], [V_CD, V_D]) and
  // ([V_DA, V_D], [V_BC, V_B]); the one with the smaller relative orthogonal spread wins.
  const auto& p = mesh_.points;
  const Point2 vb = p[b.inner_b], vd = p[b.inner_d];
  const std::optional<LineFit> line_1 =
      fit_line({{{p[interfaces[0]], vb}, {p[interfaces[2]], vd}}});
  const std::optional<LineFit> line_2 =
      fit_line({{{p[interfaces[3]], vd}, {p[interfaces[1]], vb}}});
  if (!line_1 && !line_2) return fail();
  const LineFit& frame =
      !line_2 || (line_1 && line_1->relative_spread <= line_2->relative_spread) ? *line_1 : *line_2;

  // Corners: one per arc, among its meta-vertices; an arc without any (a triangle tile)
  // takes any of its vertices, and a single-edge arc its two interfaces.
  std::array<std::vector<int>, 4> corner_candidates;
  std::array<std::vector<Point2>, 4> corner_points;
  for (int k = 0; k < 4; ++k) {
    std::vector<int>& c = corner_candidates[k];
    c = arc_meta[k];
    if (c.empty())
      for (int j = 1; j < arc_size[k]; ++j) c.push_back((arc_start[k] + j) % loop_size);
    if (c.empty()) c = {arc_start[k], at[k]};
    for (int index : c) corner_points[k].push_back(p[loop[index]]);
  }
  const std::optional<std::array<int, 4>> choice =
      choose_arc_corners(corner_points, frame.direction);
  if (!choice) return fail();
  std::array<int, 4> corner{};
  for (int k = 0; k < 4; ++k) corner[k] = corner_candidates[k][(*choice)[k]];

  // Boundary onto the unit square by arc length between the corners (counter-clockwise,
  // corner of arc A at the origin).
  std::vector<Point2> position(n), uv(n);
  for (int i = 0; i < n; ++i) position[i] = p[local_vertices[i]];
  static const std::array<Point2, 4> kSquare{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
  for (int k = 0; k < 4; ++k) {
    const int steps = forward(corner[k], corner[(k + 1) % 4]);
    if (steps == 0) return fail();
    std::vector<double> walked(steps + 1, 0.0);
    for (int j = 1; j <= steps; ++j)
      walked[j] = walked[j - 1] + distance(p[loop[(corner[k] + j - 1) % loop_size]],
                                           p[loop[(corner[k] + j) % loop_size]]);
    const Point2 &from = kSquare[k], &to = kSquare[(k + 1) % 4];
    for (int j = 0; j < steps; ++j) {
      const double t = walked[j] / walked[steps];
      uv[local_of_[loop[(corner[k] + j) % loop_size]]] = {from.x + t * (to.x - from.x),
                                                          from.y + t * (to.y - from.y)};
    }
  }
  std::vector<std::array<int, 3>> local_triangles;
  local_triangles.reserve(region.size());
  for (int f : region) {
    const auto& t = mesh_.triangles[f];
    local_triangles.push_back({local_of_[t[0]], local_of_[t[1]], local_of_[t[2]]});
  }
  if (!mean_value_parameterization(position, local_triangles, on_loop, uv)) return fail();

  // phi(v*): where the segments phi(V_AB) phi(V_CD) and phi(V_BC) phi(V_DA) cross.
  std::array<Point2, 4> target_uv;
  for (int k = 0; k < 4; ++k) target_uv[k] = uv[local_of_[interfaces[k]]];
  const Point2 r{target_uv[2].x - target_uv[0].x, target_uv[2].y - target_uv[0].y};
  const Point2 s{target_uv[3].x - target_uv[1].x, target_uv[3].y - target_uv[1].y};
  const double denominator = r.x * s.y - r.y * s.x;
  if (std::abs(denominator) < 1e-12) return fail();
  const double t =
      ((target_uv[1].x - target_uv[0].x) * s.y - (target_uv[1].y - target_uv[0].y) * s.x) /
      denominator;
  const Point2 centre_uv{target_uv[0].x + t * r.x, target_uv[0].y + t * r.y};

  // Centre candidates: interior vertices with at least 4 incident edges, nearest first.
  std::vector<std::pair<double, int>> centres;
  for (int i = 0; i < n; ++i)
    if (!on_loop[i] && fan_size(local_vertices[i]) >= 4)
      centres.emplace_back(distance(uv[i], centre_uv), i);
  std::sort(centres.begin(), centres.end());
  if (centres.size() > static_cast<std::size_t>(kMaxCentreCandidates))
    centres.resize(kMaxCentreCandidates);

  // Local edge graph for the paths, lengths in parameter space.
  std::vector<std::vector<int>> adjacent(n);
  for (const auto& t : local_triangles)
    for (int k = 0; k < 3; ++k) {
      adjacent[t[k]].push_back(t[(k + 1) % 3]);
      adjacent[t[(k + 1) % 3]].push_back(t[k]);
    }
  std::vector<double> edge_lengths;
  for (int v = 0; v < n; ++v) {
    auto& list = adjacent[v];
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    for (int w : list)
      if (v < w) edge_lengths.push_back(distance(uv[v], uv[w]));
  }
  std::nth_element(edge_lengths.begin(), edge_lengths.begin() + edge_lengths.size() / 2,
                   edge_lengths.end());
  const double typical_edge = std::max(edge_lengths[edge_lengths.size() / 2], 1e-12);

  // The path from the centre to an interface follows the segment between their images:
  // on a triangulation many edge paths are about as short (any order of steps along two
  // edge directions), and the plain shortest one can bulge by a third of its length. Each
  // edge costs its length times 1 + (distance of its midpoint to the segment, in typical
  // edge lengths)^2.
  auto trace_path = [&](int source, int target, const std::vector<char>& blocked,
                        std::vector<int>& path) {
    const Point2 a = uv[source], b = uv[target];
    const double abx = b.x - a.x, aby = b.y - a.y, ab2 = abx * abx + aby * aby;
    auto off_segment = [&](const Point2& x) {
      double t = ab2 > 0.0 ? ((x.x - a.x) * abx + (x.y - a.y) * aby) / ab2 : 0.0;
      t = std::max(0.0, std::min(1.0, t));
      return distance(x, {a.x + t * abx, a.y + t * aby}) / typical_edge;
    };
    std::vector<double> best(n, std::numeric_limits<double>::infinity());
    std::vector<int> parent(n, -1);
    using Entry = std::pair<double, int>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
    best[source] = 0.0;
    queue.emplace(0.0, source);
    while (!queue.empty()) {
      const auto [d, v] = queue.top();
      queue.pop();
      if (d > best[v]) continue;
      if (v == target) break;
      for (int w : adjacent[v]) {
        if (w != target && blocked[w]) continue;
        const double off = off_segment({0.5 * (uv[v].x + uv[w].x), 0.5 * (uv[v].y + uv[w].y)});
        const double candidate = d + distance(uv[v], uv[w]) * (1.0 + off * off);
        if (candidate < best[w]) {
          best[w] = candidate;
          parent[w] = v;
          queue.emplace(candidate, w);
        }
      }
    }
    if (parent[target] < 0) return false;
    path.clear();
    for (int v = target; v >= 0; v = parent[v]) path.push_back(v);
    std::reverse(path.begin(), path.end());
    return true;
  };

  // Labels before, to restore and to compare the tiles around the boundary vertices.
  std::vector<int> old_label(region.size());
  for (std::size_t k = 0; k < region.size(); ++k) old_label[k] = tiling_.label[region[k]];
  // The tiles round each loop vertex, in one list: loop vertex i's from
  // loop_tiles_begin[i] to loop_tiles_begin[i + 1].
  std::vector<int> loop_tiles_before, loop_tiles_begin(loop_size + 1, 0), tiles_now;
  for (int i = 0; i < loop_size; ++i) {
    append_tiles_at(loop[i], loop_tiles_before);
    loop_tiles_begin[i + 1] = static_cast<int>(loop_tiles_before.size());
  }
  auto same_tiles_as_before = [&](int i) {
    tiles_now.clear();
    append_tiles_at(loop[i], tiles_now);
    return std::equal(tiles_now.begin(), tiles_now.end(),
                      loop_tiles_before.begin() + loop_tiles_begin[i],
                      loop_tiles_before.begin() + loop_tiles_begin[i + 1]);
  };
  const int irregular_before = num_irregular(local_vertices);
  auto restore = [&]() {
    for (std::size_t k = 0; k < region.size(); ++k) tiling_.label[region[k]] = old_label[k];
  };

  for (const auto& entry : centres) {
    const int centre = entry.second;
    // Four edge paths, the shortest (in parameter space) first, meeting only at the
    // centre and touching the region boundary only at their own interface.
    std::array<int, 4> order{0, 1, 2, 3};
    std::stable_sort(order.begin(), order.end(), [&](int x, int y) {
      return distance(uv[centre], target_uv[x]) < distance(uv[centre], target_uv[y]);
    });
    std::vector<char> blocked = on_loop;
    blocked[centre] = 1;
    std::unordered_set<std::uint64_t> cut;
    bool traced = true;
    std::vector<int> path;
    for (int k : order) {
      if (!trace_path(centre, local_of_[interfaces[k]], blocked, path)) {
        traced = false;
        break;
      }
      for (std::size_t j = 0; j + 1 < path.size(); ++j) {
        blocked[path[j]] = 1;
        cut.insert(edge_key(path[j], path[j + 1]));
      }
    }
    if (!traced) continue;

    // Flood the four parts from their boundary arcs; each takes the arc's tile.
    std::vector<int> part(region.size(), -1);
    bool separated = true;
    for (int k = 0; k < 4 && separated; ++k) {
      std::vector<int> stack;
      for (int j = 0; j < arc_size[k]; ++j) {
        const int f = region_of_[boundary->inner_triangle[(arc_start[k] + j) % loop_size]];
        if (part[f] >= 0 && part[f] != k) separated = false;
        if (part[f] < 0) {
          part[f] = k;
          stack.push_back(f);
        }
      }
      while (!stack.empty() && separated) {
        const int f = stack.back();
        stack.pop_back();
        const auto& t = mesh_.triangles[region[f]];
        for (int i = 0; i < 3; ++i) {
          const int g = mesh_.neighbours[region[f]][i];
          if (g < 0 || region_of_[g] < 0) continue;
          if (cut.count(edge_key(local_of_[t[(i + 1) % 3]], local_of_[t[(i + 2) % 3]]))) continue;
          const int h = region_of_[g];
          if (part[h] >= 0 && part[h] != k) {
            separated = false;
            break;
          }
          if (part[h] < 0) {
            part[h] = k;
            stack.push_back(h);
          }
        }
      }
    }
    if (!separated || std::count(part.begin(), part.end(), -1) > 0) continue;

    for (std::size_t k = 0; k < region.size(); ++k) tiling_.label[region[k]] = tiles[part[k]];
    const int centre_vertex = local_vertices[centre];
    bool valid = num_tiles_at(centre_vertex) == 4;
    // Every new tile a disk; the tiles around every boundary vertex unchanged (the
    // interfaces and the rest of the meta-graph stay); no meta-vertex inside but v*.
    for (int k = 0; k < 4 && valid; ++k) {
      std::vector<int> tile;
      for (std::size_t j = 0; j < region.size(); ++j)
        if (part[j] == k) tile.push_back(region[j]);
      valid = !tile.empty() && disk_boundary(tile, [&](int f) {
                                 return region_of_[f] >= 0 && part[region_of_[f]] == k;
                               }).has_value();
    }
    for (int i = 0; i < loop_size && valid; ++i) valid = same_tiles_as_before(i);
    for (int i = 0; i < n && valid; ++i)
      if (!on_loop[i] && i != centre && is_meta(local_vertices[i])) valid = false;
    // Never more irregular meta-vertices than before.
    if (valid) valid = num_irregular(local_vertices) <= irregular_before;
    if (!valid) {
      restore();
      continue;
    }

    // A generator now outside its tile moves to the tile's triangle nearest its
    // centroid, as relocation does (2.3).
    for (int k = 0; k < 4; ++k) {
      const int tile = tiles[k];
      if (tile >= static_cast<int>(tiling_.generator.size())) continue;
      const int generator = tiling_.generator[tile];
      if (generator < 0 || tiling_.label[generator] == tile) continue;
      double weight = 0.0, cx = 0.0, cy = 0.0;
      std::vector<std::pair<int, Point2>> centroids;
      for (std::size_t j = 0; j < region.size(); ++j) {
        if (part[j] != k) continue;
        const auto& tr = mesh_.triangles[region[j]];
        const Point2 &p0 = p[tr[0]], &p1 = p[tr[1]], &p2 = p[tr[2]];
        const double area =
            0.5 * std::abs((p1.x - p0.x) * (p2.y - p0.y) - (p1.y - p0.y) * (p2.x - p0.x));
        const double w = area;  // rho = 1, as relocation (tile_geometry.h)
        const Point2 centroid{(p0.x + p1.x + p2.x) / 3.0, (p0.y + p1.y + p2.y) / 3.0};
        weight += w;
        cx += w * centroid.x;
        cy += w * centroid.y;
        centroids.emplace_back(region[j], centroid);
      }
      const Point2 mean{cx / weight, cy / weight};
      double nearest = std::numeric_limits<double>::infinity();
      for (const auto& [f, centroid] : centroids)
        if (distance(centroid, mean) < nearest) {
          nearest = distance(centroid, mean);
          tiling_.generator[tile] = f;
        }
    }
    cleanup();
    return true;
  }
  return fail();
}

ButterflyStats ButterflyRemover::run(const Progress& progress) {
  std::set<std::pair<int, int>> found;
  std::map<std::pair<int, int>, std::uint64_t> failed;  // signature of the region when it failed
  int removed = 0;
  for (int round = 0; round < kMaxRounds; ++round) {
    // Candidates from the meta-graph; later rounds catch what earlier removals changed.
    const MetaGraph graph = build_meta_graph(mesh_, tiling_, params_.graph);
    for (std::size_t v = 0; v < mesh_.points.size(); ++v)
      if (on_domain_boundary(static_cast<int>(v)))
        boundary_meta_[v] = graph.meta_index[v] >= 0 ? 1 : 0;
    using Entry = std::tuple<double, int, int>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
    for (const MetaEdge& e : graph.edges) {
      if (e.on_boundary() || e.path.size() < 2) continue;
      const int a = e.path.front(), b = e.path.back();
      const int ma = graph.meta_index[a], mb = graph.meta_index[b];
      if (a == b || ma < 0 || mb < 0 || graph.vertex_on_boundary[ma] ||
          graph.vertex_on_boundary[mb] || graph.vertex_num_tiles[ma] != 3 ||
          graph.vertex_num_tiles[mb] != 3)
        continue;
      const double length = path_length(e.path);
      if (length < params_.max_length_ratio * size_at_midpoint(e.path))
        queue.emplace(length, std::min(a, b), std::max(a, b));
    }

    // Increasing length; an entry is re-validated against the current labels when popped
    // (a removal changes the tiles of overlapping butterflies) and re-queued if longer.
    // The first round does most of the work: it takes the progress to 0.85.
    int removed_in_round = 0;
    const double queued = static_cast<double>(queue.size());
    progress.report(kStage, round == 0 ? 0.0 : 0.85 + 0.15 * round / kMaxRounds);
    for (long popped = 1; !queue.empty(); ++popped) {
      if (round == 0 && popped % 256 == 0)
        progress.report(kStage, 0.85 * std::min(1.0, popped / queued));
      const auto [length, a, b] = queue.top();
      queue.pop();
      const std::optional<Butterfly> butterfly = identify(a, b);
      if (!butterfly) continue;
      if (butterfly->length_m > length * (1.0 + 1e-12)) {
        queue.emplace(butterfly->length_m, a, b);
        continue;
      }
      found.insert({a, b});
      const std::vector<int> region = collect_region(*butterfly);
      const std::uint64_t sig = signature(region);
      const auto it = failed.find({a, b});
      if (it != failed.end() && it->second == sig) continue;
      if (reparameterize(*butterfly, region)) {
        ++removed_in_round;
        failed.erase({a, b});
      } else {
        failed[{a, b}] = sig;
      }
    }
    removed += removed_in_round;
    if (removed_in_round == 0) break;
  }
  ButterflyStats stats;
  stats.found = static_cast<int>(found.size());
  stats.removed = removed;
  return stats;
}

}  // namespace

ButterflyStats remove_butterflies(const BackgroundMesh& mesh, const SizingField& size,
                                  Tiling& tiling, const ButterflyParams& params,
                                  const Progress& progress) {
  ButterflyRemover remover(mesh, size, tiling, params);
  return remover.run(progress);
}

}  // namespace isoquad
