// The all-quadrangle mesh (paper, sections 2.6 and 2.7) as flat arrays, with what
// smoothing needs to slide boundary vertices along the domain boundary.
#pragma once

#include <array>
#include <vector>

#include "core/geometry.h"
#include "mesh/background_mesh.h"

namespace isoquad {

struct QuadMesh {
  std::vector<Point2> points;            // #P positions, metres (meshing CRS)
  std::vector<std::array<int, 4>> quads;  // #Q vertex ids, counter-clockwise
  std::vector<int> chain;                // #P boundary chain (BackgroundMesh::chains) or -1
  std::vector<double> arc_m;             // #P arc length along that chain
  std::vector<char> fixed;               // #P 1 for domain corners: never moved
};

// The point at arc length `arc_m` (taken modulo the chain length) along a boundary chain.
Point2 chain_point(const BackgroundMesh& mesh, const BoundaryChain& chain, double arc_m);

// Convexity of a quad: the smallest sine of its four turning angles (positive for every
// corner of a strictly convex counter-clockwise quad, in (-1, 1]); -1 when a side is
// shorter than a millionth of the longest (a degenerate quad, whatever its turns).
double quad_convexity(const Point2& a, const Point2& b, const Point2& c, const Point2& d);
double quad_convexity(const QuadMesh& mesh, int q);
// The mean of the quad's four vertices.
Point2 quad_centroid(const QuadMesh& mesh, int q);

// Pairs of boundary edges (edges of one quad only) that cross or touch other than at a
// shared end: with every quad convex and counter-clockwise, the mesh then folds over
// itself (quads overlap) although no quad is wrong on its own, as when the chord of one
// bank of an inlet narrower than the quads cuts across the other bank's quads. Returns
// the number of such pairs; `where` gets a point of the first (in edge order).
std::size_t count_boundary_crossings(const QuadMesh& mesh, Point2* where = nullptr);
// The pairs themselves: (a, b, c, d) for boundary edges a->b and c->d.
std::vector<std::array<int, 4>> boundary_crossings(const QuadMesh& mesh);
// The boundary edges (a, b), directed with the mesh on their left.
std::vector<std::array<int, 2>> boundary_edges(const QuadMesh& mesh);
// Whether two boundary edges meet other than at a shared end (the test above).
bool boundary_edges_meet(const QuadMesh& mesh, const std::array<int, 2>& e,
                         const std::array<int, 2>& f);

// Which boundary edges (as boundary_edges gives them) run backwards along their chain:
// the mesh's boundary, walked with the mesh on its left, turns back over a stretch of
// the domain's (around the mouth of an inlet narrower than the quads, say) instead of
// following it once round. Per boundary loop whose vertices are all on one chain, the
// forward arc spans of its edges add up to the chain's length once, plus a length for
// each edge that goes back; those are the loop's longest forward spans.
std::vector<char> boundary_backtracks(const QuadMesh& mesh, const BackgroundMesh& background,
                                      const std::vector<std::array<int, 2>>& edges);

// How far the boundary chain between the two ends of boundary edge a->b (directed with
// the mesh on its left, as boundary_edges gives them, so that it runs the chain's way)
// lies from the edge: the largest distance of the chain's vertices between them, and
// that vertex (a background vertex id; -1 when none lies between or the ends are on
// different chains).
struct ChordDeparture {
  double distance_m = 0.0;
  int vertex = -1;
};
ChordDeparture chord_departure(const QuadMesh& mesh, const BackgroundMesh& background, int a, int b);

// The four interior angles in degrees.
std::array<double, 4> quad_angles_deg(const QuadMesh& mesh, int q);
double quad_area(const QuadMesh& mesh, int q);
// The longest side over the shortest (SCHISM's aspect ratio; infinite with a side of 0).
double quad_aspect(const QuadMesh& mesh, int q);

// SCHISM's checks of a quad, as its manual gives them (and its fix_bad_quads splits the
// quads that fail them into two triangles): the smallest interior angle under half the
// largest, and the longest side over five times the shortest.
constexpr double kSchismAngleRatio = 0.5;
constexpr double kSchismAspectRatio = 5.0;
bool fails_schism_angle_ratio(const std::array<double, 4>& angles_deg);
bool fails_schism_aspect_ratio(double aspect);
bool fails_schism_checks(const QuadMesh& mesh, int q);

}  // namespace isoquad
