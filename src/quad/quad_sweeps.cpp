#include "quad/quad_sweeps.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <thread>

#include "core/paired_math.h"
#include "mesh/locate.h"
#include "quad/quad_quality.h"

namespace isoquad {

namespace {

// Colours of the vertices such that no two vertices of a quad share one (greedy, in vertex
// order): vertices of a colour are moved independently of each other, each colour's in
// vertex order.
std::vector<std::vector<int>> quad_colouring(const QuadMesh& m, const QuadTopology& t) {
  const int nv = static_cast<int>(m.points.size());
  std::vector<int> colour(nv, -1);
  std::vector<std::vector<int>> classes;
  std::vector<char> taken;
  for (int v = 0; v < nv; ++v) {
    taken.assign(classes.size() + 1, 0);
    for (int k = t.quad_start[v]; k < t.quad_start[v + 1]; ++k)
      for (int w : m.quads[t.quad_items[k]])
        if (colour[w] >= 0) taken[colour[w]] = 1;
    int c = 0;
    while (taken[c]) ++c;
    colour[v] = c;
    if (c == static_cast<int>(classes.size())) classes.emplace_back();
    classes[c].push_back(v);
  }
  return classes;
}

// Threads for the sweeps (SmoothParams::threads; the result does not depend on it).
int sweep_threads(const SmoothParams& params) {
  if (params.threads > 0) return params.threads;
  return static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 4u));
}

// body(begin, end, thread) over [0, n) in `threads` contiguous chunks, in parallel.
template <class Body>
void parallel_chunks(int n, int threads, const Body& body) {
  const int chunk = (n + threads - 1) / std::max(threads, 1);
  if (threads <= 1 || n < 64) {
    body(0, n, 0);
    return;
  }
  std::vector<std::thread> pool;
  for (int k = 1; k < threads; ++k) {
    const int begin = k * chunk, end = std::min(n, begin + chunk);
    if (begin < end) pool.emplace_back([&body, begin, end, k] { body(begin, end, k); });
  }
  body(0, std::min(n, chunk), 0);
  for (std::thread& th : pool) th.join();
}

// The field-aligned sweeps (SmoothParams::aligned_iterations).
class AlignedSmoother {
 public:
  AlignedSmoother(const BackgroundMesh& bg, QuadMesh& m, const QuadTopology& t,
                  const SizingField& size, const CrossField& cross, const SmoothParams& params)
      : bg_(bg), m_(m), t_(t), size_(size), cross_(cross), params_(params), locator_(bg) {}

  void run(const Progress& progress) {
    const int nv = static_cast<int>(m_.points.size());
    h_.resize(nv);
    theta_.resize(nv);
    triangle_.assign(nv, -1);  // where each vertex was last: the next search starts there
    const int threads = sweep_threads(params_);
    for (int it = 0; it < params_.aligned_iterations; ++it) {
      parallel_chunks(nv, threads, [&](int begin, int end, int) {
        for (int v = begin; v < end; ++v) {
          const Location loc = locator_.locate(m_.points[v], triangle_[v]);
          triangle_[v] = loc.triangle;
          h_[v] = loc.triangle >= 0 ? size_.at(bg_, loc.triangle, loc.bary) : 0.0;
          theta_[v] = loc.triangle >= 0 ? cross_angle_at(bg_, cross_, loc.triangle, loc.bary) : 0.0;
        }
      });
      for (int v = 0; v < nv; ++v) {
        if (m_.fixed[v]) continue;
        if (m_.chain[v] >= 0)
          slide_boundary(v);
        else
          move_interior(v);
      }
      progress.report("smooth", (it + 1.0) / params_.aligned_iterations);
    }
  }

 private:
  // A regular vertex: its four neighbours in angular order take the four axes of the
  // cross at v in the rotation that fits them best; each predicts v one edge length
  // back along its axis (the mean h of the edge's ends, blended with the current mean
  // edge length by aligned_keep_length). Other vertices: Laplacian.
  void move_interior(int v) {
    const std::vector<int>& nb = t_.neighbours[v];
    const Point2 p = m_.points[v];
    Point2 target{0, 0};
    if (nb.size() != 4 || !(h_[v] > 0.0)) {
      if (nb.empty()) return;
      for (int w : nb) target.x += m_.points[w].x, target.y += m_.points[w].y;
      target.x /= nb.size();
      target.y /= nb.size();
    } else {
      std::array<std::pair<double, int>, 4> around;
      for (int j = 0; j < 4; ++j)
        around[j] = {std::atan2(m_.points[nb[j]].y - p.y, m_.points[nb[j]].x - p.x), nb[j]};
      std::sort(around.begin(), around.end());
      int best_rotation = 0;
      double best_cost = std::numeric_limits<double>::infinity();
      for (int r = 0; r < 4; ++r) {
        double cost = 0;
        for (int j = 0; j < 4; ++j)
          cost +=
              std::abs(std::remainder(around[j].first - theta_[v] - (r + j) * M_PI / 2, 2 * M_PI));
        if (cost < best_cost) best_cost = cost, best_rotation = r;
      }
      const double keep = params_.aligned_keep_length;
      double mean_length = 0;
      for (int w : nb) mean_length += 0.25 * distance(p, m_.points[w]);
      for (int j = 0; j < 4; ++j) {
        const int w = around[j].second;
        const double a = theta_[v] + (best_rotation + j) * M_PI / 2;
        const double h_edge = h_[w] > 0.0 ? 0.5 * (h_[v] + h_[w]) : h_[v];
        const double h = (1 - keep) * h_edge + keep * mean_length;
        target.x += m_.points[w].x - h * std::cos(a);
        target.y += m_.points[w].y - h * std::sin(a);
      }
      target.x /= 4;
      target.y /= 4;
    }
    const double s = params_.aligned_step;
    try_move(m_, t_, v, {p.x + s * (target.x - p.x), p.y + s * (target.y - p.y)}, m_.arc_m[v],
             params_.min_convexity);
  }

  // A boundary vertex with one interior neighbour w slides halfway between the foot of
  // w on the boundary (an orthogonal inward edge) and the midpoint of its boundary
  // neighbours.
  void slide_boundary(int v) {
    const auto& bn = t_.boundary_neighbours[v];
    if (bn[0] < 0 || bn[1] < 0) return;
    const int c = m_.chain[v];
    if (m_.chain[bn[0]] != c || m_.chain[bn[1]] != c) return;
    const double len = bg_.chains[c].length_m;
    const double d0 = arc_delta(m_.arc_m[v], m_.arc_m[bn[0]], len);
    const double d1 = arc_delta(m_.arc_m[v], m_.arc_m[bn[1]], len);
    if (d0 * d1 >= 0) return;
    const int ahead = d0 > 0 ? bn[0] : bn[1], behind = d0 > 0 ? bn[1] : bn[0];
    double shift = 0.5 * (d0 + d1);
    int inner = -1;
    for (int w : t_.neighbours[v])
      if (w != bn[0] && w != bn[1]) inner = inner < 0 ? w : -2;
    if (inner >= 0) {
      const Point2 &pa = m_.points[ahead], &pb = m_.points[behind], &p = m_.points[v];
      const double tx = pa.x - pb.x, ty = pa.y - pb.y, tl = std::hypot(tx, ty);
      if (tl > 0.0) {
        double foot = ((m_.points[inner].x - p.x) * tx + (m_.points[inner].y - p.y) * ty) / tl;
        const double limit = 0.5 * std::min(std::abs(d0), std::abs(d1));
        foot = std::max(-limit, std::min(limit, foot));
        shift = 0.5 * (shift + foot);
      }
    }
    const double arc = m_.arc_m[v] + params_.aligned_step * shift;
    try_move(m_, t_, v, chain_point(bg_, bg_.chains[c], arc), arc, params_.min_convexity);
  }

  const BackgroundMesh& bg_;
  QuadMesh& m_;
  const QuadTopology& t_;
  const SizingField& size_;
  const CrossField& cross_;
  const SmoothParams& params_;
  TriangleLocator locator_;
  std::vector<int> triangle_;
  std::vector<double> h_, theta_;
};

// The logistic function 1 / (1 + exp(-x)), a smooth step from 0 (x << 0) to 1 (x >> 0),
// given exp(-x).
double smooth_step_of(double exp_minus_x) {
  return 1.0 / (1.0 + exp_minus_x);
}

// The angle at corner o of a quad whose corners run p, o, n counter-clockwise, in (-pi, pi]
// (negative where the quad folds).
double corner_angle_rad(const Point2& p, const Point2& o, const Point2& n) {
  const double ax = p.x - o.x, ay = p.y - o.y, bx = n.x - o.x, by = n.y - o.y;
  return std::atan2(bx * ay - by * ax, ax * bx + ay * by);
}

// The angle sweeps' energy at v: over the quads around v, the sum of (angle - 90 deg)^2
// (rad^2) plus the smooth count of corners out of range (SmoothParams::angle_range_*) of
// the corners that a move of v changes (at v and at its two neighbours in the quad; the
// fourth is constant: opposite_angle, per quad of v in order), plus per quad
// area_weight (log(area / area0))^2, the smooth count of sizes out of range
// (size_range_*; area0: the target area), of smallest over largest angle under
// min_angle_ratio and of longest over shortest side over max_aspect; infinite when one
// of the moving corners turns by less than min_convexity (quad_convexity's measure; the
// caller has checked the fourth).
// `sharpest` takes the smallest of the moving corners' angles, if smaller.
double moving_corner_energy(const QuadMesh& m, const QuadTopology& t, int v,
                            const SmoothParams& params, const std::vector<double>& area0,
                            const double* opposite_angle, double& sharpest) {
  const double range = params.angle_range_deg * M_PI / 180;
  const double softness = params.angle_range_softness_deg * M_PI / 180;
  const double log_max_aspect = std::log(params.max_aspect);
  double e = 0;
  for (int k = t.quad_start[v]; k < t.quad_start[v + 1]; ++k) {
    const int q = t.quad_items[k];
    const auto& c = m.quads[q];
    const int j = c[0] == v ? 0 : c[1] == v ? 1 : c[2] == v ? 2 : 3;
    // The three moving corners' angles, the quad's sides and area, then the six smooth
    // steps' exponentials two at a time (core/paired_math.h), and the terms added in
    // the order of one quad's formula.
    double cross[3], dot[3], l2[3], angle[3];
    for (int d = 3; d <= 5; ++d) {
      const int i = (j + d) % 4;
      const Point2 &p = m.points[c[(i + 3) % 4]], &o = m.points[c[i]],
                   &n = m.points[c[(i + 1) % 4]];
      const double ax = p.x - o.x, ay = p.y - o.y, bx = n.x - o.x, by = n.y - o.y;
      cross[d - 3] = bx * ay - by * ax;
      dot[d - 3] = ax * bx + ay * by;
      l2[d - 3] = (ax * ax + ay * ay) * (bx * bx + by * by);
    }
    atan2_pair(cross[0], dot[0], cross[1], dot[1], angle[0], angle[1]);
    angle[2] = std::atan2(cross[2], dot[2]);
    double smallest = opposite_angle[k - t.quad_start[v]], largest = smallest;
    double a[3];
    for (int i = 0; i < 3; ++i) {
      smallest = std::min(smallest, angle[i]);
      largest = std::max(largest, angle[i]);
      sharpest = std::min(sharpest, angle[i]);
      // quad_convexity's measure at this corner: the sine of the turn between edges.
      if (l2[i] == 0 || cross[i] <= params.min_convexity * std::sqrt(l2[i]))
        return std::numeric_limits<double>::infinity();
      a[i] = angle[i] - 0.5 * M_PI;
    }
    const bool aspect_terms = params.aspect_weight > 0 || params.aspect_log_weight > 0;
    const bool size_terms = params.angle_area_weight > 0 || params.size_range_weight > 0;
    double shortest = std::numeric_limits<double>::infinity(), longest = 0;
    if (aspect_terms)
      for (int i = 0; i < 4; ++i) {
        const double l = distance(m.points[c[i]], m.points[c[(i + 1) % 4]]);
        shortest = std::min(shortest, l), longest = std::max(longest, l);
      }
    double log_aspect, r;
    log_pair(longest / shortest, size_terms ? quad_area(m, q) / area0[q] : 1.0, log_aspect, r);
    const double over = log_aspect - log_max_aspect;
    double ex[6];
    exp_pair(-((std::abs(a[0]) - range) / softness), -((std::abs(a[1]) - range) / softness), ex[0],
             ex[1]);
    exp_pair(-((std::abs(a[2]) - range) / softness),
             -((params.min_angle_ratio - smallest / largest) / params.angle_ratio_softness), ex[2],
             ex[3]);
    exp_pair(-(over / params.aspect_softness),
             -((std::abs(r) - params.size_range_log_area) / params.size_range_softness), ex[4],
             ex[5]);
    for (int i = 0; i < 3; ++i) {
      e += a[i] * a[i];
      if (params.angle_range_weight > 0) e += params.angle_range_weight * smooth_step_of(ex[i]);
    }
    if (params.angle_ratio_weight > 0) e += params.angle_ratio_weight * smooth_step_of(ex[3]);
    if (aspect_terms && shortest > 0) {
      e += params.aspect_weight * smooth_step_of(ex[4]);
      if (over > 0) e += params.aspect_log_weight * over;
    }
    if (size_terms) {
      e += params.angle_area_weight * r * r;
      if (params.size_range_weight > 0) e += params.size_range_weight * smooth_step_of(ex[5]);
    }
  }
  return e;
}

}  // namespace

// Untangling: move the vertices of non-convex quads to maximise the worst convexity
// around them (pattern search with shrinking steps). When that stalls, the vertices of
// the quads around them move too, and at last domain corners may slide along the
// boundary (a cut corner is better than a non-convex quad).
// With `only`, the quads looked at are those (ascending ids): a local repair after a
// local change.
void untangle(const BackgroundMesh& bg, QuadMesh& m, const QuadTopology& t,
              const SmoothParams& params, SmoothStats& stats, bool may_free_corners,
              const std::vector<int>* only) {
  const int nq = static_cast<int>(m.quads.size());
  const int nv = static_cast<int>(m.points.size());
  std::vector<char> active(nv, 0);
  int stalled = 0, previous_bad = -1;
  auto widen_at = [&](int sweep, int stalled_then) {
    return sweep >= params.untangle_iterations / 10 && stalled_then > 2;
  };
  auto free_corners_at = [&](int sweep) {
    return may_free_corners && sweep >= params.untangle_iterations / 2;
  };
  for (int sweep = 0; sweep < params.untangle_iterations; ++sweep) {
    std::vector<int> bad;
    if (only) {
      for (int q : *only)
        if (quad_convexity(m, q) <= params.min_convexity) bad.push_back(q);
    } else {
      for (int q = 0; q < nq; ++q)
        if (quad_convexity(m, q) <= params.min_convexity) bad.push_back(q);
    }
    if (bad.empty()) break;
    ++stats.num_untangle_sweeps;
    stalled = static_cast<int>(bad.size()) >= previous_bad && previous_bad >= 0 ? stalled + 1 : 0;
    previous_bad = static_cast<int>(bad.size());
    const bool widen = widen_at(sweep, stalled);
    const bool free_corners = free_corners_at(sweep);
    bool moved = false;
    std::fill(active.begin(), active.end(), 0);
    std::vector<int> order;
    for (int q : bad)
      for (int v : m.quads[q]) {
        if (!active[v]) active[v] = 1, order.push_back(v);
        if (!widen) continue;
        for (int k = t.quad_start[v]; k < t.quad_start[v + 1]; ++k)
          for (int w : m.quads[t.quad_items[k]])
            if (!active[w]) active[w] = 1, order.push_back(w);
      }
    for (int v : order) {
      if (m.fixed[v] && !(free_corners && m.chain[v] >= 0)) continue;
      const Point2 was = m.points[v];
      const double was_arc = m.arc_m[v];
      double edge = 0, shortest = std::numeric_limits<double>::infinity();
      for (int w : t.neighbours[v]) {
        const double l = distance(m.points[w], m.points[v]);
        edge = std::max(edge, l), shortest = std::min(shortest, l);
      }
      // No move shortens an edge at v below untangle_min_side times its longest (or below
      // its shortest, when that is already shorter).
      const double floor_side = std::min(shortest, params.untangle_min_side * edge);
      auto short_edge = [&] {
        if (floor_side <= 0) return false;
        for (int w : t.neighbours[v])
          if (distance(m.points[w], m.points[v]) < floor_side) return true;
        return false;
      };
      // A boundary vertex between its two boundary neighbours stays between them
      // (SmoothParams::untangle_keeps_boundary_order).
      const bool keep_order =
          params.untangle_keeps_boundary_order && between_boundary_neighbours(bg, m, t, v);
      double best = worst_convexity(m, t, v);
      if (m.chain[v] < 0 && best <= params.min_convexity) {
        // A local search may sit in the wrong part of a non-convex 1-ring: try a grid
        // over the ring's bounding box first.
        double x0 = m.points[v].x, x1 = x0, y0 = m.points[v].y, y1 = y0;
        for (int w : t.neighbours[v]) {
          x0 = std::min(x0, m.points[w].x), x1 = std::max(x1, m.points[w].x);
          y0 = std::min(y0, m.points[w].y), y1 = std::max(y1, m.points[w].y);
        }
        const Point2 start = m.points[v];
        Point2 best_point = start;
        constexpr int kGrid = 24;
        for (int i = 1; i < kGrid; ++i)
          for (int j = 1; j < kGrid; ++j) {
            m.points[v] = {x0 + (x1 - x0) * i / kGrid, y0 + (y1 - y0) * j / kGrid};
            const double value = worst_convexity(m, t, v);
            if (value > best + 1e-12 && !short_edge()) best = value, best_point = m.points[v];
          }
        m.points[v] = best_point;
      }
      for (double step = 0.25 * edge; step > 1e-3 * edge; step *= 0.5) {
        bool improved = true;
        while (improved) {
          improved = false;
          for (int dir = 0; dir < 8; ++dir) {
            const double a = dir * M_PI / 4;
            const Point2 old = m.points[v];
            const double old_arc = m.arc_m[v];
            if (m.chain[v] >= 0) {
              // Boundary vertices only slide along the boundary.
              if (dir >= 2) break;
              const double arc = old_arc + (dir == 0 ? step : -step);
              m.points[v] = chain_point(bg, bg.chains[m.chain[v]], arc);
              m.arc_m[v] = arc;
            } else {
              m.points[v] = {old.x + step * std::cos(a), old.y + step * std::sin(a)};
            }
            const double value = worst_convexity(m, t, v);
            if (value > best + 1e-12 && !short_edge() &&
                (!keep_order || between_boundary_neighbours(bg, m, t, v))) {
              best = value;
              improved = true;
            } else {
              m.points[v] = old;
              m.arc_m[v] = old_arc;
            }
          }
        }
      }
      moved = moved || m.points[v].x != was.x || m.points[v].y != was.y || m.arc_m[v] != was_arc;
    }
    // A sweep that moved nothing is a fixed point: the sweeps after it, with the same
    // quads bad (stalled one more each) and the same rules, would move nothing either.
    // Skip to the first one whose rules change (widened, or corners freed), counted.
    if (!moved) {
      int next = sweep + 1;
      while (next < params.untangle_iterations &&
             widen_at(next, stalled + (next - sweep)) == widen &&
             free_corners_at(next) == free_corners)
        ++next;
      const int skipped = next - sweep - 1;
      stats.num_untangle_sweeps += skipped;
      stalled += skipped;
      sweep += skipped;
    }
  }
}

void aligned_sweeps(const BackgroundMesh& bg, QuadMesh& m, const QuadTopology& t,
                    const SizingField& size, const CrossField& cross, const SmoothParams& params,
                    const Progress& progress) {
  AlignedSmoother(bg, m, t, size, cross, params).run(progress);
}

// Angle sweeps: every free vertex takes the best of its candidate moves (interior: eight
// directions; boundary: both ways along its chain, staying between its boundary
// neighbours), each angle_step of its shortest edge long (0.3 of that in the second
// half of the sweeps), if that lowers moving_corner_energy (target areas h^2 with a sizing
// field) plus the orientation term of its edges; convexity never drops below
// min_convexity. `iterations` sweeps (default angle_iterations); with `only`, the
// vertices it marks move, the others stay.
void angle_sweeps(const BackgroundMesh& bg, QuadMesh& m, const QuadTopology& t,
                  const SmoothParams& params, const CrossField* cross, const SizingField* size,
                  const std::vector<char>* only, int iterations, const Progress& progress,
                  SweepSetup* setup) {
  const int nv = static_cast<int>(m.points.size());
  if (iterations < 0) iterations = params.angle_iterations;
  const double ow = params.angle_orientation_weight;
  SweepSetup own;
  if (!setup) setup = &own;
  if (((cross && ow > 0) || size) && !setup->locator)
    setup->locator = std::make_unique<TriangleLocator>(bg);
  const TriangleLocator* locator = setup->locator.get();
  // The cross at every vertex where the sweeps start: the unit vector of one of its axes.
  std::vector<Point2> axis;
  if (cross && ow > 0) {
    axis.resize(nv);
    for (int v = 0; v < nv; ++v) {
      if (only && !(*only)[v]) continue;
      const Location loc = locator->locate(m.points[v]);
      const double theta =
          loc.triangle >= 0 ? cross_angle_at(bg, *cross, loc.triangle, loc.bary) : 0.0;
      axis[v] = {std::cos(theta), std::sin(theta)};
    }
  }
  // Target areas: h^2 at the quad centroids where the sweeps start (the sizing field),
  // else the areas there; with `only`, of the quads of its vertices (the others' are not
  // read).
  std::vector<double> area0(m.quads.size());
  std::vector<char> read_area;
  if (only) {
    read_area.assign(m.quads.size(), 0);
    for (int v = 0; v < nv; ++v)
      if ((*only)[v])
        for (int k = t.quad_start[v]; k < t.quad_start[v + 1]; ++k) read_area[t.quad_items[k]] = 1;
  }
  for (std::size_t q = 0; q < m.quads.size(); ++q) {
    if (only && !read_area[q]) continue;
    area0[q] = quad_area(m, static_cast<int>(q));
    if (!size) continue;
    const Location loc = locator->locate(quad_centroid(m, static_cast<int>(q)));
    const double h = loc.triangle >= 0 ? size->at(bg, loc.triangle, loc.bary) : 0.0;
    if (h > 0) area0[q] = h * h;
  }
  // moving_corner_energy plus ow (rotation from the nearest cross axis)^2 over the edges at
  // v: in the frame of the cross, an edge (x, y) is atan(min(|x|, |y|) / max(|x|, |y|))
  // away from the nearest axis.
  // `opposite`: the constant corners of v's quads (moving_corner_energy).
  auto energy = [&](int v, const std::vector<double>& opposite, double& sharpest) {
    sharpest = M_PI;
    double e = moving_corner_energy(m, t, v, params, area0, opposite.data(), sharpest);
    if (!std::isfinite(e)) return e;
    if (params.coast_weight > 0 && m.chain[v] >= 0)
      for (int w : t.boundary_neighbours[v]) {
        if (w < 0) continue;
        // The edge's way with the mesh on its left: as its quad has it.
        bool forward = true;
        for (int k = t.quad_start[v]; k < t.quad_start[v + 1]; ++k) {
          const auto& c = m.quads[t.quad_items[k]];
          const int j = c[0] == v ? 0 : c[1] == v ? 1 : c[2] == v ? 2 : 3;
          if (c[(j + 3) % 4] == w) forward = false;
        }
        const double len = distance(m.points[v], m.points[w]);
        const double d =
            (forward ? chord_departure(m, bg, v, w) : chord_departure(m, bg, w, v)).distance_m;
        if (len > 0) e += params.coast_weight * (d / len) * (d / len);
      }
    if (axis.empty()) return e;
    const Point2 u = axis[v];
    for (int w : t.neighbours[v]) {
      const double dx = m.points[w].x - m.points[v].x, dy = m.points[w].y - m.points[v].y;
      const double x = std::abs(dx * u.x + dy * u.y), y = std::abs(dy * u.x - dx * u.y);
      const double r = std::max(x, y) > 0 ? std::atan(std::min(x, y) / std::max(x, y)) : 0.0;
      e += ow * r * r;
    }
    return e;
  };
  // The best move of v (false: it stays where it is).
  auto move = [&](int v, double step_factor, std::vector<double>& opposite) {
    const Point2 start = m.points[v];
    const double start_arc = m.arc_m[v];
    double shortest = std::numeric_limits<double>::infinity();
    for (int w : t.neighbours[v]) shortest = std::min(shortest, distance(start, m.points[w]));
    const double step = step_factor * params.angle_step * shortest;
    // A vertex with a quad not convex enough (at any corner) stays where it is.
    if (worst_convexity(m, t, v) <= params.min_convexity) return false;
    opposite.clear();
    for (int k = t.quad_start[v]; k < t.quad_start[v + 1]; ++k) {
      const auto& c = m.quads[t.quad_items[k]];
      const int i = c[0] == v ? 2 : c[1] == v ? 3 : c[2] == v ? 0 : 1;
      opposite.push_back(
          corner_angle_rad(m.points[c[(i + 3) % 4]], m.points[c[i]], m.points[c[(i + 1) % 4]]));
    }
    double sharpest = 0;
    double best = energy(v, opposite, sharpest);
    // No move makes a corner sharper than angle_floor_deg, or sharper still.
    const double floor = std::min(sharpest, params.angle_floor_deg * M_PI / 180);
    if (!std::isfinite(best)) return false;
    Point2 best_point = start;
    double best_arc = start_arc;
    auto consider = [&](const Point2& p, double arc) {
      m.points[v] = p;
      m.arc_m[v] = arc;
      double sharp = 0;
      const double e = energy(v, opposite, sharp);
      if (e < best && sharp >= floor) best = e, best_point = p, best_arc = arc;
    };
    const int c = m.chain[v];
    if (c < 0) {
      for (int k = 0; k < 8; ++k)
        consider({start.x + step * std::cos(k * M_PI / 4), start.y + step * std::sin(k * M_PI / 4)},
                 start_arc);
    } else {
      // Along the boundary, between the boundary neighbours of the same chain.
      const auto& bn = t.boundary_neighbours[v];
      if (bn[0] < 0 || bn[1] < 0 || m.chain[bn[0]] != c || m.chain[bn[1]] != c) return false;
      const double len = bg.chains[c].length_m;
      const double d0 = arc_delta(start_arc, m.arc_m[bn[0]], len);
      const double d1 = arc_delta(start_arc, m.arc_m[bn[1]], len);
      if (d0 * d1 >= 0) return false;
      for (double d : {-step, step})
        if (std::abs(d) < 0.5 * std::min(std::abs(d0), std::abs(d1)))
          consider(chain_point(bg, bg.chains[c], start_arc + d), start_arc + d);
    }
    m.points[v] = best_point;
    m.arc_m[v] = best_arc;
    return best_point.x != start.x || best_point.y != start.y;
  };
  // Which vertices need another look: one that stayed where it was stays again until a
  // vertex of its quads moves (its energy and moves depend on nothing else), or the steps
  // shorten. Times count the colours swept.
  std::vector<long> moved_at(nv, -1), stayed_at(nv, -1);
  auto unchanged = [&](int v) {
    if (stayed_at[v] < 0) return false;
    for (int k = t.quad_start[v]; k < t.quad_start[v + 1]; ++k)
      for (int w : m.quads[t.quad_items[k]])
        if (moved_at[w] > stayed_at[v]) return false;
    return true;
  };
  // The vertices of one colour move independently, so in parallel; with `only`, its
  // vertices of each colour, in the same order.
  if (setup->colours.empty()) setup->colours = quad_colouring(m, t);
  std::vector<std::vector<int>> some;
  if (only)
    for (const std::vector<int>& colour : setup->colours) {
      some.emplace_back();
      for (int v : colour)
        if ((*only)[v]) some.back().push_back(v);
    }
  const std::vector<std::vector<int>>& colours = only ? some : setup->colours;
  const int threads = sweep_threads(params);
  std::vector<std::vector<double>> scratch(threads);
  long time = 0;
  for (int it = 0; it < iterations; ++it) {
    // The second half of the sweeps refines with steps 0.3 as long.
    const bool refine = 2 * it >= iterations;
    if (refine && 2 * (it - 1) < iterations) std::fill(stayed_at.begin(), stayed_at.end(), -1);
    for (const std::vector<int>& colour : colours) {
      ++time;
      parallel_chunks(
          static_cast<int>(colour.size()), threads, [&](int begin, int end, int thread) {
            for (int i = begin; i < end; ++i) {
              const int v = colour[i];
              if (m.fixed[v] || t.neighbours[v].empty() || (only && !(*only)[v]) || unchanged(v))
                continue;
              if (move(v, refine ? 0.3 : 1.0, scratch[thread]))
                moved_at[v] = time, stayed_at[v] = -1;
              else
                stayed_at[v] = time;
            }
          });
    }
    progress.report("smooth", (it + 1.0) / iterations);
  }
}

int orthogonality_sweeps(QuadMesh& m, const QuadTopology& t, const SmoothParams& params,
                         int* before) {
  const int nq = static_cast<int>(m.quads.size());
  const std::vector<std::array<int, 4>> across = quads_across(m);  // -1: the boundary
  auto shared = [&](int q) {
    return std::array<bool, 4>{across[q][0] >= 0, across[q][1] >= 0, across[q][2] >= 0,
                               across[q][3] >= 0};
  };
  std::vector<Point2> centre(nq);
  for (int q = 0; q < nq; ++q) centre[q] = dflowfm_centre(m, q, shared(q));
  auto link = [&](int q, int i) {  // orthogonality of quad q's side i (shared)
    return link_orthogonality(m.points[m.quads[q][i]], m.points[m.quads[q][(i + 1) % 4]], centre[q],
                              centre[across[q][i]]);
  };
  // How far the links of the quads round vertex v are over the bound, summed.
  auto excess_round = [&](int v) {
    double excess = 0;
    for (int k = t.quad_start[v]; k < t.quad_start[v + 1]; ++k) {
      const int q = t.quad_items[k];
      for (int i = 0; i < 4; ++i)
        if (across[q][i] >= 0) excess += std::max(0.0, link(q, i) - params.max_orthogonality);
    }
    return excess;
  };
  auto count_over = [&]() {
    int n = 0;
    for (int q = 0; q < nq; ++q)
      for (int i = 0; i < 4; ++i) n += across[q][i] > q && link(q, i) > params.max_orthogonality;
    return n;
  };
  if (before) *before = count_over();
  const double bound = std::max(params.min_convexity, params.lift_convexity);
  for (int round = 0; round < params.orthogonality_rounds; ++round) {
    // The interior corners of the quads of the links over the bound, in id order.
    std::vector<int> movable;
    for (int q = 0; q < nq; ++q)
      for (int i = 0; i < 4; ++i)
        if (across[q][i] > q && link(q, i) > params.max_orthogonality)
          for (int r : {q, across[q][i]})
            for (int v : m.quads[r])
              if (m.chain[v] < 0 && !m.fixed[v]) movable.push_back(v);
    if (movable.empty()) break;
    std::sort(movable.begin(), movable.end());
    movable.erase(std::unique(movable.begin(), movable.end()), movable.end());
    bool moved = false;
    for (int v : movable) {
      double shortest = std::numeric_limits<double>::infinity();
      for (int w : t.neighbours[v])
        shortest = std::min(shortest, distance(m.points[v], m.points[w]));
      if (!std::isfinite(shortest)) continue;
      const Point2 start = m.points[v];
      auto recentre = [&]() {
        for (int k = t.quad_start[v]; k < t.quad_start[v + 1]; ++k) {
          const int q = t.quad_items[k];
          centre[q] = dflowfm_centre(m, q, shared(q));
        }
      };
      double best = excess_round(v);
      Point2 best_at = start;
      if (best == 0) continue;
      constexpr double kD = 0.70710678118654752;  // the 8 directions, 45 degrees apart
      constexpr double kDirections[8][2] = {{1, 0},  {kD, kD},   {0, 1},  {-kD, kD},
                                            {-1, 0}, {-kD, -kD}, {0, -1}, {kD, -kD}};
      for (double share : {0.2, 0.07, 0.02})
        for (const auto& dir : kDirections) {
          const Point2 p{start.x + share * shortest * dir[0], start.y + share * shortest * dir[1]};
          m.points[v] = start;
          if (!try_move(m, t, v, p, m.arc_m[v], bound)) continue;
          recentre();
          const double w = excess_round(v);
          if (w < best - 1e-9) best = w, best_at = p;
        }
      m.points[v] = best_at;
      recentre();
      moved = moved || !(best_at == start);
    }
    if (!moved) break;
  }
  return count_over();
}

}  // namespace isoquad
