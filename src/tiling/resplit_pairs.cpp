#include "tiling/resplit_pairs.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <map>
#include <optional>
#include <queue>
#include <utility>
#include <vector>

#include "core/geometry.h"
#include "tiling/tile_boundary.h"

namespace isoquad {

namespace {

double triangle_area(const BackgroundMesh& mesh, int f) {
  const auto& t = mesh.triangles[f];
  const Point2 &a = mesh.points[t[0]], &b = mesh.points[t[1]], &c = mesh.points[t[2]];
  return std::abs(signed_area(a, b, c));
}

// The largest deviation from 90 degrees of the corners of the quadrilateral a b c d
// (counter-clockwise), or 180 when a corner turns the wrong way.
double corner_deviation_deg(const std::array<Point2, 4>& q) {
  double worst = 0.0;
  for (int i = 0; i < 4; ++i) {
    const Point2 &p = q[(i + 3) % 4], &c = q[i], &n = q[(i + 1) % 4];
    const double ux = p.x - c.x, uy = p.y - c.y, vx = n.x - c.x, vy = n.y - c.y;
    const double cross = vx * uy - vy * ux;  // > 0: convex corner of a CCW polygon
    if (!(cross > 0.0)) return 180.0;
    const double angle = std::atan2(cross, ux * vx + uy * vy) * 180.0 / M_PI;
    worst = std::max(worst, std::abs(angle - 90.0));
  }
  return worst;
}

// Whether every corner of the polygon (counter-clockwise) has an interior angle between
// 10 and 200 degrees: the tile left beside the quadrangle is not folded, though a corner
// may be flat (a T-junction).
bool corners_open(const std::vector<Point2>& poly) {
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Point2 &p = poly[(i + n - 1) % n], &c = poly[i], &nx = poly[(i + 1) % n];
    const double ux = nx.x - c.x, uy = nx.y - c.y, vx = p.x - c.x, vy = p.y - c.y;
    double a = std::atan2(ux * vy - uy * vx, ux * vx + uy * vy) * 180.0 / M_PI;
    if (a < 0.0) a += 360.0;
    if (a < 10.0 || a > 200.0) return false;
  }
  return true;
}

// Convexity of the quadrilateral a b c d (counter-clockwise): the smallest sine of its
// four turning angles, negative when a corner turns the wrong way.
double convexity(const Point2& a, const Point2& b, const Point2& c, const Point2& d) {
  const std::array<Point2, 4> q{a, b, c, d};
  double worst = 1.0;
  for (int i = 0; i < 4; ++i) {
    const Point2 &p = q[(i + 3) % 4], &o = q[i], &n = q[(i + 1) % 4];
    const double ux = o.x - p.x, uy = o.y - p.y, vx = n.x - o.x, vy = n.y - o.y;
    const double lu = std::hypot(ux, uy), lv = std::hypot(vx, vy);
    if (!(lu > 0 && lv > 0)) return -1.0;
    worst = std::min(worst, (ux * vy - uy * vx) / (lu * lv));
  }
  return worst;
}

// The point at half the arc length of a polyline.
Point2 arc_midpoint(const std::vector<Point2>& line) {
  double left = 0.5 * polyline_length(line);
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    const double l = distance(line[i], line[i + 1]);
    if (l >= left && l > 0) {
      const double t = left / l;
      return {line[i].x + t * (line[i + 1].x - line[i].x), line[i].y + t * (line[i + 1].y - line[i].y)};
    }
    left -= l;
  }
  return line.back();
}

// The worst convexity of the quads that barycentric subdivision would make of a tile
// with the given sides (polylines from corner to corner, counter-clockwise, each side
// starting where the previous one ends): corner, midpoint of its outgoing side, area
// centroid, midpoint of its incoming side.
double subdivision_convexity(const std::vector<std::vector<Point2>>& sides) {
  double area = 0.0, cx = 0.0, cy = 0.0;
  for (const auto& side : sides)
    for (std::size_t i = 0; i + 1 < side.size(); ++i) {
      const Point2 &a = side[i], &b = side[i + 1];
      const double w = a.x * b.y - b.x * a.y;
      area += w;
      cx += (a.x + b.x) * w;
      cy += (a.y + b.y) * w;
    }
  if (!(area > 0)) return -1.0;
  const Point2 centre{cx / (3.0 * area), cy / (3.0 * area)};
  double worst = 1.0;
  const std::size_t k = sides.size();
  for (std::size_t i = 0; i < k; ++i) {
    const std::vector<Point2>& in = sides[(i + k - 1) % k];
    const std::vector<Point2>& out = sides[i];
    worst = std::min(worst, convexity(out.front(), arc_midpoint(out), centre, arc_midpoint(in)));
  }
  return worst;
}

struct Candidate {
  int gain = 0;
  int quad_gain = 0;  // quadrangle tiles gained
  double deviation = 0.0;
  int edge = -1;
  int tile_a = -1, tile_b = -1;
  std::vector<int> side_a;       // triangles of the first new tile (tile_a)
  std::vector<int> side_b;       // triangles of the second (tile_b)
  std::vector<int> path;         // the cut, background vertices from y to x
  std::vector<int> meta_locked;  // meta-vertices whose tile count or tiles change
  std::vector<int> tiles_locked; // tiles whose meta-vertex count changes
};

class Resplitter {
 public:
  Resplitter(const BackgroundMesh& mesh, Tiling& tiling, const ResplitParams& params)
      : mesh_(mesh), tiling_(tiling), params_(params), vt_(vertex_triangles(mesh)),
        on_boundary_(boundary_vertex_flags(mesh)), turning_(vertex_turning_angles_deg(mesh)) {
    is_corner_.assign(mesh.points.size(), 0);
    for (const BoundaryChain& c : mesh.chains)
      for (std::size_t k = 0; k < c.vertices.size(); ++k)
        if (c.is_corner[k]) is_corner_[c.vertices[k]] = 1;
    mark_.assign(mesh.triangles.size(), 0);
    vmark_.assign(mesh.points.size(), 0);
    dist_.assign(mesh.points.size(), 0.0);
    prev_.assign(mesh.points.size(), -1);
  }

  // One round: candidates from a fresh meta-graph, applied greedily without conflicts.
  int round(int* num_candidates) {
    graph_ = build_meta_graph(mesh_, tiling_, params_.graph);
    tiles_at_.assign(graph_.vertices.size(), {});
    for (int t = 0; t < static_cast<int>(graph_.tiles.size()); ++t)
      for (int m : graph_.tiles[t].vertices) tiles_at_[m].push_back(t);
    std::vector<Candidate> cands;
    for (int e = 0; e < static_cast<int>(graph_.edges.size()); ++e)
      if (auto c = evaluate(e)) cands.push_back(std::move(*c));
    if (num_candidates) *num_candidates = static_cast<int>(cands.size());
    std::stable_sort(cands.begin(), cands.end(), [](const Candidate& a, const Candidate& b) {
      if (a.gain != b.gain) return a.gain > b.gain;
      if (a.quad_gain != b.quad_gain) return a.quad_gain > b.quad_gain;
      return a.deviation < b.deviation;
    });
    std::vector<char> tile_used(graph_.tiles.size(), 0), meta_used(graph_.vertices.size(), 0);
    int applied = 0;
    for (const Candidate& c : cands) {
      bool free = true;
      for (int t : c.tiles_locked) free = free && !tile_used[t];
      for (int m : c.meta_locked) free = free && !meta_used[m];
      if (!free) continue;
      for (int t : c.tiles_locked) tile_used[t] = 1;
      for (int m : c.meta_locked) meta_used[m] = 1;
      apply(c);
      ++applied;
    }
    return applied;
  }

 private:
  // Irregularity of meta-vertex m (background vertex v) if it had `tiles` tiles: |d - 4|
  // inside, |d - ideal| on the boundary (ideal: the boundary angle in quarter turns); 0
  // when it would not be a meta-vertex at all.
  int vertex_cost(int m, int tiles) const {
    const int v = graph_.vertices[m];
    if (!on_boundary_[v]) return tiles >= 3 ? std::abs(tiles - 4) : 0;
    if (tiles < 2 && !(is_corner_[v] && tiles >= 1)) return 0;
    const int ideal = std::max(1, static_cast<int>(std::lround((180.0 - turning_[v]) / 90.0)));
    return std::abs(tiles - ideal);
  }
  bool stays_meta(int m, int tiles) const {
    const int v = graph_.vertices[m];
    if (!on_boundary_[v]) return tiles >= 3;
    return tiles >= 2 || (is_corner_[v] && tiles >= 1);
  }

  std::optional<Candidate> evaluate(int e) const {
    const MetaEdge& me = graph_.edges[e];
    const int L = me.tile_left, R = me.tile_right;
    if (L < 0 || R < 0 || L == R) return std::nullopt;
    const TileCycle &cl = graph_.tiles[L], &cr = graph_.tiles[R];
    const int nl = static_cast<int>(cl.edges.size()), nr = static_cast<int>(cr.edges.size());
    int i = -1, j = -1, shared = 0;
    for (int k = 0; k < nl; ++k) {
      const MetaEdge& x = graph_.edges[cl.edges[k]];
      if (x.tile_left == R || x.tile_right == R) ++shared;
      if (cl.edges[k] == e) i = k;
    }
    for (int k = 0; k < nr; ++k)
      if (cr.edges[k] == e) j = k;
    if (shared != 1 || i < 0 || j < 0) return std::nullopt;
    const int p = cl.vertices[i], q = cl.vertices[(i + 1) % nl];
    if (cr.vertices[j] != q || cr.vertices[(j + 1) % nr] != p || p == q) return std::nullopt;

    // The union's boundary, counter-clockwise: L from q round to p, then R from p to q.
    const int tp = graph_.vertex_num_tiles[p], tq = graph_.vertex_num_tiles[q];
    std::vector<int> cycle;
    for (int s = 1; s <= nl; ++s) {
      const int m = cl.vertices[(i + s) % nl];
      if ((m == p && !stays_meta(p, tp - 1)) || (m == q && !stays_meta(q, tq - 1))) continue;
      cycle.push_back(m);
    }
    for (int s = 2; s < nr; ++s) cycle.push_back(cr.vertices[(j + s) % nr]);
    const int n = static_cast<int>(cycle.size());
    if (n < params_.min_union_vertices || n > params_.max_union_vertices) return std::nullopt;
    {
      std::vector<int> sorted = cycle;
      std::sort(sorted.begin(), sorted.end());
      if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return std::nullopt;
    }

    // The union's boundary as background vertices (same walk), and where each of its
    // meta-vertices is on it.
    std::vector<int> loop;
    auto append = [&](const TileCycle& t, int k) {
      const MetaEdge& me2 = graph_.edges[t.edges[k]];
      std::vector<int> path = me2.path;
      if (!t.forward[k]) std::reverse(path.begin(), path.end());
      loop.insert(loop.end(), path.begin(), path.end() - 1);  // the end starts the next
    };
    for (int s = 1; s < nl; ++s) append(cl, (i + s) % nl);
    for (int s = 1; s < nr; ++s) append(cr, (j + s) % nr);
    std::vector<int> at(n, -1);
    for (int s = 0; s < static_cast<int>(loop.size()); ++s)
      for (int k = 0; k < n; ++k)
        if (loop[s] == graph_.vertices[cycle[k]]) {
          if (at[k] >= 0) return std::nullopt;  // the union's boundary touches itself
          at[k] = s;
        }
    for (int k = 0; k < n; ++k)
      if (at[k] < 0) return std::nullopt;
    // Corner-to-corner sides of the union's boundary, from cycle[k] to cycle[k + 1].
    auto union_side = [&](int k) {
      std::vector<Point2> side;
      const int from = at[k], to = at[(k + 1) % n], len = static_cast<int>(loop.size());
      for (int s = from;; s = (s + 1) % len) {
        side.push_back(mesh_.points[loop[s]]);
        if (s == to) break;
      }
      return side;
    };

    // Tiles that lose a meta-vertex: the others at p or q when those drop out.
    std::map<int, int> tile_delta;
    for (int m : {p, q}) {
      const int t = graph_.vertex_num_tiles[m];
      if (stays_meta(m, t - 1)) continue;
      for (int x : tiles_at_[m])
        if (x != L && x != R) --tile_delta[x];
    }
    int tiles_before = std::abs(static_cast<int>(cl.vertices.size()) - 4) +
                       std::abs(static_cast<int>(cr.vertices.size()) - 4);
    int tiles_after = std::abs(n - 2 - 4);  // the split leaves a quadrangle and an (n-2)-gon
    int quads_before = (cl.vertices.size() == 4) + (cr.vertices.size() == 4);
    int quads_after = 1 + (n == 6);
    for (const auto& [t, d] : tile_delta) {
      const int k = static_cast<int>(graph_.tiles[t].vertices.size());
      tiles_before += std::abs(k - 4);
      tiles_after += std::abs(k + d - 4);
      quads_before += k == 4;
      quads_after += k + d == 4;
      if (k + d < 3) return std::nullopt;
    }

    std::optional<Candidate> best;
    // Split k: a quadrangle on cycle[k..k+3], the rest on cycle[k+3..k+n].
    for (int k = 0; k < (n == 6 ? 3 : n); ++k) {
      const int x = cycle[k], y = cycle[(k + 3) % n];
      std::map<int, int> delta{{p, -1}, {q, -1}};
      ++delta[x];
      ++delta[y];
      int before = tiles_before, after = tiles_after;
      for (const auto& [m, d] : delta) {
        const int t = graph_.vertex_num_tiles[m];
        before += vertex_cost(m, t);
        after += vertex_cost(m, t + d);
      }
      const int gain = before - after;
      const int quad_gain = quads_after - quads_before;
      // Equal irregularity: taken when it leaves more quadrangle tiles.
      if (gain < 0 || (gain == 0 && (!params_.quads_on_ties || quad_gain <= 0))) continue;
      if (best && (gain < best->gain || (gain == best->gain && quad_gain < best->quad_gain))) continue;
      std::array<Point2, 4> quad;
      for (int s = 0; s < 4; ++s) quad[s] = mesh_.points[graph_.vertices[cycle[(k + s) % n]]];
      std::vector<Point2> rest;
      for (int s = 3; s <= n; ++s) rest.push_back(mesh_.points[graph_.vertices[cycle[(k + s) % n]]]);
      double dev = corner_deviation_deg(quad);
      if (n == 6) {
        std::array<Point2, 4> other;
        std::copy(rest.begin(), rest.end(), other.begin());
        dev = std::max(dev, corner_deviation_deg(other));
      } else if (!corners_open(rest)) {
        continue;
      }
      if (dev > params_.max_corner_deviation_deg) continue;
      if (best && gain == best->gain && quad_gain == best->quad_gain && dev >= best->deviation) continue;
      Candidate c;
      c.gain = gain;
      c.quad_gain = quad_gain;
      c.deviation = dev;
      c.edge = e;
      c.tile_a = L;
      c.tile_b = R;
      if (!split(L, R, graph_.vertices[x], graph_.vertices[y], c)) continue;
      // The quads the subdivision would make of both new tiles must be convex.
      std::vector<Point2> cut;  // from x to y
      for (auto it = c.path.rbegin(); it != c.path.rend(); ++it) cut.push_back(mesh_.points[*it]);
      std::vector<std::vector<Point2>> first, second;
      for (int s = 0; s < 3; ++s) first.push_back(union_side((k + s) % n));
      first.push_back(std::vector<Point2>(cut.rbegin(), cut.rend()));
      for (int s = 3; s < n; ++s) second.push_back(union_side((k + s) % n));
      second.push_back(cut);
      if (std::min(subdivision_convexity(first), subdivision_convexity(second)) <
          params_.min_subdivision_convexity)
        continue;
      c.meta_locked = cycle;
      c.meta_locked.push_back(p);
      c.meta_locked.push_back(q);
      c.tiles_locked = {L, R};
      for (const auto& td : tile_delta) c.tiles_locked.push_back(td.first);
      best = std::move(c);
    }
    return best;
  }

  bool in_union(int f, int a, int b) const { return tiling_.label[f] == a || tiling_.label[f] == b; }

  // Whether background vertex v is strictly inside the union of tiles a and b.
  bool strictly_inside(int v, int a, int b) const {
    if (on_boundary_[v]) return false;
    for (int k = vt_.offset[v]; k < vt_.offset[v + 1]; ++k)
      if (!in_union(vt_.triangles[k], a, b)) return false;
    return true;
  }

  // The shortest edge path from x to y through vertices strictly inside the union, and
  // the two sides it cuts the union into (with their area ratio checked).
  bool split(int a, int b, int x, int y, Candidate& c) const {
    ++stamp_;
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
    auto visit = [&](int v, double d, int from) {
      if (vmark_[v] == stamp_ && dist_[v] <= d) return;
      vmark_[v] = stamp_;
      dist_[v] = d;
      prev_[v] = from;
      heap.push({d, v});
    };
    visit(x, 0.0, -1);
    bool found = false;
    while (!heap.empty()) {
      const auto [d, u] = heap.top();
      heap.pop();
      if (d > dist_[u]) continue;
      if (u == y) {
        found = true;
        break;
      }
      if (u != x && !strictly_inside(u, a, b)) continue;
      for (int k = vt_.offset[u]; k < vt_.offset[u + 1]; ++k) {
        const int f = vt_.triangles[k];
        if (!in_union(f, a, b)) continue;
        for (int w : mesh_.triangles[f]) {
          if (w == u) continue;
          // Only through the union's inside: a step from x goes to an inside vertex.
          if (w != y && !strictly_inside(w, a, b)) continue;
          if (u == x && w == y) continue;  // a chord along one triangle edge: no room
          visit(w, d + distance(mesh_.points[u], mesh_.points[w]), u);
        }
      }
    }
    if (!found) return false;
    std::vector<int>& path = c.path;
    path.clear();
    for (int v = y; v >= 0; v = prev_[v]) path.push_back(v);
    std::vector<std::pair<int, int>> cut;
    for (std::size_t k = 0; k + 1 < path.size(); ++k)
      cut.push_back({std::min(path[k], path[k + 1]), std::max(path[k], path[k + 1])});
    std::sort(cut.begin(), cut.end());
    auto is_cut = [&](int u, int v) {
      return std::binary_search(cut.begin(), cut.end(), std::make_pair(std::min(u, v), std::max(u, v)));
    };

    const std::vector<int> all = collect_union(a, b);

    // Flood one side from a triangle at the first path edge.
    const int u0 = path[0], u1 = path[1];
    int seed = -1;
    for (int k = vt_.offset[u0]; k < vt_.offset[u0 + 1] && seed < 0; ++k) {
      const int f = vt_.triangles[k];
      const auto& t = mesh_.triangles[f];
      if (in_union(f, a, b) && std::find(t.begin(), t.end(), u1) != t.end()) seed = f;
    }
    if (seed < 0) return false;
    const std::vector<int> side = flood(seed, a, b, is_cut);
    // The rest of the union, which must be one piece as well.
    const int side_tag = stamp_;
    std::vector<int> other;
    for (int f : all)
      if (mark_[f] != side_tag) other.push_back(f);
    if (side.empty() || other.empty()) return false;
    if (flood(other.front(), a, b, is_cut).size() != other.size()) return false;
    double area_side = 0.0, area_other = 0.0;
    for (int f : side) area_side += triangle_area(mesh_, f);
    for (int f : other) area_other += triangle_area(mesh_, f);
    if (area_side > params_.max_area_ratio * area_other ||
        area_other > params_.max_area_ratio * area_side)
      return false;
    c.side_a = side;
    c.side_b = std::move(other);
    return true;
  }

  // The triangles of the union of tiles a and b reachable from `seed` without crossing
  // an edge for which is_cut(u, v) holds, marked with a fresh stamp_.
  template <class IsCut>
  std::vector<int> flood(int seed, int a, int b, const IsCut& is_cut) const {
    const int tag = ++stamp_;
    std::vector<int> out = {seed};
    mark_[seed] = tag;
    for (std::size_t k = 0; k < out.size(); ++k) {
      const int f = out[k];
      for (int s = 0; s < 3; ++s) {
        const int g = mesh_.neighbours[f][s];
        if (g < 0 || mark_[g] == tag || !in_union(g, a, b)) continue;
        if (is_cut(mesh_.triangles[f][(s + 1) % 3], mesh_.triangles[f][(s + 2) % 3])) continue;
        mark_[g] = tag;
        out.push_back(g);
      }
    }
    return out;
  }

  // Every triangle of tiles a and b (tiles are connected; two adjacent ones too).
  std::vector<int> collect_union(int a, int b) const {
    int start = tiling_.generator[a];
    if (start < 0 || tiling_.label[start] != a) start = -1;
    for (int f = 0; start < 0 && f < static_cast<int>(mesh_.triangles.size()); ++f)
      if (tiling_.label[f] == a) start = f;
    if (start < 0) return {};
    return flood(start, a, b, [](int, int) { return false; });
  }

  void apply(const Candidate& c) {
    for (int f : c.side_a) tiling_.label[f] = c.tile_a;
    for (int f : c.side_b) tiling_.label[f] = c.tile_b;
    // Generators: the triangle nearest each new tile's centroid.
    auto centre_triangle = [&](const std::vector<int>& side) {
      Point2 m{0, 0};
      double total = 0.0;
      for (int f : side) {
        const auto& t = mesh_.triangles[f];
        const double w = triangle_area(mesh_, f);
        for (int v : t) m.x += w * mesh_.points[v].x / 3.0, m.y += w * mesh_.points[v].y / 3.0;
        total += w;
      }
      m.x /= total, m.y /= total;
      int best = side.front();
      double best_d = 1e300;
      for (int f : side) {
        const auto& t = mesh_.triangles[f];
        const Point2 cf{(mesh_.points[t[0]].x + mesh_.points[t[1]].x + mesh_.points[t[2]].x) / 3.0,
                        (mesh_.points[t[0]].y + mesh_.points[t[1]].y + mesh_.points[t[2]].y) / 3.0};
        const double d = distance(cf, m);
        if (d < best_d) best_d = d, best = f;
      }
      return best;
    };
    tiling_.generator[c.tile_a] = centre_triangle(c.side_a);
    tiling_.generator[c.tile_b] = centre_triangle(c.side_b);
  }

  const BackgroundMesh& mesh_;
  Tiling& tiling_;
  const ResplitParams& params_;
  VertexTriangles vt_;
  std::vector<char> on_boundary_;
  std::vector<double> turning_;
  std::vector<char> is_corner_;
  MetaGraph graph_;
  std::vector<std::vector<int>> tiles_at_;  // #MV tiles having the meta-vertex
  mutable std::vector<int> mark_, vmark_;
  mutable std::vector<double> dist_;
  mutable std::vector<int> prev_;
  mutable int stamp_ = 0;
};

}  // namespace

ResplitStats resplit_pairs(const BackgroundMesh& mesh, Tiling& tiling, const ResplitParams& params,
                           const Progress& progress) {
  ResplitStats stats;
  Resplitter r(mesh, tiling, params);
  for (int k = 0; k < params.max_rounds; ++k) {
    // Each round finds fewer pairs: the first is told as half the work.
    progress.report("tiling pairs", 1.0 - std::pow(0.5, k));
    int candidates = 0;
    const int applied = r.round(&candidates);
    if (k == 0) stats.candidates = candidates;
    ++stats.rounds;
    stats.resplit += applied;
    if (applied == 0) break;
  }
  return stats;
}

}  // namespace isoquad
