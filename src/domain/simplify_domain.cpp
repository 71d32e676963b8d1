#include "domain/simplify_domain.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_plus_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polyline_simplification_2/simplify.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <tuple>
#include <utility>
#include <vector>

#include "core/error.h"

namespace isoquad {

namespace {

namespace PS = CGAL::Polyline_simplification_2;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
// What a vertex and a face hold for the simplification's costs.
struct VertexInfo {
  char kept = 0;         // 1: the thinning keeps it (thinning_kept)
  unsigned stretch = 0;  // the check of keeps_clearance whose stretches hold it
};
struct FaceInfo {
  unsigned seen = 0;  // the check of keeps_clearance that looked at it
};
using Vb = PS::Vertex_base_2<K, CGAL::Triangulation_vertex_base_with_info_2<VertexInfo, K>>;
using Fb = CGAL::Constrained_triangulation_face_base_2<
    K, CGAL::Triangulation_face_base_with_info_2<FaceInfo, K>>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;
using Ct = CGAL::Constrained_triangulation_plus_2<Cdt>;

// Whether removing the vertex at `c` (between `p` and `n` on its ring) keeps the
// clearance: no vertex v of another ring, or of this ring beyond the stretches next to
// the new segment pn, comes closer to the ring than `clearance` where it was farther
// than that, nor closer than it was where it was nearer (a channel already narrower
// than the clearance stays as wide as it was).
//
// Vertices suffice: two segments that do not cross are nearest at an endpoint of one,
// p and n do not move, and a removal elsewhere is checked against c in its turn, so
// the distance between any two parts of the boundary never falls below the smaller of
// the clearance and what it was.
// `mark`: a number no earlier check used (the stretches' vertices and the faces looked at
// are marked with it); `pending`: scratch.
template <class Ct>
bool keeps_clearance(const Ct& ct, typename Ct::Vertex_handle c, typename Ct::Vertex_handle p,
                     typename Ct::Vertex_handle n, double clearance, unsigned mark,
                     std::vector<typename Ct::Face_handle>& pending) {
  using Vertex_handle = typename Ct::Vertex_handle;
  using Face_handle = typename Ct::Face_handle;
  const K::Segment_2 pn(p->point(), n->point());
  const double clearance2 = clearance * clearance;
  auto near_pn = [&](const Vertex_handle& v) {
    return CGAL::squared_distance(v->point(), pn) < clearance2;
  };
  // The stretches of the ring on either side that stay within the clearance of pn: a
  // coast's own next vertices, not another part of the boundary.
  for (Vertex_handle v : {c, p, n}) v->info().stretch = mark;
  auto walk = [&](Vertex_handle from, Vertex_handle v) {
    constexpr int kMaxSteps = 1000;
    for (int step = 0; step < kMaxSteps && near_pn(v); ++step) {
      Vertex_handle next;
      int constrained = 0;
      auto e = ct.incident_edges(v), end = e;
      do {
        if (ct.is_infinite(e) || !ct.is_constrained(*e)) continue;
        ++constrained;
        const Vertex_handle w = e->first->vertex(Ct::cw(e->second)) == v
                                    ? e->first->vertex(Ct::ccw(e->second))
                                    : e->first->vertex(Ct::cw(e->second));
        if (w != from) next = w;
      } while (++e != end);
      if (constrained != 2 || next == Vertex_handle() || next->info().stretch == mark) return;
      next->info().stretch = mark;
      from = v;
      v = next;
    }
  };
  walk(c, n);
  walk(c, p);
  // The faces within the clearance of pn, flooded from those round c (the region is
  // convex, so they are connected across edges); their vertices are the candidates. A
  // face whose bounding box lies farther from pn's than the clearance along x or y is
  // farther from pn too.
  const double xmin = std::min(p->point().x(), n->point().x()) - clearance,
               xmax = std::max(p->point().x(), n->point().x()) + clearance,
               ymin = std::min(p->point().y(), n->point().y()) - clearance,
               ymax = std::max(p->point().y(), n->point().y()) + clearance;
  pending.clear();
  auto visit = [&](Face_handle f) {
    if (ct.is_infinite(f) || f->info().seen == mark) return;
    f->info().seen = mark;
    const K::Point_2 &a = f->vertex(0)->point(), &b = f->vertex(1)->point(),
                     &d = f->vertex(2)->point();
    if (std::max({a.x(), b.x(), d.x()}) < xmin || std::min({a.x(), b.x(), d.x()}) > xmax ||
        std::max({a.y(), b.y(), d.y()}) < ymin || std::min({a.y(), b.y(), d.y()}) > ymax)
      return;
    if (CGAL::squared_distance(K::Triangle_2(a, b, d), pn) < clearance2) pending.push_back(f);
  };
  auto f = ct.incident_faces(c), fend = f;
  do visit(f);
  while (++f != fend);
  const K::Segment_2 pc(p->point(), c->point()), cn(c->point(), n->point());
  while (!pending.empty()) {
    const Face_handle g = pending.back();
    pending.pop_back();
    for (int i = 0; i < 3; ++i) {
      const Vertex_handle v = g->vertex(i);
      if (v->info().stretch != mark) {
        const double now = CGAL::squared_distance(v->point(), pn);
        if (now < clearance2) {
          const double before = std::min(CGAL::squared_distance(v->point(), pc),
                                         CGAL::squared_distance(v->point(), cn));
          if (now < before) return false;
        }
      }
      visit(g->neighbor(i));
    }
  }
  return true;
}

// A number in [0, 1) from the bits of a position (FNV-1a), the same in every process.
double position_hash(const K::Point_2& p) {
  std::uint64_t h = 1469598103934665603ull;
  for (double c : {p.x(), p.y()}) {
    std::uint64_t bits;
    std::memcpy(&bits, &c, sizeof bits);
    for (int k = 0; k < 8; ++k) {
      h ^= (bits >> (8 * k)) & 0xffu;
      h *= 1099511628211ull;
    }
  }
  return static_cast<double>(h >> 11) / static_cast<double>(1ull << 53);
}

// CGAL's squared distance cost, made unique by a tiny term hashed from the vertex
// position (at most 1e-9 of the threshold): the simplification queue otherwise breaks
// ties between equal costs (symmetric shapes) by vertex address, and the result would
// depend on the memory layout of the process. A removal that would break the clearance
// has no cost (the vertex stays; it is tried again when a neighbour goes).
class SimplificationCost {
 public:
  SimplificationCost(double threshold, double clearance)
      : threshold_(threshold), epsilon_(1e-9 * threshold), clearance_(clearance) {}
  template <class CDT>
  boost::optional<typename CDT::Geom_traits::FT> operator()(
      const CGAL::Constrained_triangulation_plus_2<CDT>& pct,
      typename CGAL::Constrained_triangulation_plus_2<CDT>::Vertices_in_constraint_iterator vicq)
      const {
    auto cost = PS::Squared_distance_cost()(pct, vicq);
    if (!cost) return cost;
    // Beyond the threshold the vertex stays anyway: the clearance is not looked at.
    if (clearance_ > 0 && *cost <= threshold_) {
      auto prev = vicq, next = vicq;  // (the iterator is bidirectional, not tagged so)
      --prev;
      ++next;
      if (!keeps_clearance(pct, *vicq, *prev, *next, clearance_, ++mark_, pending_))
        return boost::none;
    }
    return *cost + epsilon_ * position_hash((*vicq)->point());
  }

 private:
  double threshold_;
  double epsilon_;
  double clearance_;
  mutable unsigned mark_ = 0;                     // the last check's (keeps_clearance)
  mutable std::vector<Ct::Face_handle> pending_;  // its scratch
};

// The thinning. Where a ring's vertices lie much closer together than the tolerance (a
// coastline drawn at 1:25,000 meshed with quads of kilometres), the simplification proper
// is slow: each removal checks the clearance over every vertex near the new segment, and
// a dense ring puts hundreds there (France's coast with a vertex every 40 m: 27 s). A
// first pass removes, in the same triangulation and order of cost, each vertex whose two
// neighbours lie within delta (a quarter of the tolerance) and whose removal keeps every
// original vertex within delta of the ring, so that the second pass finds the vertices
// about delta/2 apart or more. It leaves alone the vertices near another part of the
// boundary (within clearance + 2 delta, thinning_kept): every change it makes lies within
// delta of a vertex it removed, so no other part comes within the clearance of a change,
// and the second pass's clearance holds as without it. Rings with few vertices that dense
// (Natural Earth's at the tolerances of their scale) are not thinned at all.

// Per ring, per vertex: whether the thinning keeps it, as a vertex of another ring, or of
// the same ring beyond the run of its neighbours that stays within `radius` of it (the
// far bank of an inlet, not the next vertices of the same coast, however jagged), lies
// within `radius`.
std::vector<std::vector<char>> thinning_kept(const std::vector<Ring*>& rings, double radius) {
  struct Entry {
    std::int64_t cx, cy;
    int ring, index;
  };
  std::vector<Entry> entries;
  auto cell = [&](double v) { return static_cast<std::int64_t>(std::floor(v / radius)); };
  for (std::size_t r = 0; r < rings.size(); ++r)
    for (std::size_t i = 0; i < rings[r]->size(); ++i)
      entries.push_back({cell((*rings[r])[i].x), cell((*rings[r])[i].y), static_cast<int>(r),
                         static_cast<int>(i)});
  auto by_cell = [](const Entry& a, const Entry& b) {
    return std::tie(a.cx, a.cy, a.ring, a.index) < std::tie(b.cx, b.cy, b.ring, b.index);
  };
  std::sort(entries.begin(), entries.end(), by_cell);
  std::vector<std::vector<char>> kept(rings.size());
  for (std::size_t r = 0; r < rings.size(); ++r) kept[r].assign(rings[r]->size(), 0);
  for (const Entry& e : entries) {
    const Ring& ring = *rings[e.ring];
    const int n = static_cast<int>(ring.size());
    const Point2& x = ring[e.index];
    // The run: `back` vertices before x and `ahead` after it, all within the radius.
    int back = 0, ahead = 0;
    while (ahead < n - 1 && distance(x, ring[(e.index + ahead + 1) % n]) < radius) ++ahead;
    while (back < n - 1 - ahead && distance(x, ring[(e.index - back - 1 + n) % n]) < radius) ++back;
    bool near = false;
    for (std::int64_t dx = -1; dx <= 1 && !near; ++dx)
      for (std::int64_t dy = -1; dy <= 1 && !near; ++dy) {
        const Entry lo{e.cx + dx, e.cy + dy, -1, -1};
        const Entry hi{e.cx + dx, e.cy + dy, std::numeric_limits<int>::max(), 0};
        for (auto it = std::lower_bound(entries.begin(), entries.end(), lo, by_cell);
             it != entries.end() && by_cell(*it, hi) && !near; ++it) {
          if (it->ring == e.ring) {  // x itself, or its run
            const int forward = (it->index - e.index + n) % n;
            if (forward <= ahead || n - forward <= back) continue;
          }
          near = distance(x, (*rings[it->ring])[it->index]) < radius;
        }
      }
    kept[e.ring][e.index] = near ? 1 : 0;
  }
  return kept;
}

// The thinning's cost: CGAL's squared distance (made unique as SimplificationCost's),
// for a vertex not kept whose two neighbours lie within delta of it and whose removal
// keeps every original vertex within delta of the ring; none otherwise.
class ThinningCost {
 public:
  explicit ThinningCost(double delta) : delta2_(delta * delta), epsilon_(1e-9 * delta2_) {}
  template <class CDT>
  boost::optional<typename CDT::Geom_traits::FT> operator()(
      const CGAL::Constrained_triangulation_plus_2<CDT>& pct,
      typename CGAL::Constrained_triangulation_plus_2<CDT>::Vertices_in_constraint_iterator vicq)
      const {
    const auto c = *vicq;
    if (c->info().kept) return boost::none;
    auto prev = vicq, next = vicq;
    --prev;
    ++next;
    if (CGAL::squared_distance(c->point(), (*prev)->point()) >= delta2_ ||
        CGAL::squared_distance(c->point(), (*next)->point()) >= delta2_)
      return boost::none;
    auto cost = PS::Squared_distance_cost()(pct, vicq);
    if (!cost || *cost > delta2_) return boost::none;
    return *cost + epsilon_ * position_hash(c->point());
  }

 private:
  double delta2_;
  double epsilon_;
};

// Whether a quarter or more of the rings' vertices have both their neighbours within
// delta: a ring drawn much more finely than the tolerance, not a few close vertices of a
// coarser one (whose simplification is quick, and the same as before the thinning was).
bool is_dense(const std::vector<Ring*>& rings, double delta) {
  std::size_t dense = 0, all = 0;
  for (const Ring* r : rings)
    for (std::size_t i = 0; i < r->size(); ++i, ++all) {
      const Point2& p = (*r)[(i + r->size() - 1) % r->size()];
      const Point2 &c = (*r)[i], &n = (*r)[(i + 1) % r->size()];
      if (distance(p, c) < delta && distance(c, n) < delta) ++dense;
    }
  return 4 * dense >= all && dense > 0;
}

}  // namespace

SimplifyResult simplify_domain(Domain& domain, const SimplifyParams& params) {
  SimplifyResult result;
  result.num_vertices_before = num_vertices(domain);
  if (params.tolerance_m <= 0.0) {
    result.num_vertices_after = result.num_vertices_before;
    return result;
  }

  Ct ct;
  std::vector<Ring*> rings;
  std::vector<Ct::Constraint_id> ids;
  for (Polygon& p : domain.polygons) {
    rings.push_back(&p.outer);
    for (Ring& h : p.holes) rings.push_back(&h);
  }
  // The points first, all at once (CGAL sorts them along a space-filling curve), then
  // the rings through them: inserted one after the other along a dense ring, each point
  // would flip the triangles of the ones before it (a ring of 142,000 vertices: 1.0 s
  // instead of 0.1).
  std::vector<K::Point_2> all;
  for (const Ring* r : rings)
    for (const Point2& q : *r) all.emplace_back(q.x, q.y);
  ct.insert(all.begin(), all.end());
  for (Ring* r : rings) {
    std::vector<K::Point_2> pts;
    pts.reserve(r->size());
    for (const Point2& q : *r) pts.emplace_back(q.x, q.y);
    ids.push_back(ct.insert_constraint(pts.begin(), pts.end(), /*close=*/true));
  }

  // The thinning first, where vertices are dense; it keeps the removed vertices' points
  // for the second pass's cost, which measures the distance of every original vertex.
  const double delta = 0.25 * params.tolerance_m;
  if (is_dense(rings, delta)) {
    const std::vector<std::vector<char>> kept =
        thinning_kept(rings, params.clearance_m + 2.0 * delta);
    std::map<std::pair<double, double>, char> kept_at;  // a point of two rings: kept
    for (std::size_t r = 0; r < rings.size(); ++r)
      for (std::size_t i = 0; i < rings[r]->size(); ++i) {
        char& k = kept_at[{(*rings[r])[i].x, (*rings[r])[i].y}];
        k = static_cast<char>(k || kept[r][i]);
      }
    for (auto v = ct.finite_vertices_begin(); v != ct.finite_vertices_end(); ++v) {
      const auto it = kept_at.find({v->point().x(), v->point().y()});
      v->info().kept = it == kept_at.end() ? 1 : it->second;  // a vertex CGAL added: kept
    }
    PS::simplify(ct, ThinningCost(delta), PS::Stop_above_cost_threshold(2.0 * delta * delta),
                 /*erase_unnecessary_points=*/false);
  }

  // The cost is a squared distance, so the threshold is the squared tolerance.
  PS::simplify(ct, SimplificationCost(params.tolerance_m * params.tolerance_m, params.clearance_m),
               PS::Stop_above_cost_threshold(params.tolerance_m * params.tolerance_m),
               /*erase_unnecessary_points=*/true);

  for (std::size_t i = 0; i < rings.size(); ++i) {
    Ring out;
    for (auto it = ct.points_in_constraint_begin(ids[i]); it != ct.points_in_constraint_end(ids[i]);
         ++it)
      out.push_back({it->x(), it->y()});
    if (out.size() > 1 && out.front() == out.back()) out.pop_back();
    if (out.size() < 3)
      throw Error(ErrorClass::internal, "simplify", "a ring collapsed to fewer than 3 vertices");
    *rings[i] = std::move(out);
  }
  for (Polygon& p : domain.polygons) orient_polygon(p);
  result.num_vertices_after = num_vertices(domain);
  return result;
}

}  // namespace isoquad
