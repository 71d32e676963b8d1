#include "quad/smooth_quads.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <thread>
#include <tuple>

#include "mesh/locate.h"

namespace isoquad {

namespace {

struct Topology {
  std::vector<int> quad_start, quad_items;  // CSR vertex -> incident quads
  std::vector<std::vector<int>> neighbours;  // vertex -> edge-adjacent vertices
  std::vector<std::array<int, 2>> boundary_neighbours;  // along the boundary, -1 if none
};

Topology topology(const QuadMesh& m) {
  Topology t;
  const std::size_t n = m.points.size();
  t.quad_start.assign(n + 1, 0);
  for (const auto& q : m.quads)
    for (int v : q) ++t.quad_start[v + 1];
  for (std::size_t i = 0; i < n; ++i) t.quad_start[i + 1] += t.quad_start[i];
  t.quad_items.resize(t.quad_start[n]);
  std::vector<int> fill(t.quad_start.begin(), t.quad_start.end() - 1);
  for (std::size_t q = 0; q < m.quads.size(); ++q)
    for (int v : m.quads[q]) t.quad_items[fill[v]++] = static_cast<int>(q);
  // A vertex's edge neighbours from its quads (each quad gives the corners before and
  // after it); an edge used by one quad only is a boundary edge. Boundary neighbours in
  // increasing order (the second slot keeps the last when there are more than two).
  t.neighbours.assign(n, {});
  t.boundary_neighbours.assign(n, {-1, -1});
  std::vector<int> around;
  for (std::size_t v = 0; v < n; ++v) {
    around.clear();
    for (int k = t.quad_start[v]; k < t.quad_start[v + 1]; ++k) {
      const auto& q = m.quads[t.quad_items[k]];
      const int i = static_cast<int>(std::find(q.begin(), q.end(), static_cast<int>(v)) - q.begin());
      around.push_back(q[(i + 1) % 4]);
      around.push_back(q[(i + 3) % 4]);
    }
    std::sort(around.begin(), around.end());
    auto& nb = t.neighbours[v];
    auto& bn = t.boundary_neighbours[v];
    for (std::size_t i = 0; i < around.size();) {
      std::size_t j = i;
      while (j < around.size() && around[j] == around[i]) ++j;
      nb.push_back(around[i]);
      if (j - i == 1) (bn[0] < 0 ? bn[0] : bn[1]) = around[i];
      i = j;
    }
  }
  return t;
}

// Points in lexicographic order (x, then y).
bool point_less(const Point2& a, const Point2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }

double worst_convexity(const QuadMesh& m, const Topology& t, int v) {
  double worst = 1.0;
  for (int k = t.quad_start[v]; k < t.quad_start[v + 1]; ++k)
    worst = std::min(worst, quad_convexity(m, t.quad_items[k]));
  return worst;
}

// Signed arc distance from a to b along a closed chain of length len, in (-len/2, len/2].
double arc_delta(double a, double b, double len) {
  double d = std::fmod(b - a, len);
  if (d > 0.5 * len) d -= len;
  if (d <= -0.5 * len) d += len;
  return d;
}

// Whether boundary vertex v lies strictly between its two boundary neighbours along
// its chain (false when it has not two on its chain).
bool between_boundary_neighbours(const BackgroundMesh& bg, const QuadMesh& m, const Topology& t,
                                 int v) {
  const auto& bn = t.boundary_neighbours[v];
  const int c = m.chain[v];
  if (c < 0 || bn[0] < 0 || bn[1] < 0 || m.chain[bn[0]] != c || m.chain[bn[1]] != c) return false;
  const double len = bg.chains[c].length_m;
  const double d0 = arc_delta(m.arc_m[v], m.arc_m[bn[0]], len);
  return d0 * arc_delta(m.arc_m[v], m.arc_m[bn[1]], len) < 0;
}

// Tries to move vertex v to `target` (and arc `arc` on the boundary): kept only if the
// incident quads stay at least as convex as required (or as they were).
bool try_move(QuadMesh& m, const Topology& t, int v, const Point2& target, double arc,
              double min_convexity) {
  const double before = worst_convexity(m, t, v);
  const Point2 old = m.points[v];
  const double old_arc = m.arc_m[v];
  m.points[v] = target;
  m.arc_m[v] = arc;
  const double after = worst_convexity(m, t, v);
  if (after > min_convexity || after >= before) return true;
  m.points[v] = old;
  m.arc_m[v] = old_arc;
  return false;
}

// The boundary target of v: the arc-length midpoint of its two boundary neighbours.
bool boundary_target(const BackgroundMesh& bg, const QuadMesh& m, const Topology& t, int v,
                     Point2& target, double& arc) {
  const auto& bn = t.boundary_neighbours[v];
  if (bn[0] < 0 || bn[1] < 0) return false;
  const int c = m.chain[v];
  if (m.chain[bn[0]] != c || m.chain[bn[1]] != c) return false;
  const double len = bg.chains[c].length_m;
  const double d0 = arc_delta(m.arc_m[v], m.arc_m[bn[0]], len);
  const double d1 = arc_delta(m.arc_m[v], m.arc_m[bn[1]], len);
  if (d0 * d1 >= 0) return false;  // neighbours must lie on both sides
  arc = m.arc_m[v] + 0.5 * (d0 + d1);
  target = chain_point(bg, bg.chains[c], arc);
  return true;
}

// Untangling: move the vertices of non-convex quads to maximise the worst convexity
// around them (pattern search with shrinking steps). When that stalls, the vertices of
// the quads around them move too, and at last domain corners may slide along the
// boundary (a cut corner is better than a non-convex quad).
// With `only`, the quads looked at are those (ascending ids): a local repair after a
// local change.
void untangle(const BackgroundMesh& bg, QuadMesh& m, const Topology& t, const SmoothParams& params,
              SmoothStats& stats, bool may_free_corners = true,
              const std::vector<int>* only = nullptr) {
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

// The quads that share each edge (an edge used by one quad only is on the boundary).
class EdgeQuads {
 public:
  explicit EdgeQuads(const QuadMesh& m) {
    for (int q = 0; q < static_cast<int>(m.quads.size()); ++q)
      for (int i = 0; i < 4; ++i) {
        const int a = m.quads[q][i], b = m.quads[q][(i + 1) % 4];
        edges_.push_back({{std::min(a, b), std::max(a, b)}, q});
      }
    std::sort(edges_.begin(), edges_.end());
  }
  // The quad other than q on edge (a, b), or -1.
  int other(int a, int b, int q) const {
    const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
    auto it = std::lower_bound(edges_.begin(), edges_.end(), std::make_pair(key, -1));
    for (; it != edges_.end() && it->first == key; ++it)
      if (it->second != q) return it->second;
    return -1;
  }

 private:
  std::vector<std::pair<std::pair<int, int>, int>> edges_;  // (edge, quad), sorted
};

// A quad edge flip: quads q and n, which share an edge, replaced by a and b.
struct QuadFlip {
  int q = -1, n = -1;
  std::array<int, 4> a{}, b{};
  double convexity = 0;  // the worse of a and b (quad_convexity)
};

// The flips of quad q: with each neighbour n it forms a hexagon, which splits into two
// quads along its two other long diagonals.
std::vector<QuadFlip> flips_of(const QuadMesh& m, const EdgeQuads& edges, int q) {
  std::vector<QuadFlip> out;
  for (int i = 0; i < 4; ++i) {
    const int a = m.quads[q][i], b = m.quads[q][(i + 1) % 4];
    const int n = edges.other(a, b, q);
    if (n < 0) continue;
    // Hexagon: q from b round to a (b, q[i+2], q[i+3], a), then n, which runs from b to
    // a (both counter-clockwise), from a round to b.
    // (An index built before other flips may name a quad that no longer has the edge.)
    const auto& nq4 = m.quads[n];
    const int j = static_cast<int>(std::find(nq4.begin(), nq4.end(), a) - nq4.begin());
    if (j == 4 || nq4[(j + 3) % 4] != b) continue;  // not the edge, or inconsistent orientation
    const std::array<int, 6> h = {b, m.quads[q][(i + 2) % 4], m.quads[q][(i + 3) % 4], a,
                                  nq4[(j + 1) % 4], nq4[(j + 2) % 4]};
    // Two quads that share two sides (a doublet) make no hexagon.
    std::array<int, 6> sorted = h;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) continue;
    for (int d = 1; d < 3; ++d) {  // diagonal (h0, h3) = the shared edge: the current pair
      QuadFlip f;
      f.q = q;
      f.n = n;
      f.a = {h[d], h[d + 1], h[d + 2], h[(d + 3) % 6]};
      f.b = {h[(d + 3) % 6], h[(d + 4) % 6], h[(d + 5) % 6], h[d]};
      const Point2* pa[4];
      const Point2* pb[4];
      for (int k = 0; k < 4; ++k) pa[k] = &m.points[f.a[k]], pb[k] = &m.points[f.b[k]];
      f.convexity = std::min(quad_convexity(*pa[0], *pa[1], *pa[2], *pa[3]),
                             quad_convexity(*pb[0], *pb[1], *pb[2], *pb[3]));
      out.push_back(f);
    }
  }
  return out;
}

// Quad edge flips: a non-convex quad and a neighbour form a hexagon, which splits into
// two quads along any of its three long diagonals. A split is kept when its worse quad
// is more convex than the worse of the pair before. Returns the number of flips.
int flip_nonconvex(QuadMesh& m, double min_convexity) {
  const int nq = static_cast<int>(m.quads.size());
  const EdgeQuads edges(m);
  std::vector<char> done(nq, 0);
  int flips = 0;
  for (int q = 0; q < nq; ++q) {
    if (done[q] || quad_convexity(m, q) > min_convexity) continue;
    const QuadFlip* best = nullptr;
    const std::vector<QuadFlip> flips_here = flips_of(m, edges, q);
    for (const QuadFlip& f : flips_here) {
      if (done[f.n]) continue;
      const double before = std::min(quad_convexity(m, q), quad_convexity(m, f.n));
      if (f.convexity > before + 1e-9 && (!best || f.convexity > best->convexity)) best = &f;
    }
    if (!best) continue;
    m.quads[q] = best->a;
    m.quads[best->n] = best->b;
    done[q] = done[best->n] = 1;
    ++flips;
  }
  return flips;
}

// Drops the quads marked in `removed` and the vertices no quad uses any more (ids
// renumbered in order).
void remove_quads(QuadMesh& m, const std::vector<char>& removed) {
  const int nv = static_cast<int>(m.points.size());
  const int nq = static_cast<int>(m.quads.size());
  std::vector<std::array<int, 4>> quads;
  std::vector<int> id(nv, -1);
  for (int q = 0; q < nq; ++q)
    if (!removed[q]) {
      quads.push_back(m.quads[q]);
      for (int v : m.quads[q]) id[v] = 0;
    }
  QuadMesh out;
  for (int v = 0; v < nv; ++v) {
    if (id[v] < 0) continue;
    id[v] = static_cast<int>(out.points.size());
    out.points.push_back(m.points[v]);
    out.chain.push_back(m.chain[v]);
    out.arc_m.push_back(m.arc_m[v]);
    out.fixed.push_back(m.fixed[v]);
  }
  for (auto& quad : quads)
    for (int& v : quad) v = id[v];
  out.quads = std::move(quads);
  m = std::move(out);
}

// Diagonal collapses: each quad `wanted` picks, with a diagonal whose end c is inside
// the domain and movable, is removed by merging c into the other end a (c's other quads
// take a; a keeps its place, on the boundary if it is there). Of the possible merges the
// one along the shorter diagonal is made (with `choice` k > 0, the k-th shortest, when
// there are that many). Refused when another quad holds both a and c,
// when an edge at the merged vertex would be used twice in the same direction, or when
// a corner on the other diagonal would be left in fewer than 3 quads inside the domain
// (1 on the boundary). Quads around a merge are not touched again in the same call.
// Vertices left without quads are dropped and the ids renumbered. Returns the number
// of quads removed.
int collapse_quads(QuadMesh& m, const std::function<bool(int)>& wanted, int choice = 0) {
  const int nv = static_cast<int>(m.points.size());
  const int nq = static_cast<int>(m.quads.size());
  std::vector<std::vector<int>> around(nv);
  for (int q = 0; q < nq; ++q)
    for (int v : m.quads[q]) around[v].push_back(q);
  std::vector<char> removed(nq, 0), touched(nq, 0);
  int collapses = 0;
  for (int q = 0; q < nq; ++q) {
    if (touched[q] || !wanted(q)) continue;
    const auto& c4 = m.quads[q];
    std::vector<std::tuple<double, int, int>> options;  // (diagonal length, keep, drop)
    for (int i = 0; i < 4; ++i) {
      const int a = c4[i], c = c4[(i + 2) % 4];
      if (m.chain[c] >= 0 || m.fixed[c]) continue;
      bool ok = true;
      for (int k : {1, 3}) {
        const int b = c4[(i + k) % 4];
        const std::size_t need = m.chain[b] >= 0 ? 2 : 4;
        if (around[b].size() < need) ok = false;
      }
      for (int o : around[c])
        if (o != q && (touched[o] || std::find(m.quads[o].begin(), m.quads[o].end(), a) != m.quads[o].end()))
          ok = false;
      // The merged vertex's edges stay manifold and consistently oriented: no directed
      // edge from or to it twice.
      std::vector<std::pair<int, int>> directed;
      for (int end : {a, c})
        for (int o : around[end]) {
          if (o == q) continue;
          const auto& t = m.quads[o];
          for (int j = 0; j < 4; ++j) {
            const int from = t[j] == c ? a : t[j], to = t[(j + 1) % 4] == c ? a : t[(j + 1) % 4];
            if (from == a || to == a) directed.push_back({from, to});
          }
        }
      std::sort(directed.begin(), directed.end());
      if (std::adjacent_find(directed.begin(), directed.end()) != directed.end()) ok = false;
      if (ok) options.emplace_back(distance(m.points[a], m.points[c]), a, c);
    }
    if (static_cast<int>(options.size()) <= choice) continue;
    std::sort(options.begin(), options.end());
    const int best_keep = std::get<1>(options[choice]), best_drop = std::get<2>(options[choice]);
    removed[q] = 1;
    for (int o : around[best_drop]) {
      touched[o] = 1;
      for (int& v : m.quads[o])
        if (v == best_drop) v = best_keep;
    }
    for (int v : c4)
      for (int o : around[v]) touched[o] = 1;
    ++collapses;
  }
  if (collapses == 0) return 0;
  remove_quads(m, removed);
  return collapses;
}


// Colours of the vertices such that no two vertices of a quad share one (greedy, in vertex
// order): vertices of a colour are moved independently of each other, each colour's in
// vertex order.
std::vector<std::vector<int>> quad_colouring(const QuadMesh& m, const Topology& t) {
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
  AlignedSmoother(const BackgroundMesh& bg, QuadMesh& m, const Topology& t,
                  const SizingField& size, const CrossField& cross, const SmoothParams& params)
      : bg_(bg), m_(m), t_(t), size_(size), cross_(cross), params_(params), locator_(bg) {}

  void run() {
    const int nv = static_cast<int>(m_.points.size());
    h_.resize(nv);
    theta_.resize(nv);
    const int threads = sweep_threads(params_);
    for (int it = 0; it < params_.aligned_iterations; ++it) {
      parallel_chunks(nv, threads, [&](int begin, int end, int) {
        for (int v = begin; v < end; ++v) {
          const Location loc = locator_.locate(m_.points[v]);
          h_[v] = loc.triangle >= 0 ? size_.at(bg_, loc.triangle, loc.bary) : 0.0;
          theta_[v] = loc.triangle >= 0 ? cross_angle_at(bg_, cross_, loc.triangle, loc.bary) : 0.0;
        }
      });
      for (int v = 0; v < nv; ++v) {
        if (m_.fixed[v]) continue;
        if (m_.chain[v] >= 0) slide_boundary(v);
        else move_interior(v);
      }
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
          cost += std::abs(std::remainder(around[j].first - theta_[v] - (r + j) * M_PI / 2, 2 * M_PI));
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
  const Topology& t_;
  const SizingField& size_;
  const CrossField& cross_;
  const SmoothParams& params_;
  TriangleLocator locator_;
  std::vector<double> h_, theta_;
};

// The logistic function: a smooth step from 0 (x << 0) to 1 (x >> 0).
double smooth_step(double x) { return 1.0 / (1.0 + std::exp(-x)); }

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
double moving_corner_energy(const QuadMesh& m, const Topology& t, int v, const SmoothParams& params,
                            const std::vector<double>& area0, const double* opposite_angle,
                            double& sharpest) {
  const double range = params.angle_range_deg * M_PI / 180;
  const double softness = params.angle_range_softness_deg * M_PI / 180;
  double e = 0;
  for (int k = t.quad_start[v]; k < t.quad_start[v + 1]; ++k) {
    const int q = t.quad_items[k];
    const auto& c = m.quads[q];
    const int j = c[0] == v ? 0 : c[1] == v ? 1 : c[2] == v ? 2 : 3;
    double smallest = opposite_angle[k - t.quad_start[v]], largest = smallest;
    for (int d = 3; d <= 5; ++d) {
      const int i = (j + d) % 4;
      const Point2 &p = m.points[c[(i + 3) % 4]], &o = m.points[c[i]], &n = m.points[c[(i + 1) % 4]];
      const double ax = p.x - o.x, ay = p.y - o.y, bx = n.x - o.x, by = n.y - o.y;
      const double cross = bx * ay - by * ax, dot = ax * bx + ay * by;
      const double angle = std::atan2(cross, dot);
      smallest = std::min(smallest, angle);
      largest = std::max(largest, angle);
      sharpest = std::min(sharpest, angle);
      // quad_convexity's measure at this corner: the sine of the turn between edges.
      const double l2 = (ax * ax + ay * ay) * (bx * bx + by * by);
      if (l2 == 0 || cross <= params.min_convexity * std::sqrt(l2))
        return std::numeric_limits<double>::infinity();
      const double a = angle - 0.5 * M_PI;
      e += a * a;
      if (params.angle_range_weight > 0)
        e += params.angle_range_weight * smooth_step((std::abs(a) - range) / softness);
    }
    if (params.angle_ratio_weight > 0)
      e += params.angle_ratio_weight *
           smooth_step((params.min_angle_ratio - smallest / largest) / params.angle_ratio_softness);
    if (params.aspect_weight > 0 || params.aspect_log_weight > 0) {
      double shortest = std::numeric_limits<double>::infinity(), longest = 0;
      for (int i = 0; i < 4; ++i) {
        const double l = distance(m.points[c[i]], m.points[c[(i + 1) % 4]]);
        shortest = std::min(shortest, l), longest = std::max(longest, l);
      }
      if (shortest > 0) {
        const double over = std::log(longest / shortest) - std::log(params.max_aspect);
        e += params.aspect_weight * smooth_step(over / params.aspect_softness);
        if (over > 0) e += params.aspect_log_weight * over;
      }
    }
    if (params.angle_area_weight > 0 || params.size_range_weight > 0) {
      const double r = std::log(quad_area(m, q) / area0[q]);
      e += params.angle_area_weight * r * r;
      if (params.size_range_weight > 0)
        e += params.size_range_weight *
             smooth_step((std::abs(r) - params.size_range_log_area) / params.size_range_softness);
    }
  }
  return e;
}

// Angle sweeps: every free vertex takes the best of its candidate moves (interior: eight
// directions; boundary: both ways along its chain, staying between its boundary
// neighbours), each angle_step of its shortest edge long (0.3 of that in the second
// half of the sweeps), if that lowers moving_corner_energy (target areas h^2 with a sizing
// field) plus the orientation term of its edges; convexity never drops below
// min_convexity. `iterations` sweeps (default angle_iterations); with `only`, the
// vertices it marks move, the others stay.
void angle_sweeps(const BackgroundMesh& bg, QuadMesh& m, const Topology& t,
                  const SmoothParams& params, const CrossField* cross, const SizingField* size,
                  const std::vector<char>* only = nullptr, int iterations = -1) {
  const int nv = static_cast<int>(m.points.size());
  if (iterations < 0) iterations = params.angle_iterations;
  const double ow = params.angle_orientation_weight;
  std::unique_ptr<TriangleLocator> locator;
  if ((cross && ow > 0) || size) locator = std::make_unique<TriangleLocator>(bg);
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
  // else the areas there.
  std::vector<double> area0(m.quads.size());
  for (std::size_t q = 0; q < m.quads.size(); ++q) {
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
        const double d = (forward ? chord_departure(m, bg, v, w) : chord_departure(m, bg, w, v)).distance_m;
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
  // The vertices of one colour move independently, so in parallel.
  const std::vector<std::vector<int>> colours = quad_colouring(m, t);
  const int threads = sweep_threads(params);
  std::vector<std::vector<double>> scratch(threads);
  long time = 0;
  for (int it = 0; it < iterations; ++it) {
    // The second half of the sweeps refines with steps 0.3 as long.
    const bool refine = 2 * it >= iterations;
    if (refine && 2 * (it - 1) < iterations)
      std::fill(stayed_at.begin(), stayed_at.end(), -1);
    for (const std::vector<int>& colour : colours) {
      ++time;
      parallel_chunks(static_cast<int>(colour.size()), threads, [&](int begin, int end, int thread) {
        for (int i = begin; i < end; ++i) {
          const int v = colour[i];
          if (m.fixed[v] || t.neighbours[v].empty() || (only && !(*only)[v]) || unchanged(v)) continue;
          if (move(v, refine ? 0.3 : 1.0, scratch[thread]))
            moved_at[v] = time, stayed_at[v] = -1;
          else
            stayed_at[v] = time;
        }
      });
    }
  }
}

bool contains_point(const std::vector<Point2>& points, const Point2& p) {
  return std::any_of(points.begin(), points.end(),
                     [&](const Point2& o) { return o.x == p.x && o.y == p.y; });
}

// The possible collapses of quad `pick` in turn (shorter diagonal first, while `tries`
// is under collapse_tries), each followed by the untangling sweeps: keeps the first
// that `better` accepts (called with the new connectivity) and undoes the others.
bool collapse_first_better(const BackgroundMesh& bg, QuadMesh& m, const SmoothParams& params,
                           SmoothStats& stats, int pick, int& tries,
                           const std::function<bool(const Topology&)>& better) {
  for (int choice = 0; choice < 4 && tries < params.collapse_tries; ++choice, ++tries) {
    QuadMesh before = m;
    const SmoothStats stats_before = stats;
    if (collapse_quads(m, [&](int q) { return q == pick; }, choice) == 0) return false;
    const Topology t = topology(m);
    untangle(bg, m, t, params, stats);
    if (better(t)) return true;
    m = std::move(before);
    stats = stats_before;
  }
  return false;
}

// The edge flips of quad `pick` with its neighbours in turn (while `tries` is under
// collapse_tries), each followed by the untangling sweeps: keeps the first that
// `better` accepts and undoes the others. Unlike flip_nonconvex, a flip need not make
// the two quads better where the vertices stand: a boundary vertex in one quad only,
// where the boundary runs straight, is a corner of 180 degrees that no move mends, and a
// flip that gives it a second quad lets the sweeps make both convex (France at hmax 29
// km: a quad on a lake's straight side, whose tiling was retried before).
bool flip_first_better(const BackgroundMesh& bg, QuadMesh& m, const SmoothParams& params,
                       SmoothStats& stats, int pick, int& tries,
                       const std::function<bool()>& better) {
  const std::vector<QuadFlip> flips = flips_of(m, EdgeQuads(m), pick);
  for (std::size_t k = 0; k < flips.size() && tries < params.collapse_tries; ++k, ++tries) {
    QuadMesh before = m;
    const SmoothStats stats_before = stats;
    m.quads[flips[k].q] = flips[k].a;
    m.quads[flips[k].n] = flips[k].b;
    untangle(bg, m, topology(m), params, stats);
    if (better()) {
      ++stats.num_flips;
      return true;
    }
    m = std::move(before);
    stats = stats_before;
  }
  return false;
}

// Non-convex quads the collapse rounds left, one at a time (at most collapse_tries):
// each of its possible collapses in turn (shorter diagonal first), the first that
// leaves fewer quads non-convex kept; failing those, each of its edge flips (at most
// collapse_tries of them in all; none with flip_rounds 0), kept the same way when no
// more boundary edges cross.
// Returns the number of collapses kept.
int collapse_one_by_one(const BackgroundMesh& bg, QuadMesh& m, const SmoothParams& params,
                        SmoothStats& stats) {
  auto count_nonconvex = [&] {
    int n = 0;
    for (int q = 0; q < static_cast<int>(m.quads.size()); ++q)
      n += quad_convexity(m, q) <= params.min_convexity;
    return n;
  };
  std::vector<Point2> tried;  // centroids of the quads tried (ids change on a collapse)
  int kept = 0, flip_tries = 0;
  for (int attempt = 0; attempt < params.collapse_tries || flip_tries < params.collapse_tries;) {
    const int bad = count_nonconvex();
    if (bad == 0) break;
    int pick = -1;
    for (int q = 0; q < static_cast<int>(m.quads.size()) && pick < 0; ++q)
      if (quad_convexity(m, q) <= params.min_convexity && !contains_point(tried, quad_centroid(m, q)))
        pick = q;
    if (pick < 0) break;
    tried.push_back(quad_centroid(m, pick));
    if (collapse_first_better(bg, m, params, stats, pick, attempt,
                              [&](const Topology&) { return count_nonconvex() < bad; })) {
      ++kept;
      continue;
    }
    if (params.flip_rounds == 0) continue;  // flips off
    const std::size_t crossings = count_boundary_crossings(m);
    flip_first_better(bg, m, params, stats, pick, flip_tries, [&] {
      return count_nonconvex() < bad && count_boundary_crossings(m) <= crossings;
    });
  }
  return kept;
}

// Folds (count_boundary_crossings): the boundary vertices of crossing boundary edges
// slide along the boundary, each to the first of a few shrinking steps either way that
// leaves fewer crossings and every quad around it convex; rounds until none is left or
// no slide helps. Returns the crossings left.
std::size_t unfold_boundary(const BackgroundMesh& bg, QuadMesh& m, const Topology& t,
                            const SmoothParams& params) {
  std::size_t crossings = count_boundary_crossings(m);
  for (int round = 0; round < params.unfold_rounds && crossings > 0; ++round) {
    bool moved = false;
    // The ends of the crossing edges, then their neighbours along the boundary.
    std::vector<int> ends;
    auto add = [&](int v) {
      if (v >= 0 && m.chain[v] >= 0 && !m.fixed[v] && std::find(ends.begin(), ends.end(), v) == ends.end())
        ends.push_back(v);
    };
    for (const auto& pair : boundary_crossings(m))
      for (int v : pair) add(v);
    for (std::size_t k = 0, n = ends.size(); k < n; ++k)
      for (int w : t.boundary_neighbours[ends[k]]) add(w);
    const std::vector<std::array<int, 2>> edges = boundary_edges(m);
    for (int v : ends) {
      const auto& bn = t.boundary_neighbours[v];
      const int c = m.chain[v];
      if (bn[0] < 0 || bn[1] < 0 || m.chain[bn[0]] != c || m.chain[bn[1]] != c) continue;
      const double len = bg.chains[c].length_m;
      const double d0 = arc_delta(m.arc_m[v], m.arc_m[bn[0]], len);
      const double d1 = arc_delta(m.arc_m[v], m.arc_m[bn[1]], len);
      if (d0 * d1 >= 0) continue;
      const Point2 start = m.points[v];
      const double start_arc = m.arc_m[v];
      // Only the crossings of v's two boundary edges change as it slides.
      std::vector<std::array<int, 2>> at_v;
      for (const auto& e : edges)
        if (e[0] == v || e[1] == v) at_v.push_back(e);
      auto crossings_at_v = [&] {
        std::size_t n = 0;
        for (const auto& e : at_v)
          for (const auto& f : edges)
            if (f != e && !(std::find(at_v.begin(), at_v.end(), f) != at_v.end() && f < e) &&
                boundary_edges_meet(m, e, f))
              ++n;
        return n;
      };
      const std::size_t before = crossings_at_v();
      bool done = false;
      for (double fraction : {0.8, 0.5, 0.3, 0.15, 0.05}) {
        for (double d : {d0, d1}) {
          const double arc = start_arc + fraction * d;
          m.points[v] = chain_point(bg, bg.chains[c], arc);
          m.arc_m[v] = arc;
          if (worst_convexity(m, t, v) > params.min_convexity) {
            const std::size_t after = crossings_at_v();
            if (after < before) {
              crossings = crossings - before + after;
              done = moved = true;
              break;
            }
          }
          m.points[v] = start;
          m.arc_m[v] = start_arc;
        }
        if (done) break;
      }
      if (crossings == 0) break;
    }
    if (!moved) break;
  }
  return crossings;
}

// Folds the slides leave: a quad with a crossing boundary edge is removed by a diagonal
// collapse (each possible one in turn, at most collapse_tries in all), or failing that
// re-split with a neighbour by an edge flip (as many; none with flip_rounds 0) and
// untangled, then the slides run again; kept when fewer crossings are left and every
// quad is convex (France at hmax 24 km --simplify 800: a quad across a narrow inlet,
// whose tiling was retried before). Returns the number of collapses kept.
int collapse_folds(const BackgroundMesh& bg, QuadMesh& m, const SmoothParams& params,
                   SmoothStats& stats) {
  auto nonconvex = [&] {
    for (int q = 0; q < static_cast<int>(m.quads.size()); ++q)
      if (quad_convexity(m, q) <= params.min_convexity) return true;
    return false;
  };
  std::vector<Point2> tried;  // centroids of the quads tried
  int kept = 0, flip_tries = 0;
  for (int attempt = 0; attempt < params.collapse_tries || flip_tries < params.collapse_tries;) {
    const std::size_t crossings = count_boundary_crossings(m);
    if (crossings == 0) break;
    // A quad that owns a crossing edge and was not tried yet.
    int pick = -1;
    for (const auto& pair : boundary_crossings(m)) {
      for (int e = 0; e < 2 && pick < 0; ++e) {
        const int a = pair[2 * e], b = pair[2 * e + 1];
        for (int q = 0; q < static_cast<int>(m.quads.size()) && pick < 0; ++q) {
          const auto& c = m.quads[q];
          for (int i = 0; i < 4; ++i)
            if (c[i] == a && c[(i + 1) % 4] == b && !contains_point(tried, quad_centroid(m, q))) pick = q;
        }
      }
      if (pick >= 0) break;
    }
    if (pick < 0) break;
    tried.push_back(quad_centroid(m, pick));
    if (collapse_first_better(bg, m, params, stats, pick, attempt, [&](const Topology& t) {
          return !nonconvex() && unfold_boundary(bg, m, t, params) < crossings;
        })) {
      ++kept;
      continue;
    }
    // Failing those, its edge flips, each followed by the sweeps and the slides.
    if (params.flip_rounds == 0) continue;
    flip_first_better(bg, m, params, stats, pick, flip_tries, [&] {
      return !nonconvex() && unfold_boundary(bg, m, topology(m), params) < crossings;
    });
  }
  return kept;
}

// How far the repair after a sliver's collapse or flip reaches, in rings of quads.
constexpr int kSliverRings = 3;

// The quads within `rings` rings (sharing a vertex, ring by ring) of the quad whose
// centroid is nearest `at`, ascending.
std::vector<int> quads_near(const QuadMesh& m, const Topology& t, const Point2& at, int rings) {
  const int nq = static_cast<int>(m.quads.size());
  int seed = -1;
  double best = 1e300;
  for (int q = 0; q < nq; ++q) {
    const Point2 c = quad_centroid(m, q);
    const double d = (c.x - at.x) * (c.x - at.x) + (c.y - at.y) * (c.y - at.y);
    if (d < best) best = d, seed = q;
  }
  std::vector<int> out;
  if (seed < 0) return out;
  std::vector<char> in(nq, 0);
  in[seed] = 1;
  out.push_back(seed);
  for (std::size_t first = 0, ring = 0; ring < static_cast<std::size_t>(rings); ++ring) {
    const std::size_t last = out.size();
    for (std::size_t i = first; i < last; ++i)
      for (int v : m.quads[out[i]])
        for (int k = t.quad_start[v]; k < t.quad_start[v + 1]; ++k)
          if (!in[t.quad_items[k]]) in[t.quad_items[k]] = 1, out.push_back(t.quad_items[k]);
    first = last;
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Ten Gauss-Seidel sweeps, in vertex order, that put each interior vertex of `quads`
// (neither on the boundary nor fixed) at the middle of its neighbours; convexity is left
// to the untangling after.
void move_to_neighbours_middle(QuadMesh& m, const Topology& t, const std::vector<int>& quads) {
  std::vector<int> movable;
  for (int q : quads)
    for (int v : m.quads[q])
      if (m.chain[v] < 0 && !m.fixed[v] && !t.neighbours[v].empty()) movable.push_back(v);
  std::sort(movable.begin(), movable.end());
  movable.erase(std::unique(movable.begin(), movable.end()), movable.end());
  for (int sweep = 0; sweep < 10; ++sweep)
    for (int v : movable) {
      Point2 c{0, 0};
      for (int w : t.neighbours[v]) c.x += m.points[w].x, c.y += m.points[w].y;
      const double k = static_cast<double>(t.neighbours[v].size());
      m.points[v] = {c.x / k, c.y / k};
    }
}

// A thin chord: a row of quads joined by their short sides, from the boundary to the
// boundary, each quad's short sides under a quarter of its long ones (Croatia at 1:10m:
// a column 27 m wide and 615 m long, ending in a quad with a side of 0.7 m). No
// collapse of a diagonal or flip mends it; merging the two ends of every short side
// removes the row, and the quads on its two sides meet. A merged vertex is the boundary
// one where one is on the boundary (the fixed one where one is a corner), at the arc's
// middle where both are, else at the middle. Returns false, the mesh unchanged, when
// the row is not thin throughout, does not reach the boundary both ways within max_row
// quads, would merge two corners or two chains, or would leave a quad with a vertex
// twice or an edge used twice the same way.
bool collapse_chord(const BackgroundMesh& bg, QuadMesh& m, int start, int max_row) {
  const EdgeQuads edges(m);
  auto side = [&](int q, int i) {
    return distance(m.points[m.quads[q][i]], m.points[m.quads[q][(i + 1) % 4]]);
  };
  // Whether quad q's sides i and i + 2 are its short ones, and short enough.
  auto thin = [&](int q, int i) {
    return std::max(side(q, i), side(q, i + 2)) < 0.25 * std::min(side(q, i + 1), side(q, (i + 3) % 4));
  };
  const int k = std::max(side(start, 0), side(start, 2)) < std::max(side(start, 1), side(start, 3)) ? 0 : 1;
  if (!thin(start, k)) return false;
  std::vector<int> row{start};
  std::vector<std::array<int, 2>> sides{{m.quads[start][k], m.quads[start][k + 1]},
                                        {m.quads[start][k + 2], m.quads[start][(k + 3) % 4]}};
  for (int way = 0; way < 2; ++way) {
    int cur = start;
    std::array<int, 2> e = sides[way];
    for (;;) {
      const int n = edges.other(e[0], e[1], cur);
      if (n < 0) break;  // the boundary
      if (static_cast<int>(row.size()) >= max_row || std::find(row.begin(), row.end(), n) != row.end())
        return false;
      const auto& t = m.quads[n];
      int j = 0;
      while (j < 4 && !(t[j] == e[1] && t[(j + 1) % 4] == e[0])) ++j;
      if (j == 4 || !thin(n, j % 2)) return false;
      row.push_back(n);
      e = {t[(j + 2) % 4], t[(j + 3) % 4]};
      sides.push_back(e);
      cur = n;
    }
  }
  // Merge each short side's ends: w into u.
  const int nv = static_cast<int>(m.points.size());
  std::vector<int> into(nv);
  for (int v = 0; v < nv; ++v) into[v] = v;
  QuadMesh out = m;
  for (auto [u, w] : sides) {
    if (m.fixed[u] && m.fixed[w]) return false;
    if (m.chain[u] >= 0 && m.chain[w] >= 0) {
      if (m.chain[u] != m.chain[w]) return false;
      if (m.fixed[w]) std::swap(u, w);
      if (!m.fixed[u]) {
        const BoundaryChain& c = bg.chains[m.chain[u]];
        const double arc = m.arc_m[u] + 0.5 * arc_delta(m.arc_m[u], m.arc_m[w], c.length_m);
        out.arc_m[u] = arc;
        out.points[u] = chain_point(bg, c, arc);
      }
    } else if (m.chain[w] >= 0 || m.fixed[w]) {
      std::swap(u, w);  // keep the boundary (or fixed) one
    } else if (m.chain[u] < 0 && !m.fixed[u]) {
      out.points[u] = {0.5 * (m.points[u].x + m.points[w].x), 0.5 * (m.points[u].y + m.points[w].y)};
    }
    if (into[w] != w || into[u] != u) return false;  // an end of two sides: not a plain row
    into[w] = u;
  }
  std::vector<char> removed(m.quads.size(), 0);
  for (int q : row) removed[q] = 1;
  std::vector<std::pair<int, int>> directed;
  for (std::size_t q = 0; q < out.quads.size(); ++q) {
    if (removed[q]) continue;
    for (int& v : out.quads[q]) v = into[v];
    const auto& t = out.quads[q];
    for (int i = 0; i < 4; ++i) {
      for (int j = i + 1; j < 4; ++j)
        if (t[i] == t[j]) return false;
      directed.push_back({t[i], t[(i + 1) % 4]});
    }
  }
  std::sort(directed.begin(), directed.end());
  if (std::adjacent_find(directed.begin(), directed.end()) != directed.end()) return false;
  remove_quads(out, removed);
  m = std::move(out);
  return true;
}

// Slivers, once every quad is convex: quads still flatter than sliver_convexity, the
// flattest first, each removed by a diagonal collapse when that (with the lift and
// untangling sweeps after it, on the quads within kSliverRings of it) leaves every quad
// convex, no more boundary crossings, and either raises the flattest quad's convexity or
// leaves fewer slivers without lowering it. At most sliver_tries quads are tried; a
// collapse not kept is undone. (Sweeps over the whole mesh after each try cost the
// Arctic Ocean at 1:10m, 39,770 quads, 10 s of its 13 s here; the local ones 0.1 s.)
// With `relocate` (SmoothParams::sliver_relocate), each try moves the interior vertices
// next to the change to their neighbours' middle first, and no thin row is collapsed.
void collapse_slivers(const BackgroundMesh& bg, QuadMesh& m, const SmoothParams& params,
                      const SmoothParams& lift, SmoothStats& stats, bool relocate = false) {
  auto scan = [&](int& slivers, int& nonconvex, double& worst) {
    slivers = nonconvex = 0;
    worst = 1.0;
    for (int q = 0; q < static_cast<int>(m.quads.size()); ++q) {
      const double c = quad_convexity(m, q);
      slivers += c <= params.sliver_convexity;
      nonconvex += c <= params.min_convexity;
      worst = std::min(worst, c);
    }
  };
  std::vector<Point2> tried;  // centroids of the slivers tried (ids change on a collapse)
  // The mesh's counts before a try: the same as before the last one unless that changed
  // the mesh (a change not kept is undone exactly), so counted again only then.
  bool changed = true;
  int slivers0 = 0, nonconvex0 = 0;
  double worst0 = 1.0;
  std::size_t crossings0 = 0;
  for (int attempt = 0; attempt < params.sliver_tries; ++attempt) {
    int pick = -1;
    double flattest = params.sliver_convexity;
    for (int q = 0; q < static_cast<int>(m.quads.size()); ++q) {
      const double c = quad_convexity(m, q);
      if (c > flattest || (pick >= 0 && c == flattest)) continue;
      if (contains_point(tried, quad_centroid(m, q))) continue;
      pick = q;
      flattest = c;
    }
    if (pick < 0) break;
    tried.push_back(quad_centroid(m, pick));
    if (changed) {
      scan(slivers0, nonconvex0, worst0);
      crossings0 = count_boundary_crossings(m);
      changed = false;
    }
    // A change of the topology around the sliver, kept when the mesh is then better.
    // With `relocate`, the interior vertices of the quads next to it first go to the
    // middle of their neighbours (a change that leaves a vertex of three or five quads
    // can need it moved further than the untangling's steps take it).
    auto kept = [&](const std::function<bool()>& change) {
      QuadMesh before = m;
      const SmoothStats stats_before = stats;
      if (!change()) {
        changed = true;  // (a change that fails may have begun)
        return false;
      }
      const Topology t = topology(m);
      const std::vector<int> near = quads_near(m, t, tried.back(), kSliverRings);
      if (relocate) move_to_neighbours_middle(m, t, quads_near(m, t, tried.back(), 1));
      SmoothStats ignored;
      untangle(bg, m, t, lift, ignored, false, &near);
      untangle(bg, m, t, params, stats, true, &near);
      int slivers1, nonconvex1;
      double worst1;
      scan(slivers1, nonconvex1, worst1);
      if (nonconvex1 == 0 && worst1 >= worst0 && (worst1 > worst0 || slivers1 < slivers0) &&
          count_boundary_crossings(m) <= crossings0) {
        changed = true;
        return true;
      }
      m = std::move(before);
      stats = stats_before;
      return false;
    };
    // Each diagonal collapse (shortest diagonal first), then each edge flip with a
    // neighbour (its hexagon split along another diagonal).
    bool done = false;
    for (int choice = 0; choice < 4 && !done; ++choice)
      if (kept([&] {
            return collapse_quads(
                       m, [&](int q) { return q == pick; }, choice) > 0;
          })) {
        ++stats.num_sliver_collapses;
        done = true;
      }
    const std::vector<QuadFlip> flips =
        done ? std::vector<QuadFlip>{} : flips_of(m, EdgeQuads(m), pick);
    for (std::size_t k = 0; k < flips.size() && !done; ++k)
      if (kept([&] {
            m.quads[flips[k].q] = flips[k].a;
            m.quads[flips[k].n] = flips[k].b;
            return true;
          })) {
        ++stats.num_flips;
        done = true;
      }
    // Failing those, the thin row it ends, collapsed (not again with the relocation).
    if (!done && !relocate && params.sliver_row_max > 0 &&
        kept([&] { return collapse_chord(bg, m, pick, params.sliver_row_max); }))
      ++stats.num_sliver_collapses;
  }
}

// A doubled corner (SmoothParams::doubled_corner_side): boundary vertex b in two quads,
// interior vertex i in four. The four quads round i bound an octagon b, v1, ..., v7
// (counter-clockwise); it is split into three quads fanned from b, along b-v3 and b-v5,
// and i goes. Returns false, the mesh unchanged, when the quads round i do not close
// round it or b is not among their corners as expected.
bool split_doubled_corner(QuadMesh& m, const Topology& t, int b, int i) {
  // Each quad round i from i: (i, x1, x2, x3); the octagon is the x1, x2 of each in turn
  // (one's x3 is the next one's x1), from the quad whose x1 is b.
  std::vector<std::array<int, 3>> outer;
  std::vector<int> round_i;
  for (int k = t.quad_start[i]; k < t.quad_start[i + 1]; ++k) {
    const int q = t.quad_items[k];
    const auto& v = m.quads[q];
    int j = 0;
    while (v[j] != i) ++j;
    outer.push_back({v[(j + 1) % 4], v[(j + 2) % 4], v[(j + 3) % 4]});
    round_i.push_back(q);
  }
  if (outer.size() != 4) return false;
  std::vector<int> octagon;
  int from = b;
  for (int step = 0; step < 4; ++step) {
    int next = -1;
    for (const auto& o : outer)
      if (o[0] == from) next = &o - outer.data();
    if (next < 0) return false;
    octagon.push_back(outer[next][0]);
    octagon.push_back(outer[next][1]);
    from = outer[next][2];
  }
  if (from != b) return false;
  for (std::size_t a = 0; a < octagon.size(); ++a)
    for (std::size_t c = a + 1; c < octagon.size(); ++c)
      if (octagon[a] == octagon[c]) return false;
  std::vector<char> removed(m.quads.size(), 0);
  for (int q : round_i) removed[q] = 1;
  const auto& o = octagon;
  m.quads.push_back({o[0], o[1], o[2], o[3]});
  m.quads.push_back({o[0], o[3], o[4], o[5]});
  m.quads.push_back({o[0], o[5], o[6], o[7]});
  removed.resize(m.quads.size(), 0);
  remove_quads(m, removed);  // i, in none of them now, goes too
  return true;
}

// Doubled corners, every quad convex: each tried once, kept when the mesh is then
// convex (after the lift and untangling sweeps on the quads within kSliverRings), its
// flattest quad no flatter and no more boundary edges cross; otherwise undone. Returns
// where the kept splits left the vertices of their three quads (for the sweeps after).
std::vector<Point2> split_doubled_corners(const BackgroundMesh& bg, QuadMesh& m,
                                          const SmoothParams& params, const SmoothParams& lift,
                                          SmoothStats& stats) {
  std::vector<Point2> touched;
  // The corners, by position (ids change with each split): b and i.
  std::vector<std::pair<Point2, Point2>> found;
  {
    const Topology t = topology(m);
    for (int b = 0; b < static_cast<int>(m.points.size()); ++b) {
      if (m.chain[b] < 0 && !m.fixed[b]) continue;
      if (t.quad_start[b + 1] - t.quad_start[b] != 2) continue;
      double turn = 0, longest = 0;
      for (int k = t.quad_start[b]; k < t.quad_start[b + 1]; ++k) {
        const int q = t.quad_items[k];
        int j = 0;
        while (m.quads[q][j] != b) ++j;
        turn += quad_angles_deg(m, q)[j];
      }
      if (turn <= 200.0) continue;
      for (int w : t.neighbours[b]) longest = std::max(longest, distance(m.points[b], m.points[w]));
      for (int i : t.neighbours[b])
        if (m.chain[i] < 0 && !m.fixed[i] && t.quad_start[i + 1] - t.quad_start[i] == 4 &&
            distance(m.points[b], m.points[i]) < params.doubled_corner_side * longest)
          found.push_back({m.points[b], m.points[i]});
    }
  }
  // The flattest quad's convexity (every quad is convex when this pass starts).
  auto worst_convexity = [&] {
    double worst = 1.0;
    for (int q = 0; q < static_cast<int>(m.quads.size()); ++q) worst = std::min(worst, quad_convexity(m, q));
    return worst;
  };
  // The mesh as it stands (measured again after each kept split).
  double worst0 = 1.0;
  std::size_t crossings0 = 0;
  if (!found.empty()) {
    worst0 = worst_convexity();
    crossings0 = count_boundary_crossings(m);
  }
  for (const auto& [pb, pi] : found) {
    int b = -1, i = -1;
    for (int v = 0; v < static_cast<int>(m.points.size()); ++v) {
      if (m.points[v] == pb) b = v;
      if (m.points[v] == pi) i = v;
    }
    if (b < 0 || i < 0) continue;  // moved by an earlier split's sweeps
    QuadMesh before = m;
    const SmoothStats stats_before = stats;
    if (!split_doubled_corner(m, topology(m), b, i)) continue;
    const Topology t = topology(m);
    const std::vector<int> near = quads_near(m, t, pb, kSliverRings);
    SmoothStats ignored;
    untangle(bg, m, t, lift, ignored, false, &near);
    untangle(bg, m, t, params, stats, true, &near);
    // No flatter than before, which was convex: so every quad is convex.
    const double worst1 = worst_convexity();
    const std::size_t crossings1 = worst1 >= worst0 ? count_boundary_crossings(m) : 0;
    if (worst1 >= worst0 && crossings1 <= crossings0) {
      ++stats.num_corner_splits;
      worst0 = worst1;
      crossings0 = crossings1;
      // remove_quads keeps the order of the quads left: the three new ones are last.
      for (std::size_t q = m.quads.size() - 3; q < m.quads.size(); ++q)
        for (int v : m.quads[q]) touched.push_back(m.points[v]);
      continue;
    }
    m = std::move(before);
    stats = stats_before;
  }
  std::sort(touched.begin(), touched.end(), point_less);
  return touched;
}

}  // namespace

SmoothStats smooth_quads(const BackgroundMesh& bg, QuadMesh& m, const SmoothParams& params,
                         const SizingField* size, const CrossField* cross) {
  SmoothStats stats;
  const Topology t = topology(m);
  auto count_nonconvex = [&] {
    int n = 0;
    for (int q = 0; q < static_cast<int>(m.quads.size()); ++q)
      n += quad_convexity(m, q) <= params.min_convexity;
    return n;
  };
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
    AlignedSmoother(bg, m, t, *size, *cross, params).run();
  angle_sweeps(bg, m, t, params, cross, size);
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
    untangle(bg, m, topology(m), params, stats);
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
    untangle(bg, m, topology(m), params, stats);
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
    if (unfold_boundary(bg, m, topology(m), params) > 0)
      stats.num_collapses += collapse_folds(bg, m, params, stats);
    // The slides and collapses that unfold the mesh can leave a sliver where it folded
    // (France at hmax 18 km --simplify 800: 2.2 degrees): the sliver pass again there.
    if (count_nonconvex() == 0) collapse_slivers(bg, m, params, lift, stats);
  }
  std::vector<Point2> split;  // where the corner splits left their quads' vertices
  if (params.doubled_corner_side > 0 && count_nonconvex() == 0)
    split = split_doubled_corners(bg, m, params, lift, stats);
  // The repairs move vertices for convexity alone, and flips and collapses leave new
  // quads unswept: the angle sweeps again (SmoothParams::resweep_iterations) on the
  // vertices that moved since `swept_at` (sorted positions) or stand at `also`, and the
  // ones next to them, undone should they fold the mesh.
  auto resweep_moved = [&](const std::vector<Point2>& swept_at, const std::vector<Point2>& also) {
    if (params.resweep_iterations <= 0 || params.angle_iterations <= 0 || count_nonconvex() > 0)
      return;
    const Topology t2 = topology(m);
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
  stats.num_nonconvex_after = count_nonconvex();
  return stats;
}

}  // namespace isoquad
