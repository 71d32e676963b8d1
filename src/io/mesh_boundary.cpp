#include "io/mesh_boundary.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/error.h"

namespace isoquad {

const char* boundary_kind_name(BoundaryKind k) { return k == BoundaryKind::open ? "open" : "land"; }

MeshBoundary extract_boundary(const QuadMesh& mesh, const PolylineIndex& open_lines,
                              double tolerance_m, double chord_share,
                              const std::vector<int>* line_group) {
  // Directed edges of the counter-clockwise quads; a boundary edge has no twin.
  std::map<std::pair<int, int>, int> count;
  for (const auto& q : mesh.quads)
    for (int i = 0; i < 4; ++i) ++count[{q[i], q[(i + 1) % 4]}];
  std::map<int, int> next;
  for (const auto& [e, n] : count) {
    if (count.count({e.second, e.first})) continue;
    if (n != 1 || !next.emplace(e.first, e.second).second)
      throw Error(ErrorClass::internal, "write",
                  "the mesh boundary is not a set of simple loops at vertex " +
                      std::to_string(e.first));
  }
  MeshBoundary b;
  std::vector<char> on_open(mesh.points.size(), 0);
  if (!open_lines.empty())
    for (const auto& [v, w] : next) {
      (void)w;
      on_open[v] = open_lines.near(mesh.points[v], tolerance_m);
    }
  std::map<int, char> seen;
  // By loop and edge: -1 for land, else the open edge's group.
  std::vector<std::vector<int>> edge_group;
  for (const auto& [start, w] : next) {  // increasing vertex id: deterministic order
    (void)w;
    if (seen.count(start)) continue;
    std::vector<int> loop;
    int v = start;
    do {
      seen[v] = 1;
      loop.push_back(v);
      auto it = next.find(v);
      if (it == next.end())
        throw Error(ErrorClass::internal, "write", "an open boundary chain in the mesh");
      v = it->second;
    } while (v != start && !seen.count(v));
    if (v != start) throw Error(ErrorClass::internal, "write", "a boundary loop does not close");
    std::vector<BoundaryKind> kinds(loop.size(), BoundaryKind::land);
    std::vector<int> groups(loop.size(), -1);
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const int a = loop[i], c = loop[(i + 1) % loop.size()];
      const Point2 mid{0.5 * (mesh.points[a].x + mesh.points[c].x),
                       0.5 * (mesh.points[a].y + mesh.points[c].y)};
      // A chord of a curved open side (a projected parallel) sags away from it by about
      // length^2 / (8 radius): 1% of the length allows radii down to 12.5 lengths. One
      // across a corner that turns by a, from one side to the other, passes up to
      // length sin(a/2) / 2 from it (19% at 45 degrees).
      const double length = std::hypot(mesh.points[c].x - mesh.points[a].x,
                                       mesh.points[c].y - mesh.points[a].y);
      if (on_open[a] && on_open[c]) {
        const PolylineIndex::Nearest nearest =
            open_lines.nearest(mid, tolerance_m + chord_share * length);
        if (nearest.line >= 0) {
          kinds[i] = BoundaryKind::open;
          const bool grouped =
              line_group && static_cast<std::size_t>(nearest.line) < line_group->size();
          groups[i] = grouped ? (*line_group)[nearest.line] : 0;
        }
      }
      ++(kinds[i] == BoundaryKind::open ? b.num_open_edges : b.num_land_edges);
    }
    b.loops.push_back(std::move(loop));
    b.edge_kind.push_back(std::move(kinds));
    edge_group.push_back(std::move(groups));
  }
  for (std::size_t l = 0; l < b.loops.size(); ++l) {
    const auto& loop = b.loops[l];
    const auto& kinds = b.edge_kind[l];
    const auto& groups = edge_group[l];  // a run ends where the group changes
    Ring ring;
    for (int v : loop) ring.push_back(mesh.points[v]);
    const bool island = signed_area(ring) < 0;
    const std::size_t n = loop.size();
    std::size_t first = n;  // an edge where the kind changes from the previous edge
    for (std::size_t i = 0; i < n; ++i)
      if (groups[i] != groups[(i + n - 1) % n]) {
        first = i;
        break;
      }
    if (first == n && kinds[0] == BoundaryKind::open && n >= 3) {
      // A loop open all round (a box of sea round an island): two segments that share
      // their ends, in every format alike, since SCHISM refuses an open boundary that
      // closes on itself.
      for (std::vector<int>& half : loop_halves(loop)) {
        BoundarySegment s;
        s.nodes = std::move(half);
        s.kind = BoundaryKind::open;
        s.island = island;
        s.loop = static_cast<int>(l);
        b.segments.push_back(std::move(s));
      }
      continue;
    }
    if (first == n) {
      BoundarySegment s;
      s.nodes = loop;
      s.kind = kinds[0];
      s.closed = true;
      s.island = island;
      s.loop = static_cast<int>(l);
      b.segments.push_back(std::move(s));
      continue;
    }
    for (std::size_t k = 0; k < n;) {
      const std::size_t i0 = (first + k) % n;
      BoundarySegment s;
      s.kind = kinds[i0];
      s.island = island;
      s.loop = static_cast<int>(l);
      s.nodes.push_back(loop[i0]);
      const int group = groups[i0];
      while (k < n && groups[(first + k) % n] == group) {
        s.nodes.push_back(loop[(first + k + 1) % n]);
        ++k;
      }
      b.segments.push_back(std::move(s));
    }
  }
  return b;
}

std::array<std::vector<int>, 2> loop_halves(const std::vector<int>& loop) {
  const auto half = loop.begin() + static_cast<std::ptrdiff_t>(loop.size() / 2);
  std::array<std::vector<int>, 2> out{std::vector<int>(loop.begin(), half + 1),
                                      std::vector<int>(half, loop.end())};
  out[1].push_back(loop.front());
  return out;
}

}  // namespace isoquad
