// Quality of a quad mesh against the paper's criteria and what ocean modellers check:
// angles, size conformance sqrt(area)/h, orientation deviation from the cross field,
// vertex regularity, Gmsh's eta, SCHISM's angle-ratio and aspect-ratio checks, D-Flow
// FM's orthogonality and smoothness.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "fields/cross_field.h"
#include "fields/sizing_field.h"
#include "mesh/background_mesh.h"
#include "quad/quad_mesh.h"

namespace isoquad {

// Per-element and per-vertex values (written to the outputs).
struct QuadMetrics {
  std::vector<double> min_angle_deg;    // #Q
  std::vector<double> max_angle_deg;    // #Q
  std::vector<double> aspect_ratio;     // #Q longest side / shortest (SCHISM's, checked at 5)
  std::vector<double> size_ratio;       // #Q sqrt(area) / h(centroid)
  std::vector<double> orientation_deg;  // #Q mean deviation of the 4 edges from the cross, [0, 45]
  std::vector<double> eta;              // #Q Gmsh's eta = 1 - max|90 - a| / 90
  std::vector<double> orthogonality;    // #Q the largest D-Flow FM orthogonality of its links
  std::vector<int> degree;              // #P number of quads at each vertex
  std::vector<char> boundary;           // #P 1 on the domain boundary
  std::vector<int> ideal_degree;        // #P 4 inside; on the boundary round(angle / 90)
  std::vector<double> irregular_corners;  // #Q corners whose degree is not their ideal one
};

struct QualitySummary {
  std::size_t num_quads = 0, num_vertices = 0, num_boundary_vertices = 0;
  std::size_t num_nonconvex = 0;  // not strictly convex counter-clockwise
  std::size_t num_boundary_crossings = 0;  // count_boundary_crossings: 0 unless it folds
  double share_angles_75_105 = 0, min_angle_deg = 0, max_angle_deg = 0;
  std::vector<int> angle_histogram;  // 36 bins of 5 degrees over [0, 180)
  double size_ratio_median = 0, share_size_08_125 = 0;
  std::vector<int> size_ratio_histogram;  // 30 bins of 0.05 over [0.25, 1.75), clamped
  double orientation_mean_deg = 0, orientation_p90_deg = 0;
  std::vector<int> orientation_histogram;  // 45 bins of 1 degree over [0, 45]
  double share_regular_interior = 0, share_regular_boundary = 0, share_regular_all = 0;
  std::vector<int> interior_degree_histogram;  // [d] interior vertices of degree d
  double eta_mean = 0, eta_min = 0;
  std::size_t schism_angle_ratio_violations = 0;  // min/max angle < 0.5
  std::size_t schism_aspect_violations = 0;       // longest / shortest edge > 5
  std::size_t schism_failures = 0;  // quads failing either: what SCHISM's fix_bad_quads splits
  // D-Flow FM's checks of its network (the UGRID .nc), over the links between two quads
  // (dflowfm_links): the orthogonality, which D-Flow FM refuses over 0.5 (its
  // CosPhiuTrsh: "network is not orthogonal"; Deltares advise 0.02 or less), and the
  // smoothness, the larger area over the smaller (advised 1.1 to 1.2).
  double dflowfm_orthogonality_max = 0, dflowfm_orthogonality_mean = 0;
  std::size_t dflowfm_orthogonality_violations = 0;                    // links over 0.5
  double dflowfm_share_orthogonality_002 = 0;                          // links at 0.02 or less
  double dflowfm_smoothness_max = 0, dflowfm_share_smoothness_12 = 0;  // at 1.2 or less
  // How closely the mesh follows the domain: its area against the domain's (the
  // background mesh's), and how far the domain's boundary lies from the mesh's. Each
  // boundary edge is a chord of the boundary chain between its two ends; its departure
  // is the largest distance from the chord of the chain's vertices between them, also
  // in sizes h (at that vertex).
  double mesh_area_m2 = 0, domain_area_m2 = 0;
  double boundary_departure_max_m = 0;
  Point2 boundary_departure_where{0, 0};  // the chain vertex farthest from its chord
  double boundary_departure_max_h = 0, boundary_departure_p95_h = 0;
  // Boundary edges that run backwards along the domain's boundary (boundary_backtracks;
  // 0 unless the mesh's boundary turns back over the coast). Such an edge's departure is
  // that of the stretch it runs back over.
  std::size_t num_boundary_backtracks = 0;
  // With --align (measure_line_following): the quads along the lines, and the mean
  // angle of their edges to the lines' crosses, degrees.
  std::size_t align_num_quads = 0;
  double align_deviation_mean_deg = 0;
};

// A quad's centre as D-Flow FM takes it for a cell of more than three corners (its cell
// "circumcentre", after Zhang, Schmidt and Perot 2002): from the corners' mean, sweeps
// over the edges shared with another quad (`shared[i]`: the edge from corner i), each
// moving the point a tenth of its distance to the edge's perpendicular bisector, until a
// sweep moves it under a millimetre (100 at most); the corners' mean with fewer than two
// shared edges. A centre outside the quad goes back along the line from the mean to
// where that line leaves it.
Point2 dflowfm_centre(const QuadMesh& mesh, int q, const std::array<bool, 4>& shared);

// D-Flow FM's orthogonality of a link: the |cosine| of the angle between its edge a-b and
// the segment joining the two cells' centres; 1 when the centres coincide.
double link_orthogonality(const Point2& a, const Point2& b, const Point2& centre_a,
                          const Point2& centre_b);

// For each quad, the quad across each side (side i from corner i; -1 on the boundary).
std::vector<std::array<int, 4>> quads_across(const QuadMesh& mesh);

// D-Flow FM's links: each edge shared by two quads (its net link) with its orthogonality,
// the |cosine| of the angle between the edge and the segment joining the two quads'
// centres (the flow link; 0 when they are perpendicular), and its smoothness, the larger
// of the two quads' areas over the smaller.
struct DflowfmLinks {
  std::vector<std::array<int, 2>> edge;   // vertex ids
  std::vector<std::array<int, 2>> quads;  // the two quads
  std::vector<double> orthogonality, smoothness;
};
DflowfmLinks dflowfm_links(const QuadMesh& mesh);
// The same over a network of quads and triangles (a mesh read from a file): cells are
// the quads (0 ..) then the triangles (#Q ..), a triangle's centre its circumcentre (as
// D-Flow FM takes it), moved back inside as a quad's is (where the segment from its
// centroid leaves it: an obtuse triangle's links then tilt), a quad's dflowfm_centre
// with the sides it shares with any cell.
DflowfmLinks dflowfm_links(const QuadMesh& mesh, const std::vector<std::array<int, 3>>& triangles);
// The summary's D-Flow FM figures from the links; with `per_quad`, each quad's largest
// orthogonality (#Q; cells past the quads ignored).
void summarize_dflowfm(const DflowfmLinks& links, QualitySummary& summary,
                       std::vector<double>* per_quad = nullptr);

QualitySummary measure_quality(const QuadMesh& mesh, const BackgroundMesh& background,
                               const SizingField& size, const CrossField& cross,
                               QuadMetrics* metrics = nullptr);

// How far the domain's boundary departs from the mesh's boundary `edges` (domain on the
// left; their ends on the background mesh's chains: chain and arc_m), into the summary's
// boundary_departure_* and num_boundary_backtracks. measure_quality does it for the
// quads' boundary edges; a mesh with triangles (read from a file) gives its outline's.
void measure_coast(const QuadMesh& mesh, const BackgroundMesh& background, const SizingField& size,
                   const std::vector<std::array<int, 2>>& edges, QualitySummary& summary);

// How closely the quads along lines follow them (--align): the quads whose centroid lies
// within half their own size (the square root of their area) of a line, and the mean
// over them of their four edges' angle to the nearest segment's cross, in degrees, into
// summary.align_num_quads and summary.align_deviation_mean_deg.
void measure_line_following(const QuadMesh& mesh, const std::vector<std::vector<Point2>>& lines,
                            QualitySummary& summary);

}  // namespace isoquad
