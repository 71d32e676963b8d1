#include "domain/simplify_domain.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_plus_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polyline_simplification_2/simplify.h>

#include <cstdint>
#include <cstring>
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

// CGAL's squared distance cost, made unique by a tiny term hashed from the vertex
// position (at most 1e-9 of the threshold): the simplification queue otherwise breaks
// ties between equal costs (symmetric shapes) by vertex address, and the result would
// depend on the memory layout of the process.
class UniqueSquaredDistanceCost {
 public:
  explicit UniqueSquaredDistanceCost(double threshold) : epsilon_(1e-9 * threshold) {}
  template <class CDT>
  boost::optional<typename CDT::Geom_traits::FT> operator()(
      const CGAL::Constrained_triangulation_plus_2<CDT>& pct,
      typename CGAL::Constrained_triangulation_plus_2<CDT>::Vertices_in_constraint_iterator vicq)
      const {
    auto cost = PS::Squared_distance_cost()(pct, vicq);
    if (!cost) return cost;
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
  double epsilon_;
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
  PS::simplify(ct, UniqueSquaredDistanceCost(params.tolerance_m * params.tolerance_m),
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
