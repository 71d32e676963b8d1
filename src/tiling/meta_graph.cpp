#include "tiling/meta_graph.h"

#include <algorithm>
#include <cmath>

#include "tiling/tile_boundary.h"

namespace isoquad {

namespace {

double edge_length_m(const BackgroundMesh& mesh, int a, int b) {
  return std::hypot(mesh.points[b].x - mesh.points[a].x, mesh.points[b].y - mesh.points[a].y);
}

}  // namespace

MetaGraph build_meta_graph(const BackgroundMesh& mesh, const Tiling& tiling,
                           const MetaGraphParams& /*params*/) {
  return build_meta_graph(mesh, tiling, count_vertex_sectors(mesh, tiling.label),
                          walk_tile_boundaries(mesh, tiling.label, tiling.num_tiles()));
}

MetaGraph build_meta_graph(const BackgroundMesh& mesh, const Tiling& tiling,
                           const std::vector<int>& sectors, const TileBoundaries& b) {
  const std::vector<int>& label = tiling.label;
  const int num_tiles = tiling.num_tiles();
  const int num_vertices = static_cast<int>(mesh.points.size());
  MetaGraph g;

  // Meta-vertices (2.1): >= 3 tiles inside, >= 2 on the boundary, or a boundary corner.
  const std::vector<char> is_corner = corner_flags(mesh);
  g.meta_index.assign(num_vertices, -1);
  for (int v = 0; v < num_vertices; ++v) {
    if (!is_meta_vertex(mesh, sectors, is_corner, v)) continue;
    g.meta_index[v] = static_cast<int>(g.vertices.size());
    g.vertices.push_back(v);
    g.vertex_num_tiles.push_back(sectors[v]);
    g.vertex_on_boundary.push_back(mesh.boundary_chain_of_vertex[v] >= 0 ? 1 : 0);
  }

  // Meta-edges: the runs of each boundary cycle between meta-vertices. The twin run (the
  // same meta-edge seen from the tile on the other side) is found through the twin of its
  // first half-edge, which is the last half-edge of the run already stored.
  std::vector<int> edge_at(3 * mesh.triangles.size(), -1);
  g.tiles.assign(num_tiles, TileCycle());
  for (int c = 0; c < b.num_cycles(); ++c) {
    const int begin = b.cycle_begin[c], n = b.cycle_begin[c + 1] - begin;
    const int* he = b.halfedges.data() + begin;
    int first = -1;
    for (int k = 0; k < n && first < 0; ++k)
      if (g.meta_index[halfedge_from(mesh, he[k])] >= 0) first = k;
    if (first < 0) continue;  // a closed boundary without meta-vertex: no meta-edge
    const int tile = b.cycle_tile[c];
    const bool listed = b.tile_outer_cycle[tile] == c;
    TileCycle& cycle = g.tiles[tile];
    int k = first;
    do {
      const int run_begin = k;
      int run_end = k;  // last half-edge of the run
      while (g.meta_index[halfedge_to(mesh, he[run_end % n])] < 0) ++run_end;
      const int h_first = he[run_begin % n], h_last = he[run_end % n];
      const int twin = halfedge_twin(mesh, h_first);
      int id = twin >= 0 ? edge_at[twin] : -1;
      const bool forward = id < 0;
      if (forward) {
        id = static_cast<int>(g.edges.size());
        MetaEdge e;
        e.tile_left = tile;
        e.tile_right = twin >= 0 ? label[twin / 3] : -1;
        e.path.reserve(run_end - run_begin + 2);
        e.path.push_back(halfedge_from(mesh, h_first));
        for (int j = run_begin; j <= run_end; ++j) {
          const int h = he[j % n];
          e.path.push_back(halfedge_to(mesh, h));
          e.length_m += edge_length_m(mesh, halfedge_from(mesh, h), halfedge_to(mesh, h));
        }
        g.edges.push_back(std::move(e));
        edge_at[h_first] = id;
        edge_at[h_last] = id;
      }
      if (listed) {
        cycle.edges.push_back(id);
        cycle.forward.push_back(forward ? 1 : 0);
        cycle.vertices.push_back(g.meta_index[halfedge_from(mesh, h_first)]);
      }
      k = run_end + 1;
    } while (k % n != first);
  }
  return g;
}

std::vector<char> corner_flags(const BackgroundMesh& mesh) {
  std::vector<char> is_corner(mesh.points.size(), 0);
  for (const BoundaryChain& chain : mesh.chains)
    for (std::size_t k = 0; k < chain.vertices.size(); ++k)
      if (chain.is_corner[k]) is_corner[chain.vertices[k]] = 1;
  return is_corner;
}

std::vector<int> count_tile_meta_vertices(const BackgroundMesh& mesh,
                                          const std::vector<int>& sectors,
                                          const TileBoundaries& b) {
  // build_meta_graph starts a meta-edge, and lists its first meta-vertex, at every
  // half-edge of the outer cycle that leaves a meta-vertex.
  const std::vector<char> is_corner = corner_flags(mesh);
  std::vector<int> count(b.tile_outer_cycle.size(), 0);
  for (std::size_t t = 0; t < count.size(); ++t) {
    const int c = b.tile_outer_cycle[t];
    if (c < 0) continue;
    for (int k = b.cycle_begin[c]; k < b.cycle_begin[c + 1]; ++k)
      if (is_meta_vertex(mesh, sectors, is_corner, halfedge_from(mesh, b.halfedges[k]))) ++count[t];
  }
  return count;
}

namespace {

// What is wrong with the labelling itself (its size, labels outside the tiles), or "".
std::string labelling_problem(const BackgroundMesh& mesh, const Tiling& tiling) {
  const int num_faces = static_cast<int>(mesh.triangles.size());
  const int num_tiles = tiling.num_tiles();
  const std::vector<int>& label = tiling.label;
  if (static_cast<int>(label.size()) != num_faces)
    return "the labelling has " + std::to_string(label.size()) + " entries for " +
           std::to_string(num_faces) + " triangles";
  for (int f = 0; f < num_faces; ++f)
    if (label[f] < 0 || label[f] >= num_tiles)
      return "triangle " + std::to_string(f) + " has label " + std::to_string(label[f]) +
             " outside [0, " + std::to_string(num_tiles) + ")";
  return "";
}

}  // namespace

std::string check_tiling(const BackgroundMesh& mesh, const Tiling& tiling, const MetaGraph& graph,
                         std::optional<Point2>* where) {
  const std::string problem = labelling_problem(mesh, tiling);
  if (!problem.empty()) return problem;
  return check_tiling(mesh, tiling, graph,
                      walk_tile_boundaries(mesh, tiling.label, tiling.num_tiles()), where);
}

std::string check_tiling(const BackgroundMesh& mesh, const Tiling& tiling, const MetaGraph& graph,
                         const TileBoundaries& b, std::optional<Point2>* where) {
  auto at = [&](const Point2& p) {
    if (where) *where = p;
    return format_point(p);
  };
  const int num_faces = static_cast<int>(mesh.triangles.size());
  const int num_tiles = tiling.num_tiles();
  const std::vector<int>& label = tiling.label;
  const std::string problem = labelling_problem(mesh, tiling);
  if (!problem.empty()) return problem;
  if (static_cast<int>(graph.tiles.size()) != num_tiles)
    return "the meta-graph has " + std::to_string(graph.tiles.size()) + " tiles, the tiling " +
           std::to_string(num_tiles);

  // Connectivity: one flood per tile from its first triangle.
  std::vector<char> seen(num_faces, 0), tile_seen(num_tiles, 0);
  std::vector<int> stack;
  for (int f = 0; f < num_faces; ++f) {
    if (seen[f]) continue;
    const int tile = label[f];
    if (tile_seen[tile])
      return "tile " + std::to_string(tile) + " is not connected (triangle " + std::to_string(f) +
             " at " + at(mesh.points[mesh.triangles[f][0]]) + ")";
    tile_seen[tile] = 1;
    seen[f] = 1;
    stack.assign(1, f);
    while (!stack.empty()) {
      const int t = stack.back();
      stack.pop_back();
      for (int g : mesh.neighbours[t])
        if (g >= 0 && !seen[g] && label[g] == tile) {
          seen[g] = 1;
          stack.push_back(g);
        }
    }
  }
  for (int t = 0; t < num_tiles; ++t)
    if (!tile_seen[t]) return "tile " + std::to_string(t) + " is empty";

  for (int t = 0; t < num_tiles; ++t)
    if (b.tile_num_cycles[t] != 1) {
      // Where: on a cycle other than its outer one, round what it wraps (the retry's
      // smaller sizes there give tiles that do not).
      std::string near;
      for (int c = 0; c < b.num_cycles() && near.empty(); ++c)
        if (b.cycle_tile[c] == t && c != b.tile_outer_cycle[t])
          near = " near " + at(mesh.points[halfedge_from(mesh, b.halfedges[b.cycle_begin[c]])]);
      return "tile " + std::to_string(t) + near +
             " is not a disk: " + std::to_string(b.tile_num_cycles[t]) +
             " boundary cycles (it wraps an island or another tile)";
    }
  for (int c = 0; c < b.num_cycles(); ++c)
    if (b.cycle_pinch[c] >= 0)
      return "tile " + std::to_string(b.cycle_tile[c]) + " is not a disk: it touches itself at " +
             at(mesh.points[b.cycle_pinch[c]]);
  for (int t = 0; t < num_tiles; ++t)
    if (graph.tiles[t].vertices.size() < 3) {
      const int c = b.tile_outer_cycle[t];
      const Point2& p = mesh.points[halfedge_from(mesh, b.halfedges[b.cycle_begin[c]])];
      return "tile " + std::to_string(t) + " near " + at(p) + " has " +
             std::to_string(graph.tiles[t].vertices.size()) + " meta-vertices (at least 3 needed)";
    }

  // A corner (a meta-vertex of a single tile) that is reflex would give a non-convex quad.
  const std::vector<double> turning = vertex_turning_angles_deg(mesh);
  for (std::size_t m = 0; m < graph.vertices.size(); ++m) {
    const int v = graph.vertices[m];
    if (graph.vertex_on_boundary[m] && graph.vertex_num_tiles[m] < 2 && turning[v] < 0.0)
      return "the reflex corner at " + at(mesh.points[v]) +
             " lies in a single tile (it needs at least two)";
  }
  return "";
}

TilingStats tiling_stats(const MetaGraph& graph) {
  TilingStats s;
  s.num_tiles = static_cast<int>(graph.tiles.size());
  int num_quads = 0;
  for (const TileCycle& c : graph.tiles) {
    const std::size_t k = c.vertices.size();
    if (s.tile_num_vertices_histogram.size() <= k) s.tile_num_vertices_histogram.resize(k + 1, 0);
    ++s.tile_num_vertices_histogram[k];
    if (k == 4) ++num_quads;
  }
  s.share_quads = s.num_tiles > 0 ? static_cast<double>(num_quads) / s.num_tiles : 0.0;
  for (std::size_t m = 0; m < graph.vertices.size(); ++m) {
    if (graph.vertex_on_boundary[m]) continue;
    const std::size_t d = graph.vertex_num_tiles[m];
    if (s.interior_degree_histogram.size() <= d) s.interior_degree_histogram.resize(d + 1, 0);
    ++s.interior_degree_histogram[d];
    if (d != 4) ++s.num_irregular_interior;
  }
  auto interior_degree3 = [&](int v) {
    const int m = graph.meta_index[v];
    return m >= 0 && !graph.vertex_on_boundary[m] && graph.vertex_num_tiles[m] == 3;
  };
  for (const MetaEdge& e : graph.edges)
    if (!e.on_boundary() && interior_degree3(e.path.front()) && interior_degree3(e.path.back()))
      ++s.num_degree3_pairs;
  return s;
}

}  // namespace isoquad
