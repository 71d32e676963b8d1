// The background triangle mesh M of the paper (section 2.2): a constrained Delaunay
// triangulation of the domain boundary, refined (Ruppert/Chew, CGAL Mesh_2) until every
// triangle is isotropic (min angle bound) and no longer than a sizing oracle asks.
// Every later stage works on the flat arrays returned here, never on CGAL types.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <vector>

#include "core/geometry.h"

namespace isoquad {

struct BackgroundMeshParams {
  // Lower bound on triangle angles. 20.7 deg (B = sin^2 = 0.125) is CGAL's safe maximum:
  // above it Delaunay refinement may not terminate.
  double min_angle_deg = 20.7;
  // Max triangle edge length at a point, metres (e.g. 0.1 * tile size 2h(x)). Must be
  // > 0 everywhere in the domain. Evaluated at triangle centroids: a triangle is refined
  // while its longest edge exceeds max_edge_m(centroid).
  std::function<double(const Point2&)> max_edge_m;
  // An input ring vertex whose |turning angle| exceeds this is a corner.
  double corner_angle_deg = 30.0;
  // Refinement gives up (Error(meshing)) past this many vertices. Input vertices that are
  // very close together force tiny triangles (refinement then runs away): simplify the
  // domain beforehand (simplify_domain) at a tolerance tied to the sizing.
  std::size_t max_num_vertices = 20000000;
  // Seed the inside with a quadtree of points at the requested density before
  // refinement (same guarantees, several times faster on large meshes).
  bool seed_interior = true;
  // Told the share of the work done, in [0, 1], as the steps end (seeds, refinement,
  // arrays); may be empty.
  std::function<void(double)> progress;
};

// One closed boundary chain per domain ring: the ring with every Steiner point that
// refinement inserted on it.
struct BoundaryChain {
  int polygon = -1;  // index in Domain::polygons
  int ring = -1;     // 0 = outer ring, k > 0 = hole k-1
  // #C background vertex ids, closed chain in ring orientation (domain on the left),
  // first not repeated. vertices[0] is the ring's first input vertex.
  std::vector<int> vertices;
  std::vector<double> arc_length_m;  // #C cumulative arc length at each vertex, from 0
  double length_m = 0.0;             // total length of the closed chain
  // #C signed turning angle of the input ring at each chain vertex, degrees, positive =
  // left turn = convex (domain on the left); 0 at Steiner points.
  std::vector<double> turning_angle_deg;
  // #C 1 where |turning_angle_deg| > corner_angle_deg (convex or reflex by the sign of
  // the turning angle), else 0.
  std::vector<char> is_corner;
  // #C at corners, the signed turning that made them corners (tag_corners: the turning
  // within one tile; here: turning_angle_deg), 0 elsewhere. Negative = reflex.
  std::vector<double> corner_turning_deg;
  // #C 1 where the vertex is an input ring vertex, 0 for Steiner points.
  std::vector<char> is_input_vertex;
};

struct BackgroundMesh {
  std::vector<Point2> points;                 // #V positions, metres
  std::vector<std::array<int, 3>> triangles;  // #F vertex ids, counter-clockwise
  // #F neighbours[f][i] = the face across the edge opposite triangles[f][i] (the edge
  // triangles[f][i+1] -> triangles[f][i+2]), -1 on the domain boundary.
  std::vector<std::array<int, 3>> neighbours;
  // One per domain ring in ring order: polygon 0 outer, its holes, polygon 1 outer...
  std::vector<BoundaryChain> chains;
  std::vector<int> boundary_chain_of_vertex;  // #V chain index, -1 for interior vertices
};

// Builds the refined background mesh of `domain` (planar, metres; outer rings CCW, holes
// CW, rings open, see orient_polygon). Holes stay empty. The output is a deterministic
// function of the input. Throws Error(input) when rings are degenerate, wrongly
// oriented, cross, touch or share vertices, or nest inconsistently (a polygon inside
// another, a hole outside its polygon); Error(meshing) when refinement exceeds
// params.max_num_vertices or the oracle returns a non-positive size; Error(internal) if
// the result fails validation (a bug).
BackgroundMesh build_background_mesh(const Domain& domain, const BackgroundMeshParams& params);

// Incident triangles of every background vertex, as compressed rows: those of vertex v
// are triangles[offset[v]] .. triangles[offset[v + 1] - 1], in increasing id order.
struct VertexTriangles {
  std::vector<int> offset;  // #V + 1
  std::vector<int> triangles;
};
VertexTriangles vertex_triangles(const BackgroundMesh& mesh);

// The sum of the triangles' areas: the domain's area, which they cover exactly.
double area(const BackgroundMesh& mesh);

// Throws Error(internal) unless every triangle is counter-clockwise with positive area,
// neighbours are symmetric, and the boundary edges (neighbour -1) are exactly the chain
// edges, each oriented with the domain on its left.
void validate_background_mesh(const BackgroundMesh& mesh);

}  // namespace isoquad
