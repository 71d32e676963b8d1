#include "tiling/tile_boundary.h"

#include <algorithm>

namespace isoquad {

int halfedge_twin(const BackgroundMesh& mesh, int h) {
  const int f = h / 3;
  const int g = mesh.neighbours[f][h % 3];
  if (g < 0) return -1;
  const auto& n = mesh.neighbours[g];
  return 3 * g + (n[0] == f ? 0 : n[1] == f ? 1 : 2);
}

int next_tile_boundary_halfedge(const BackgroundMesh& mesh, const std::vector<int>& label,
                                int h) {
  int f = h / 3;
  int k = (h % 3 + 1) % 3;  // leaves the end vertex of h inside f
  const int tile = label[f];
  for (;;) {
    const int g = mesh.neighbours[f][k];
    if (g < 0 || label[g] != tile) return 3 * f + k;
    const auto& n = mesh.neighbours[g];
    const int back = n[0] == f ? 0 : n[1] == f ? 1 : 2;  // the same edge, seen from g
    f = g;
    k = (back + 1) % 3;
  }
}

std::vector<int> count_vertex_sectors(const BackgroundMesh& mesh, const std::vector<int>& label) {
  const int num_faces = static_cast<int>(mesh.triangles.size());
  std::vector<int> changes(mesh.points.size(), 0);
  std::vector<char> on_boundary(mesh.points.size(), 0);
  for (int f = 0; f < num_faces; ++f) {
    const auto& t = mesh.triangles[f];
    const auto& n = mesh.neighbours[f];
    for (int i = 0; i < 3; ++i) {
      const int g = n[i];
      const int a = t[(i + 1) % 3], b = t[(i + 2) % 3];
      if (g < 0) {
        on_boundary[a] = on_boundary[b] = 1;
      } else if (g > f && label[g] != label[f]) {
        ++changes[a];
        ++changes[b];
      }
    }
  }
  for (std::size_t v = 0; v < changes.size(); ++v)
    changes[v] = on_boundary[v] ? changes[v] + 1 : std::max(changes[v], 1);
  return changes;
}

std::vector<char> boundary_vertex_flags(const BackgroundMesh& mesh) {
  std::vector<char> flags(mesh.points.size(), 0);
  for (const BoundaryChain& chain : mesh.chains)
    for (int v : chain.vertices) flags[v] = 1;
  return flags;
}

std::vector<double> vertex_turning_angles_deg(const BackgroundMesh& mesh) {
  std::vector<double> angle(mesh.points.size(), 0.0);
  for (const BoundaryChain& chain : mesh.chains)
    for (std::size_t k = 0; k < chain.vertices.size(); ++k)
      angle[chain.vertices[k]] = chain.corner_turning_deg[k];
  return angle;
}

CycleWalk walk_boundary_cycle(const BackgroundMesh& mesh, const std::vector<int>& label, int start,
                              std::vector<char>& visited, std::vector<int>& vertex_stamp, int stamp,
                              std::vector<int>& halfedges) {
  CycleWalk w;
  const Point2 origin = mesh.points[halfedge_from(mesh, start)];
  double twice_area = 0.0;
  int h = start;
  do {
    visited[h] = 1;
    halfedges.push_back(h);
    const int a = halfedge_from(mesh, h), c = halfedge_to(mesh, h);
    if (vertex_stamp[a] == stamp && w.pinch < 0) w.pinch = a;
    vertex_stamp[a] = stamp;
    const Point2 &pa = mesh.points[a], &pc = mesh.points[c];
    twice_area += (pa.x - origin.x) * (pc.y - origin.y) - (pc.x - origin.x) * (pa.y - origin.y);
    h = next_tile_boundary_halfedge(mesh, label, h);
  } while (h != start);
  w.area_m2 = 0.5 * twice_area;
  return w;
}

void close_cycle(TileBoundaries& b, int tile, const CycleWalk& walk) {
  const int cycle = b.num_cycles();
  b.cycle_begin.push_back(static_cast<int>(b.halfedges.size()));
  b.cycle_tile.push_back(tile);
  b.cycle_area_m2.push_back(walk.area_m2);
  b.cycle_pinch.push_back(walk.pinch);
  ++b.tile_num_cycles[tile];
  const int outer = b.tile_outer_cycle[tile];
  if (outer < 0 || walk.area_m2 > b.cycle_area_m2[outer]) b.tile_outer_cycle[tile] = cycle;
}

TileBoundaries walk_tile_boundaries(const BackgroundMesh& mesh, const std::vector<int>& label,
                                    int num_tiles) {
  const int num_faces = static_cast<int>(mesh.triangles.size());
  TileBoundaries b;
  b.cycle_begin.push_back(0);
  b.tile_outer_cycle.assign(num_tiles, -1);
  b.tile_num_cycles.assign(num_tiles, 0);
  std::vector<char> visited(3 * static_cast<std::size_t>(num_faces), 0);
  // stamp[v] = 1 + the last cycle through v: finds a cycle passing a vertex twice.
  std::vector<int> stamp(mesh.points.size(), 0);
  for (int f = 0; f < num_faces; ++f) {
    for (int i = 0; i < 3; ++i) {
      const int start = 3 * f + i;
      if (visited[start] || !is_tile_boundary(mesh, label, start)) continue;
      const CycleWalk w =
          walk_boundary_cycle(mesh, label, start, visited, stamp, b.num_cycles() + 1, b.halfedges);
      close_cycle(b, label[f], w);
    }
  }
  return b;
}

}  // namespace isoquad
