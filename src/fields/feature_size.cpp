#include "fields/feature_size.h"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/parallel.h"
#include "gis/map_scale.h"

namespace isoquad {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;  // the sample's index
using Delaunay = CGAL::Delaunay_triangulation_2<K, CGAL::Triangulation_data_structure_2<Vb>>;
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

// A site of the size field: h(x) = h + K |x - p|.
struct Site {
  double x, y, h;
};

}  // namespace

// h(x) = min_i(h_i + K |x - p_i|) through a grid: every cell keeps the site that is
// best at its centre, propagated from neighbouring cells in raster sweeps (the vector
// distance transform, with additive weights); a query evaluates the sites of the 3 x 3
// cells around it exactly. Sites of lower h win over larger distances as K decreases,
// which CGAL's Apollonius graph (negative weights, |w| = h/K) did not survive: with
// K < 1 its nearest-site queries returned sites of the far bank of a channel, and
// non-negative weights made its construction quadratic.
struct BoundaryFeatureSize::Impl {
  std::vector<Site> sites;
  double gradation = 1.0;
  double x0 = 0, y0 = 0, cell = 1;
  int nx = 1, ny = 1;
  std::vector<int> best;  // #cells site index, -1 before any reaches the cell

  double value(int site, double x, double y) const {
    const Site& s = sites[site];
    const double dx = x - s.x, dy = y - s.y;
    return s.h + gradation * std::sqrt(dx * dx + dy * dy);
  }

  void build(double min_cell) {
    double x1 = -std::numeric_limits<double>::infinity(), y1 = x1;
    x0 = y0 = std::numeric_limits<double>::infinity();
    for (const Site& s : sites) {
      x0 = std::min(x0, s.x), y0 = std::min(y0, s.y);
      x1 = std::max(x1, s.x), y1 = std::max(y1, s.y);
    }
    // Cells of min_cell, at most 2048 along the longer side.
    cell = std::max({min_cell, (x1 - x0) / 2048.0, (y1 - y0) / 2048.0, 1e-9});
    nx = static_cast<int>((x1 - x0) / cell) + 1;
    ny = static_cast<int>((y1 - y0) / cell) + 1;
    best.assign(static_cast<std::size_t>(nx) * ny, -1);
    std::vector<double> at(best.size(), std::numeric_limits<double>::infinity());
    auto centre_x = [&](int i) { return x0 + (i + 0.5) * cell; };
    auto centre_y = [&](int j) { return y0 + (j + 0.5) * cell; };
    auto offer = [&](int i, int j, int site) {
      const std::size_t c = static_cast<std::size_t>(j) * nx + i;
      const double v = value(site, centre_x(i), centre_y(j));
      if (v < at[c] || (v == at[c] && site < best[c])) at[c] = v, best[c] = site;
    };
    for (int k = 0; k < static_cast<int>(sites.size()); ++k) offer(cell_x(sites[k].x), cell_y(sites[k].y), k);
    // Forward and backward sweeps over the 8 neighbours, twice. A cell's best site and
    // value are kept in registers while its neighbours are offered (only the cell itself
    // changes meanwhile), and its centre computed once: the same comparisons in the same
    // order as offer() for each neighbour, so the same sites.
    for (int round = 0; round < 2; ++round)
      for (int pass = 0; pass < 2; ++pass) {
        const int step = pass == 0 ? 1 : -1;
        for (int jj = 0; jj < ny; ++jj) {
          const int j = pass == 0 ? jj : ny - 1 - jj;
          const double cy = centre_y(j);
          for (int ii = 0; ii < nx; ++ii) {
            const int i = pass == 0 ? ii : nx - 1 - ii;
            const double cx = centre_x(i);
            const std::size_t c = static_cast<std::size_t>(j) * nx + i;
            int best_site = best[c];
            double best_value = at[c];
            const bool inside = i > 0 && j > 0 && i < nx - 1 && j < ny - 1;
            for (int dj = -1; dj <= 1; ++dj)
              for (int di = -1; di <= 1; ++di) {
                const int a = i - step * di, b = j - step * dj;
                if (di == 0 && dj == 0) continue;
                if (!inside && (a < 0 || b < 0 || a >= nx || b >= ny)) continue;
                const int site = best[static_cast<std::size_t>(b) * nx + a];
                // The cell's own site again changes nothing (most neighbours share it).
                if (site < 0 || site == best_site) continue;
                const double v = value(site, cx, cy);
                if (v < best_value || (v == best_value && site < best_site))
                  best_value = v, best_site = site;
              }
            best[c] = best_site;
            at[c] = best_value;
          }
        }
      }
  }

  int cell_x(double x) const { return std::clamp(static_cast<int>((x - x0) / cell), 0, nx - 1); }
  int cell_y(double y) const { return std::clamp(static_cast<int>((y - y0) / cell), 0, ny - 1); }

  double operator()(double x, double y) const {
    const int i = cell_x(x), j = cell_y(y);
    double h = std::numeric_limits<double>::infinity();
    for (int b = std::max(0, j - 1); b <= std::min(ny - 1, j + 1); ++b)
      for (int a = std::max(0, i - 1); a <= std::min(nx - 1, i + 1); ++a) {
        const int site = best[static_cast<std::size_t>(b) * nx + a];
        if (site >= 0) h = std::min(h, value(site, x, y));
      }
    return h;
  }
};

BoundaryFeatureSize::BoundaryFeatureSize(const Domain& domain, const FeatureSizeParams& params)
    : impl_(std::make_unique<Impl>()) {
  if (!(params.lambda_m > 0) || !(params.gradation > 0) || !(params.cells_across > 0) ||
      !std::isfinite(params.max_size_m))
    throw Error(ErrorClass::internal, "sizing",
                "feature size needs lambda, K, cells > 0 and a finite max size");
  const bool with_narrow = params.narrow_lambda_m > 0 && params.narrow_lambda_m < params.lambda_m;
  const double spacing =
      params.sample_spacing_m > 0 ? params.sample_spacing_m : 0.5 * params.lambda_m;

  // Dense boundary samples: every ring vertex plus evenly spaced points on each segment,
  // each with its ring and its arc length along it.
  std::vector<int> ring_of;
  std::vector<double> arc_of, ring_length;
  std::vector<Point2> inward;  // #samples unit normal of its segment, towards the domain
  for (const Polygon& p : domain.polygons) {
    std::vector<const Ring*> rings{&p.outer};
    for (const Ring& h : p.holes) rings.push_back(&h);
    for (const Ring* r : rings) {
      // The domain is left of an outer ring drawn counter-clockwise, right of a hole so.
      const double left = (signed_area(*r) > 0) == (r == &p.outer) ? 1.0 : -1.0;
      double arc = 0.0;
      for (std::size_t i = 0; i < r->size(); ++i) {
        const Point2 a = (*r)[i], b = (*r)[(i + 1) % r->size()];
        const double len = std::hypot(b.x - a.x, b.y - a.y);
        const int n = std::max(1, static_cast<int>(std::ceil(len / spacing)));
        for (int k = 0; k < n; ++k) {
          const double t = static_cast<double>(k) / n;
          samples_.push_back({a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)});
          ring_of.push_back(static_cast<int>(ring_length.size()));
          arc_of.push_back(arc + t * len);
          inward.push_back(len > 0 ? Point2{-left * (b.y - a.y) / len, left * (b.x - a.x) / len}
                                   : Point2{0, 0});
        }
        arc += len;
      }
      ring_length.push_back(arc);
    }
  }
  // Distance along the boundary between two samples (infinite on different rings).
  auto along = [&](int i, int j) {
    if (ring_of[i] != ring_of[j]) return std::numeric_limits<double>::infinity();
    const double d = std::abs(arc_of[i] - arc_of[j]);
    return std::min(d, ring_length[ring_of[i]] - d);
  };

  // The lambda-medial axis: circumcentres of Delaunay triangles of the samples whose
  // vertices are spread over a circle of radius >= lambda.
  std::vector<K::Point_2> pts;
  std::vector<std::pair<K::Point_2, int>> indexed;
  pts.reserve(samples_.size());
  indexed.reserve(samples_.size());
  for (const Point2& s : samples_) {
    indexed.emplace_back(K::Point_2(s.x, s.y), static_cast<int>(pts.size()));
    pts.emplace_back(s.x, s.y);
  }
  Delaunay dt(indexed.begin(), indexed.end());
  std::vector<K::Point_2> medial;
  std::vector<double> medial_radius;
  std::vector<Site> narrow_sites;  // features between 2 narrow_lambda and 2 lambda wide
  // Size per unit of feature size. In a straight channel of width w, sites sit on both
  // banks and on the centre line (all with lfs = w/2), and between them h grows with
  // slope K. Requiring the integral of dy / h across the channel to be at least N gives
  // h_site = K (w/4) / (exp(N K / 4) - 1), i.e. this factor times lfs. It tends to
  // 2 / N (h = w / N) as K -> 0. A 2% margin covers the sampling.
  const double n = params.cells_across, k = params.gradation;
  const double size_per_lfs = 0.98 * k / (2.0 * std::expm1(n * k / 4.0));
  const double size_per_lfs_one = 0.98 * k / (2.0 * std::expm1(k / 4.0));  // N = 1
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
    const K::Point_2 &a = f->vertex(0)->point(), &b = f->vertex(1)->point(),
                     &c = f->vertex(2)->point();
    if (CGAL::orientation(a, b, c) == CGAL::COLLINEAR) continue;
    // Not collinear, yet flat enough that the circumcentre's denominator rounds to zero
    // (the centre is at infinity in doubles): no medial point there.
    if (CGAL::determinant(b.x() - a.x(), b.y() - a.y(), c.x() - a.x(), c.y() - a.y()) == 0.0)
      continue;
    const double spread = enclosing_radius(a, b, c);
    // The widths are the ground's: in the CRS, times its scale there.
    const double scale =
        params.scale ? params.scale->at({(a.x() + b.x() + c.x()) / 3, (a.y() + b.y() + c.y()) / 3})
                     : 1.0;
    if (spread >= params.lambda_m * scale) {
      medial.push_back(CGAL::circumcenter(a, b, c));
      medial_radius.push_back(std::sqrt(CGAL::squared_radius(a, b, c)));
    } else if (with_narrow && spread >= params.narrow_lambda_m * scale) {
      // A narrow channel or inlet of the domain (not of its outside: a land domain's
      // estuaries are no place for its quads): the triangle is on the inner side of the
      // samples' segments, for two of its three vertices at least.
      const int ia = f->vertex(0)->info(), ib = f->vertex(1)->info(), ic = f->vertex(2)->info();
      const double gx = (a.x() + b.x() + c.x()) / 3, gy = (a.y() + b.y() + c.y()) / 3;
      int inner = 0;
      for (int i : {ia, ib, ic})
        inner += (gx - samples_[i].x) * inward[i].x + (gy - samples_[i].y) * inward[i].y > 0;
      if (inner < 2) continue;
      // Its banks are joined along the boundary only far away (or never: a strait
      // between two rings). Vertices joined within a few radii are a corner's (angle
      // over 37 degrees), whose sizes stay hmin.
      const double apart = std::max({along(ia, ib), along(ib, ic), along(ic, ia)});
      if (apart < 6.0 * spread) continue;
      const K::Point_2 centre = CGAL::circumcenter(a, b, c);
      const double h = std::max(params.narrow_floor_m * scale,
                                size_per_lfs_one * std::sqrt(CGAL::squared_radius(a, b, c)));
      // On the centre line and on both banks, as the samples and medial points below.
      narrow_sites.push_back({centre.x(), centre.y(), h});
      for (const K::Point_2* v : {&a, &b, &c}) narrow_sites.push_back({v->x(), v->y(), h});
    }
  }
  // Nearest medial point by kd-tree: the circumcentres are highly degenerate (many
  // coincide where the boundary is straight), which a Delaunay triangulation of them
  // handles badly.
  MedialTree tree(medial.begin(), medial.end());

  lfs_.resize(samples_.size(), std::numeric_limits<double>::infinity());
  size_.resize(samples_.size(), params.max_size_m);
  std::vector<Site>& sites = impl_->sites;
  sites.reserve(samples_.size());
  for (std::size_t i = 0; i < samples_.size(); ++i) {
    if (!medial.empty()) {
      MedialSearch search(tree, pts[i], 1);
      lfs_[i] = std::sqrt(search.begin()->second);
      size_[i] = std::min(params.max_size_m, size_per_lfs * lfs_[i]);
    }
    sites.push_back({samples_[i].x, samples_[i].y, size_[i]});
  }
  // The medial points are sites too, with the size of the feature they sit in, so that
  // the size stays small across a whole channel and not only along its banks.
  for (std::size_t m = 0; m < medial.size(); ++m) {
    const double h = std::min(params.max_size_m, size_per_lfs * medial_radius[m]);
    if (h < params.max_size_m) sites.push_back({medial[m].x(), medial[m].y(), h});
  }
  impl_->gradation = params.gradation;
  if (narrow_sites.empty()) {
    impl_->build(0.5 * params.lambda_m);
    return;
  }
  narrow_ = std::make_unique<Impl>();
  narrow_->sites = std::move(narrow_sites);
  narrow_->gradation = params.gradation;
  // The two grids are independent: built at once on two threads.
  run_in_parallel([&] { impl_->build(0.5 * params.lambda_m); },
                  [&] { narrow_->build(0.5 * params.lambda_m); });
}

BoundaryFeatureSize::~BoundaryFeatureSize() = default;

double BoundaryFeatureSize::operator()(const Point2& x) const { return (*impl_)(x.x, x.y); }

double BoundaryFeatureSize::narrow(const Point2& x) const {
  return narrow_ ? (*narrow_)(x.x, x.y) : std::numeric_limits<double>::infinity();
}

std::size_t BoundaryFeatureSize::num_narrow_sites() const {
  return narrow_ ? narrow_->sites.size() : 0;
}

CoastDistance::CoastDistance(const Domain& domain, const PolylineIndex& open,
                             double open_tolerance_m, double spacing_m) {
  if (!(spacing_m > 0))
    throw Error(ErrorClass::internal, "sizing", "the coast's samples need a positive spacing");
  auto on_open = [&](const Point2& p) { return !open.empty() && open.near(p, open_tolerance_m); };
  std::vector<Point2> samples;
  for_each_side(domain, [&](const Point2& a, const Point2& b) {
    const Point2 middle{0.5 * (a.x + b.x), 0.5 * (a.y + b.y)};
    if (on_open(a) && on_open(b) && on_open(middle)) return;  // the open sea
    const int n = std::max(1, static_cast<int>(std::ceil(distance(a, b) / spacing_m)));
    for (int k = 0; k <= n; ++k) {
      const double t = static_cast<double>(k) / n;
      samples.push_back({a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)});
    }
  });
  samples_ = std::make_unique<NearestPoints>(std::move(samples));
}

CoastDistance::~CoastDistance() = default;

double CoastDistance::operator()(const Point2& x) const {
  const auto nearest = samples_->nearest(x, 1);
  return nearest.empty() ? std::numeric_limits<double>::infinity() : nearest[0].first;
}

}  // namespace isoquad
