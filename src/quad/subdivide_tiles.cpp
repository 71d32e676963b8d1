#include "quad/subdivide_tiles.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.h"

namespace isoquad {

namespace {

// Position of each boundary vertex in its chain.
std::vector<int> chain_positions(const BackgroundMesh& bg) {
  std::vector<int> pos(bg.points.size(), -1);
  for (const BoundaryChain& c : bg.chains)
    for (std::size_t i = 0; i < c.vertices.size(); ++i) pos[c.vertices[i]] = static_cast<int>(i);
  return pos;
}

}  // namespace

QuadMesh subdivide_tiles(const BackgroundMesh& bg, const Tiling& tiling, const MetaGraph& graph,
                         const SubdivideParams& params) {
  QuadMesh qm;
  const std::vector<int> in_chain = chain_positions(bg);
  auto add_point = [&](const Point2& p, int chain, double arc, bool fixed) {
    qm.points.push_back(p);
    qm.chain.push_back(chain);
    qm.arc_m.push_back(arc);
    qm.fixed.push_back(fixed ? 1 : 0);
    return static_cast<int>(qm.points.size() - 1);
  };

  // Meta-vertices.
  std::vector<int> of_meta_vertex(graph.vertices.size());
  for (std::size_t i = 0; i < graph.vertices.size(); ++i) {
    const int v = graph.vertices[i];
    const int c = bg.boundary_chain_of_vertex[v];
    double arc = 0;
    bool fixed = false;
    if (c >= 0) {
      const BoundaryChain& ch = bg.chains[c];
      const int k = in_chain[v];
      arc = ch.arc_length_m[k];
      fixed = ch.is_corner[k] != 0;
    }
    of_meta_vertex[i] = add_point(bg.points[v], c, arc, fixed);
  }

  // Meta-edge midpoints at the arc-length middle of their paths.
  std::vector<int> of_meta_edge(graph.edges.size());
  for (std::size_t e = 0; e < graph.edges.size(); ++e) {
    const MetaEdge& me = graph.edges[e];
    const auto& path = me.path;
    double total = 0;
    for (std::size_t i = 0; i + 1 < path.size(); ++i) {
      const Point2 &a = bg.points[path[i]], &b = bg.points[path[i + 1]];
      total += std::hypot(b.x - a.x, b.y - a.y);
    }
    double half = 0.5 * total, walked = 0;
    Point2 mid = bg.points[path.front()];
    for (std::size_t i = 0; i + 1 < path.size(); ++i) {
      const Point2 &a = bg.points[path[i]], &b = bg.points[path[i + 1]];
      const double len = std::hypot(b.x - a.x, b.y - a.y);
      if (walked + len >= half) {
        const double t = len > 0 ? (half - walked) / len : 0;
        mid = {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)};
        break;
      }
      walked += len;
    }
    int chain = -1;
    double arc = 0;
    if (me.on_boundary()) {
      chain = bg.boundary_chain_of_vertex[path.front()];
      if (chain < 0 || path.size() < 2)
        throw Error(ErrorClass::internal, "subdivide", "a boundary meta-edge is not on the boundary");
      const BoundaryChain& ch = bg.chains[chain];
      const int n = static_cast<int>(ch.vertices.size());
      const int k0 = in_chain[path[0]], k1 = in_chain[path[1]];
      const bool along = (k0 + 1) % n == k1;  // walking the chain's own direction
      arc = ch.arc_length_m[k0] + (along ? half : -half);
      arc = std::fmod(arc, ch.length_m);
      if (arc < 0) arc += ch.length_m;
      mid = chain_point(bg, ch, arc);
    }
    of_meta_edge[e] = add_point(mid, chain, arc, false);
  }

  // Tile centres: the area-weighted centroid of the tile's triangles, unless a quad of
  // the tile would then be flat or folded (the centroid of a bent tile may lie outside
  // it or see a side at a grazing angle); then the triangle centroid of the tile that
  // makes its flattest quad the most convex. Convexity as quad_convexity (sine of the
  // sharpest turn).
  const int nt = tiling.num_tiles();
  std::vector<double> area(nt, 0.0), cx(nt, 0.0), cy(nt, 0.0);
  std::vector<int> tile_start(nt + 1, 0), tile_faces(bg.triangles.size());
  for (std::size_t f = 0; f < bg.triangles.size(); ++f) {
    const auto& t = bg.triangles[f];
    const Point2 &a = bg.points[t[0]], &b = bg.points[t[1]], &c = bg.points[t[2]];
    const double ar = signed_area(a, b, c);
    const int tile = tiling.label[f];
    area[tile] += ar;
    cx[tile] += ar * (a.x + b.x + c.x) / 3;
    cy[tile] += ar * (a.y + b.y + c.y) / 3;
    ++tile_start[tile + 1];
  }
  for (int tile = 0; tile < nt; ++tile) tile_start[tile + 1] += tile_start[tile];
  std::vector<int> fill(tile_start.begin(), tile_start.end() - 1);
  for (std::size_t f = 0; f < bg.triangles.size(); ++f)
    tile_faces[fill[tiling.label[f]]++] = static_cast<int>(f);

  for (int tile = 0; tile < nt; ++tile) {
    const TileCycle& cyc = graph.tiles[tile];
    const int k = static_cast<int>(cyc.edges.size());
    if (k < 3) throw Error(ErrorClass::internal, "subdivide", "a tile has fewer than 3 meta-edges");
    auto flattest = [&](const Point2& c) {
      double worst = 1.0;
      for (int i = 0; i < k; ++i)
        worst = std::min(worst, quad_convexity(c, qm.points[of_meta_edge[cyc.edges[(i + k - 1) % k]]],
                                               qm.points[of_meta_vertex[cyc.vertices[i]]],
                                               qm.points[of_meta_edge[cyc.edges[i]]]));
      return worst;
    };
    Point2 best{cx[tile] / area[tile], cy[tile] / area[tile]};
    double best_convexity = flattest(best);
    if (best_convexity < params.centre_min_convexity) {
      for (int j = tile_start[tile]; j < tile_start[tile + 1]; ++j) {
        const auto& t = bg.triangles[tile_faces[j]];
        const Point2 c{(bg.points[t[0]].x + bg.points[t[1]].x + bg.points[t[2]].x) / 3,
                       (bg.points[t[0]].y + bg.points[t[1]].y + bg.points[t[2]].y) / 3};
        const double convexity = flattest(c);
        if (convexity > best_convexity) best_convexity = convexity, best = c;
      }
    }
    const int centre = add_point(best, -1, 0, false);
    for (int i = 0; i < k; ++i) {
      const int prev_edge = cyc.edges[(i + k - 1) % k];
      qm.quads.push_back({centre, of_meta_edge[prev_edge], of_meta_vertex[cyc.vertices[i]],
                          of_meta_edge[cyc.edges[i]]});
    }
  }
  return qm;
}

}  // namespace isoquad
