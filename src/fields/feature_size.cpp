#include "fields/feature_size.h"

#include <CGAL/Apollonius_graph_2.h>
#include <CGAL/Apollonius_graph_traits_2.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_2.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace isoquad {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Delaunay = CGAL::Delaunay_triangulation_2<K>;
using ApolloniusTraits = CGAL::Apollonius_graph_traits_2<K>;
using Apollonius = CGAL::Apollonius_graph_2<ApolloniusTraits>;
using Site = ApolloniusTraits::Site_2;
using MedialTraits = CGAL::Search_traits_2<K>;
using MedialSearch = CGAL::Orthogonal_k_neighbor_search<MedialTraits>;
using MedialTree = MedialSearch::Tree;

// Radius of the smallest circle enclosing a triangle: the circumradius when it is acute,
// half the longest edge otherwise.
double enclosing_radius(const K::Point_2& a, const K::Point_2& b, const K::Point_2& c) {
  const double ab = CGAL::squared_distance(a, b), bc = CGAL::squared_distance(b, c),
               ca = CGAL::squared_distance(c, a);
  const double longest = std::max({ab, bc, ca});
  if (2 * longest >= ab + bc + ca) return 0.5 * std::sqrt(longest);  // right or obtuse
  return std::sqrt(CGAL::squared_radius(a, b, c));
}

}  // namespace

struct BoundaryFeatureSize::Impl {
  Apollonius ag;
  double gradation = 1.0;
  mutable Apollonius::Vertex_handle hint;
};

BoundaryFeatureSize::BoundaryFeatureSize(const Domain& domain, const FeatureSizeParams& params)
    : impl_(std::make_unique<Impl>()) {
  if (!(params.lambda_m > 0) || !(params.gradation > 0) || !(params.cells_across > 0) ||
      !std::isfinite(params.max_size_m))
    throw Error(ErrorClass::internal, "sizing",
                "feature size needs lambda, K, cells > 0 and a finite max size");
  const double spacing =
      params.sample_spacing_m > 0 ? params.sample_spacing_m : 0.5 * params.lambda_m;

  // Dense boundary samples: every ring vertex plus evenly spaced points on each segment.
  for (const Polygon& p : domain.polygons) {
    std::vector<const Ring*> rings{&p.outer};
    for (const Ring& h : p.holes) rings.push_back(&h);
    for (const Ring* r : rings)
      for (std::size_t i = 0; i < r->size(); ++i) {
        const Point2 a = (*r)[i], b = (*r)[(i + 1) % r->size()];
        const int n = std::max(1, static_cast<int>(std::ceil(std::hypot(b.x - a.x, b.y - a.y) / spacing)));
        for (int k = 0; k < n; ++k) {
          const double t = static_cast<double>(k) / n;
          samples_.push_back({a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)});
        }
      }
  }

  // The lambda-medial axis: circumcentres of Delaunay triangles of the samples whose
  // vertices are spread over a circle of radius >= lambda.
  std::vector<K::Point_2> pts;
  pts.reserve(samples_.size());
  for (const Point2& s : samples_) pts.emplace_back(s.x, s.y);
  Delaunay dt(pts.begin(), pts.end());
  std::vector<K::Point_2> medial;
  std::vector<double> medial_radius;
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
    const K::Point_2 &a = f->vertex(0)->point(), &b = f->vertex(1)->point(),
                     &c = f->vertex(2)->point();
    if (CGAL::orientation(a, b, c) == CGAL::COLLINEAR) continue;
    if (enclosing_radius(a, b, c) >= params.lambda_m) {
      medial.push_back(CGAL::circumcenter(a, b, c));
      medial_radius.push_back(std::sqrt(CGAL::squared_radius(a, b, c)));
    }
  }
  // Nearest medial point by kd-tree: the circumcentres are highly degenerate (many
  // coincide where the boundary is straight), which a Delaunay triangulation of them
  // handles badly.
  MedialTree tree(medial.begin(), medial.end());

  // Size per unit of feature size. In a straight channel of width w, sites sit on both
  // banks and on the centre line (all with lfs = w/2), and between them h grows with
  // slope K. Requiring the integral of dy / h across the channel to be at least N gives
  // h_site = K (w/4) / (exp(N K / 4) - 1), i.e. this factor times lfs. It tends to
  // 2 / N (h = w / N) as K -> 0. A 2% margin covers the sampling.
  const double n = params.cells_across, k = params.gradation;
  const double size_per_lfs = 0.98 * k / (2.0 * std::expm1(n * k / 4.0));
  lfs_.resize(samples_.size(), std::numeric_limits<double>::infinity());
  size_.resize(samples_.size(), params.max_size_m);
  std::vector<Site> sites;
  sites.reserve(samples_.size());
  for (std::size_t i = 0; i < samples_.size(); ++i) {
    if (!medial.empty()) {
      MedialSearch search(tree, pts[i], 1);
      lfs_[i] = std::sqrt(search.begin()->second);
      size_[i] = std::min(params.max_size_m, size_per_lfs * lfs_[i]);
    }
    // Apollonius distance |x - p| - w with w = -h/K gives (h + K |x - p|) / K.
    sites.emplace_back(pts[i], -size_[i] / params.gradation);
  }
  // The medial points are sites too, with the size of the feature they sit in, so that
  // the size stays small across a whole channel and not only along its banks.
  for (std::size_t m = 0; m < medial.size(); ++m) {
    const double h = std::min(params.max_size_m, size_per_lfs * medial_radius[m]);
    if (h < params.max_size_m) sites.emplace_back(medial[m], -h / params.gradation);
  }
  impl_->gradation = params.gradation;
  impl_->ag.insert(sites.begin(), sites.end());
}

BoundaryFeatureSize::~BoundaryFeatureSize() = default;

double BoundaryFeatureSize::operator()(const Point2& x) const {
  const K::Point_2 q(x.x, x.y);
  impl_->hint = impl_->hint == Apollonius::Vertex_handle() ? impl_->ag.nearest_neighbor(q)
                                                           : impl_->ag.nearest_neighbor(q, impl_->hint);
  const Site& s = impl_->hint->site();
  return impl_->gradation * (std::sqrt(CGAL::squared_distance(q, s.point())) - s.weight());
}

}  // namespace isoquad
