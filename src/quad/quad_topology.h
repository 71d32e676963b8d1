// The quad mesh's vertex neighbourhoods, and the vertex moves that keep its quads convex,
// shared by the smoothing sweeps (quad_sweeps.h), the local repairs (quad_repairs.h) and
// the smoothing's driver (smooth_quads.h).
#pragma once

#include <array>
#include <vector>

#include "mesh/background_mesh.h"
#include "quad/quad_mesh.h"

namespace isoquad {

// Who is next to whom in a quad mesh; built again after any change of its quads.
struct QuadTopology {
  std::vector<int> quad_start, quad_items;              // CSR vertex -> incident quads
  std::vector<std::vector<int>> neighbours;             // vertex -> edge-adjacent vertices
  std::vector<std::array<int, 2>> boundary_neighbours;  // along the boundary, -1 if none
};

QuadTopology quad_topology(const QuadMesh& m);
// The same into `t`, reusing its memory (for callers that rebuild it often).
void rebuild_quad_topology(const QuadMesh& m, QuadTopology& t);

// Points in lexicographic order (x, then y).
bool point_less(const Point2& a, const Point2& b);

// The smallest quad_convexity of the quads around vertex v.
double worst_convexity(const QuadMesh& m, const QuadTopology& t, int v);

// The quads with quad_convexity at most min_convexity.
int count_nonconvex(const QuadMesh& m, double min_convexity);

// Signed arc distance from a to b along a closed chain of length len, in (-len/2, len/2].
double arc_delta(double a, double b, double len);

// Whether boundary vertex v lies strictly between its two boundary neighbours along its
// chain (false when it has not two on its chain).
bool between_boundary_neighbours(const BackgroundMesh& bg, const QuadMesh& m, const QuadTopology& t,
                                 int v);

// Moves vertex v to `target` (and arc `arc` on the boundary) when the quads around it
// stay more convex than min_convexity (or at least as convex as they were); returns
// whether it moved.
bool try_move(QuadMesh& m, const QuadTopology& t, int v, const Point2& target, double arc,
              double min_convexity);

// The arc-length midpoint of boundary vertex v's two boundary neighbours, when they lie
// on its chain on both sides of it.
bool boundary_target(const BackgroundMesh& bg, const QuadMesh& m, const QuadTopology& t, int v,
                     Point2& target, double& arc);

}  // namespace isoquad
