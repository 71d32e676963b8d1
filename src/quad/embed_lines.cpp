#include "quad/embed_lines.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <queue>
#include <tuple>
#include <utility>

#include "fields/align_lines.h"
#include "mesh/locate.h"
#include "mesh/nearest_points.h"
#include "quad/quad_sweeps.h"
#include "quad/quad_topology.h"

namespace isoquad {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A piece of a line inside the domain; `own_ends[0]` / `[1]`: whether its first / last
// point is a point of the line inside the domain (the line's own end, or where a
// closed line is cut in two), not where the walk left the domain.
struct Run {
  int line = 0;
  std::vector<Point2> points;
  std::array<bool, 2> own_ends{false, false};
};

// The runs of each line inside the background mesh (the domain), walked as --align's
// crosses are (walk_line: points a fraction of the mesh's edges apart), each with two
// points at least; with `size`, not within coast_share h of the domain's boundary.
std::vector<Run> runs_inside(const BackgroundMesh& bg,
                             const std::vector<std::vector<Point2>>& lines, const SizingField* size,
                             double coast_share) {
  const TriangleLocator locator(bg);
  std::vector<std::vector<Point2>> chains;  // the domain's boundary, closed
  for (const BoundaryChain& c : bg.chains) {
    std::vector<Point2> ring;
    for (int v : c.vertices) ring.push_back(bg.points[v]);
    if (!ring.empty()) ring.push_back(ring.front());
    chains.push_back(std::move(ring));
  }
  const PolylineIndex coast(std::move(chains));
  std::vector<Run> runs;
  for (std::size_t l = 0; l < lines.size(); ++l) {
    std::vector<Run> mine;
    Run run{static_cast<int>(l), {}, {true, false}};
    double h = 0;  // the size where the run starts
    auto end_run = [&](bool own) {
      run.own_ends[1] = own;
      double length = 0;
      for (std::size_t i = 1; i < run.points.size(); ++i)
        length += distance(run.points[i - 1], run.points[i]);
      // (Not the bits of a line that runs at about coast_share h from the coast.)
      if (run.points.size() >= 2 && (length >= h || (run.own_ends[0] && own))) mine.push_back(run);
      run.points.clear();
      run.own_ends = {false, false};
    };
    walk_line(bg, locator, lines[l], [&](const Point2& p, const Location& at, double) {
      if (!at.inside) return end_run(false);
      const double here = size ? size->at(bg, at.triangle, at.bary) : 0.0;
      // Near the coast, the boundary's row of quads holds the line already.
      if (size && coast.near(p, coast_share * here)) return end_run(false);
      if (run.points.empty()) h = here;
      if (run.points.empty() || run.points.back() != p) run.points.push_back(p);
    });
    end_run(true);
    // A closed line wholly inside: two halves, so that a path joins different ends.
    if (mine.size() == 1 && mine[0].points.size() >= 4 &&
        mine[0].points.front() == mine[0].points.back()) {
      Run second = mine[0];
      const std::size_t half = mine[0].points.size() / 2;
      mine[0].points.resize(half + 1);
      second.points.erase(second.points.begin(), second.points.begin() + half);
      mine[0].own_ends = second.own_ends = {true, true};
      mine.push_back(std::move(second));
    }
    runs.insert(runs.end(), mine.begin(), mine.end());
  }
  return runs;
}

int nearest_vertex(const QuadMesh& m, const QuadTopology& t, const Point2& p) {
  int best = -1;
  double best_d = kInf;
  for (int v = 0; v < static_cast<int>(m.points.size()); ++v) {
    if (t.neighbours[v].empty()) continue;
    const double d = distance(m.points[v], p);
    if (d < best_d) best_d = d, best = v;
  }
  return best;
}

// The nearest point of the run to p within `tolerance`; false when none is.
bool nearest_on_run(const PolylineIndex& run, const Point2& p, double tolerance, Point2& q) {
  Point2 a, b;
  if (!run.nearest_segment(p, tolerance, a, b)) return false;
  q = nearest_on_segment(p, a, b);
  return true;
}

// The nearest point of a polyline to p and its arc length along it: of its first vertex
// and its segments' nearest points, the first nearest. Only the segments near p are
// looked at (a line drawn every 10 m has thousands), found by an index in a radius
// doubled from 1 m until one is within it, then widened by a rounding error's margin:
// the same point and arc as a look at every segment.
class PolylineLocator {
 public:
  explicit PolylineLocator(const std::vector<Point2>& line)
      : line_(line), index_({line}), along_(line.size(), 0.0) {
    for (std::size_t i = 1; i < line.size(); ++i)
      along_[i] = along_[i - 1] + distance(line[i - 1], line[i]);
  }
  Point2 nearest(const Point2& p, double* arc = nullptr) const {
    Point2 best = line_.front();
    double best_d = distance(p, best), best_arc = 0;
    double radius = 1.0;
    while (radius < best_d && !index_.near(p, radius)) radius *= 2;
    radius = std::min(radius, best_d) * (1 + 1e-9) + 1e-9;
    for (const auto& [l, s] : index_.segments_near(p, radius)) {
      const Point2 q = nearest_on_segment(p, line_[s], line_[s + 1]);
      const double d = distance(p, q);
      if (d < best_d) best_d = d, best = q, best_arc = along_[s] + distance(line_[s], q);
    }
    if (arc) *arc = best_arc;
    return best;
  }
  // The arc length from the line's start to its vertex i.
  double arc_at(std::size_t i) const { return along_[i]; }
  // The point at arc length `arc` along the line (clamped to its ends).
  Point2 point_at(double arc) const {
    if (!(arc > 0)) return line_.front();
    if (arc >= along_.back()) return line_.back();
    const std::size_t s = static_cast<std::size_t>(
        std::upper_bound(along_.begin(), along_.end(), arc) - along_.begin() - 1);
    const double len = along_[s + 1] - along_[s], t = len > 0 ? (arc - along_[s]) / len : 0.0;
    return {line_[s].x + t * (line_[s + 1].x - line_[s].x),
            line_[s].y + t * (line_[s + 1].y - line_[s].y)};
  }

 private:
  const std::vector<Point2>& line_;
  PolylineIndex index_;
  std::vector<double> along_;  // arc length at each vertex
};

// Where the ray from `from` along `dir` (unit) first meets the domain's boundary within
// `reach`: the chain, the point and its arc length along the chain; false when it does not.
bool ray_meets_boundary(const BackgroundMesh& bg, const Point2& from, const Point2& dir,
                        double reach, int& chain, Point2& at, double& arc) {
  double best = reach;
  bool found = false;
  for (std::size_t c = 0; c < bg.chains.size(); ++c) {
    const BoundaryChain& ch = bg.chains[c];
    const std::size_t n = ch.vertices.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Point2 &a = bg.points[ch.vertices[i]], &b = bg.points[ch.vertices[(i + 1) % n]];
      const double ex = b.x - a.x, ey = b.y - a.y;
      const double den = dir.x * ey - dir.y * ex;
      if (den == 0) continue;
      const double wx = a.x - from.x, wy = a.y - from.y;
      const double s = (wx * ey - wy * ex) / den;        // along the ray
      const double u = (wx * dir.y - wy * dir.x) / den;  // along the segment
      if (s < 0 || s >= best || u < 0 || u > 1) continue;
      best = s;
      found = true;
      chain = static_cast<int>(c);
      at = {a.x + u * ex, a.y + u * ey};
      arc = ch.arc_length_m[i] + u * std::hypot(ex, ey);
    }
  }
  return found;
}

// The look-ups of --embed-points, indexed: the domain's boundary (its chains), its
// triangles (whether a point is inside), and the mesh's interior and boundary vertices.
class PointLookup {
 public:
  PointLookup(const BackgroundMesh& bg, const QuadMesh& m, const QuadTopology& t)
      : bg_(bg), m_(m), t_(t), locator_(bg), interior_(vertices(false)), coast_(vertices(true)) {
    std::vector<std::vector<Point2>> chains;
    for (const BoundaryChain& ch : bg.chains) {
      chains.emplace_back();
      for (int v : ch.vertices) chains.back().push_back(bg.points[v]);
      if (!ch.vertices.empty()) chains.back().push_back(bg.points[ch.vertices.front()]);
    }
    boundary_ = PolylineIndex(std::move(chains));
  }

  bool inside(const Point2& p) const { return locator_.locate(p).inside; }

  // The mean length of the edges at the vertex nearest p.
  double local_edge(const Point2& p) const {
    const auto in = interior_.nearest(p, 1), on = coast_.nearest(p, 1);
    int v = -1;
    if (!in.empty()) v = interior_ids_[in[0].second];
    if (!on.empty() && (v < 0 || on[0].first < in[0].first)) v = coast_ids_[on[0].second];
    if (v < 0 || t_.neighbours[v].empty()) return 0.0;
    double sum = 0;
    for (int w : t_.neighbours[v]) sum += distance(m_.points[v], m_.points[w]);
    return sum / static_cast<double>(t_.neighbours[v].size());
  }

  // The nearest point of the domain's boundary to p within `reach`: its chain, the point
  // and its arc length along the chain; returns its distance (infinity: none).
  double nearest_on_boundary(const Point2& p, double reach, int& chain, Point2& at,
                             double& arc) const {
    const PolylineIndex::Nearest n = boundary_.nearest(p, reach);
    if (n.line < 0) return kInf;
    const BoundaryChain& ch = bg_.chains[n.line];
    const Point2& a = bg_.points[ch.vertices[n.segment]];
    const Point2& b = bg_.points[ch.vertices[(n.segment + 1) % ch.vertices.size()]];
    chain = n.line;
    at = nearest_on_segment(p, a, b);
    arc = ch.arc_length_m[n.segment] + distance(a, at);
    return distance(p, at);
  }

  // The boundary vertex of `chain` that a point of the coast (x, at `arc` along it)
  // takes: one already there (a corner too), else the nearest along the chain, not a
  // corner, that can slide there between its boundary neighbours (the ends of the
  // mesh's boundary edge round x); not one `held`. -1: none. Looked for among the
  // boundary vertices nearest x.
  int coast_vertex(const std::vector<char>& held, int chain, const Point2& x, double arc,
                   double on_m) const {
    int best = -1;
    double best_d = kInf;
    for (const auto& [d, i] : coast_.nearest(x, 16)) {
      const int v = coast_ids_[i];
      if (m_.chain[v] != chain || held[v]) continue;
      if (d <= on_m) return v;
      const double along = slide(v, chain, arc);
      if (along < best_d) best_d = along, best = v;
    }
    return best;
  }

  // The `count` interior vertices nearest p that are not `held`, nearest first, with
  // their distances.
  std::vector<std::pair<double, int>> nearest_free(const std::vector<char>& held, const Point2& p,
                                                   std::size_t count) const {
    for (std::size_t ask = 2 * count;; ask *= 4) {
      std::vector<std::pair<double, int>> free;
      const auto near = interior_.nearest(p, ask);
      for (const auto& [d, i] : near)
        if (!held[interior_ids_[i]] && free.size() < count) free.push_back({d, interior_ids_[i]});
      if (free.size() == count || near.size() < ask) return free;
    }
  }

 private:
  // The interior (not `boundary`) or boundary vertices in use, for the kd-trees (their
  // ids kept in interior_ids_ or coast_ids_).
  std::vector<Point2> vertices(bool boundary) {
    std::vector<int>& ids = boundary ? coast_ids_ : interior_ids_;
    std::vector<Point2> at;
    for (int v = 0; v < static_cast<int>(m_.points.size()); ++v) {
      if (t_.neighbours[v].empty()) continue;
      const bool on = m_.chain[v] >= 0 || m_.fixed[v];
      if (on != boundary) continue;
      ids.push_back(v);
      at.push_back(m_.points[v]);
    }
    return at;
  }

  // How far boundary vertex v slides along `chain` to `arc`; infinity where it cannot:
  // a corner, or `arc` not strictly between its boundary neighbours, on v's side of
  // them (not round the far side of the chain).
  double slide(int v, int chain, double arc) const {
    const double length = bg_.chains[chain].length_m;
    const auto& bn = t_.boundary_neighbours[v];
    if (m_.fixed[v] || bn[0] < 0 || bn[1] < 0 || m_.chain[bn[0]] != chain ||
        m_.chain[bn[1]] != chain)
      return kInf;
    const double a = arc_delta(m_.arc_m[v], m_.arc_m[bn[0]], length);
    const double b = arc_delta(m_.arc_m[v], m_.arc_m[bn[1]], length);
    const double x = arc_delta(m_.arc_m[v], arc, length);
    if (a * b >= 0 || !(x > std::min(a, b) && x < std::max(a, b))) return kInf;
    return std::abs(x);
  }

  const BackgroundMesh& bg_;
  const QuadMesh& m_;
  const QuadTopology& t_;
  TriangleLocator locator_;
  PolylineIndex boundary_;
  std::vector<int> interior_ids_, coast_ids_;
  NearestPoints interior_, coast_;
};

// The mean length of boundary vertex v's boundary edges (its longest edge without two).
double boundary_edge_length(const QuadMesh& m, const QuadTopology& t, int v) {
  const auto& bn = t.boundary_neighbours[v];
  if (bn[0] >= 0 && bn[1] >= 0)
    return 0.5 * (distance(m.points[v], m.points[bn[0]]) + distance(m.points[v], m.points[bn[1]]));
  double longest = 0;
  for (int w : t.neighbours[v]) longest = std::max(longest, distance(m.points[v], m.points[w]));
  return longest;
}

// Whether u, v, w are consecutive corners of one quad.
bool same_quad_corner(const QuadMesh& m, const QuadTopology& t, int u, int v, int w) {
  for (int k = t.quad_start[v]; k < t.quad_start[v + 1]; ++k) {
    const auto& q = m.quads[t.quad_items[k]];
    for (int i = 0; i < 4; ++i)
      if (q[i] == v) {
        const int next = q[(i + 1) % 4], prev = q[(i + 3) % 4];
        if ((next == u && prev == w) || (next == w && prev == u)) return true;
      }
  }
  return false;
}

// The cheapest path of mesh edges from `from` to `to` near the run: an edge costs its
// length times 1 + 16 (offset / length)^2 + 2 sin^2(its angle to the run), its offset
// the mean distance of its ends and middle (twice) from the run; edges offset by
// max_offset of their length or more are not taken. Turning round two sides of a quad
// costs three lengths of the second edge more: moved onto a line, the three vertices
// would be in a row, so the middle one stays off it. The search runs over directed
// edges (the turns need the edge before); ties go to the lower edge id. Empty when `to`
// cannot be reached.
std::vector<int> path_along(const QuadMesh& m, const QuadTopology& t, const PolylineIndex& run,
                            int from, int to, double max_offset) {
  const int nv = static_cast<int>(m.points.size());
  std::vector<int> first(nv + 1, 0);  // directed edge ids: first[u] + k for u -> neighbours[u][k]
  for (int v = 0; v < nv; ++v) first[v + 1] = first[v] + static_cast<int>(t.neighbours[v].size());
  std::vector<int> head(first[nv]), tail(first[nv]);
  for (int v = 0; v < nv; ++v)
    for (std::size_t k = 0; k < t.neighbours[v].size(); ++k)
      tail[first[v] + k] = v, head[first[v] + k] = t.neighbours[v][k];
  std::vector<double> off(nv, -1.0);  // a vertex's distance from the run (cached)
  auto offset = [&](const Point2& p, double tolerance) {
    Point2 q;
    return nearest_on_run(run, p, tolerance, q) ? distance(p, q) : kInf;
  };
  auto edge_cost = [&](int e, double& length) {
    const int v = tail[e], w = head[e];
    const Point2 &a = m.points[v], &b = m.points[w];
    length = distance(a, b);
    if (length <= 0) return kInf;
    const double tolerance = max_offset * length;
    if (off[v] < 0) off[v] = offset(a, 4 * tolerance);
    if (off[w] < 0) off[w] = offset(b, 4 * tolerance);
    Point2 s0, s1;
    const Point2 mid{0.5 * (a.x + b.x), 0.5 * (a.y + b.y)};
    if (!run.nearest_segment(mid, 4 * tolerance, s0, s1)) return kInf;
    const double mean = 0.25 * (off[v] + 2 * distance_to_segment(mid, s0, s1) + off[w]);
    if (!(mean < tolerance)) return kInf;
    const double share = mean / length;
    // How far the edge turns from the line: a step across it gains nothing along it.
    const double sx = s1.x - s0.x, sy = s1.y - s0.y, sl = std::hypot(sx, sy);
    const double sine = sl > 0 ? ((b.x - a.x) * sy - (b.y - a.y) * sx) / (length * sl) : 0.0;
    return length * (1 + 16 * share * share + 2 * sine * sine);
  };
  std::vector<double> cost(first[nv], kInf);
  std::vector<int> previous(first[nv], -1);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (int e = first[from]; e < first[from + 1]; ++e) {
    double length;
    const double c = edge_cost(e, length);
    if (c < cost[e]) cost[e] = c, queue.push({c, e});
  }
  int last = -1;
  while (!queue.empty()) {
    const auto [c, e] = queue.top();
    queue.pop();
    if (c > cost[e]) continue;
    const int u = tail[e], v = head[e];
    if (v == to) {
      last = e;
      break;
    }
    for (int f = first[v]; f < first[v + 1]; ++f) {
      const int w = head[f];
      if (w == u) continue;
      double length;
      double next = c + edge_cost(f, length);
      if (next == kInf) continue;
      if (same_quad_corner(m, t, u, v, w)) next += 3 * length;
      if (next < cost[f]) {
        cost[f] = next;
        previous[f] = e;
        queue.push({next, f});
      }
    }
  }
  if (last < 0) return {};
  std::vector<int> path{to};
  for (int e = last; e >= 0; e = previous[e]) path.push_back(tail[e]);
  std::reverse(path.begin(), path.end());
  return path;
}

}  // namespace

EmbedStats embed_lines(const BackgroundMesh& bg, QuadMesh& m,
                       const std::vector<std::vector<Point2>>& lines, const EmbedParams& embed,
                       const SmoothParams& params, const CrossField* cross, const SizingField* size,
                       std::vector<EmbeddedPath>* paths, const std::vector<Point2>& points,
                       std::vector<EmbeddedPoint>* point_vertices) {
  EmbedStats stats;
  stats.requested = !lines.empty();
  if (paths) paths->clear();
  std::vector<Run> runs = runs_inside(bg, lines, size, embed.coast_share);
  const QuadTopology t = quad_topology(m);
  const int nv = static_cast<int>(m.points.size());
  std::vector<Point2> target(nv);
  std::vector<char> held(nv, 0);       // on a path: 1 to move onto its line, 2 boundary or taken
  std::vector<int> order;              // the vertices to move, in path order
  std::vector<double> reach(nv, 0.0);  // their longest edge along the path
  std::vector<std::vector<int>> found;
  std::vector<std::size_t> found_run;
  std::vector<double> target_arc(nv, 0.0);  // for boundary vertices: along their chain
  for (std::size_t r = 0; r < runs.size(); ++r) {
    std::vector<Point2>& run = runs[r].points;
    const int from = nearest_vertex(m, t, run.front()), to = nearest_vertex(m, t, run.back());
    std::vector<int> path;
    if (from >= 0 && to >= 0 && from != to)
      path = path_along(m, t, PolylineIndex({run}), from, to, embed.max_offset);
    if (path.empty()) {
      for (std::size_t i = 1; i < run.size(); ++i)
        stats.line_length_m += distance(run[i - 1], run[i]);
      ++stats.num_skipped;
      continue;
    }
    // A run cut near the coast (the line goes on to meet it): the path goes on to the
    // boundary vertex next to its end that is nearest where the line meets the coast,
    // and that vertex slides there along the coast, when it stays between its boundary
    // neighbours; the run gets that point.
    for (int end = 0; end < 2; ++end) {
      if (runs[r].own_ends[end] || run.size() < 2) continue;
      const Point2 e = end ? run.back() : run.front(), e2 = end ? run[run.size() - 2] : run[1];
      const double len = distance(e, e2);
      const int v = end ? path.back() : path.front();
      double reach_m = 0;
      for (int w : t.neighbours[v]) reach_m = std::max(reach_m, distance(m.points[v], m.points[w]));
      int chain = -1;
      Point2 x;
      double arc = 0;
      if (len <= 0 || !ray_meets_boundary(bg, e, {(e.x - e2.x) / len, (e.y - e2.y) / len},
                                          2 * reach_m, chain, x, arc))
        continue;
      int b = m.chain[v] == chain && !m.fixed[v] ? v : -1;
      if (b < 0)
        for (int w : t.neighbours[v])
          if (m.chain[w] == chain && !m.fixed[w] && !held[w] &&
              (b < 0 || distance(m.points[w], x) < distance(m.points[b], x)))
            b = w;
      if (b < 0 || held[b]) continue;
      const auto& bn = t.boundary_neighbours[b];
      const double length = bg.chains[chain].length_m;
      if (bn[0] < 0 || bn[1] < 0 || m.chain[bn[0]] != chain || m.chain[bn[1]] != chain ||
          arc_delta(arc, m.arc_m[bn[0]], length) * arc_delta(arc, m.arc_m[bn[1]], length) >= 0)
        continue;  // not between its neighbours
      if (b != v) end ? path.push_back(b) : (void)path.insert(path.begin(), b);
      end ? run.push_back(x) : (void)run.insert(run.begin(), x);
      target[b] = x;
      target_arc[b] = arc;
      held[b] = 1;
      order.push_back(b);
      ++stats.num_coast_ends;
    }
    for (std::size_t i = 1; i < run.size(); ++i)
      stats.line_length_m += distance(run[i - 1], run[i]);
    const PolylineLocator locator(run);
    ++stats.num_runs;
    stats.num_edges += path.size() - 1;
    // The line's corners: where it turns by corner_turn_rad or more.
    std::vector<std::pair<Point2, double>> corners;  // point, turn (radians)
    for (std::size_t i = 1; i + 1 < run.size(); ++i) {
      const Point2 &a = run[i - 1], &b = run[i], &c = run[i + 1];
      const double turn =
          std::abs(std::atan2((b.x - a.x) * (c.y - b.y) - (b.y - a.y) * (c.x - b.x),
                              (b.x - a.x) * (c.x - b.x) + (b.y - a.y) * (c.y - b.y)));
      if (turn >= embed.corner_turn_rad) corners.push_back({b, turn});
    }
    std::vector<int> mine;  // the path's vertices this run moves
    double last_arc = -kInf;
    for (std::size_t i = 0; i < path.size(); ++i) {
      const int v = path[i];
      if (held[v]) continue;  // where lines cross: the first line's
      const double step = i > 0 ? distance(m.points[path[i - 1]], m.points[v]) : 0.0;
      const double next = i + 1 < path.size() ? distance(m.points[v], m.points[path[i + 1]]) : 0.0;
      // Round two sides of a quad, unless the line turns there too (a corner of 30
      // degrees or more within the vertex's edges).
      bool turns_in_quad =
          i > 0 && i + 1 < path.size() && same_quad_corner(m, t, path[i - 1], v, path[i + 1]);
      for (const auto& [corner, turn] : corners)
        if (turns_in_quad && turn >= M_PI / 6 &&
            distance(corner, m.points[v]) < std::min(step, next))
          turns_in_quad = false;
      double arc = 0;
      Point2 q = locator.nearest(m.points[v], &arc);
      // The path's ends at the line's own ends: those points exactly.
      const bool first = i == 0, last = i + 1 == path.size();
      if ((first && runs[r].own_ends[0]) || (last && runs[r].own_ends[1])) {
        q = first ? run.front() : run.back();
        arc = first ? 0.0 : kInf;
      }
      // Where the path steps across the line, its vertex that would not move on along
      // the line (by a fifth of its edge before) stays off it: moved onto it, the edge
      // would shrink to nothing.
      if (m.chain[v] < 0 && !m.fixed[v] && !turns_in_quad && arc >= last_arc + 0.2 * step) {
        target[v] = q;
        held[v] = 1;
        mine.push_back(v);
        last_arc = arc;
        reach[v] = std::max(step, next);
      } else {
        held[v] = 2;
      }
    }
    // The line's corners each to the nearest of them within its edges' reach, so that
    // the edges follow the bends (a chord across a corner would not).
    // Nearest pairs first: taken corner by corner, a vertex could go to an earlier
    // corner than its nearest, each after it one corner back (a sine of 5 km amplitude
    // drawn every 500 m, meshed at 2 km: 37 of 49 vertices on it against 42).
    std::vector<std::tuple<double, std::size_t, int>> pairs;  // (distance, corner, vertex)
    for (std::size_t c = 0; c < corners.size(); ++c)
      for (int v : mine) {
        const double d = distance(m.points[v], corners[c].first);
        if (d <= reach[v]) pairs.emplace_back(d, c, v);
      }
    std::sort(pairs.begin(), pairs.end());
    std::vector<char> at_corner(nv, 0), corner_taken(corners.size(), 0);
    for (const auto& [d, c, v] : pairs) {
      if (at_corner[v] || corner_taken[c]) continue;
      target[v] = corners[c].first;
      at_corner[v] = corner_taken[c] = 1;
    }
    // Two consecutive vertices whose targets came within a fifth of their edges of each
    // other (a corner taken next to the point the one before goes to), else their edge
    // would shrink to nothing (Brittany's water with the Loire lane at hmax 8 km: a side
    // of 21.8 m between quads 1.2 km wide): the one not at a corner goes halfway along
    // the line between the other and its other neighbour on the path, or where that is
    // as close, stays off the line.
    std::vector<double> arc_of(mine.size());
    for (std::size_t k = 0; k < mine.size(); ++k) locator.nearest(target[mine[k]], &arc_of[k]);
    auto too_close = [&](int a, int b) {
      return distance(target[a], target[b]) < 0.2 * std::min(reach[a], reach[b]);
    };
    std::vector<int> spaced;
    std::vector<double> spaced_arc;
    for (std::size_t k = 0; k < mine.size(); ++k) {
      const int v = mine[k];
      if (!spaced.empty() && too_close(spaced.back(), v)) {
        const int u = spaced.back();
        const bool move_u = at_corner[v] && !at_corner[u];
        const int w = move_u ? u : v;
        // w's neighbours along the line: the one it came too close to, and its other.
        const bool has_other = move_u ? spaced.size() >= 2 : k + 1 < mine.size();
        const double a0 =
            move_u ? (has_other ? spaced_arc[spaced.size() - 2] : 0) : spaced_arc.back();
        const double a1 = move_u ? arc_of[k] : (has_other ? arc_of[k + 1] : 0);
        const int n0 = move_u ? (has_other ? spaced[spaced.size() - 2] : -1) : u;
        const int n1 = move_u ? v : (has_other ? mine[k + 1] : -1);
        const Point2 keep = target[w];
        bool placed = false;
        if (has_other && a1 > a0) {
          target[w] = locator.point_at(0.5 * (a0 + a1));
          placed = !too_close(n0, w) && !too_close(w, n1);
          if (!placed) target[w] = keep;
        }
        if (move_u) spaced.pop_back(), spaced_arc.pop_back();
        if (placed) {
          const double arc = 0.5 * (a0 + a1);
          if (move_u) {
            spaced.push_back(u);
            spaced_arc.push_back(arc);
          } else {
            spaced.push_back(v);
            spaced_arc.push_back(arc);
            continue;
          }
        } else {
          held[w] = 2;
          if (!move_u) continue;
        }
      }
      spaced.push_back(v);
      spaced_arc.push_back(arc_of[k]);
    }
    mine = std::move(spaced);
    order.insert(order.end(), mine.begin(), mine.end());
    found.push_back(std::move(path));
    found_run.push_back(r);
  }

  // The points: near the coast, to the coast's point nearest them by a boundary vertex;
  // else inside the domain, to themselves by the nearest interior vertex not held yet.
  std::vector<EmbeddedPoint> on_point(points.size());
  std::optional<PointLookup> lookup;
  double coast_reach = 0;  // the farthest a point may lie from the coast to go there
  if (!points.empty()) {
    lookup.emplace(bg, m, t);
    for (int v = 0; v < nv; ++v)
      if (m.chain[v] >= 0) coast_reach = std::max(coast_reach, boundary_edge_length(m, t, v));
    coast_reach = std::max(coast_reach * std::max({embed.point_coast_share, embed.point_land_share,
                                                   embed.point_retry_share}),
                           embed.point_coast_m);
  }
  constexpr std::size_t kCandidates = 4;
  std::vector<std::tuple<double, std::size_t, int>> pairs;  // (distance, point, vertex)
  std::vector<char> wants(points.size(), 0);                // inside, not at the coast
  std::optional<NearestPoints> given;  // the points, to find those that share a vertex
  if (!points.empty()) given.emplace(points);
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Point2& p = points[k];
    EmbeddedPoint& e = on_point[k];
    const double near = embed.point_merge_share * lookup->local_edge(p);
    for (const auto& [d, j] : given->nearest(p, 8))
      if (d <= near && static_cast<std::size_t>(j) < k && on_point[j].shares < 0 &&
          (e.shares < 0 || j < e.shares))
        e.shares = j;
    if (e.shares >= 0) continue;
    int chain = -1;
    Point2 x;
    double arc = 0;
    const double off = lookup->nearest_on_boundary(p, coast_reach, chain, x, arc);
    const bool inside = lookup->inside(p);
    const int b = chain >= 0 ? lookup->coast_vertex(held, chain, x, arc, embed.on_line_m) : -1;
    const double share = inside ? embed.point_coast_share : embed.point_land_share;
    if (b >= 0 && off <= std::max(share * boundary_edge_length(m, t, b), embed.point_coast_m)) {
      e = {b, true, x};
      if (distance(m.points[b], x) > embed.on_line_m) {
        target[b] = x;
        target_arc[b] = arc;
        order.push_back(b);
      }
      held[b] = 1;
      ++stats.num_points;
      continue;
    }
    if (!inside) {
      ++stats.num_points_outside;
      continue;
    }
    e.target = p;
    wants[k] = 1;
    for (const auto& [d, v] : lookup->nearest_free(held, p, kCandidates))
      pairs.emplace_back(d, k, v);
  }
  // The points inside, each to one of its nearest free interior vertices, nearest pairs
  // first: taken point by point, two points in one quad could send the second to a far
  // vertex while a nearer one stayed free.
  std::sort(pairs.begin(), pairs.end());
  auto take = [&](std::size_t k, int v) {
    on_point[k].vertex = v;
    target[v] = points[k];
    held[v] = 1;
    order.push_back(v);
    ++stats.num_points;
  };
  for (const auto& [d, k, v] : pairs)
    if (on_point[k].vertex < 0 && !held[v]) take(k, v);
  for (std::size_t k = 0; k < points.size(); ++k)  // all its candidates taken by others
    if (wants[k] && on_point[k].vertex < 0) {
      const auto next = lookup->nearest_free(held, points[k], 1);
      if (!next.empty()) take(k, next[0].second);
    }

  // Onto the lines, a round at a time; the vertices next to the paths make room. No move
  // (theirs or the sweeps') makes a quad's corner leave [30, 150] degrees, or one already
  // outside go farther (EmbedParams::min_turn_sine).
  SmoothParams sweep = params;
  sweep.min_convexity = std::max(params.min_convexity, embed.min_turn_sine);
  std::vector<char> room(nv, 0);
  for (int v : order)
    for (int w : t.neighbours[v])
      if (!held[w]) room[w] = 1;
  // A point's vertex may have to move across most of a quad: two rings make room.
  for (const EmbeddedPoint& e : on_point)
    if (e.vertex >= 0)
      for (int w : t.neighbours[e.vertex])
        for (int u : t.neighbours[w])
          if (!held[u]) room[u] = 1;
  // The points' neighbours dragged along first, those two quads round by a third of the
  // way, then those one quad round by two thirds: the quads round the point shift
  // instead of folding round its vertex (Brittany's 300 random points: 233 -> 252 on
  // their vertex, against a quarter and a half: 245).
  const std::vector<Point2> before_points = m.points;
  const std::vector<double> before_arcs = m.arc_m;
  auto drag_neighbours = [&](const std::vector<const EmbeddedPoint*>& which) {
    for (const double share : {0.33, 0.67})
      for (const EmbeddedPoint* ep : which) {
        const EmbeddedPoint& e = *ep;
        if (e.vertex < 0 || e.coast) continue;
        const Point2 from = m.points[e.vertex];
        const Point2 d{share * (e.target.x - from.x), share * (e.target.y - from.y)};
        std::vector<int> ring;
        for (int w : t.neighbours[e.vertex])
          if (share > 0.5)
            ring.push_back(w);
          else
            for (int u : t.neighbours[w])
              if (u != e.vertex) ring.push_back(u);
        std::sort(ring.begin(), ring.end());
        ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
        for (int w : ring)
          if (!held[w] && m.chain[w] < 0 && !m.fixed[w])
            try_move(m, t, w, {m.points[w].x + d.x, m.points[w].y + d.y}, m.arc_m[w],
                     sweep.min_convexity);
      }
  };
  {
    std::vector<const EmbeddedPoint*> all;
    for (const EmbeddedPoint& e : on_point) all.push_back(&e);
    drag_neighbours(all);
  }
  std::vector<char> done(nv, 0);
  SweepSetup sweep_setup;  // one topology for every round here
  auto move_rounds = [&](const std::vector<int>& moving) {
    for (int round = 0; round < embed.rounds; ++round) {
      bool all = true;
      for (int v : moving) {
        if (done[v]) continue;
        const Point2 p = m.points[v], q = target[v];
        const bool boundary = m.chain[v] >= 0;
        const double bound = boundary ? std::max(params.min_convexity, embed.coast_min_turn_sine)
                                      : sweep.min_convexity;
        if (try_move(m, t, v, q, boundary ? target_arc[v] : m.arc_m[v], bound)) {
          done[v] = 1;
          continue;
        }
        all = false;
        if (!boundary) {
          try_move(m, t, v, {0.5 * (p.x + q.x), 0.5 * (p.y + q.y)}, m.arc_m[v],
                   sweep.min_convexity);
        } else {  // half of the way along the coast
          const BoundaryChain& ch = bg.chains[m.chain[v]];
          const double half = m.arc_m[v] + 0.5 * arc_delta(m.arc_m[v], target_arc[v], ch.length_m);
          try_move(m, t, v, chain_point(bg, ch, half), half, bound);
        }
      }
      if (all) break;
      angle_sweeps(bg, m, t, sweep, cross, size, &room, embed.sweep_iterations, Progress(),
                   &sweep_setup);
    }
  };
  move_rounds(order);
  // A point inside that its interior vertex did not reach, within point_retry_share of a
  // boundary edge of the coast (in the boundary's row of quads, where the vertex cannot
  // cross to it without folding them), goes to the coast instead; its vertex is let go
  // to the sweeps.
  std::vector<int> retry;
  for (EmbeddedPoint& e : on_point) {
    if (e.vertex < 0 || e.coast || e.shares >= 0 || done[e.vertex]) continue;
    int chain = -1;
    Point2 x;
    double arc = 0;
    const double off = lookup->nearest_on_boundary(e.target, coast_reach, chain, x, arc);
    const int b = chain >= 0 ? lookup->coast_vertex(held, chain, x, arc, embed.on_line_m) : -1;
    if (b < 0 || off > embed.point_retry_share * boundary_edge_length(m, t, b)) continue;
    held[e.vertex] = 0;
    room[e.vertex] = 1;
    e = {b, true, x};
    held[b] = 1;
    room[b] = 0;
    for (int w : t.neighbours[b])
      for (int u : t.neighbours[w])
        if (!held[u]) room[u] = 1;
    if (distance(m.points[b], x) <= embed.on_line_m) continue;
    target[b] = x;
    target_arc[b] = arc;
    retry.push_back(b);
  }
  move_rounds(retry);
  order.insert(order.end(), retry.begin(), retry.end());
  // A point inside whose vertex still stopped short tries the others of its nearest free
  // interior vertices in turn, one point at a time: its vertex goes back where it was
  // (if its quads allow) and is let go, the other is dragged and moved as the first was,
  // with room round the two alone; when it stops short too, the positions and arcs the
  // try changed are put back (Brittany's 300 random points: 269 -> 289 on their vertex).
  // A point at the coast whose boundary vertex could not slide to it (where the coast
  // bends) tries the boundary vertex at the other end of the edge it lies on.
  for (EmbeddedPoint& e : on_point) {
    if (e.vertex < 0 || e.shares >= 0 || done[e.vertex] ||
        distance(m.points[e.vertex], e.target) <= embed.on_line_m)
      continue;
    const int old = e.vertex;
    std::vector<std::pair<double, int>> others;  // by their distance now
    if (e.coast) {
      const int other = m.chain[old] >= 0 ? lookup->coast_vertex(held, m.chain[old], e.target,
                                                                 target_arc[old], embed.on_line_m)
                                          : -1;
      if (other >= 0) others.emplace_back(0.0, other);
    } else {
      for (const auto& [d, v] : lookup->nearest_free(held, e.target, kCandidates))
        if (v != old) others.emplace_back(distance(m.points[v], e.target), v);
    }
    std::sort(others.begin(), others.end());
    for (const auto& [d, next] : others) {
      const std::vector<Point2> kept = m.points;
      const std::vector<double> kept_arc = m.arc_m;
      std::vector<char> local(nv, 0);
      for (int v : {old, next})
        for (int w : t.neighbours[v])
          for (int u : t.neighbours[w])
            if (!held[u] || u == old) local[u] = 1;
      local[next] = 0;
      std::swap(room, local);
      try_move(m, t, old, before_points[old], before_arcs[old],
               m.chain[old] >= 0 ? std::max(params.min_convexity, embed.coast_min_turn_sine)
                                 : sweep.min_convexity);
      held[old] = 0;
      held[next] = 1;
      target[next] = e.target;
      target_arc[next] = target_arc[old];
      e.vertex = next;
      drag_neighbours({&e});
      move_rounds({next});
      std::swap(room, local);
      if (done[next]) {
        room[old] = 1;
        room[next] = 0;
        order.push_back(next);
        for (int w : t.neighbours[next])
          for (int u : t.neighbours[w])
            if (!held[u]) room[u] = 1;
        break;
      }
      m.points = kept;
      m.arc_m = kept_arc;
      held[next] = 0;
      held[old] = 1;
      e.vertex = old;
    }
  }
  // The vertices next to the paths swept with the paths held, as smoothing left the rest.
  if (!order.empty())
    angle_sweeps(bg, m, t, sweep, cross, size, &room, embed.sweep_iterations, Progress(),
                 &sweep_setup);
  // D-Flow FM's orthogonality again (SmoothParams::max_orthogonality), the vertices on the
  // lines and points held: the moves onto them bent links that the smoothing had
  // straightened.
  if (params.max_orthogonality > 0 && !order.empty()) {
    const std::vector<char> fixed = m.fixed;
    for (int v = 0; v < nv; ++v)
      if (held[v]) m.fixed[v] = 1;
    orthogonality_sweeps(m, t, params);
    m.fixed = fixed;
  }

  // How closely the paths follow the lines: their vertices' distances, and the stretches
  // of line between two consecutive vertices on it (an edge's ends) that stay within
  // max_chord_share of the edge's length of it, with how far they bend away.
  for (std::size_t k = 0; k < found.size(); ++k) {
    const std::vector<Point2>& run = runs[found_run[k]].points;
    const PolylineLocator locator(run);
    int previous = -1;  // the last vertex on the line
    double previous_arc = 0;
    for (int v : found[k]) {
      ++stats.num_vertices;
      double arc = 0;
      const double d = distance(m.points[v], locator.nearest(m.points[v], &arc));
      const bool boundary = m.chain[v] >= 0 || m.fixed[v];
      if (boundary) ++stats.num_boundary;
      if (!boundary) stats.max_vertex_off_m = std::max(stats.max_vertex_off_m, d);
      if (d > embed.on_line_m) {
        previous = -1;
        continue;
      }
      if (!boundary) ++stats.num_on_line;
      if (previous >= 0 && arc > previous_arc) {
        double off = 0;
        for (std::size_t i = 0; i < run.size(); ++i)
          if (locator.arc_at(i) > previous_arc && locator.arc_at(i) < arc)
            off = std::max(off, distance_to_segment(run[i], m.points[previous], m.points[v]));
        // Spanned where the line stays near the edge (a curve's chord), not where it
        // winds away between the edge's ends.
        if (off <= embed.max_chord_share * distance(m.points[previous], m.points[v])) {
          stats.covered_length_m += arc - previous_arc;
          stats.max_chord_off_m = std::max(stats.max_chord_off_m, off);
        }
      }
      previous = v;
      previous_arc = arc;
    }
  }
  if (paths)
    for (std::size_t k = 0; k < found.size(); ++k)
      paths->push_back({runs[found_run[k]].line, std::move(found[k])});
  for (std::size_t k = 0; k < points.size(); ++k) {
    EmbeddedPoint& e = on_point[k];
    if (e.shares >= 0) {
      const EmbeddedPoint& first = on_point[e.shares];
      e.vertex = first.vertex;
      e.coast = first.coast;
      e.target = first.target;
      if (e.vertex < 0) {  // (outside the domain, as the first)
        ++stats.num_points_outside;
        continue;
      }
      ++stats.num_points;
      ++stats.num_points_shared;
      stats.max_shared_distance_m =
          std::max(stats.max_shared_distance_m, distance(points[k], e.target));
      continue;
    }
    if (e.vertex < 0) continue;
    const double d = distance(m.points[e.vertex], e.target);
    if (d <= embed.on_line_m) ++stats.num_points_on;
    stats.max_point_off_m = std::max(stats.max_point_off_m, d);
    if (!e.coast) continue;
    ++stats.num_points_coast;
    stats.max_coast_distance_m =
        std::max(stats.max_coast_distance_m, distance(points[k], e.target));
  }
  if (point_vertices) *point_vertices = on_point;
  return stats;
}

}  // namespace isoquad
