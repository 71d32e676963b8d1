// The boundary of a quad mesh as closed loops of boundary edges, each edge flagged
// `open` (on the bbox of a water domain: the sea boundary of an ocean model) or `land`
// (a coastline), and cut into segments of one kind, as SCHISM and Gmsh want them.
#pragma once

#include <array>
#include <vector>

#include "core/geometry.h"
#include "quad/quad_mesh.h"

namespace isoquad {

enum class BoundaryKind { land, open };

const char* boundary_kind_name(BoundaryKind k);  // "land" or "open"

// A run of boundary edges of one kind: nodes[i] -> nodes[i+1], domain on the left. A
// whole loop of land is one closed segment (last node not repeated); a whole loop open is
// two segments that share their ends (loop_halves), as SCHISM needs them.
struct BoundarySegment {
  std::vector<int> nodes;
  BoundaryKind kind = BoundaryKind::land;
  bool closed = false;  // a whole loop
  bool island = false;  // on a clockwise loop (a hole of the domain)
  int loop = -1;
};

struct MeshBoundary {
  // Closed loops of boundary vertex ids (first not repeated), domain on the left: outer
  // loops counter-clockwise, holes clockwise. Loop and start vertex are deterministic
  // (ordered by their smallest vertex id).
  std::vector<std::vector<int>> loops;
  // loops[l][i] -> loops[l][i+1] kind.
  std::vector<std::vector<BoundaryKind>> edge_kind;
  std::vector<BoundarySegment> segments;  // loop by loop
  std::size_t num_open_edges = 0, num_land_edges = 0;
};

// `open_lines`: polylines (meshing CRS) whose neighbourhood within `tolerance_m` is open
// boundary (a water domain's bbox, or the lines of --open-boundary); an edge is open
// when both its ends are that close and its midpoint within `tolerance_m` plus
// `chord_share` of the edge's length (1%: a chord of a curved side; more for a chord
// across a corner of the lines). Without lines every edge is land. Throws
// Error(internal) when the boundary is not a set of simple loops.
// `line_group` (by line of open_lines; none: one group) cuts the open runs where the
// line nearest their edges' midpoints changes group: two open boundaries that meet
// (a river's and the sea's) stay two segments.
MeshBoundary extract_boundary(const QuadMesh& mesh, const PolylineIndex& open_lines,
                              double tolerance_m, double chord_share = 0.01,
                              const std::vector<int>* line_group = nullptr);

// A whole loop (its first node not repeated, at least 3) as two runs that share their
// ends: the first half of its nodes, then the rest back to its first node. For the
// models whose segments may not close on themselves (SCHISM's open boundaries; ADCIRC's
// as hgrid.gr3's).
std::array<std::vector<int>, 2> loop_halves(const std::vector<int>& loop);

}  // namespace isoquad
