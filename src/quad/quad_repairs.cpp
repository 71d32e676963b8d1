#include "quad/quad_repairs.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <tuple>

#include "quad/quad_sweeps.h"

namespace isoquad {

namespace {

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
    const std::array<int, 6> h = {b, m.quads[q][(i + 2) % 4], m.quads[q][(i + 3) % 4],
                                  a, nq4[(j + 1) % 4],        nq4[(j + 2) % 4]};
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

bool contains_point(const std::vector<Point2>& points, const Point2& p) {
  return std::any_of(points.begin(), points.end(),
                     [&](const Point2& o) { return o.x == p.x && o.y == p.y; });
}

// The possible collapses of quad `pick` in turn (shorter diagonal first, while `tries`
// is under collapse_tries), each followed by the untangling sweeps: keeps the first
// that `better` accepts (called with the new connectivity) and undoes the others.
bool collapse_first_better(const BackgroundMesh& bg, QuadMesh& m, const SmoothParams& params,
                           SmoothStats& stats, int pick, int& tries,
                           const std::function<bool(const QuadTopology&)>& better) {
  for (int choice = 0; choice < 4 && tries < params.collapse_tries; ++choice, ++tries) {
    QuadMesh before = m;
    const SmoothStats stats_before = stats;
    if (collapse_quads(
            m, [&](int q) { return q == pick; }, choice) == 0)
      return false;
    const QuadTopology t = quad_topology(m);
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
    untangle(bg, m, quad_topology(m), params, stats);
    if (better()) {
      ++stats.num_flips;
      return true;
    }
    m = std::move(before);
    stats = stats_before;
  }
  return false;
}

// How far the repair after a sliver's collapse or flip reaches, in rings of quads.
constexpr int kSliverRings = 3;

// The quads within `rings` rings (sharing a vertex, ring by ring) of quad `seed`,
// ascending.
std::vector<int> quads_within(const QuadMesh& m, const QuadTopology& t, int seed, int rings) {
  const int nq = static_cast<int>(m.quads.size());
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

// The same round the quad whose centroid is nearest `at` (the first such).
std::vector<int> quads_near(const QuadMesh& m, const QuadTopology& t, const Point2& at, int rings) {
  int seed = -1;
  double best = 1e300;
  for (int q = 0; q < static_cast<int>(m.quads.size()); ++q) {
    const Point2 c = quad_centroid(m, q);
    const double d = (c.x - at.x) * (c.x - at.x) + (c.y - at.y) * (c.y - at.y);
    if (d < best) best = d, seed = q;
  }
  return quads_within(m, t, seed, rings);
}

// Ten Gauss-Seidel sweeps, in vertex order, that put each interior vertex of `quads`
// (neither on the boundary nor fixed) at the middle of its neighbours; convexity is left
// to the untangling after.
void move_to_neighbours_middle(QuadMesh& m, const QuadTopology& t, const std::vector<int>& quads) {
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
// Whether quad q's sides i and i + 2 are its short ones, each under a quarter of its long
// ones (a quad of a thin chord).
bool thin_across(const QuadMesh& m, int q, int i) {
  auto side = [&](int j) {
    return distance(m.points[m.quads[q][j % 4]], m.points[m.quads[q][(j + 1) % 4]]);
  };
  return std::max(side(i), side(i + 2)) < 0.25 * std::min(side(i + 1), side(i + 3));
}

// The side (0 or 1) across which quad q is thin, or -1.
int thin_side(const QuadMesh& m, int q) {
  auto side = [&](int j) {
    return distance(m.points[m.quads[q][j]], m.points[m.quads[q][(j + 1) % 4]]);
  };
  const int k = std::max(side(0), side(2)) < std::max(side(1), side(3)) ? 0 : 1;
  return thin_across(m, q, k) ? k : -1;
}

bool collapse_chord(const BackgroundMesh& bg, QuadMesh& m, int start, int max_row) {
  const int k = thin_side(m, start);
  if (k < 0) return false;
  const EdgeQuads edges(m);
  auto thin = [&](int q, int i) { return thin_across(m, q, i); };
  std::vector<int> row{start};
  std::vector<std::array<int, 2>> sides{{m.quads[start][k], m.quads[start][k + 1]},
                                        {m.quads[start][k + 2], m.quads[start][(k + 3) % 4]}};
  for (int way = 0; way < 2; ++way) {
    int cur = start;
    std::array<int, 2> e = sides[way];
    for (;;) {
      const int n = edges.other(e[0], e[1], cur);
      if (n < 0) break;  // the boundary
      if (static_cast<int>(row.size()) >= max_row ||
          std::find(row.begin(), row.end(), n) != row.end())
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
      out.points[u] = {0.5 * (m.points[u].x + m.points[w].x),
                       0.5 * (m.points[u].y + m.points[w].y)};
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

// A doubled corner (SmoothParams::doubled_corner_side): boundary vertex b in two quads,
// interior vertex i in four. The four quads round i bound an octagon b, v1, ..., v7
// (counter-clockwise); it is split into three quads fanned from b, along b-v3 and b-v5,
// and i goes. Returns false, the mesh unchanged, when the quads round i do not close
// round it or b is not among their corners as expected.
bool split_doubled_corner(QuadMesh& m, const QuadTopology& t, int b, int i) {
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
  std::array<std::array<int, 4>, 3> fan = {
      {{o[0], o[1], o[2], o[3]}, {o[0], o[3], o[4], o[5]}, {o[0], o[5], o[6], o[7]}}};
  // A far corner of the fan (o2, o4, o6: a neighbour of i) that was in three quads is in
  // two once i's go, which share both its edges (a doublet: one of the two has an angle
  // of 180 degrees or more there, whatever the untangling does). The two become one
  // quad, without it: (o0, P, apex, Q) and (R, Q, apex, P) give (o0, P, R, Q).
  for (auto& f : fan) {
    const int apex = f[2];
    if (m.chain[apex] >= 0 || m.fixed[apex] || t.quad_start[apex + 1] - t.quad_start[apex] != 3)
      continue;
    int other = -1;
    for (int k = t.quad_start[apex]; k < t.quad_start[apex + 1]; ++k)
      if (!removed[t.quad_items[k]]) other = t.quad_items[k];
    if (other < 0) continue;
    const auto& w = m.quads[other];
    int j = 0;
    while (w[j] != apex) ++j;
    if (w[(j + 1) % 4] != f[1] || w[(j + 3) % 4] != f[3]) continue;
    const int r = w[(j + 2) % 4];
    if (r == f[0]) continue;
    f = {f[0], f[1], r, f[3]};
    removed[other] = 1;
  }
  for (const auto& f : fan) m.quads.push_back(f);
  removed.resize(m.quads.size(), 0);
  remove_quads(m, removed);  // i (and a doublet's vertex), in none of them now, goes too
  return true;
}

}  // namespace

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
int collapse_quads(QuadMesh& m, const std::function<bool(int)>& wanted, int choice) {
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
        if (o != q &&
            (touched[o] || std::find(m.quads[o].begin(), m.quads[o].end(), a) != m.quads[o].end()))
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

// Non-convex quads the collapse rounds left, one at a time (at most collapse_tries):
// each of its possible collapses in turn (shorter diagonal first), the first that
// leaves fewer quads non-convex kept; failing those, each of its edge flips (at most
// collapse_tries of them in all; none with flip_rounds 0), kept the same way when no
// more boundary edges cross.
// Returns the number of collapses kept.
int collapse_one_by_one(const BackgroundMesh& bg, QuadMesh& m, const SmoothParams& params,
                        SmoothStats& stats) {
  auto count_nonconvex = [&] { return isoquad::count_nonconvex(m, params.min_convexity); };
  std::vector<Point2> tried;  // centroids of the quads tried (ids change on a collapse)
  int kept = 0, flip_tries = 0;
  for (int attempt = 0; attempt < params.collapse_tries || flip_tries < params.collapse_tries;) {
    const int bad = count_nonconvex();
    if (bad == 0) break;
    int pick = -1;
    for (int q = 0; q < static_cast<int>(m.quads.size()) && pick < 0; ++q)
      if (quad_convexity(m, q) <= params.min_convexity &&
          !contains_point(tried, quad_centroid(m, q)))
        pick = q;
    if (pick < 0) break;
    tried.push_back(quad_centroid(m, pick));
    if (collapse_first_better(bg, m, params, stats, pick, attempt,
                              [&](const QuadTopology&) { return count_nonconvex() < bad; })) {
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
std::size_t unfold_boundary(const BackgroundMesh& bg, QuadMesh& m, const QuadTopology& t,
                            const SmoothParams& params) {
  std::size_t crossings = count_boundary_crossings(m);
  for (int round = 0; round < params.unfold_rounds && crossings > 0; ++round) {
    bool moved = false;
    // The ends of the crossing edges, then their neighbours along the boundary.
    std::vector<int> ends;
    auto add = [&](int v) {
      if (v >= 0 && m.chain[v] >= 0 && !m.fixed[v] &&
          std::find(ends.begin(), ends.end(), v) == ends.end())
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
            if (c[i] == a && c[(i + 1) % 4] == b && !contains_point(tried, quad_centroid(m, q)))
              pick = q;
        }
      }
      if (pick >= 0) break;
    }
    if (pick < 0) break;
    tried.push_back(quad_centroid(m, pick));
    if (collapse_first_better(bg, m, params, stats, pick, attempt, [&](const QuadTopology& t) {
          return !nonconvex() && unfold_boundary(bg, m, t, params) < crossings;
        })) {
      ++kept;
      continue;
    }
    // Failing those, its edge flips, each followed by the sweeps and the slides.
    if (params.flip_rounds == 0) continue;
    flip_first_better(bg, m, params, stats, pick, flip_tries, [&] {
      return !nonconvex() && unfold_boundary(bg, m, quad_topology(m), params) < crossings;
    });
  }
  return kept;
}

namespace {

// A mesh's counts that the one-by-one repairs compare before and after a change.
struct RepairCounts {
  int defects = 0;     // quads the repair looks for
  int slivers = 0;     // quads at most SmoothParams::sliver_convexity
  int nonconvex = 0;   // quads at most SmoothParams::min_convexity
  double worst = 1.0;  // the flattest quad's convexity
  // Counted only for QuadDefect::better_angles:
  int ratio = 0;              // quads under SmoothParams::min_angle_ratio (smallest / largest)
  double smallest_deg = 180;  // the smallest angle
};

// What a one-by-one repair looks for: quads whose `badness` is at least `threshold`, the
// worst first; a change is kept when every quad is convex, `better` (before, after)
// holds, then `better_angles` (when set; the angles are counted for it only), and no
// more boundary edges cross (counted last, only for a change that passed the others).
// With `local_first`, each collapse and flip is first tried on a patch of the mesh round
// the defect (patch_around), and on the whole mesh only when the patch's counts say the
// mesh would pass: `better` and `better_angles` must then hold whenever they hold for
// `before` with the patch's differences added to its counts and its worst convexity and
// smallest angle the lower of the patch's and `before`'s (a rule that asks for them no
// lower than before, not higher).
struct QuadDefect {
  std::function<double(const QuadMesh&, int)> badness;
  double threshold;
  int tries;  // at most this many defects tried
  std::function<bool(const RepairCounts&, const RepairCounts&)> better;
  std::function<bool(const RepairCounts&, const RepairCounts&)> better_angles;
  bool local_first = false;
};

// The changes a one-by-one repair tries on a quad: a diagonal collapse (`choice`, as
// collapse_quads'), an edge flip, or the merge of the thin row the quad is in.
struct RepairChange {
  enum Kind { collapse, flip, chord } kind = collapse;
  int choice = 0;
  QuadFlip edge_flip;
};

// The quads within `rings` rings of quad `q` as a mesh of their own, ids in the same
// order as in m (so that ties between ids fall the same way): the vertices also on quads
// outside it pinned (fixed and off any chain). With rings = kSliverRings + 3, what a
// change of q and the untangling within kSliverRings after it move lies inside, and
// nothing pinned moves in the whole mesh either.
struct Patch {
  QuadMesh mesh;
  std::vector<int> quad_of, vertex_of;  // ids in m
  int pick = -1;                        // q's id in the patch
};
Patch patch_around(const QuadMesh& m, const QuadTopology& t, int q, int rings) {
  Patch p;
  p.quad_of = quads_within(m, t, q, rings);
  std::vector<char> in(m.quads.size(), 0);
  for (int o : p.quad_of) in[o] = 1;
  for (int o : p.quad_of)
    p.vertex_of.insert(p.vertex_of.end(), m.quads[o].begin(), m.quads[o].end());
  std::sort(p.vertex_of.begin(), p.vertex_of.end());
  p.vertex_of.erase(std::unique(p.vertex_of.begin(), p.vertex_of.end()), p.vertex_of.end());
  for (int v : p.vertex_of) {
    bool pinned = false;
    for (int k = t.quad_start[v]; k < t.quad_start[v + 1] && !pinned; ++k)
      pinned = !in[t.quad_items[k]];
    p.mesh.points.push_back(m.points[v]);
    p.mesh.chain.push_back(pinned ? -1 : m.chain[v]);
    p.mesh.arc_m.push_back(m.arc_m[v]);
    p.mesh.fixed.push_back(pinned ? 1 : m.fixed[v]);
  }
  auto local = [&](int v) {
    return static_cast<int>(std::lower_bound(p.vertex_of.begin(), p.vertex_of.end(), v) -
                            p.vertex_of.begin());
  };
  for (std::size_t i = 0; i < p.quad_of.size(); ++i) {
    const auto& c = m.quads[p.quad_of[i]];
    p.mesh.quads.push_back({local(c[0]), local(c[1]), local(c[2]), local(c[3])});
    if (p.quad_of[i] == q) p.pick = static_cast<int>(i);
  }
  return p;
}

// A patch's flip in the whole mesh's ids.
QuadFlip flip_in_mesh(const Patch& p, const QuadFlip& f) {
  QuadFlip out = f;
  out.q = p.quad_of[f.q];
  out.n = p.quad_of[f.n];
  for (int k = 0; k < 4; ++k) out.a[k] = p.vertex_of[f.a[k]], out.b[k] = p.vertex_of[f.b[k]];
  return out;
}

// The changes a one-by-one repair kept.
struct RepairsKept {
  int collapses = 0;  // diagonal collapses and thin rows merged
  int flips = 0;
};

// The defects one by one, every quad convex: at most QuadDefect::tries of them, each tried
// once (by where it was: ids change on a collapse) for each diagonal collapse (shorter
// diagonal first), then each edge flip with a neighbour (its hexagon split along another
// diagonal), then (without `relocate`) the merge of the thin row it ends; the first
// change kept (with the lift and untangling sweeps after it, on the quads within
// kSliverRings of it) stays, the others are undone exactly. With `relocate`, each try
// moves the interior vertices of the quads next to the change to the middle of their
// neighbours first (a change that leaves a vertex of three or five quads can need it
// moved further than the untangling's steps take it). (Sweeps over the whole mesh after
// each try cost the Arctic Ocean at 1:10m, 39,770 quads, 10 s of its 13 s here; the
// local ones 0.1 s.) Returns the changes kept.
RepairsKept repair_one_by_one(const BackgroundMesh& bg, QuadMesh& m, const SmoothParams& params,
                              const SmoothParams& lift, SmoothStats& stats, bool relocate,
                              const QuadDefect& defect) {
  auto count = [&](const QuadMesh& mesh) {
    RepairCounts c;
    for (int q = 0; q < static_cast<int>(mesh.quads.size()); ++q) {
      const double convexity = quad_convexity(mesh, q);
      c.defects += defect.badness(mesh, q) >= defect.threshold;
      c.slivers += convexity <= params.sliver_convexity;
      c.nonconvex += convexity <= params.min_convexity;
      c.worst = std::min(c.worst, convexity);
    }
    return c;
  };
  auto count_angles = [&](const QuadMesh& mesh, RepairCounts& c) {
    for (int q = 0; q < static_cast<int>(mesh.quads.size()); ++q) {
      const auto angles = quad_angles_deg(mesh, q);
      const double smallest = *std::min_element(angles.begin(), angles.end());
      c.ratio +=
          smallest < params.min_angle_ratio * *std::max_element(angles.begin(), angles.end());
      c.smallest_deg = std::min(c.smallest_deg, smallest);
    }
  };
  // `change` made to quad `pick` of `mesh`, then the sweeps round `at`; false when the
  // change could not be made (the mesh may have begun to change).
  auto change_and_untangle = [&](QuadMesh& mesh, QuadTopology& t, int pick, const Point2& at,
                                 const RepairChange& change, SmoothStats& st) {
    bool made = true;
    if (change.kind == RepairChange::collapse) {
      made = collapse_quads(
                 mesh, [&](int q) { return q == pick; }, change.choice) > 0;
    } else if (change.kind == RepairChange::flip) {
      mesh.quads[change.edge_flip.q] = change.edge_flip.a;
      mesh.quads[change.edge_flip.n] = change.edge_flip.b;
    } else {
      made = collapse_chord(bg, mesh, pick, params.sliver_row_max);
    }
    if (!made) return false;
    rebuild_quad_topology(mesh, t);
    const std::vector<int> near = quads_near(mesh, t, at, kSliverRings);
    if (relocate) move_to_neighbours_middle(mesh, t, quads_near(mesh, t, at, 1));
    SmoothStats ignored;
    untangle(bg, mesh, t, lift, ignored, false, &near);
    untangle(bg, mesh, t, params, st, true, &near);
    return true;
  };
  std::vector<Point2> tried;  // centroids of the defects tried
  // The mesh's counts (and with local_first its topology) before a try: the same as
  // before the last one unless that changed the mesh (a change not kept is undone
  // exactly), so counted again only then.
  bool changed = true;
  RepairCounts before_try;
  std::size_t crossings0 = 0;
  QuadTopology t, current;  // after each change; of the mesh before the try
  RepairsKept out;
  for (int attempt = 0; attempt < defect.tries; ++attempt) {
    int pick = -1;
    double worst = defect.threshold;
    for (int q = 0; q < static_cast<int>(m.quads.size()); ++q) {
      const double b = defect.badness(m, q);
      if (b < worst || (pick >= 0 && b == worst)) continue;
      if (contains_point(tried, quad_centroid(m, q))) continue;
      pick = q;
      worst = b;
    }
    if (pick < 0) break;
    const Point2 at = quad_centroid(m, pick);
    tried.push_back(at);
    if (changed) {
      before_try = count(m);
      if (defect.better_angles) count_angles(m, before_try);
      crossings0 = count_boundary_crossings(m);
      if (defect.local_first) rebuild_quad_topology(m, current);
      changed = false;
    }
    auto passes = [&](const RepairCounts& after) {
      return after.nonconvex == 0 && defect.better(before_try, after) &&
             (!defect.better_angles || defect.better_angles(before_try, after));
    };
    Patch patch;
    RepairCounts patch0;
    if (defect.local_first) {
      patch = patch_around(m, current, pick, kSliverRings + 3);
      patch0 = count(patch.mesh);
      if (defect.better_angles) count_angles(patch.mesh, patch0);
    }
    // Whether the change, made to the patch, leaves counts that pass.
    auto promising = [&](const RepairChange& change) {
      QuadMesh pm = patch.mesh;
      QuadTopology pt;
      SmoothStats ignored;
      if (!change_and_untangle(pm, pt, patch.pick, at, change, ignored)) return false;
      RepairCounts c = count(pm);
      if (defect.better_angles) count_angles(pm, c);
      RepairCounts after = before_try;
      after.defects += c.defects - patch0.defects;
      after.slivers += c.slivers - patch0.slivers;
      after.nonconvex += c.nonconvex - patch0.nonconvex;
      after.ratio += c.ratio - patch0.ratio;
      after.worst = std::min(after.worst, c.worst);
      after.smallest_deg = std::min(after.smallest_deg, c.smallest_deg);
      return passes(after);
    };
    // The change made to the whole mesh, kept when the mesh then passes.
    auto kept = [&](const RepairChange& change) {
      QuadMesh before = m;
      const SmoothStats stats_before = stats;
      if (!change_and_untangle(m, t, pick, at, change, stats)) {
        m = std::move(before);
        stats = stats_before;
        return false;
      }
      RepairCounts after = count(m);
      if (defect.better_angles) count_angles(m, after);
      if (passes(after) && count_boundary_crossings(m) <= crossings0) {
        changed = true;
        return true;
      }
      m = std::move(before);
      stats = stats_before;
      return false;
    };
    bool done = false;
    for (int choice = 0; choice < 4 && !done; ++choice) {
      RepairChange change;
      change.choice = choice;
      if ((!defect.local_first || promising(change)) && kept(change)) {
        ++out.collapses;
        done = true;
      }
    }
    if (!done) {
      const std::vector<QuadFlip> flips =
          defect.local_first ? flips_of(patch.mesh, EdgeQuads(patch.mesh), patch.pick)
                             : flips_of(m, EdgeQuads(m), pick);
      for (std::size_t k = 0; k < flips.size() && !done; ++k) {
        RepairChange change;
        change.kind = RepairChange::flip;
        change.edge_flip = flips[k];
        if (defect.local_first) {
          if (!promising(change)) continue;
          change.edge_flip = flip_in_mesh(patch, flips[k]);
        }
        if (kept(change)) {
          ++out.flips;
          done = true;
        }
      }
    }
    // (A thin row may run out of any patch: tried on the whole mesh.)
    RepairChange chord;
    chord.kind = RepairChange::chord;
    if (!done && !relocate && params.sliver_row_max > 0 && thin_side(m, pick) >= 0 && kept(chord))
      ++out.collapses;
  }
  return out;
}

}  // namespace

// Slivers, once every quad is convex: quads still flatter than sliver_convexity, the
// flattest first (repair_one_by_one), a change kept when it either raises the flattest
// quad's convexity or leaves fewer slivers without lowering it.
void collapse_slivers(const BackgroundMesh& bg, QuadMesh& m, const SmoothParams& params,
                      const SmoothParams& lift, SmoothStats& stats, bool relocate) {
  const QuadDefect slivers{[](const QuadMesh& mesh, int q) { return -quad_convexity(mesh, q); },
                           -params.sliver_convexity, params.sliver_tries,
                           [](const RepairCounts& before, const RepairCounts& after) {
                             return after.worst >= before.worst &&
                                    (after.worst > before.worst || after.slivers < before.slivers);
                           },
                           nullptr};
  const RepairsKept kept = repair_one_by_one(bg, m, params, lift, stats, relocate, slivers);
  stats.num_sliver_collapses += kept.collapses;
  stats.num_flips += kept.flips;
}

// Thin quads, every quad convex: longest side over shortest at least thin_aspect, the
// thinnest first (repair_one_by_one), a change kept when it leaves fewer thin quads,
// fewer thin quads and quads under min_angle_ratio together (SCHISM's two checks), no
// more slivers, the mesh's flattest quad no flatter, and its smallest angle no more than
// kThinAngleSlackDeg under the smallest before the pass. (Without the angle rule, Chile
// at 1:50m lost its smallest angle, 30.0 -> 16.8 degrees, for 4 of its 22 thin quads;
// with no slack, France automatic at 28 km keeps 23 of its 25, since mending them makes
// angles of about 22.3 degrees, its smallest 22.8; with 1 degree, 19, its smallest
// angle unchanged.)
constexpr double kThinAngleSlackDeg = 1.0;
void collapse_thin(const BackgroundMesh& bg, QuadMesh& m, const SmoothParams& params,
                   const SmoothParams& lift, SmoothStats& stats) {
  if (params.thin_aspect <= 0) return;
  double smallest0_deg = 180;
  for (int q = 0; q < static_cast<int>(m.quads.size()); ++q) {
    const auto angles = quad_angles_deg(m, q);
    smallest0_deg = std::min(smallest0_deg, *std::min_element(angles.begin(), angles.end()));
  }
  const QuadDefect thin{quad_aspect,
                        params.thin_aspect,
                        params.thin_tries,
                        [](const RepairCounts& before, const RepairCounts& after) {
                          return after.defects < before.defects &&
                                 after.slivers <= before.slivers && after.worst >= before.worst;
                        },
                        [&](const RepairCounts& before, const RepairCounts& after) {
                          return after.defects + after.ratio < before.defects + before.ratio &&
                                 after.smallest_deg >= smallest0_deg - kThinAngleSlackDeg;
                        },
                        params.thin_patch_first};
  const RepairsKept kept = repair_one_by_one(bg, m, params, lift, stats, false, thin);
  stats.num_thin_repairs += kept.collapses + kept.flips;
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
    const QuadTopology t = quad_topology(m);
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
    for (int q = 0; q < static_cast<int>(m.quads.size()); ++q)
      worst = std::min(worst, quad_convexity(m, q));
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
    if (!split_doubled_corner(m, quad_topology(m), b, i)) continue;
    const QuadTopology t = quad_topology(m);
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

}  // namespace isoquad
