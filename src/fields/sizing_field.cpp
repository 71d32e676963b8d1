#include "fields/sizing_field.h"

#include <muParser.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <queue>
#include <sstream>

#include "core/error.h"
#include "core/text.h"
#include "fields/feature_size.h"
#include "fields/size_features.h"
#include "gis/map_scale.h"
#include "gis/mesh_field.h"
#include "gis/raster_field.h"
#include "gis/read_size_features.h"
#include "mesh/background_mesh.h"

namespace isoquad {

struct SizingOracle::Expression {
  mu::Parser parser;
  double x = 0.0, y = 0.0, d = 0.0, lon = 0.0, lat = 0.0, c = 0.0;
  std::string text;
  bool uses_depth = false;
  bool uses_coast = false;
  std::unique_ptr<CrsTransform> to_lonlat;  // when it uses lon or lat

  // Parses `text` now, so that a bad expression fails before any work. Throws
  // mu::Parser::exception_type.
  void parse(const std::string& expression) {
    text = expression;
    parser.DefineVar("x", &x);
    parser.DefineVar("y", &y);
    parser.DefineVar("d", &d);
    parser.DefineVar("lon", &lon);
    parser.DefineVar("lat", &lat);
    parser.DefineVar("c", &c);
    parser.DefineConst("pi", M_PI);
    parser.DefineConst("e", M_E);
    parser.SetExpr(expression);
    uses_depth = parser.GetUsedVar().count("d") > 0;
    uses_coast = parser.GetUsedVar().count("c") > 0;
    parser.Eval();
  }

  bool uses_lonlat() const {
    return parser.GetUsedVar().count("lon") > 0 || parser.GetUsedVar().count("lat") > 0;
  }
};

bool has_explicit_source(const SizingParams& p) {
  return p.constant_m || !p.expression.empty() || !p.raster_path.empty() ||
         !p.size_mesh_path.empty() ||
         (!p.bathymetry.empty() && (p.wavelength_period_s > 0 || p.slope_factor > 0));
}

bool expression_uses_depth(const std::string& expression) {
  if (expression.empty()) return false;
  try {
    SizingOracle::Expression e;
    e.parse(expression);
    return e.uses_depth;
  } catch (const mu::Parser::exception_type&) {
    return false;  // the oracle reports it
  }
}

bool sizing_reads_depths(const SizingParams& p) {
  return p.wavelength_period_s > 0 || p.slope_factor > 0 || p.time_step_s > 0 ||
         expression_uses_depth(p.expression);
}

SizingOracle::SizingOracle(const Domain& domain, const SizingParams& params) : params_(params) {
  auto usage = [](const std::string& what) { throw Error(ErrorClass::usage, "sizing", what); };
  if (params.gradation <= 0) usage("--gradation must be positive");
  if (params.cells_across <= 0) usage("--cells-across must be positive");
  if (params.hmin_m < 0 || params.hmax_m < 0) usage("--hmin and --hmax must not be negative");
  if (params.hmin_m > 0 && params.hmax_m > 0 && params.hmin_m > params.hmax_m)
    usage("--hmin must not exceed --hmax");
  if (params.constant_m && *params.constant_m <= 0) usage("--size must be positive");
  for (const LocalRefinement& r : params.refinements)
    if (!(r.size_m > 0) || !(r.radius_m >= 0)) usage("a local refinement needs a positive size");
  const CrsInfo crs{domain.crs_wkt, domain.crs_name, false, true, 1.0};
  const std::array<double, 4> extent = bounding_box(domain);  // rasters: only that part read

  if (auto scale = params.ground_sizes ? domain_map_scale(domain) : nullptr) {
    summary_.scale_min = scale->min();
    summary_.scale_max = scale->max();
    summary_.scale_applied = scale->max_error() > kGroundScaleTolerance;
    if (summary_.scale_applied) scale_ = std::move(scale);
  }

  const bool automatic = params.automatic || !has_explicit_source(params);
  hmax_ = params.hmax_m > 0 ? params.hmax_m : std::numeric_limits<double>::infinity();
  hmin_ = params.hmin_m;
  if (automatic) {
    // Without a bound the automatic field has no scale: default to the size that would
    // give about 2000 quads over the domain (its area on the ground), and hmin a tenth of
    // hmax.
    if (!std::isfinite(hmax_))
      hmax_ = std::sqrt((scale_ ? ground_area(domain, *scale_) : area(domain)) / 2000.0);
    if (hmin_ <= 0) hmin_ = hmax_ / 10.0;
  }
  summary_.hmin_m = hmin_;
  summary_.hmax_m = hmax_;
  summary_.gradation = params.gradation;
  gradation_ = params.gradation;
  gradient_step_m_ = std::max(1e-3, hmin_ > 0 ? 0.5 * hmin_ : 1.0);

  if (params.constant_m)
    summary_.sources.push_back(printf_string("constant %.6g m", *params.constant_m));
  if (!params.expression.empty()) {
    expression_ = std::make_unique<Expression>();
    try {
      expression_->parse(params.expression);
    } catch (const mu::Parser::exception_type& ex) {
      throw Error(ErrorClass::usage, "sizing",
                  "--size-expr '" + params.expression + "': " + ex.GetMsg() +
                      " (variables: x, y in metres, lon, lat in degrees, d the depth and c the "
                      "distance to the coast in metres; constants: pi, e)");
    }
    if (expression_->uses_lonlat())
      expression_->to_lonlat = std::make_unique<CrsTransform>(crs, geographic_base(crs));
    if (expression_->uses_coast) {
      // Samples a quarter of hmin apart, or (without hmin) 20,000 along the boundary; at
      // most 400,000.
      const double length = perimeter(domain);
      const double spacing =
          std::max(hmin_ > 0 ? 0.25 * hmin_ : length / 20000.0, length / 400000.0);
      coast_ = std::make_unique<CoastDistance>(domain, PolylineIndex(params.open_parts),
                                               params.open_tolerance_m, spacing);
      if (coast_->empty())
        usage("--size-expr '" + params.expression +
              "' uses c, the distance to the coast, and the domain's boundary is open all round");
    }
    if (expression_->uses_depth && params.bathymetry.empty())
      usage("--size-expr '" + params.expression +
            "' uses d, the depth: give --bathymetry or --elevation");
    summary_.sources.push_back("expression " + params.expression);
  }
  if (!params.raster_path.empty()) {
    raster_ = std::make_unique<RasterField>(params.raster_path, "--size-raster", crs, extent);
    // A raster that misses the domain (one in another CRS, or of another place) would
    // leave the sizes to the other sources without a word.
    constexpr int kProbes = 64;
    bool covers = false;
    for (int i = 0; i <= kProbes && !covers; ++i)
      for (int j = 0; j <= kProbes && !covers; ++j)
        covers = !std::isnan(raster_->sample({extent[0] + (extent[2] - extent[0]) * i / kProbes,
                                              extent[1] + (extent[3] - extent[1]) * j / kProbes}));
    if (!covers)
      throw Error(ErrorClass::input, "sizing",
                  "--size-raster '" + params.raster_path +
                      "' has no size anywhere over the domain (check its extent, its CRS and "
                      "its nodata value)");
    summary_.sources.push_back("raster " + params.raster_path);
  }
  if (!params.size_mesh_path.empty()) {
    mesh_sizes_ =
        std::make_unique<MeshNodeField>(params.size_mesh_path, "--size-mesh", crs,
                                        params.size_mesh_crs, MeshNodeField::Values::element_sizes);
    summary_.sources.push_back("mesh " + params.size_mesh_path + " (its elements' sides)");
    // Off the mesh, without --hmax: its largest elements' size on the ground (the
    // refinement's size cache takes that off the mesh, round the domain).
    if (!std::isfinite(hmax_)) {
      std::function<double(const Point2&)> ground;
      if (scale_) ground = [scale = scale_.get()](const Point2& p) { return scale->at(p); };
      hmax_ = summary_.hmax_m = mesh_sizes_->max_value(ground);
    }
  }
  if (!(params.courant > 0)) usage("--courant must be positive");
  if (params.time_step_s < 0) usage("--time-step must be positive");
  if (params.time_step_s > 0 && params.bathymetry.empty())
    usage("--time-step needs depths: --bathymetry or --elevation");
  summary_.time_step_s = params.time_step_s;
  summary_.courant = params.courant;
  if (!params.bathymetry.empty()) {
    if (!sizing_reads_depths(params))
      usage(
          "--bathymetry needs --wavelength-period with --cells-per-wavelength, --slope-factor, "
          "--time-step or a --size-expr in d");
    if (params.wavelength_period_s > 0 && params.cells_per_wavelength <= 0)
      usage("--wavelength-period needs --cells-per-wavelength");
    bathymetry_ = std::make_shared<const RasterStack>(params.bathymetry, crs, extent,
                                                      params.share_depths.get());
    if (has_explicit_source(params))  // the time step rule is a bound, not a source
      for (const DepthRaster& r : params.bathymetry)
        summary_.sources.push_back((r.elevation ? "elevation " : "bathymetry ") + r.path);
  }
  if (!params.refine_path.empty()) {
    SizeFeatures in =
        read_size_features(params.refine_path, params.refine_layer, params.refine_field, "--refine",
                           params.refine_width_field);
    CrsTransform to_mesh(in.crs, crs);
    double smallest = INFINITY, largest = 0, widest = 0;
    for (SizeFeature& f : in.features) {
      bool ok = true;
      for (auto* parts : {&f.rings, &f.lines})
        for (auto& part : *parts) ok = ok && to_mesh.transform(part) < 0;
      ok = ok && to_mesh.transform(f.points) < 0;
      if (!ok)
        throw Error(ErrorClass::crs, "--refine",
                    "'" + params.refine_path + "': feature " + std::to_string(f.fid) +
                        " has a point that cannot be transformed to the meshing CRS");
      smallest = std::min(smallest, f.size_m), largest = std::max(largest, f.size_m);
      widest = std::max(widest, f.width_m);
    }
    features_ = std::make_unique<FeatureSizes>(in.features, params.gradation);
    std::ostringstream s;
    s << "features " << params.refine_path << " (" << in.features.size() << ", " << smallest;
    if (largest > smallest) s << " to " << largest;
    s << " m";
    if (widest > 0) s << ", up to " << widest << " m wide";
    s << ")";
    summary_.sources.push_back(s.str());
  }
  if (automatic) {
    FeatureSizeParams fp;
    fp.cells_across = params.cells_across;
    fp.gradation = params.gradation;
    fp.max_size_m = hmax_ * (scale_ ? scale_->max() : 1.0);  // the CRS's metres
    // Channels narrower than cells_across * hmin cannot be resolved at hmin: the medial
    // axis below that scale is left out of the feature size. Without more, such a
    // channel takes the sizes around it, up to hmax, and quads wider than it fold across
    // it. So the domain's channels, inlets and spits from hmin/2 wide up get one element
    // across, down to hmin/2 (operator() below).
    fp.lambda_m = 0.5 * params.cells_across * hmin_;
    fp.narrow_lambda_m = params.narrow_sizes ? 0.25 * hmin_ : 0.0;
    fp.narrow_floor_m = 0.5 * hmin_;
    if (scale_) {
      fp.scale = scale_.get();
      fp.sample_spacing_m = 0.5 * fp.lambda_m * scale_->min();
    }
    automatic_ = std::make_unique<BoundaryFeatureSize>(domain, fp);
    summary_.num_boundary_samples = automatic_->samples().size();
    summary_.num_narrow_sites = automatic_->num_narrow_sites();
    summary_.narrow_min_width_m = 2 * fp.narrow_lambda_m;
    summary_.narrow_max_width_m = 2 * fp.lambda_m;
    summary_.narrow_floor_m = fp.narrow_floor_m;
    summary_.sources.insert(summary_.sources.begin(), "automatic (local feature size)");
  }
}

SizingOracle::~SizingOracle() = default;

bool SizingOracle::is_uniform() const {
  return params_.constant_m && !automatic_ && !expression_ && !raster_ && !mesh_sizes_ &&
         !bathymetry_ && !features_ && params_.refinements.empty();
}

std::shared_ptr<const MapScale> domain_map_scale(const Domain& domain) {
  if (domain.crs_wkt.empty()) return nullptr;  // a plane (tests' domains)
  const CrsInfo crs{domain.crs_wkt, domain.crs_name, false, true, 1.0};
  const std::array<double, 4> box = bounding_box(domain);
  // A coarse look first: the fine grid only where the scale may matter.
  auto scale = std::make_shared<const MapScale>(crs, box, 8);
  if (scale->max_error() > 0.5 * kGroundScaleTolerance)
    scale = std::make_shared<const MapScale>(crs, box, 64);
  return scale;
}

double ground_area(const Domain& domain, const MapScale& scale) {
  // The mean of 1 / k^2 over the grid's cells inside the domain, times its area in the
  // CRS; a domain of parts smaller than the cells (islands spread over an ocean) has none
  // inside: each part's area over the square of the scale at its box's centre.
  const double cells = estimate_num_quads(domain, [](const Point2&) { return 1.0; });
  if (cells > 0)
    return area(domain) *
           estimate_num_quads(domain, [&scale](const Point2& p) { return scale.at(p); }) / cells;
  double sum = 0.0;
  for (const Polygon& polygon : domain.polygons) {
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (const Point2& p : polygon.outer)
      x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x),
      y1 = std::max(y1, p.y);
    const double k = scale.at({0.5 * (x0 + x1), 0.5 * (y0 + y1)});
    sum += area(polygon) / (k * k);
  }
  return sum;
}

double SizingOracle::scale_at(const Point2& p) const {
  return scale_ ? scale_->at(p) : 1.0;
}

double SizingOracle::operator()(const Point2& p) const {
  // Sizes on the ground until the end; the automatic ones are the CRS's, divided by its
  // scale k.
  const double k = scale_at(p);
  double h = std::numeric_limits<double>::infinity();
  if (params_.constant_m) h = std::min(h, *params_.constant_m);
  if (automatic_) h = std::min(h, (*automatic_)(p) / k);
  const double raw = depth_at(p);
  // An expression in the depth holds where a raster gives one.
  if (expression_ && !(expression_->uses_depth && std::isnan(raw))) {
    expression_->x = p.x;
    expression_->y = p.y;
    expression_->d = raw;
    if (coast_) expression_->c = (*coast_)(p) / k;  // on the ground, at the scale here
    if (expression_->to_lonlat) {
      Point2 q = p;
      if (!expression_->to_lonlat->transform(q))
        throw Error(ErrorClass::crs, "sizing",
                    "--size-expr: " + format_point(p) + " has no longitude and latitude");
      expression_->lon = q.x;
      expression_->lat = q.y;
    }
    double v = 0.0;
    try {
      v = expression_->parser.Eval();
    } catch (const mu::Parser::exception_type& ex) {
      throw Error(ErrorClass::usage, "sizing", "--size-expr: " + ex.GetMsg());
    }
    if (!(v > 0) || !std::isfinite(v))
      throw Error(ErrorClass::usage, "sizing",
                  "--size-expr '" + expression_->text + "' gives " + std::to_string(v) + " at " +
                      format_point(p) +
                      (expression_->uses_depth ? " (d = " + std::to_string(raw) + ")" : "") +
                      (coast_ ? " (c = " + std::to_string(expression_->c) + ")" : "") +
                      "; sizes must be positive");
    h = std::min(h, v);
  }
  if (raster_) {
    const double v = raster_->sample(p);
    if (!std::isnan(v)) {
      if (!(v > 0))
        throw Error(ErrorClass::input, "sizing",
                    "--size-raster '" + raster_->path() + "' has size " + std::to_string(v) +
                        " at " + format_point(p) + "; sizes must be positive");
      h = std::min(h, v);
    }
  }
  if (mesh_sizes_) {
    const double v = mesh_sizes_->sample(p);  // its sides in the CRS
    if (v > 0) h = std::min(h, v / k);
  }
  if (bathymetry_) {
    if (!std::isnan(raw)) {
      const double d = std::max(params_.min_depth_m, raw);
      if (params_.wavelength_period_s > 0)
        h = std::min(h, params_.wavelength_period_s * std::sqrt(kGravity * d) /
                            params_.cells_per_wavelength);
      if (params_.slope_factor > 0) {
        const double s = gradient_step_m_;
        const double dx = bathymetry_->sample({p.x + s, p.y}) - bathymetry_->sample({p.x - s, p.y});
        const double dy = bathymetry_->sample({p.x, p.y + s}) - bathymetry_->sample({p.x, p.y - s});
        const double grad = std::hypot(dx, dy) / (2 * s) * k;  // per metre on the ground
        if (std::isfinite(grad) && grad > 0)
          h = std::min(h, 2 * M_PI * d / (params_.slope_factor * grad));
      }
    }
  }
  if (!std::isfinite(h)) h = hmax_;
  if (!std::isfinite(h))
    throw Error(ErrorClass::usage, "sizing",
                "no size at " + format_point(p) +
                    " (outside every raster or mesh of sizes); give --hmax or --size");
  h = std::clamp(h, hmin_, hmax_);
  if (automatic_) h = std::min(h, automatic_->narrow(p) / k);
  const double floor = raw_time_step_floor(raw);
  const double size = limit_locally(p, k * std::max(h, floor), k);
  // Only the time step's floor raises sizes over hmax: --time-step 1e308 would give
  // infinite sizes, and vertices nowhere.
  if (!std::isfinite(size))
    throw Error(ErrorClass::usage, "sizing",
                "--time-step " + std::to_string(params_.time_step_s) + " s with --courant " +
                    std::to_string(params_.courant) + " asks for cells " + std::to_string(floor) +
                    " m wide at " + format_point(p) + "; sizes must be finite");
  return size;
}

double SizingOracle::depth_at(const Point2& p) const {
  return bathymetry_ ? bathymetry_->sample(p) : std::numeric_limits<double>::quiet_NaN();
}

double SizingOracle::raw_time_step_floor(double depth) const {
  if (!(params_.time_step_s > 0) || std::isnan(depth)) return 0.0;
  const double d = std::max(params_.min_depth_m, depth);
  return kTimeStepMargin * params_.time_step_s * std::sqrt(kGravity * d) / params_.courant;
}

double SizingOracle::time_step_floor(const Point2& p) const {
  const double floor = raw_time_step_floor(depth_at(p));
  if (!(floor > 0)) return 0.0;
  const double k = scale_at(p);
  return limit_locally(p, k * floor, k);
}

double SizingOracle::limit_locally(const Point2& p, double h, double k) const {
  if (features_) h = k * features_->limit(p, h / k);
  for (const LocalRefinement& r : params_.refinements) {
    const double d = std::hypot(p.x - r.centre.x, p.y - r.centre.y);
    h = std::min(h, r.size_m + gradation_ * std::max(0.0, d - r.radius_m));
  }
  return h;
}

double SizingField::at(const BackgroundMesh& mesh, int f, const std::array<double, 3>& b) const {
  const auto& t = mesh.triangles[f];
  return b[0] * size_m[t[0]] + b[1] * size_m[t[1]] + b[2] * size_m[t[2]];
}

void limit_gradient(const BackgroundMesh& mesh, double gradation, std::vector<double>& h) {
  const std::size_t nv = mesh.points.size();
  // Vertex adjacency (CSR) from the triangles.
  std::vector<int> start(nv + 1, 0), adj;
  for (const auto& t : mesh.triangles)
    for (int v : t) start[v + 1] += 2;
  for (std::size_t i = 0; i < nv; ++i) start[i + 1] += start[i];
  adj.resize(start[nv]);
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (const auto& t : mesh.triangles)
    for (int i = 0; i < 3; ++i) {
      adj[fill[t[i]]++] = t[(i + 1) % 3];
      adj[fill[t[i]]++] = t[(i + 2) % 3];
    }
  // Dijkstra from the smallest sizes: a popped vertex is final; each relaxation enforces
  // h_v <= h_u + K |u - v|.
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (std::size_t v = 0; v < nv; ++v) queue.push({h[v], static_cast<int>(v)});
  while (!queue.empty()) {
    const auto [hu, u] = queue.top();
    queue.pop();
    if (hu > h[u]) continue;  // stale
    const Point2& pu = mesh.points[u];
    for (int k = start[u]; k < start[u + 1]; ++k) {
      const int v = adj[k];
      const Point2& pv = mesh.points[v];
      const double bound = hu + gradation * distance(pu, pv);
      if (bound < h[v]) {
        h[v] = bound;
        queue.push({bound, v});
      }
    }
  }
}

namespace {

// Interleaves the bits of two 21-bit integers (Morton order).
uint64_t morton(uint32_t x, uint32_t y) {
  uint64_t key = 0;
  for (int b = 0; b < 21; ++b)
    key |= (static_cast<uint64_t>((x >> b) & 1) << (2 * b)) |
           (static_cast<uint64_t>((y >> b) & 1) << (2 * b + 1));
  return key;
}

}  // namespace

std::vector<int> spatial_order(const std::vector<Point2>& points) {
  double xmin = 1e300, ymin = 1e300, xmax = -1e300, ymax = -1e300;
  for (const Point2& p : points)
    xmin = std::min(xmin, p.x), ymin = std::min(ymin, p.y), xmax = std::max(xmax, p.x),
    ymax = std::max(ymax, p.y);
  const double scale = ((1 << 21) - 1) / std::max({xmax - xmin, ymax - ymin, 1e-300});
  std::vector<std::pair<uint64_t, int>> keys(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    keys[i] = {morton(static_cast<uint32_t>((points[i].x - xmin) * scale),
                      static_cast<uint32_t>((points[i].y - ymin) * scale)),
               static_cast<int>(i)};
  std::sort(keys.begin(), keys.end());
  std::vector<int> order(points.size());
  for (std::size_t i = 0; i < keys.size(); ++i) order[i] = keys[i].second;
  return order;
}

double predicted_num_quads(const BackgroundMesh& mesh, const SizingField& field) {
  double n = 0.0;
  for (const auto& t : mesh.triangles) {
    const Point2 &a = mesh.points[t[0]], &b = mesh.points[t[1]], &c = mesh.points[t[2]];
    const double area = signed_area(a, b, c);
    const double h = (field.size_m[t[0]] + field.size_m[t[1]] + field.size_m[t[2]]) / 3.0;
    n += area / (h * h);
  }
  return n;
}

double estimate_num_quads(const Domain& domain, const std::function<double(const Point2&)>& size,
                          int cells_across) {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  std::vector<const Ring*> rings;
  for (const Polygon& poly : domain.polygons) {
    rings.push_back(&poly.outer);
    for (const Ring& hole : poly.holes) rings.push_back(&hole);
    for (const Point2& p : poly.outer)
      x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x),
      y1 = std::max(y1, p.y);
  }
  if (rings.empty() || !(x1 > x0 && y1 > y0)) return 0.0;
  const double cell = std::max(x1 - x0, y1 - y0) / cells_across;
  double n = 0.0;
  std::vector<double> crossings;
  for (double y = y0 + 0.5 * cell; y < y1; y += cell) {
    // Where the row's line crosses the rings: between the 1st and 2nd crossing, the 3rd
    // and 4th..., it is inside (holes and components included, by parity).
    crossings.clear();
    for (const Ring* ring : rings)
      for (std::size_t i = 0, j = ring->size() - 1; i < ring->size(); j = i++) {
        const Point2 &a = (*ring)[j], &b = (*ring)[i];
        if ((a.y > y) != (b.y > y))
          crossings.push_back(a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x));
      }
    std::sort(crossings.begin(), crossings.end());
    for (std::size_t k = 0; k + 1 < crossings.size(); k += 2)
      for (double x = x0 + (std::ceil((crossings[k] - x0) / cell - 0.5) + 0.5) * cell;
           x < crossings[k + 1]; x += cell) {
        const double h = size({x, y});
        if (h > 0) n += cell * cell / (h * h);
      }
  }
  return n;
}

SizingField sample_sizing_field(const BackgroundMesh& mesh, const SizingOracle& oracle,
                                double gradation) {
  SizingField field;
  field.size_m.resize(mesh.points.size());
  // In spatial order: consecutive queries are close, which keeps them cheap.
  const std::vector<int> order = spatial_order(mesh.points);
  for (int v : order) field.size_m[v] = oracle(mesh.points[v]);
  limit_gradient(mesh, gradation, field.size_m);
  if (oracle.has_time_step_floor())
    for (int v : order) {
      const double floor = oracle.time_step_floor(mesh.points[v]);
      if (floor > 0 && floor >= field.size_m[v]) {
        field.size_m[v] = floor;
        ++field.num_set_by_time_step;
        field.max_time_step_size_m = std::max(field.max_time_step_size_m, floor);
      }
    }
  return field;
}

}  // namespace isoquad
