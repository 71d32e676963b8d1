// The boundaries of the tiles of a labelling, as closed cycles of background half-edges
// (paper, section 2.1). The meta-graph, the invariant checks and the repairs all start
// from this walk; it is O(#F).
#pragma once

#include <vector>

#include "mesh/background_mesh.h"

namespace isoquad {

// Half-edge h = 3 f + i is the edge of triangle f opposite its vertex i, walked from
// triangles[f][i+1] to triangles[f][i+2], so that f lies on its left.
inline int halfedge_from(const BackgroundMesh& mesh, int h) {
  return mesh.triangles[h / 3][(h % 3 + 1) % 3];
}
inline int halfedge_to(const BackgroundMesh& mesh, int h) {
  return mesh.triangles[h / 3][(h % 3 + 2) % 3];
}
// The triangle on the other side of h, or -1 on the domain boundary.
inline int halfedge_across(const BackgroundMesh& mesh, int h) {
  return mesh.neighbours[h / 3][h % 3];
}
// The opposite half-edge (in the triangle across), or -1 on the domain boundary.
int halfedge_twin(const BackgroundMesh& mesh, int h);

// Whether h separates its triangle's tile from another tile or from the outside.
inline bool is_tile_boundary(const BackgroundMesh& mesh, const std::vector<int>& label, int h) {
  const int g = halfedge_across(mesh, h);
  return g < 0 || label[g] != label[h / 3];
}

// The boundary half-edge of the same tile that follows h (a boundary half-edge) around
// that tile: rotates about the end vertex of h through the triangles of the tile, so a
// tile touching itself at a vertex keeps its two sectors apart.
int next_tile_boundary_halfedge(const BackgroundMesh& mesh, const std::vector<int>& label, int h);

// #V number of tile sectors around each vertex: on the domain boundary, 1 + the number
// of interior edges at the vertex whose two triangles have different labels; inside,
// that number (at least 1). It equals the number of incident tiles when no tile touches
// itself at the vertex.
std::vector<int> count_vertex_sectors(const BackgroundMesh& mesh, const std::vector<int>& label);

// #V 1 on the domain boundary.
std::vector<char> boundary_vertex_flags(const BackgroundMesh& mesh);

// #V signed turning angle of the domain boundary at its corners
// (BoundaryChain::corner_turning_deg; negative = reflex), 0 elsewhere.
std::vector<double> vertex_turning_angles_deg(const BackgroundMesh& mesh);

struct TileBoundaries {
  // Boundary half-edges, cycle after cycle; each cycle is closed and has its tile on
  // the left (outer boundaries counter-clockwise, holes clockwise).
  std::vector<int> halfedges;
  std::vector<int> cycle_begin;      // #C + 1 offsets into halfedges
  std::vector<int> cycle_tile;       // #C
  std::vector<double> cycle_area_m2; // #C signed area (> 0: an outer boundary)
  std::vector<int> cycle_pinch;      // #C a vertex the cycle passes twice, or -1
  // #T the tile's outer cycle (largest signed area), -1 for an empty tile.
  std::vector<int> tile_outer_cycle;
  std::vector<int> tile_num_cycles;  // #T
  int num_cycles() const { return static_cast<int>(cycle_tile.size()); }
};

// Walks every tile boundary. Labels must lie in [0, num_tiles). The cycles come in the
// order of their first half-edge (the smallest id in the cycle), each starting there.
TileBoundaries walk_tile_boundaries(const BackgroundMesh& mesh, const std::vector<int>& label,
                                    int num_tiles);

// The pieces of that walk, for callers that walk some tiles again (the repairs).
struct CycleWalk {
  double area_m2 = 0.0;  // signed area
  int pinch = -1;        // a vertex the cycle passes twice, or -1
};
// Walks the cycle of tile boundary half-edge `start`: appends its half-edges to
// `halfedges` and marks them in `visited` (#3F). `vertex_stamp` (#V) must hold no
// `stamp` before the walk: the walk writes it at the cycle's vertices.
CycleWalk walk_boundary_cycle(const BackgroundMesh& mesh, const std::vector<int>& label, int start,
                              std::vector<char>& visited, std::vector<int>& vertex_stamp, int stamp,
                              std::vector<int>& halfedges);
// Ends the cycle of `tile` whose half-edges were appended last to b.halfedges (b's
// per-tile arrays sized for every tile).
void close_cycle(TileBoundaries& b, int tile, const CycleWalk& walk);

}  // namespace isoquad
