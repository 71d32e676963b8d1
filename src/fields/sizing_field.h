// The sizing field h(x) in metres (paper, section 2): the target edge length of the
// final quads. Sources are combined by minimum, clamped to [hmin, hmax], sampled on the
// background mesh vertices and made K-Lipschitz there (gradation).
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry.h"
#include "gis/crs.h"
#include "gis/mesh_field.h"
#include "gis/raster_field.h"

namespace isoquad {

struct BackgroundMesh;
class BoundaryFeatureSize;
class CoastDistance;
class FeatureSizes;
class MapScale;

constexpr double kGravity = 9.81;  // m/s2 (the wavelength rule, the time steps of the outputs)

// The sizes the time step rule asks for are this much above DT sqrt(g d) / C: a quad's
// width (between the midpoints of opposite sides) falls under its size where it is
// smaller than the field or not square (measured in docs/measurements.md).
constexpr double kTimeStepMargin = 1.25;

// A place where the sizes must be smaller than the sources say: at most size_m within
// radius_m of centre, growing by the gradation beyond (a cone, already graded). Not
// clamped to hmin. The mesh job adds these where a tiling attempt failed (a fold where a
// channel is narrower than the quads, a quad no repair made convex).
struct LocalRefinement {
  Point2 centre;
  double radius_m = 0.0;
  double size_m = 0.0;
};

struct SizingParams {
  // Sources; `automatic` is the boundary's local feature size (feature_size.h).
  bool automatic = true;
  std::optional<double> constant_m;  // --size
  // --size-expr, in x and y (metres, meshing CRS), lon and lat (degrees, on the meshing
  // CRS's datum), d, the depth (metres, positive down, from `bathymetry`; where no raster
  // gives a depth, an expression in d does not apply) and c, the distance to the coast
  // (metres: to the domain's boundary but its open parts, CoastDistance).
  std::string expression;
  // The domain's open boundary (FrontEndResult::open_boundary_parts) and the tolerance
  // within which a boundary edge lies on it: c is measured to the rest of the boundary.
  std::vector<std::vector<Point2>> open_parts;
  double open_tolerance_m = 0.0;
  std::string raster_path;           // --size-raster: sizes in metres, any GDAL raster
  // --size-mesh: the sizes of a mesh's elements (MeshNodeField::Values::element_sizes: a
  // model's grid, to mesh again at its resolution), in its CRS, else size_mesh_crs
  // (--src-crs), else the meshing CRS.
  std::string size_mesh_path, size_mesh_crs;
  // Ocean-model sizing from depth rasters (--bathymetry, --elevation), in priority
  // order: the first with a depth at a point gives it.
  std::vector<DepthRaster> bathymetry;
  // Depths read before (an earlier attempt's), whose scattered samples the sizes share
  // (RasterStack's `share`) instead of triangulating them again.
  std::shared_ptr<const RasterStack> share_depths;
  double wavelength_period_s = 0.0;   // --wavelength-period T (0: off)
  double cells_per_wavelength = 0.0;  // --cells-per-wavelength N: h <= T sqrt(g d) / N
  double slope_factor = 0.0;          // --slope-factor R: h <= 2 pi d / (R |grad d|) (0: off)
  double min_depth_m = 1.0;           // depths below this (and dry land) count as this
                                      // (--min-depth when larger)
  // --time-step DT: sizes raised to at least kTimeStepMargin DT sqrt(g d) / C (C:
  // --courant), so that the quads allow an explicit model the time step DT at that
  // Courant number (most of them: a quad narrower than its size may not). Over every
  // source, hmin and hmax; under --refine features and local refinements. 0: off.
  double time_step_s = 0.0;
  double courant = 1.0;
  // --refine: vector features (any OGR format with a CRS) whose attribute refine_field
  // gives the size in metres inside their polygons and on their lines and points (and,
  // with refine_width_field, within half the width it gives), growing by the gradation
  // away from them; not clamped to hmin.
  std::string refine_path, refine_layer, refine_field = "size", refine_width_field;

  double cells_across = 2.0;  // --cells-across: elements across a narrow channel
  bool narrow_sizes = true;   // one element across narrower ones, down to hmin/2
  double hmin_m = 0.0;        // --hmin (0: none, or the automatic default)
  double hmax_m = 0.0;        // --hmax (0: none, or the automatic default)
  double gradation = 0.2;     // --gradation K: |h(x) - h(y)| <= K |x - y|
  std::vector<LocalRefinement> refinements;
  // --size-scale: true (ground), sizes in metres are lengths on the ground, multiplied by
  // the meshing CRS's scale (map_scale.h) where it differs from 1 by more than
  // kGroundScaleTolerance somewhere in the domain's box; false (crs), the CRS's metres.
  // The gradation and the local refinements are the CRS's either way.
  bool ground_sizes = true;
};

// Under this largest |k - 1|, the meshing CRS's metres are taken for the ground's (a
// domain within about 1,300 km of the automatic projection's centre): sizes change by
// less than the quads' own spread, and the meshes of regional domains stay as they were.
constexpr double kGroundScaleTolerance = 0.005;

// The meshing CRS's scale over the domain's box (its CRS: domain.crs_wkt), sampled
// coarsely first and finely where it may stray from 1 by more than the tolerance; null
// for a domain without a CRS (a plane).
std::shared_ptr<const MapScale> domain_map_scale(const Domain& domain);
// The domain's area on the ground: its area in the CRS times the mean of 1 / k^2 over it
// (on a grid of 128 x 128 cells over its box; parts smaller than the cells, each at the
// scale at its centre).
double ground_area(const Domain& domain, const MapScale& scale);

// A size source besides the automatic one: --size, --size-expr, --size-raster, --size-mesh, or
// --bathymetry with the wavelength or slope rule (the time step rule only bounds sizes).
// Without one, the sizing is automatic.
bool has_explicit_source(const SizingParams& params);
// Whether the sizes read depths (--bathymetry, --elevation): the wavelength, slope or time
// step rule, or an expression in d.
bool sizing_reads_depths(const SizingParams& params);
// Whether --size-expr uses d, the depth (false for one that does not parse: the oracle
// reports that).
bool expression_uses_depth(const std::string& expression);

// The resolved parameters and what the summary reports.
struct SizingSummary {
  double hmin_m = 0.0;
  double hmax_m = 0.0;
  double gradation = 1.0;
  std::vector<std::string> sources;  // e.g. "automatic (local feature size)"
  std::size_t num_boundary_samples = 0;
  std::size_t num_narrow_sites = 0;  // medial points of features too narrow for hmin
  double narrow_min_width_m = 0.0;   // the widths those features have (about)
  double narrow_max_width_m = 0.0;
  double narrow_floor_m = 0.0;  // their smallest size
  double time_step_s = 0.0;     // --time-step (0: off) and --courant
  double courant = 1.0;
  // The meshing CRS's scale over the domain's box (1 and 1 with --size-scale crs), and
  // whether the sizes were multiplied by it (SizingParams::ground_sizes).
  double scale_min = 1.0, scale_max = 1.0;
  bool scale_applied = false;
};

// h(x) before gradation: the minimum of the sources, clamped to [hmin, hmax], then of the
// narrow features' sizes (automatic sizing; down to hmin/2), raised to the time step
// rule's floor, then the minimum with the --refine features' and the local refinements.
// Not thread-safe. Throws Error(input) for a bad source (unreadable raster, expression
// that does not parse) and Error(meshing) for a non-positive size.
class SizingOracle {
 public:
  SizingOracle(const Domain& domain, const SizingParams& params);
  ~SizingOracle();
  SizingOracle(const SizingOracle&) = delete;
  SizingOracle& operator=(const SizingOracle&) = delete;

  double operator()(const Point2& x) const;
  // The size the time step rule asks for at x (0: off, or no depth there), limited by the
  // --refine features and the local refinements as operator() is.
  double time_step_floor(const Point2& x) const;
  bool has_time_step_floor() const { return params_.time_step_s > 0; }
  const SizingSummary& summary() const { return summary_; }
  // The same size everywhere: --size alone (clamped to hmin and hmax), no other source
  // and no local refinement.
  bool is_uniform() const;
  // The depths the sizes read (--bathymetry, --elevation), null when they read none.
  std::shared_ptr<const RasterStack> depths() const { return bathymetry_; }
  // The scale the ground's sizes were multiplied by, null when none was.
  std::shared_ptr<const MapScale> scale() const { return scale_; }

 private:
  friend bool expression_uses_depth(const std::string& expression);
  struct Expression;
  double hmin_ = 0.0, hmax_ = 1e300;
  double gradation_ = 1.0;
  SizingParams params_;
  SizingSummary summary_;
  std::unique_ptr<BoundaryFeatureSize> automatic_;
  std::unique_ptr<Expression> expression_;
  std::unique_ptr<RasterField> raster_;
  std::unique_ptr<MeshNodeField> mesh_sizes_;
  std::shared_ptr<const RasterStack> bathymetry_;
  std::unique_ptr<FeatureSizes> features_;
  std::unique_ptr<CoastDistance> coast_;  // an expression in c
  std::shared_ptr<const MapScale> scale_;
  double scale_at(const Point2& x) const;
  double gradient_step_m_ = 1.0;
  double depth_at(const Point2& x) const;                 // NaN: none
  double raw_time_step_floor(double depth) const;         // 0 for NaN
  // The --refine features (ground sizes) and the local refinements (the CRS's), on h in
  // the CRS's metres at x, whose scale is k.
  double limit_locally(const Point2& x, double h, double k) const;
};

// Sizes at the background mesh vertices, made K-Lipschitz along every background edge.
struct SizingField {
  std::vector<double> size_m;  // #V
  // Vertices whose size the time step rule sets (--time-step), and the largest it sets.
  std::size_t num_set_by_time_step = 0;
  double max_time_step_size_m = 0.0;
  // Barycentric interpolation in triangle f.
  double at(const BackgroundMesh& mesh, int f, const std::array<double, 3>& bary) const;
};

// The number of quads of size h that cover the mesh: the integral of 1 / h^2 over the
// domain (one quad of side h(x) per h(x)^2 of area), by the midpoint rule per triangle.
double predicted_num_quads(const BackgroundMesh& mesh, const SizingField& field);

// The same before any mesh: the integral of 1 / size^2 over the domain by the midpoint
// rule on a grid of cells_across x cells_across cells over its bounding box (the cells
// whose centre is inside). Coarse where sizes change within a cell; an order of
// magnitude for a guard, not a count (see FieldsOptions::max_quads).
double estimate_num_quads(const Domain& domain, const std::function<double(const Point2&)>& size,
                          int cells_across = 128);

// Samples the oracle at every vertex and limits the gradient: afterwards
// |h_u - h_v| <= K |u - v| holds on every background edge (Dijkstra-like sweep from
// the smallest sizes). The time step rule's sizes are then raised again to its floor,
// where the gradation took them under it (the gradient there is the floor's own).
SizingField sample_sizing_field(const BackgroundMesh& mesh, const SizingOracle& oracle,
                                double gradation);

// Point indices sorted along a Morton (Z-order) curve.
std::vector<int> spatial_order(const std::vector<Point2>& points);

// Limits the gradient of per-vertex values in place (see sample_sizing_field).
void limit_gradient(const BackgroundMesh& mesh, double gradation, std::vector<double>& size_m);

}  // namespace isoquad
