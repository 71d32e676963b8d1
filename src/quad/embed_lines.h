// Lines embedded in the quad mesh (--embed, with --align's lines): a path of the mesh's
// edges along each line, its vertices moved onto the line, so that a breakline, a dyke's
// crest or a thin dam is a chain of edges of the mesh, as Gmsh's embedded curves are.
// --align has already laid rows of tiles along the lines; the barycentric subdivision
// then puts a chain of edges near each (through the tiles' centres and the midpoints of
// the meta-edges between them), which this moves onto the line.
#pragma once

#include <cstddef>
#include <vector>

#include "core/geometry.h"
#include "fields/cross_field.h"
#include "fields/sizing_field.h"
#include "mesh/background_mesh.h"
#include "quad/quad_mesh.h"
#include "quad/smooth_quads.h"

namespace isoquad {

struct EmbedParams {
  // Rounds of moving the path's vertices onto the line, each followed by angle sweeps of
  // the vertices next to the path (those on it held) where a move would have made a
  // quad non-convex; a vertex that cannot move the whole way moves half of it.
  int rounds = 6;
  int sweep_iterations = 10;
  // Of a path's edges, one that runs this share of its length or farther from the line
  // (the mean over its ends and middle) is not taken: the path stays near the line.
  double max_offset = 1.0;
  // A line's vertex where it turns by this much or more (radians; 0.02 ~ 1 degree) is
  // the target of the path's vertex nearest it, so that the edges follow the bend.
  double corner_turn_rad = 0.02;
  // No move while embedding makes a quad's smallest turning sine (quad_convexity) less
  // than this, or less than it was: 0.5 keeps corners in [30, 150] degrees. The
  // smoothing's lift bound (0.26, 15 degrees) instead, on a sine-shaped line of 5 km
  // amplitude and 40 km wavelength meshed at 2 km: 84.2% of the line spanned by edges
  // on it against 81.9%, but corners of 44.3 and 155.4 degrees against 50.2 and 148.7
  // (without --embed: 50.4 and 145.2).
  double min_turn_sine = 0.5;
  // The same bound for a boundary vertex sliding along the coast (to a point near it, or
  // where a line meets it): the smoothing's lift bound (0.26, 15 degrees). Its quads lie
  // along a coast that bends, their corners near 30 or 150 degrees already. 40 tide
  // gauges on Brittany's coast at hmax 8 km: 38 reach their coast point against 35 at
  // 0.5, the mesh's smallest angle 17.5 against 18.1 degrees, angles in range 87.7% both
  // (87.8% without points), 318 quads under SCHISM's angle ratio against 317 (315).
  double coast_min_turn_sine = 0.26;
  // The lines are embedded where they lie farther than this share of the size h from
  // the domain's boundary (with a sizing field): nearer, the boundary's row of quads
  // holds them (a country's border drawn along its coast, a line's last stretch to the
  // shore). Without it, every country's borders at 1:50m over western Europe at hmax
  // 30 km: 90.1% -> 86.9% of angles in range and 15 -> 40 quads over SCHISM's aspect
  // ratio, interior vertices pulled onto the coast.
  double coast_share = 0.5;
  // A vertex is on the line when it lies within this (metres) of it.
  double on_line_m = 1e-6;
  // A stretch of line between two consecutive path vertices on it counts as spanned by
  // their edge when it stays within this share of the edge's length of it (a curve's
  // chord: the 5 km sine at 2 km quads departs by up to 4%; a line zigzagging within a
  // quad, by more than the edge's length).
  double max_chord_share = 0.1;
  // --embed-points: a point inside the domain within this share of the boundary's edges
  // (those of the boundary vertex nearest where it would go) from its boundary gets a
  // boundary vertex, slid along the coast to the boundary's point nearest it: a tide
  // gauge on the shore. An interior vertex there would leave a quad thinner than
  // SCHISM's aspect ratio of 5 between it and the coast.
  double point_coast_share = 0.2;
  // The same for a point outside the domain within this share of the boundary's edges
  // from it (a station a little inland of a coast drawn coarser than the real one);
  // farther, it gets no vertex.
  double point_land_share = 1.0;
  // And, either side, a point within this distance (metres) of the coast: the domain's
  // simplification tolerance (the mesh's job sets it), within which a point on the
  // coast as drawn lies off the coast as meshed.
  double point_coast_m = 0.0;
  // A point inside whose interior vertex stopped short of it goes to the coast after all
  // when it lies within this share of the boundary's edges from it (the boundary's row
  // of quads).
  double point_retry_share = 0.5;
  // A point within this share of the quads' edges there of a point before it in the file
  // shares that point's vertex (a station given twice, or two a quad cannot tell apart):
  // two vertices that near would leave a quad thinner than SCHISM's aspect ratio of 5.
  double point_merge_share = 0.2;
};

// A point of --embed-points and its vertex.
struct EmbeddedPoint {
  int vertex = -1;     // -1: none (outside the domain and not near it, or no vertex left)
  bool coast = false;  // a boundary vertex, for a point near the coast
  Point2 target;       // where the vertex goes: the point, or the coast's point nearest it
  int shares = -1;     // the earlier point whose vertex (and target) it shares, if any
};

struct EmbedStats {
  bool requested = false;         // embed_lines ran
  std::size_t num_runs = 0;       // pieces of the lines inside the mesh given a path
  std::size_t num_edges = 0;      // mesh edges on those paths
  std::size_t num_vertices = 0;   // vertices of the paths (interior and boundary)
  std::size_t num_on_line = 0;    // of them, on their line at the end
  std::size_t num_boundary = 0;   // of them, on the domain's boundary
  // Boundary vertices slid along the coast to where a line meets it (a path's end).
  std::size_t num_coast_ends = 0;
  double max_vertex_off_m = 0.0;  // the farthest interior path vertex from its line
  // The lines' length inside the mesh; of it, the length between consecutive path
  // vertices on the line that their edge spans (EmbedParams::max_chord_share); and how
  // far the line departs from those edges (where it curves, the edges are its chords).
  double line_length_m = 0.0;
  double covered_length_m = 0.0;
  double max_chord_off_m = 0.0;
  // Runs too short for a path (both ends nearest one vertex) or with no path near them.
  std::size_t num_skipped = 0;
  // --embed-points: the points given a vertex, those it reached (within on_line_m of
  // its target), and the farthest one stayed from its target; of them, those given a
  // boundary vertex (EmbedParams::point_coast_share) and the farthest such point from
  // its target on the coast; and the points outside the domain not near it (no vertex).
  std::size_t num_points = 0;
  std::size_t num_points_on = 0;
  double max_point_off_m = 0.0;
  std::size_t num_points_coast = 0;
  double max_coast_distance_m = 0.0;
  std::size_t num_points_outside = 0;
  // Points sharing an earlier point's vertex (EmbedParams::point_merge_share), and the
  // farthest such point from the target it shares.
  std::size_t num_points_shared = 0;
  double max_shared_distance_m = 0.0;
};

// A path of edges on a line: its vertex ids, and the index of its line in `lines`.
struct EmbeddedPath {
  int line = 0;
  std::vector<int> vertices;
};

// Moves, for each line's runs inside the mesh, a path of edges onto the line; every quad
// stays convex (EmbedParams::min_turn_sine), and a boundary vertex moves only where a
// path ends next to the coast that its line meets: along the coast, to that point,
// between its boundary neighbours. `paths` gets each run's path. Each of `points` takes
// the nearest interior vertex that no path holds, moved onto it the same way, as Gmsh's
// embedded points (a station, a river's source), or, near the coast
// (EmbedParams::point_coast_share), the boundary vertex nearest the coast's point
// nearest it, slid there; a point outside the domain and not near it gets none.
// `point_vertices` gets what each point got.
EmbedStats embed_lines(const BackgroundMesh& bg, QuadMesh& m,
                       const std::vector<std::vector<Point2>>& lines, const EmbedParams& embed,
                       const SmoothParams& params, const CrossField* cross, const SizingField* size,
                       std::vector<EmbeddedPath>* paths = nullptr,
                       const std::vector<Point2>& points = {},
                       std::vector<EmbeddedPoint>* point_vertices = nullptr);

}  // namespace isoquad
