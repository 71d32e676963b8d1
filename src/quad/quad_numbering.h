// The final numbering of a quad mesh's vertices and quads. The subdivision numbers tile
// corners first, then the midpoints of the tiles' sides, then their centres, so that
// neighbouring vertices lie a third of the mesh apart in the numbering; models that
// store a matrix or arrays by node prefer neighbours numbered close together, and
// OceanMesh2D (renum) and SMS renumber an ADCIRC grid that way before a run.
#pragma once

#include <vector>

#include "quad/quad_mesh.h"

namespace isoquad {

// New numbers: new_vertex[old] and new_quad[old].
struct QuadNumbering {
  std::vector<int> new_vertex, new_quad;
};

// The reverse Cuthill-McKee order of the vertices (Boost's, over the quads' edges; each
// connected part from a vertex of low degree far from the rest), and the quads in the
// order of their smallest new vertex number (ties in their old order). Deterministic.
QuadNumbering reverse_cuthill_mckee(const QuadMesh& mesh);

// Renumbers the mesh's vertices and quads (each quad keeps its first vertex and
// orientation) and every vertex id in `vertex_lists`.
void renumber(QuadMesh& mesh, const QuadNumbering& numbering,
              const std::vector<std::vector<int>*>& vertex_lists = {});

// The largest difference between the numbers of two vertices of a quad's side.
int vertex_bandwidth(const QuadMesh& mesh);

}  // namespace isoquad
