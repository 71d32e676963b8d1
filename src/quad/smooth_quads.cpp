#include "quad/smooth_quads.h"

#include <algorithm>
#include <vector>

#include "quad/quad_repairs.h"
#include "quad/quad_sweeps.h"
#include "quad/quad_topology.h"

namespace isoquad {

SmoothStats smooth_quads(const BackgroundMesh& bg, QuadMesh& m, const SmoothParams& params,
                         const SizingField* size, const CrossField* cross,
                         const Progress& progress) {
  // The shares of the progress follow France at a uniform 3 km: the field-aligned sweeps
  // 30%, the angle sweeps 55%, the repairs and the sweeps after them the rest.
  progress.report("smooth", 0.0);
  SmoothStats stats;
  const QuadTopology t = quad_topology(m);
  auto count_nonconvex = [&] { return isoquad::count_nonconvex(m, params.min_convexity); };
  stats.num_nonconvex_before = count_nonconvex();
  const int nv = static_cast<int>(m.points.size());

  for (int it = 0; it < params.iterations; ++it) {
    for (int v = 0; v < nv; ++v) {
      if (m.fixed[v]) continue;
      if (m.chain[v] >= 0) {
        Point2 target;
        double arc = 0;
        if (boundary_target(bg, m, t, v, target, arc)) try_move(m, t, v, target, arc, params.min_convexity);
        continue;
      }
      Point2 c{0, 0};
      for (int w : t.neighbours[v]) c.x += m.points[w].x, c.y += m.points[w].y;
      const double k = static_cast<double>(t.neighbours[v].size());
      if (k == 0) continue;
      try_move(m, t, v, {c.x / k, c.y / k}, m.arc_m[v], params.min_convexity);
    }
  }

  if (size && cross && params.aligned_iterations > 0)
    aligned_sweeps(bg, m, t, *size, *cross, params, progress.slice(0.05, 0.35));
  angle_sweeps(bg, m, t, params, cross, size, nullptr, -1, progress.slice(0.35, 0.9));
  std::vector<Point2> swept = m.points;  // where the sweeps left the vertices
  std::sort(swept.begin(), swept.end(), point_less);

  // A few sweeps that lift the flattest quads (angles near 0 or 180 degrees) as far as
  // they can; only the pass below must succeed.
  SmoothParams lift = params;
  lift.min_convexity = params.lift_convexity;
  lift.untangle_iterations = params.lift_iterations;
  SmoothStats ignored;
  untangle(bg, m, t, lift, ignored, false);
  untangle(bg, m, t, params, stats);
  // Where moving vertices is not enough, change the local topology and untangle again.
  for (int round = 0; round < params.flip_rounds && count_nonconvex() > 0; ++round) {
    const int flips = flip_nonconvex(m, params.min_convexity);
    if (flips == 0) break;
    stats.num_flips += flips;
    untangle(bg, m, quad_topology(m), params, stats);
  }
  // Nor flips: remove the quad by a diagonal collapse, kept when the quads then left
  // non-convex are fewer.
  for (int round = 0; round < params.collapse_rounds; ++round) {
    const int bad = count_nonconvex();
    if (bad == 0) break;
    QuadMesh before = m;
    const SmoothStats stats_before = stats;
    const int collapses =
        collapse_quads(m, [&](int q) { return quad_convexity(m, q) <= params.min_convexity; });
    if (collapses == 0) break;
    untangle(bg, m, quad_topology(m), params, stats);
    if (count_nonconvex() >= bad) {
      m = std::move(before);
      stats = stats_before;
      break;
    }
    stats.num_collapses += collapses;
  }
  if (count_nonconvex() > 0) stats.num_collapses += collapse_one_by_one(bg, m, params, stats);
  if (count_nonconvex() == 0) collapse_slivers(bg, m, params, lift, stats);
  if (count_nonconvex() == 0 && count_boundary_crossings(m) > 0) {
    if (unfold_boundary(bg, m, quad_topology(m), params) > 0)
      stats.num_collapses += collapse_folds(bg, m, params, stats);
    // The slides and collapses that unfold the mesh can leave a sliver where it folded
    // (France at hmax 18 km --simplify 800: 2.2 degrees): the sliver pass again there.
    if (count_nonconvex() == 0) collapse_slivers(bg, m, params, lift, stats);
  }
  std::vector<Point2> split;  // where the corner splits left their quads' vertices
  if (params.doubled_corner_side > 0 && count_nonconvex() == 0)
    split = split_doubled_corners(bg, m, params, lift, stats);
  // (After the corners' splits: a doubled corner's two quads are thin too, and the split
  // is the change that mends them.)
  if (count_nonconvex() == 0) collapse_thin(bg, m, params, lift, stats);
  progress.report("smooth", 0.95);
  // The repairs move vertices for convexity alone, and flips and collapses leave new
  // quads unswept: the angle sweeps again (SmoothParams::resweep_iterations) on the
  // vertices that moved since `swept_at` (sorted positions) or stand at `also`, and the
  // ones next to them, undone should they fold the mesh.
  auto resweep_moved = [&](const std::vector<Point2>& swept_at, const std::vector<Point2>& also) {
    if (params.resweep_iterations <= 0 || params.angle_iterations <= 0 || count_nonconvex() > 0)
      return;
    const QuadTopology t2 = quad_topology(m);
    std::vector<char> only(m.points.size(), 0);
    bool any = false;
    for (std::size_t v = 0; v < m.points.size(); ++v) {
      if (std::binary_search(swept_at.begin(), swept_at.end(), m.points[v], point_less) &&
          !std::binary_search(also.begin(), also.end(), m.points[v], point_less))
        continue;
      any = true;
      only[v] = 1;
      for (int w : t2.neighbours[v]) only[w] = 1;
    }
    if (!any) return;
    const std::size_t crossings = count_boundary_crossings(m);
    QuadMesh before = m;
    // With the lift's convexity bound: nothing the lift raised falls back.
    SmoothParams resweep = params;
    resweep.min_convexity = std::max(params.min_convexity, params.lift_convexity);
    angle_sweeps(bg, m, t2, resweep, cross, size, &only, params.resweep_iterations);
    if (count_nonconvex() > 0 || count_boundary_crossings(m) > crossings) m = std::move(before);
  };
  resweep_moved(swept, split);
  // Slivers left after all that: the sliver pass once more, each try with the vertices
  // next to the change relocated first (SmoothParams::sliver_relocate), then the sweeps
  // again where it moved vertices.
  if (params.sliver_relocate && count_nonconvex() == 0) {
    bool any_sliver = false;
    for (int q = 0; q < static_cast<int>(m.quads.size()) && !any_sliver; ++q)
      any_sliver = quad_convexity(m, q) <= params.sliver_convexity;
    if (any_sliver) {
      std::vector<Point2> now = m.points;
      std::sort(now.begin(), now.end(), point_less);
      collapse_slivers(bg, m, params, lift, stats, true);
      resweep_moved(now, {});
    }
  }
  // D-Flow FM's orthogonality, last: nothing after it moves the centres again.
  if (params.max_orthogonality > 0 && count_nonconvex() == 0) {
    const QuadTopology t3 = quad_topology(m);
    stats.num_orthogonality_after =
        orthogonality_sweeps(m, t3, params, &stats.num_orthogonality_before);
  }
  stats.num_nonconvex_after = count_nonconvex();
  return stats;
}

}  // namespace isoquad
