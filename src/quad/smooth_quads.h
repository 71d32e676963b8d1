// Smoothing of the quad mesh (paper, section 2.7) and the convexity guarantee: Laplacian
// smoothing where boundary vertices slide along the domain boundary and corners stay
// fixed, no move allowed to make a quad non-convex; then untangling of any quad that is
// still not strictly convex. The sweeps are in quad_sweeps.h, the local repairs of the
// topology in quad_repairs.h; smooth_quads runs them in order.
#pragma once

#include "core/progress.h"
#include "fields/cross_field.h"
#include "fields/sizing_field.h"
#include "mesh/background_mesh.h"
#include "quad/quad_mesh.h"

namespace isoquad {

struct SmoothParams {
  int iterations = 10;             // Laplacian sweeps
  int untangle_iterations = 200;   // sweeps of the convexity repair
  double min_convexity = 0.02;     // a quad is accepted when quad_convexity() > this (~1.1 deg)
  // No untangling move shortens an edge at the moving vertex below this share of its
  // longest edge (or below its shortest, when that is already shorter). The convexity
  // measure ignores side lengths, and the untangling, the lift below and the repairs
  // after a sliver's collapse slid boundary vertices to within metres of a corner:
  // France automatic at 28 km, a side of 0.04 h, 48 times shorter than its quad's
  // longest; the Baltic at 1:10m, 44 quads with a side under a hundredth of their longest
  // after the repairs instead of 10 before them. With the floor, aspect_log_weight and
  // resweep_iterations, over 12 cases, quads with a side under 0.05 h: 1 to 8 -> 0 in 10
  // cases, France default 6 -> 2, the Baltic 81 -> 19 (those at near-pinches of its
  // domain, from the subdivision).
  double untangle_min_side = 0.1;
  // Untangling slides a boundary vertex that lies between its two boundary neighbours
  // only as far as stays between them; false: anywhere along its chain, as before
  // 2026-12-02. Sliding past a neighbour turns the mesh's boundary back over the coast
  // (boundary_backtracks) or folds it: 7 of 254 countries at 1:10m had such edges (India
  // kept a 13.8-degree quad by it), the Mediterranean at 1:10m with hmin 1 km four.
  bool untangle_keeps_boundary_order = true;
  int flip_rounds = 5;  // rounds of quad edge flips when untangling is not enough
  // Rounds of diagonal collapses when flips are not enough either (the last resort before
  // the caller retries the tiling): see SmoothStats::num_collapses.
  int collapse_rounds = 3;
  // Then quads still non-convex are tried one at a time, each possible collapse in turn
  // (at most this many collapses tried), then each of its edge flips followed by the
  // untangling sweeps (at most as many flips; none with flip_rounds 0). Quads on the
  // crossing edges of a fold are tried the same way.
  int collapse_tries = 20;
  // Rounds of sliding the ends of crossing boundary edges (a mesh folded where an inlet
  // is narrower than its quads) along the boundary.
  int unfold_rounds = 10;
  // Then, every quad convex, the flattest quads (sine of the worst corner turn at most
  // this; 0.26 ~ 15 degrees) are tried one by one for a diagonal collapse, or failing
  // that an edge flip with a neighbour, that makes the mesh's flattest quad less flat
  // (at most sliver_tries of them; 0 disables it). With the flips: France at hmax 24 km
  // --simplify 800 5.5 -> 16.3 degrees, Brittany's water at hmax 7 km 2.2 -> 11.6.
  // Sea areas of Natural Earth's 1:10m land, smallest angle before -> after: the Aegean
  // 4.0 -> 15.2 degrees, the Danish straits 4.0 -> 14.5, the Adriatic 2.6 -> 15.3,
  // Scotland 8.7 -> 14.2, the Gulf of Finland 7.8 -> 15.4 (the Mississippi delta keeps
  // 8.3: its collapse would fold the mesh). 0.26 instead of 0.17 (10 degrees), since
  // 2026-12-02: of 12 cases only the Baltic at 1:10m changed, smallest angle 11.0 ->
  // 14.3 degrees (the United States at 1:50m 12.1 -> 15.3; at 1:10m, countries with a
  // corner under 15 degrees 22 -> 4); at 0.34 (20 degrees) some meshes lose a small
  // angle for a large one (Chile at 1:50m 30.0 -> 25.2). 60 tries instead of 20: the
  // same meshes on those cases and both country batches; the Arctic Ocean at 1:10m 21
  // slivers removed instead of 9, smallest angle 10.0 -> 15.1.
  double sliver_convexity = 0.26;
  int sliver_tries = 60;
  // Failing those, a sliver that ends a thin row of quads (joined by their short sides,
  // each under a quarter of its long ones, boundary to boundary, at most this many
  // quads) has the row merged away (0: never). Croatia at 1:10m: 7.2 -> 19.0 degrees.
  int sliver_row_max = 8;
  // Slivers still left at the end (after the sweeps again) get the sliver pass once
  // more, each try with the interior vertices of the quads next to the change first
  // moved to the middle of their neighbours (false: never). The Alboran Sea's box at
  // 1:10m (README): a quad of 13.9 degrees at a cape's tip, in two quads where it needs
  // three, mended by a diagonal collapse that leaves the tip in four; smallest angle
  // 13.9 -> 23.3 degrees, largest 166.4 -> 162.1.
  // (Tried with the first sliver pass instead, it also changed meshes whose slivers the
  // sweeps after would have mended: China at 1:10m, smallest angle 19.5 -> 17.8.)
  bool sliver_relocate = true;
  // Then quads whose longest side is at least thin_aspect times their shortest (SCHISM's
  // aspect check is 5), the thinnest first, at most thin_tries of them, are tried one by
  // one the same way, a change kept when fewer such quads are left and fewer of them and
  // quads under min_angle_ratio together, no more slivers, no flatter quad and no smaller
  // angle (quad_repairs.cpp's collapse_thin; thin_aspect 0: never). They are mostly
  // quads fanned round a boundary vertex or squeezed at a notch of the coast. France
  // automatic at 28 km: 25 -> 19 quads over 5, 302 -> 298 under the angle ratio, the
  // other measures unchanged, smoothing 0.39 -> 0.49 s; the 241 countries at 1:50m: 587
  // -> 537 and 25,285 -> 25,266, no country's smallest angle changed (Russia 80 -> 75,
  // its smoothing's time unchanged within the noise, with thin_patch_first).
  double thin_aspect = kSchismAspectRatio;
  int thin_tries = 20;
  // Each collapse and flip of the thin pass tried first on a patch of the mesh round the
  // quad, and on the whole mesh only when the patch says it would be kept (false: on the
  // whole mesh only). The same meshes; the patch saves rebuilding the whole mesh's
  // topology and counts for every change that is undone.
  bool thin_patch_first = true;
  // Then a boundary vertex in two quads only at a reflex corner of the domain (their
  // corners there sum to over 200 degrees), with an interior vertex in four quads nearer
  // than this share of its longest other edge: that vertex stands in for the third quad
  // the corner lacks, and the two quads have a side of metres (South Korea at 1:10m:
  // 2.5 m next to 2.2 km; the Baltic, 34 m). The four quads round the interior vertex
  // become three fanned from the corner, kept when the mesh is then convex, no flatter
  // and no more folded (0: never). The Arctic Ocean at 1:10m: at 0.05, 12 corners,
  // quads with a side under 0.05 h 55 -> 43, angles in range 77.1 -> 77.0%; at 0.1, 76
  // corners for the same 43, and 76.7%.
  double doubled_corner_side = 0.05;
  // Before the convexity repair, quads flatter than this (sine of the worst corner
  // turn; 0.26 ~ 15 degrees) get `lift_iterations` sweeps of the same search.
  double lift_convexity = 0.26;
  int lift_iterations = 10;
  // Field-aligned sweeps after the Laplacian ones (when the fields are given): every
  // regular interior vertex moves towards where its four neighbours want it, one size
  // h away along the cross field axis that each edge follows; boundary vertices slide
  // to make their inward edge orthogonal to the boundary. 0 disables them.
  int aligned_iterations = 20;
  double aligned_step = 0.5;  // fraction of the way to the target per sweep
  // The edge length an aligned sweep aims at: this share of the vertex's current mean
  // edge length, the rest h. The tiling has sized the quads already; where the size and
  // cross fields are not compatible (graded sizes), pulling every edge to exactly h
  // squeezes angles. France automatic at about 4,500 quads: 0 / 0.5 / 1 give 69.4 /
  // 71.7 / 72.5% of angles in [75,105] and 76.2 / 76.3 / 75.2% of sizes in range.
  double aligned_keep_length = 0.5;
  // Angle sweeps, after the aligned ones: each free vertex (boundary vertices along the
  // boundary) takes the best of its moves of angle_step times its shortest edge when
  // that lowers the sum over its quads' corners of (angle - 90 deg)^2 (rad^2), plus
  // angle_area_weight (log(area / h^2))^2 per quad (h at the quad's centroid; without a
  // sizing field, the area before the sweeps), plus angle_orientation_weight (rotation
  // of each of its edges from the cross)^2 (with the cross field); the second half of
  // the sweeps takes steps 0.3 as long. 0 disables them. France automatic at about
  // 4,500 quads, before -> after: angles in [75,105] 71.4% -> 75.9%, sizes in
  // [0.8,1.25] 75.9% -> 85.3%, orientation 14.9 -> 12.9 deg. Area weight 1.5: 74.8%,
  // 88.6%; 0.5: 77.0%, 78.6%. Against the areas before the sweeps instead of h^2
  // (weight 3): 77.1%, 74.1%.
  int angle_iterations = 20;
  double angle_step = 0.1;
  double angle_area_weight = 1.0;
  double angle_orientation_weight = 1.5;
  // The squares alone pull every corner of a degree-5 vertex to 72 degrees and of a
  // degree-3 vertex to 120, all out of [75,105], when four corners of the five could
  // reach 75 and one take the rest. So the sweeps' energy also counts, smoothly, the
  // corners and sizes out of range: per corner angle_range_weight * s((|angle - 90| -
  // angle_range_deg) / angle_range_softness_deg), per quad size_range_weight *
  // s((|log(area / area0)| - size_range_log_area) / size_range_softness), s the logistic
  // function (0 well inside, 1 well outside); 0.40 is a margin inside the size range
  // [0.8,1.25] of sqrt(area) / h (|log(area / h^2)| <= 0.446). Counting corners out of
  // range, one corner of a quad may give way to the other three; so the quads whose
  // smallest angle is under min_angle_ratio times their largest (SCHISM's check) are
  // counted too, angle_ratio_weight each. France automatic at about 4,500 quads, with 10
  // sweeps before and 20 now: angles in [75,105] 80.3% -> 86.3%, sizes in [0.8,1.25]
  // 85.8% -> 86.9%, orientation 12.5 -> 12.6 deg, quads under SCHISM's ratio 467 -> 322.
  // Without the ratio term (orientation weight 1; sweeps in vertex order): 87.0%, 88.7%,
  // 12.7 deg, 554 quads; without the size term either, 86.5% and 82.2% of sizes.
  double angle_range_weight = 0.2;
  double angle_range_deg = 14.0;
  double angle_range_softness_deg = 1.0;
  double size_range_weight = 0.3;
  double size_range_log_area = 0.40;
  double size_range_softness = 0.03;
  double angle_ratio_weight = 0.5;
  double min_angle_ratio = kSchismAngleRatio;
  double angle_ratio_softness = 0.02;
  // Per boundary vertex, coast_weight * (departure / length)^2 over its two boundary
  // edges (chord_departure: how far the coast between an edge's ends lies off it), so
  // that boundary vertices slide towards the coast's headlands and inlets' heads. 0: off.
  double coast_weight = 0.0;
  // And no move makes a corner sharper than this, or one already sharper sharper still:
  // with the counts, one corner of a quad could otherwise give way to the others (Natural
  // Earth's 1:50m Peru: smallest angle 28.9 -> 19.7 degrees without it, 30.0 with it,
  // the same 92.6% of angles in range).
  double angle_floor_deg = 30.0;
  // And quads whose longest side is over max_aspect times their shortest, smoothly
  // (aspect_weight * s((log(longest / shortest) - log(max_aspect)) / aspect_softness)):
  // SCHISM checks that ratio against 5, and nothing else in the energy keeps a side from
  // shrinking while the quad's angles and area stay good. Measured on 12 cases (France
  // at three sizes, Corsica, Brittany's land and water, five countries at 1:50m or
  // 1:10m, the Baltic) against no such term: quads over SCHISM's 5 halved (France
  // automatic at 28 km 82 -> 40, Indonesia at 1:50m 85 -> 35, the Baltic 984 -> 648),
  // angles in range 0.1 point lower (at most 0.2), orientation up to 0.04 deg more, the
  // smallest angle the same or larger (France 20.3 -> 22.2 deg). Weight 1: 29 quads over
  // the ratio on France, but its smallest angle 16.2 deg.
  double aspect_weight = 0.5;
  double max_aspect = 4.0;
  double aspect_softness = 0.1;
  // The logistic count is flat beyond ratios of about 5, so nothing kept a side of a
  // quad over the ratio from shrinking further: plus aspect_log_weight * (log(longest /
  // shortest) - log(max_aspect)) over it.
  double aspect_log_weight = 0.5;
  // The angle sweeps again after the repairs, this many, on the vertices the repairs
  // moved and their neighbours, with convexity at least lift_convexity (0: none).
  // France automatic: angles in [75,105] 86.9 -> 87.1%, smallest angle 16.4 -> 20.1
  // deg (after the untangling's side floor), quads under SCHISM's angle ratio 316 -> 305.
  int resweep_iterations = 10;
  // Last, the links between two quads whose D-Flow FM orthogonality (dflowfm_links) is
  // over this: the interior corners of their quads move, in rounds, where that lowers the
  // largest orthogonality of the links of the quads round them, the quads kept as convex
  // as the lift leaves them (--max-orthogonality; 0: none). D-Flow FM refuses a network
  // with a link over 0.5. France automatic at 0.45: 33 links over 0.5 -> 2 (both between
  // quads whose every corner is on the coast), angles in [75,105] 87.4 -> 86.9%, quads
  // under SCHISM's angle ratio 318 -> 333.
  double max_orthogonality = 0;
  int orthogonality_rounds = 10;
  // Threads for the sweeps (0: the machine's, at most 4). The angle sweeps move the
  // vertices colour by colour, no two vertices of a quad of the same colour, so that a
  // colour's moves are independent: the mesh is the same with any number of threads.
  int threads = 0;
};

struct SmoothStats {
  int num_nonconvex_before = 0;  // after subdivision, before smoothing
  int num_nonconvex_after = 0;   // 0 unless the repair failed
  int num_untangle_sweeps = 0;
  int num_flips = 0;             // quad edge flips (local topology changes), slivers' too
  // Quads removed by merging the two ends of a diagonal (one of them inside the domain),
  // which drops a vertex, to make every quad convex or to unfold the mesh: the mesh's
  // vertex ids are renumbered.
  int num_collapses = 0;
  // The same, of slivers (SmoothParams::sliver_convexity), and thin rows of quads merged.
  int num_sliver_collapses = 0;
  // Reflex corners given their third quad (SmoothParams::doubled_corner_side), each
  // dropping a vertex and a quad.
  int num_corner_splits = 0;
  // Thin quads (SmoothParams::thin_aspect) mended by a collapse, a flip or a row merged.
  int num_thin_repairs = 0;
  // Links over max_orthogonality before and after its rounds.
  int num_orthogonality_before = 0, num_orthogonality_after = 0;
};

// Smooths in place. Does not throw (but for a cancelled `progress`); the caller decides
// what a remaining non-convex quad or fold (count_boundary_crossings) means (the
// pipeline retries the tiling, then stops with Error(internal)). Collapses drop
// vertices: ids may be renumbered. With `size` and `cross`, the field-aligned sweeps run
// too. Reports progress as stage "smooth", sweep by sweep.
SmoothStats smooth_quads(const BackgroundMesh& background, QuadMesh& mesh,
                         const SmoothParams& params, const SizingField* size = nullptr,
                         const CrossField* cross = nullptr, const Progress& progress = Progress());

}  // namespace isoquad
