// Cross fields on the background mesh (paper section 2, input (c)): per vertex, a cross
// = four directions 90 degrees apart, stored as one representative angle. Computations
// average u = exp(4 i theta), which is invariant under 90-degree rotations, never angles.
#pragma once

#include <array>
#include <vector>

#include "core/geometry.h"
#include "mesh/background_mesh.h"

namespace isoquad {

struct CrossField {
  std::vector<double> angle_rad;  // #V cross angle per background vertex, in [0, pi/2)
};

// The smoothest cross field tangent to the boundary (the paper's reference [13]):
// u = exp(4 i theta); boundary vertices are fixed to the normalised sum of
// exp(4 i phi) over their two boundary edges (phi = edge direction), interior vertices
// minimise the cotan-weighted sum of |u_j - exp(4 i omega_ij) u_i|^2 over edges (one
// sparse Cholesky factorisation). A boundary vertex whose two edges meet at 45 deg
// (mod 90) has no preferred cross and is left free.
//
// omega_ij is the rotation the field is asked to make along edge ij: 0 gives the
// smoothest field; with sizes (size_m, #V) it is `conformal` times the integral of
// J grad log h (J: rotation by +90 degrees) along the edge, the rotation of a
// conformal grid whose cells have size h (log h + i theta is holomorphic). Where no
// smooth field follows it (the Laplacian of log h is large, or the boundary holds the
// field against it, as along a coast with sizes growing inland), the minimiser places
// singularities: where a quad mesh that follows the sizes needs its irregular vertices.
//
// `lines` (--align, align_lines.h) fixes more vertices inside, as the boundary's are.
struct FixedCrosses {
  std::vector<char> is_fixed;  // #V
  std::vector<double> uc, us;  // #V cos and sin of 4 theta (0 where not fixed)
};
CrossField boundary_aligned_cross_field(const BackgroundMesh& mesh,
                                        const std::vector<double>& size_m = {},
                                        double conformal = 0.0,
                                        const FixedCrosses* lines = nullptr);

// The boundary data of that field: per vertex, whether it is fixed, and its u there.
FixedCrosses boundary_crosses(const BackgroundMesh& mesh);

// theta = arg(u) / 4 for u = c + i s, as the cross's representative in [0, pi/2).
double cross_angle_of(double c, double s);

// The same cross at every vertex; angle_deg is any angle, reduced modulo 90 degrees.
CrossField constant_cross_field(const BackgroundMesh& mesh, double angle_deg);

struct Singularity {
  int triangle = -1;           // background triangle id
  int index_quarters = 0;      // index in units of 1/4 (+1: valence-3-like, -1: valence 5)
  Point2 position;             // triangle centroid, metres
};

// Triangles around which the cross turns: index = (sum over the 3 edges, in CCW order,
// of the smallest rotation modulo pi/2 from one vertex cross to the next) / (2 pi),
// reported in quarters. The indices of all triangles sum to 4 * (Euler characteristic)
// quarters for a boundary-aligned field. Ordered by triangle id.
std::vector<Singularity> cross_field_singularities(const BackgroundMesh& mesh,
                                                   const CrossField& field);

// The cross angle in [0, pi/2) at barycentric coordinates `bary` (weights of
// triangles[triangle][0..2]) inside `triangle`, interpolating u = exp(4 i theta).
double cross_angle_at(const BackgroundMesh& mesh, const CrossField& field, int triangle,
                      const std::array<double, 3>& bary);

// The smallest signed rotation taking cross angle `from_rad` to `to_rad`, in
// [-pi/4, pi/4).
double cross_rotation_rad(double from_rad, double to_rad);

}  // namespace isoquad
