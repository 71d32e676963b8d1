// The meta-graph of a tiling (paper, section 2.1), derived from the triangle labels:
// meta-vertices, meta-edges (edge paths of the background mesh between meta-vertices)
// and, for every tile, its boundary cycle. Rebuilt from the labels whenever needed; it
// is cheap. Every tiling step and the barycentric subdivision use it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "mesh/background_mesh.h"
#include "tiling/tile_boundary.h"
#include "tiling/tiling.h"

namespace isoquad {

// A background vertex is a meta-vertex when it is incident to 3 or more tiles inside
// the domain, to 2 or more tiles on the boundary, or to 1 tile when it is a corner
// boundary vertex (BoundaryChain::is_corner, set by tag_corners for the tile scale).
struct MetaGraphParams {
  // The turning threshold tag_corners uses (--corner-angle); the meta-graph itself reads
  // the tags from the boundary chains.
  double corner_angle_deg = 45.0;
};

struct MetaEdge {
  // Background vertex ids from one meta-vertex to the next; front() and back() are
  // meta-vertices (equal for a closed loop with a single meta-vertex, which a valid
  // tiling does not have). Consecutive ids are joined by background edges.
  std::vector<int> path;
  int tile_left = -1;   // tile on the left of path (walking front to back); -1 outside
  int tile_right = -1;  // tile on the right; -1 outside the domain (boundary meta-edge)
  double length_m = 0.0;
  bool on_boundary() const { return tile_left < 0 || tile_right < 0; }
};

// The boundary of one tile, counter-clockwise (the tile on the left).
struct TileCycle {
  std::vector<int> edges;     // meta-edge ids in order
  std::vector<char> forward;  // 1 when edges[i] is walked front to back (tile on its left)
  std::vector<int> vertices;  // meta-vertex ids; vertices[i] is where edges[i] starts
};

struct MetaGraph {
  std::vector<int> vertices;    // #MV background vertex id of each meta-vertex
  std::vector<int> meta_index;  // #V meta-vertex id of a background vertex, or -1
  std::vector<int> vertex_num_tiles;  // #MV number of tiles incident to each meta-vertex
  std::vector<char> vertex_on_boundary;  // #MV
  std::vector<MetaEdge> edges;
  std::vector<TileCycle> tiles;  // #T
};

MetaGraph build_meta_graph(const BackgroundMesh& mesh, const Tiling& tiling,
                           const MetaGraphParams& params = MetaGraphParams());
// The same from the labels' vertex sectors (count_vertex_sectors) and tile boundaries
// (walk_tile_boundaries), for callers that have them already.
MetaGraph build_meta_graph(const BackgroundMesh& mesh, const Tiling& tiling,
                           const std::vector<int>& sectors, const TileBoundaries& b);

// #V 1 at the domain boundary's corners (BoundaryChain::is_corner).
std::vector<char> corner_flags(const BackgroundMesh& mesh);

// Whether background vertex v is a meta-vertex, from the sectors round it
// (count_vertex_sectors) and the corner flags.
inline bool is_meta_vertex(const BackgroundMesh& mesh, const std::vector<int>& sectors,
                           const std::vector<char>& is_corner, int v) {
  return mesh.boundary_chain_of_vertex[v] >= 0 ? (sectors[v] >= 2 || is_corner[v] != 0)
                                               : sectors[v] >= 3;
}

// #T the meta-vertices on each tile's outer cycle, as many as build_meta_graph's
// tiles[t].vertices would hold, without building the graph.
std::vector<int> count_tile_meta_vertices(const BackgroundMesh& mesh,
                                          const std::vector<int>& sectors, const TileBoundaries& b);

// The invariants that every tiling step keeps (checked in tests and debug builds):
// every triangle labelled, every tile non-empty, connected and a topological disk (one
// boundary cycle), every tile with at least 3 meta-vertices. Returns "" when they hold,
// else a description of the first violation, with a point near it in `where` (when given
// and the violation has a place).
std::string check_tiling(const BackgroundMesh& mesh, const Tiling& tiling, const MetaGraph& graph,
                         std::optional<Point2>* where = nullptr);
// The same with the tiles' boundaries of these labels (walk_tile_boundaries) at hand.
std::string check_tiling(const BackgroundMesh& mesh, const Tiling& tiling, const MetaGraph& graph,
                         const TileBoundaries& b, std::optional<Point2>* where = nullptr);

// A tiling whose invariants (check_tiling) the repairs cannot restore: Error(meshing),
// with the place when the violation has one (a retry can refine the sizes there).
class TilingError : public Error {
 public:
  TilingError(const std::string& message, std::optional<Point2> where)
      : Error(ErrorClass::meshing, "tiling", message), where_(where) {}
  const std::optional<Point2>& where() const { return where_; }

 private:
  std::optional<Point2> where_;
};

// Statistics of a tiling, as the report gives them per step.
struct TilingStats {
  int num_tiles = 0;
  double share_quads = 0.0;  // tiles with exactly 4 meta-vertices
  std::vector<int> tile_num_vertices_histogram;  // [k] = tiles with k meta-vertices
  // [d] = interior meta-vertices incident to d tiles (boundary ones are not counted)
  std::vector<int> interior_degree_histogram;
  int num_irregular_interior = 0;  // interior meta-vertices with degree != 4
  // Interior meta-edges joining two interior meta-vertices of 3 tiles each: the
  // butterfly inner edges of any length (2.5).
  int num_degree3_pairs = 0;
};
TilingStats tiling_stats(const MetaGraph& graph);

}  // namespace isoquad
