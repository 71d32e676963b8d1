#include "domain/simplify_domain.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_plus_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Handle_hash_function.h>
#include <CGAL/Polyline_simplification_2/simplify.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <unordered_set>
#include <vector>

#include "core/error.h"

namespace isoquad {

namespace {

namespace PS = CGAL::Polyline_simplification_2;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = PS::Vertex_base_2<K>;
using Fb = CGAL::Constrained_triangulation_face_base_2<K>;
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
template <class Ct>
bool keeps_clearance(const Ct& ct, typename Ct::Vertex_handle c, typename Ct::Vertex_handle p,
                     typename Ct::Vertex_handle n, double clearance) {
  using Vertex_handle = typename Ct::Vertex_handle;
  using Face_handle = typename Ct::Face_handle;
  const K::Segment_2 pn(p->point(), n->point());
  const double clearance2 = clearance * clearance;
  auto near_pn = [&](const Vertex_handle& v) {
    return CGAL::squared_distance(v->point(), pn) < clearance2;
  };
  // The stretches of the ring on either side that stay within the clearance of pn: a
  // coast's own next vertices, not another part of the boundary.
  std::vector<Vertex_handle> stretch{c, p, n};
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
      if (constrained != 2 || next == Vertex_handle() ||
          std::find(stretch.begin(), stretch.end(), next) != stretch.end())
        return;
      stretch.push_back(next);
      from = v;
      v = next;
    }
  };
  walk(c, n);
  walk(c, p);
  std::sort(stretch.begin(), stretch.end());  // (handles order by address; only looked up)
  // The faces within the clearance of pn, flooded from those round c (the region is
  // convex, so they are connected across edges); their vertices are the candidates.
  std::unordered_set<Face_handle, CGAL::Handle_hash_function> seen;
  std::vector<Face_handle> pending;
  auto visit = [&](Face_handle f) {
    if (ct.is_infinite(f) || !seen.insert(f).second) return;
    const K::Triangle_2 t(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point());
    if (CGAL::squared_distance(t, pn) < clearance2) pending.push_back(f);
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
      if (!std::binary_search(stretch.begin(), stretch.end(), v)) {
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
      if (!keeps_clearance(pct, *vicq, *prev, *next, clearance_)) return boost::none;
    }
    const auto& p = (*vicq)->point();
    std::uint64_t h = 1469598103934665603ull;  // FNV-1a over the coordinate bits
    for (double c : {p.x(), p.y()}) {
      std::uint64_t bits;
      std::memcpy(&bits, &c, sizeof bits);
      for (int k = 0; k < 8; ++k) {
        h ^= (bits >> (8 * k)) & 0xffu;
        h *= 1099511628211ull;
      }
    }
    return *cost + epsilon_ * static_cast<double>(h >> 11) / static_cast<double>(1ull << 53);
  }

 private:
  double threshold_;
  double epsilon_;
  double clearance_;
};

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
  for (Ring* r : rings) {
    std::vector<K::Point_2> pts;
    pts.reserve(r->size());
    for (const Point2& q : *r) pts.emplace_back(q.x, q.y);
    ids.push_back(ct.insert_constraint(pts.begin(), pts.end(), /*close=*/true));
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
