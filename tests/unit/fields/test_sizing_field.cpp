#include "fields/sizing_field.h"

#include <gtest/gtest.h>

#include <gdal_priv.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <iomanip>
#include <limits>
#include <set>
#include <string>

#include "core/error.h"
#include "fields/feature_size.h"
#include "fields/size_cache.h"
#include "gis/crs.h"
#include "gis/gdal_env.h"
#include "mesh/background_mesh.h"
#include "support/test_support.h"
#include "support/write_raster.h"

using namespace isoquad;
using namespace isoquad::test;

namespace {

Domain rectangle(double w, double h) {
  Domain d;
  d.polygons.push_back({{{0, 0}, {w, 0}, {w, h}, {0, h}}, {}});
  d.crs_wkt = parse_crs("EPSG:3857", "test").wkt;
  d.crs_name = "test";
  return d;
}

// A GeoTIFF in EPSG:3857 of nx x ny square pixels of `pixel` metres from (x0, y1) down
// and right, value(x, y) at the pixel centres.
std::string write_tif(const std::string& path, double x0, double y1, double pixel, int nx, int ny,
                      const std::function<double(double, double)>& value) {
  return write_geotiff(path, x0, y1, pixel, nx, ny, 3857, value);
}

BackgroundMesh mesh_for(const Domain& d, const SizingOracle& oracle, double factor = 0.5) {
  BackgroundMeshParams p;
  p.max_edge_m = [&](const Point2& x) { return factor * oracle(x); };
  return build_background_mesh(d, p);
}

void expect_lipschitz(const BackgroundMesh& mesh, const SizingField& f, double k) {
  std::size_t checked = 0;
  for (const auto& t : mesh.triangles)
    for (int i = 0; i < 3; ++i) {
      const int a = t[i], b = t[(i + 1) % 3];
      const double len = std::hypot(mesh.points[a].x - mesh.points[b].x,
                                    mesh.points[a].y - mesh.points[b].y);
      ASSERT_LE(std::abs(f.size_m[a] - f.size_m[b]), k * len * (1 + 1e-9) + 1e-9);
      ++checked;
    }
  EXPECT_GT(checked, 0u);
}

// Sizes from --size-expr alone.
SizingParams expression_sizes(const std::string& expression) {
  SizingParams p;
  p.automatic = false;
  p.expression = expression;
  return p;
}

Error error_of(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "no error";
  return Error(ErrorClass::internal, "", "");
}

}  // namespace

// A constant 50 m size on a 1000 x 500 m rectangle: reproduced at every vertex, and
// the predicted quad count is the area over h^2.
TEST(SizingField, ConstantSizeIsReproducedAtVertices) {
  const Domain d = rectangle(1000, 500);
  SizingParams p;
  p.automatic = false;
  p.constant_m = 50.0;
  SizingOracle oracle(d, p);
  const BackgroundMesh mesh = mesh_for(d, oracle);
  const SizingField f = sample_sizing_field(mesh, oracle, p.gradation);
  for (double h : f.size_m) ASSERT_DOUBLE_EQ(h, 50.0);
  EXPECT_NEAR(predicted_num_quads(mesh, f), 1000.0 * 500.0 / (50.0 * 50.0), 1e-6);
}

// Only --size alone is uniform (the background mesh then reads it without the cache):
// any other source or a local refinement makes sizes vary.
TEST(SizingField, OnlyAConstantSizeAloneIsUniform) {
  const Domain d = rectangle(1000, 500);
  SizingParams p;
  p.automatic = false;
  p.constant_m = 50.0;
  p.hmin_m = 60.0;  // clamped: still the same everywhere
  EXPECT_TRUE(SizingOracle(d, p).is_uniform());
  SizingParams refined = p;
  refined.refinements.push_back({{500, 250}, 10.0, 20.0});
  EXPECT_FALSE(SizingOracle(d, refined).is_uniform());
  SizingParams expression = p;
  expression.expression = "50";
  EXPECT_FALSE(SizingOracle(d, expression).is_uniform());
  SizingParams automatic = p;
  automatic.automatic = true;
  EXPECT_FALSE(SizingOracle(d, automatic).is_uniform());
}

// The paper's Figure 12 field on the unit square; its slope (0.19) is below K = 1, so
// gradation leaves it unchanged.
TEST(SizingField, ExpressionIsReproducedAtVertices) {
  const Domain d = rectangle(1, 1);
  const SizingParams p = expression_sizes("0.01*(2+sin(6*x*pi-pi/2))");
  SizingOracle oracle(d, p);
  const BackgroundMesh mesh = mesh_for(d, oracle);
  const SizingField f = sample_sizing_field(mesh, oracle, p.gradation);
  for (std::size_t v = 0; v < mesh.points.size(); ++v)
    ASSERT_NEAR(f.size_m[v], 0.01 * (2 + std::sin(6 * mesh.points[v].x * M_PI - M_PI / 2)), 1e-12);
  // Triangles follow the field: small where h is small.
  expect_lipschitz(mesh, f, 1.0);
}

TEST(SizingField, GradationMakesEveryEdgeLipschitz) {
  const Domain d = rectangle(1000, 1000);
  SizingParams p;
  p.automatic = false;
  p.expression = "x < 500 ? 20 : 100";  // a jump
  p.gradation = 0.3;
  SizingOracle oracle(d, p);
  const BackgroundMesh mesh = mesh_for(d, oracle);
  const SizingField f = sample_sizing_field(mesh, oracle, p.gradation);
  expect_lipschitz(mesh, f, 0.3);
  // Far from the jump the field keeps its value; near it, it is graded down.
  double far_max = 0;
  for (std::size_t v = 0; v < mesh.points.size(); ++v)
    if (mesh.points[v].x > 900) far_max = std::max(far_max, f.size_m[v]);
  EXPECT_GT(far_max, 99.0);
}

// A local refinement (what a failed tiling attempt adds): at most its size within its
// radius, growing by the gradation beyond, below hmin too; elsewhere the sources as
// before; the field stays K-Lipschitz and predicts more quads.
TEST(SizingField, LocalRefinementIsAGradedConeBelowHmin) {
  const Domain d = rectangle(2000, 2000);
  SizingParams p;
  p.automatic = false;
  p.constant_m = 100.0;
  p.hmin_m = 80.0;
  p.gradation = 0.25;
  SizingOracle plain(d, p);
  p.refinements.push_back({{500, 500}, 100.0, 40.0});
  SizingOracle refined(d, p);
  EXPECT_DOUBLE_EQ(refined({500, 500}), 40.0);
  EXPECT_DOUBLE_EQ(refined({580, 500}), 40.0);                // inside the radius
  EXPECT_NEAR(refined({500, 300}), 40.0 + 0.25 * 100.0, 1e-9);  // 200 m away: the cone
  EXPECT_DOUBLE_EQ(refined({500, 900}), 100.0);               // beyond the cone
  EXPECT_DOUBLE_EQ(refined({1500, 1500}), plain({1500, 1500}));
  const BackgroundMesh mesh = mesh_for(d, refined);
  const SizingField f = sample_sizing_field(mesh, refined, p.gradation);
  expect_lipschitz(mesh, f, 0.25);
  const BackgroundMesh plain_mesh = mesh_for(d, plain);
  const SizingField g = sample_sizing_field(plain_mesh, plain, p.gradation);
  EXPECT_GT(predicted_num_quads(mesh, f), predicted_num_quads(plain_mesh, g) + 10);
  // Triangles near the centre follow the refined size.
  double longest_near = 0;
  for (const auto& t : mesh.triangles)
    for (int i = 0; i < 3; ++i) {
      const Point2 &a = mesh.points[t[i]], &b = mesh.points[t[(i + 1) % 3]];
      if (std::hypot(a.x - 500, a.y - 500) < 50 && std::hypot(b.x - 500, b.y - 500) < 50)
        longest_near = std::max(longest_near, std::hypot(a.x - b.x, a.y - b.y));
    }
  EXPECT_GT(longest_near, 0.0);
  EXPECT_LE(longest_near, 0.5 * 40.0 * 1.01);
  p.refinements.back().size_m = 0.0;
  EXPECT_EQ(error_of([&] { SizingOracle o(d, p); }).error_class(), ErrorClass::usage);
}

TEST(SizingField, AutomaticSizingPutsCellsAcrossAThinRectangle) {
  for (double cells : {2.0, 4.0})
    for (double gradation : {1.0, 0.2}) {
    const double width = 1000.0;
    const Domain d = rectangle(20000, width);
    SizingParams p;
    p.cells_across = cells;
    p.gradation = gradation;
    p.hmax_m = 5000;
    p.hmin_m = 20;
    SizingOracle oracle(d, p);
    // Elements across the middle cross-section: the integral of dy / h(y).
    double across = 0.0;
    const int n = 2000;
    for (int i = 0; i < n; ++i) across += (width / n) / oracle({10000, (i + 0.5) * width / n});
    EXPECT_GE(across, cells) << cells << " " << gradation;
    EXPECT_LE(across, 2.5 * cells) << cells << " " << gradation;
  }
}

TEST(SizingField, AutomaticSizingIsLipschitzAndBounded) {
  // An L-shaped domain with a narrow slot.
  Domain d = rectangle(10000, 10000);
  d.polygons[0].outer = {{0, 0}, {10000, 0}, {10000, 4000}, {3000, 4000}, {3000, 4300}, {10000, 4300},
                         {10000, 10000}, {0, 10000}};
  SizingParams p;
  p.hmax_m = 2000;
  p.hmin_m = 50;
  p.gradation = 1.0;  // steep, so that hmax is reached inside the square
  SizingOracle oracle(d, p);
  EXPECT_GT(oracle.summary().num_boundary_samples, 100u);
  const BackgroundMesh mesh = mesh_for(d, oracle);
  const SizingField f = sample_sizing_field(mesh, oracle, p.gradation);
  expect_lipschitz(mesh, f, 1.0);
  for (double h : f.size_m) {
    ASSERT_GE(h, 50.0);
    ASSERT_LE(h, 2000.0);
  }
  // In the slot (300 m wide) the size is at most 300 / 2.
  EXPECT_LE(oracle({6000, 4150}), 150.0 * 1.01);
  // Far from every feature it reaches hmax.
  EXPECT_DOUBLE_EQ(oracle({5000, 8000}), 2000.0);
}

// lon and lat in --size-expr: degrees on the meshing CRS's datum (the rectangle is in
// Web Mercator from the origin: lon = x / R in degrees, lat near 0).
TEST(SizingField, AnExpressionInLongitudeAndLatitude) {
  const Domain d = rectangle(2000, 1000);
  SizingOracle oracle(d, expression_sizes("1000 + 1e5 * lon + 1e5 * lat"));
  constexpr double kDegrees = 180 / M_PI / 6378137.0;  // per metre at the equator
  for (const Point2 q : {Point2{500, 0}, Point2{1500, 800}})
    EXPECT_NEAR(oracle(q), 1000 + 1e5 * kDegrees * (q.x + q.y), 1e-3) << q.x << " " << q.y;
}

// c in --size-expr: the distance to the coast, the boundary but its open parts (here
// the rectangle's west side, the sea's), as OceanMesh2D's 'dis' grows sizes offshore.
TEST(SizingField, AnExpressionInTheDistanceToTheCoast) {
  const Domain d = rectangle(10000, 4000);
  SizingParams p = expression_sizes("100 + 0.5 * c");
  p.hmin_m = 100;  // the coast sampled every 25 m
  p.open_parts = {{{0, 4000}, {0, 0}}};
  p.open_tolerance_m = 1;
  SizingOracle oracle(d, p);
  // Nearest the south side, the north side, the east side; the west side is open sea.
  for (const auto& [q, c] : {std::pair{Point2{300, 1000}, 1000.0},
                             {Point2{5000, 3500}, 500.0},
                             {Point2{9000, 2000}, 1000.0},
                             {Point2{50, 2000}, 2000.0},
                             {Point2{2500, 0}, 0.0}})
    EXPECT_NEAR(oracle(q), 100 + 0.5 * c, 0.5 * 12.5 + 1e-9) << q.x << " " << q.y;
  // Without open parts the west side is coast too.
  SizingOracle closed(d, expression_sizes("100 + 0.5 * c"));
  EXPECT_NEAR(closed({50, 2000}), 100 + 0.5 * 50, 1.0);
  // Open all round: no coast to measure from.
  p.open_parts = {{{0, 0}, {10000, 0}, {10000, 4000}, {0, 4000}, {0, 0}}};
  const Error e = error_of([&] { SizingOracle o(d, p); });
  EXPECT_EQ(e.error_class(), ErrorClass::usage);
  EXPECT_NE(std::string(e.what()).find("open all round"), std::string::npos) << e.what();
}

TEST(SizingField, RasterIsSampledBilinearly) {
  TempDir dir;
  // 100 m pixels from (0, 1000) down to (2000, 0).
  const std::string path = write_tif(dir.file("size.tif"), 0, 1000, 100, 20, 10,
                                     [](double x, double y) { return 10 + x / 100 + y / 50; });
  const Domain d = rectangle(2000, 1000);
  SizingParams p;
  p.automatic = false;
  p.raster_path = path;
  SizingOracle oracle(d, p);
  for (const Point2 q : {Point2{123, 456}, Point2{1500, 200}, Point2{999, 999 - 400}})
    EXPECT_NEAR(oracle(q), 10 + q.x / 100 + q.y / 50, 1e-4);
}

TEST(SizingField, BadSourcesAreRejected) {
  const Domain d = rectangle(100, 100);
  for (const char* expr : {"2*", "foo(x)", "x +* y", ""}) {
    SizingParams p;
    p.automatic = false;
    p.expression = expr;
    if (!*expr) p.constant_m = -1.0;
    const Error e = error_of([&] { SizingOracle o(d, p); });
    EXPECT_EQ(e.error_class(), ErrorClass::usage) << expr << ": " << e.what();
  }
  SizingParams p;
  p.automatic = false;
  p.expression = "x - 50";
  SizingOracle o(d, p);
  const Error e = error_of([&] { o({10, 10}); });
  EXPECT_NE(std::string(e.what()).find("must be positive"), std::string::npos) << e.what();
  p.expression.clear();
  p.raster_path = "/no/such/raster.tif";
  const Error r = error_of([&] { SizingOracle o2(d, p); });
  EXPECT_EQ(r.error_class(), ErrorClass::input);
  EXPECT_NE(std::string(r.what()).find("/no/such/raster.tif"), std::string::npos);
}

TEST(FeatureSize, ConeExtensionIsTheMinimumOverTheSites) {
  // A channel 1000 m wide: both banks and the centre line are sites. For every K the
  // field is no larger than the best boundary site (up to the grid's K times a cell) and
  // symmetric across the channel; with K < 1 a wrong search once returned the far bank.
  const Domain d = rectangle(20000, 1000);
  for (double k : {1.0, 0.5, 0.2}) {
    FeatureSizeParams fp;
    fp.lambda_m = 20;
    fp.gradation = k;
    fp.max_size_m = 5000;
    const BoundaryFeatureSize fs(d, fp);
    for (double x : {3000.0, 10000.0, 15500.0})
      for (double y : {10.0, 130.0, 260.0, 500.0}) {
        double bound = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < fs.samples().size(); ++i)
          bound = std::min(bound, fs.sample_size_m()[i] +
                                      k * std::hypot(fs.samples()[i].x - x, fs.samples()[i].y - y));
        const double h = fs({x, y});
        EXPECT_LE(h, bound + k * 2 * fp.lambda_m) << k << " " << x << " " << y;
        EXPECT_NEAR(h, fs({x, 1000 - y}), 0.01 * h) << k << " " << x << " " << y;
      }
  }
}

TEST(SizeCache, RefinesOnlyOverTheRegionsItIsGiven) {
  // Two islands 100 km apart with sizes of 1 km everywhere: without regions the cache
  // refines the whole square over the sea between them; with their boxes only around
  // the islands.
  const std::array<double, 4> box{0.0, 0.0, 1.0e5, 1.0e4};
  const auto size = [](const Point2&) { return 1000.0; };
  const SizeCache everywhere(box, size, 0.5, 18);
  const SizeCache islands(box, size, 0.5, 18, {{0.0, 0.0, 1.0e4, 1.0e4}, {9.0e4, 0.0, 1.0e5, 1.0e4}});
  EXPECT_LT(islands.num_leaves() * 10, everywhere.num_leaves());
  for (const Point2 p : {Point2{5000.0, 5000.0}, Point2{95000.0, 2500.0}}) {
    EXPECT_NEAR(islands(p), 1000.0, 1e-9);
    EXPECT_NEAR(everywhere(p), 1000.0, 1e-9);
  }
}

TEST(SizeCache, EvaluatesEachCornerOnceAndInterpolatesTheSizes) {
  // Sizes growing away from a point at K = 0.2: the cells split near it. The build asks
  // the function once per distinct cell corner, and the cache is within the bilinear
  // interpolation's error of the function everywhere (cells at most half the size, so
  // a few percent where the distance's cone is sharpest).
  const auto exact = [](const Point2& p) {
    return 100.0 + 0.2 * std::hypot(p.x - 2000.0, p.y - 3000.0);
  };
  std::set<std::pair<double, double>> asked;
  std::size_t calls = 0;
  const SizeCache cache(
      {0.0, 0.0, 1.0e4, 1.0e4},
      [&](const Point2& p) {
        ++calls;
        asked.insert({p.x, p.y});
        return exact(p);
      },
      0.5, 18);
  EXPECT_EQ(calls, asked.size());
  EXPECT_EQ(cache.num_evaluations(), asked.size());
  EXPECT_GT(cache.num_leaves(), 1000u);
  double worst = 0.0;
  for (int i = 0; i <= 200; ++i)
    for (int j = 0; j <= 200; ++j) {
      const Point2 p{50.0 * i + 0.37, 50.0 * j + 0.61};
      worst = std::max(worst, std::abs(cache(p) - exact(p)) / exact(p));
    }
  EXPECT_LT(worst, 0.05);
  EXPECT_GT(worst, 0.0);  // interpolated, not the function itself
}

TEST(FeatureSize, NearlyFlatTrianglesOfTheSamplesAreSkipped) {
  // Samples spaced along long slanted edges are collinear up to rounding: some of their
  // Delaunay triangles are not collinear for the exact predicate, yet the circumcentre's
  // denominator is zero in doubles. They give no medial point (CGAL's checks, on in
  // Release, would stop on the division), and every size stays finite.
  Domain d;
  d.polygons.push_back({{{0, 0}, {98765.4321, 12345.6789}, {3210.987, 54321.123}}, {}});
  orient_polygon(d.polygons[0]);
  FeatureSizeParams fp;
  fp.lambda_m = 7.3;
  fp.max_size_m = 5000;
  const BoundaryFeatureSize fs(d, fp);
  for (double s : fs.sample_size_m()) EXPECT_TRUE(std::isfinite(s) && s > 0);
  EXPECT_TRUE(std::isfinite(fs({30000, 15000})));
}

// A channel narrower than cells_across * hmin gets one element across, down to hmin/2:
// without that it had hmax here (0.2 elements across), the lambda-medial axis ignoring
// it. A corner keeps its sizes, and a channel wide enough for hmin has no such sizes.
TEST(SizingField, ChannelsTooNarrowForHminGetOneElementAcross) {
  auto across = [](const Domain& d, double width, double* smallest) {
    SizingParams p;
    p.hmax_m = 5000;
    p.hmin_m = 800;
    SizingOracle oracle(d, p);
    double n = 0.0;
    *smallest = 1e300;
    for (int i = 0; i < 2000; ++i) {
      const double h = oracle({10000, (i + 0.5) * width / 2000});
      n += (width / 2000) / h;
      *smallest = std::min(*smallest, h);
    }
    return std::make_pair(n, oracle.summary().num_narrow_sites);
  };
  // The banks are sampled hmin/2 apart: a circle through two samples of a bank and one
  // of the other is wider than the channel, by a sixth when it is hmin/2 wide.
  double smallest = 0;
  for (double width : {500.0, 1000.0, 1500.0}) {  // hmin/2 to 2 hmin
    const auto [n, sites] = across(rectangle(20000, width), width, &smallest);
    EXPECT_GE(n, 0.7) << width;
    EXPECT_LE(n, 1.5) << width;
    EXPECT_GE(smallest, 400.0) << width;
    EXPECT_GT(sites, 0u) << width;
  }
  const auto [n4000, sites4000] = across(rectangle(20000, 4000), 4000, &smallest);
  EXPECT_GE(smallest, 800.0);  // resolved at hmin and above
  EXPECT_EQ(sites4000, 0u);
  // A square's corners are no narrow features: the sizes in them stay hmin or above.
  SizingParams p;
  p.hmax_m = 5000;
  p.hmin_m = 800;
  SizingOracle square(rectangle(20000, 20000), p);
  EXPECT_EQ(square.summary().num_narrow_sites, 0u);
  EXPECT_GE(square({100, 100}), 800.0);
}

// The estimate before any mesh: the integral of 1 / h^2 over the domain on a grid, with
// the holes and every component counted (a square with a square hole, and a second
// square beside it), constant and graded sizes. Within 4%: the cells (3000 / 128 m)
// whose centre is inside count whole, a third of a cell more along each side here.
TEST(SizingField, TheQuadsEstimatedBeforeTheMeshAreTheAreaOverTheSizeSquared) {
  Domain d = rectangle(1000, 1000);
  d.polygons[0].holes.push_back({{250, 250}, {250, 750}, {750, 750}, {750, 250}});
  d.polygons.push_back({{{2000, 0}, {3000, 0}, {3000, 1000}, {2000, 1000}}, {}});
  const double area = 2 * 1000.0 * 1000.0 - 500.0 * 500.0;
  EXPECT_NEAR(estimate_num_quads(d, [](const Point2&) { return 50.0; }), area / 2500.0,
              0.04 * area / 2500.0);
  // h = 10 + x / 100 over the first square without its hole, the second square:
  // integral of 1 / h^2 over x in [a, b] is 100 (1 / h(a) - 1 / h(b)), times the height.
  auto graded = [](const Point2& p) { return 10.0 + p.x / 100.0; };
  auto band = [](double a, double b) {
    return 100.0 * (1.0 / (10 + a / 100) - 1.0 / (10 + b / 100));
  };
  const double exact = 1000 * band(0, 1000) - 500 * band(250, 750) + 1000 * band(2000, 3000);
  EXPECT_NEAR(estimate_num_quads(d, graded), exact, 0.04 * exact);
  EXPECT_EQ(estimate_num_quads(Domain{}, graded), 0.0);
}

// The ocean-model rules from depth rasters: h <= T sqrt(g d) / N (depths under the
// minimum count as it), and h <= 2 pi d / (R |grad d|); several rasters in priority order.
TEST(SizingField, WavelengthAndSlopeRulesFollowTheDepths) {
  TempDir dir;
  const Domain d = rectangle(2000, 1000);
  // A survey over the west half, 100 m deep; a grid over everything, 10 m, and dry land
  // (-5 m) where y > 800.
  const std::string survey = write_tif(dir.file("survey.tif"), -100, 1100, 50, 24, 24,
                                       [](double, double) { return 100.0; });
  const std::string grid = write_tif(dir.file("grid.tif"), -100, 1100, 50, 44, 24,
                                     [](double, double y) { return y > 800 ? -5.0 : 10.0; });
  SizingParams p;
  p.automatic = false;
  p.bathymetry = {{survey}, {grid}};
  p.wavelength_period_s = 60;
  p.cells_per_wavelength = 50;
  SizingOracle wave(d, p);
  auto rule = [](double depth) { return 60 * std::sqrt(9.81 * depth) / 50; };
  EXPECT_NEAR(wave({500, 500}), rule(100), 1e-6);
  EXPECT_NEAR(wave({1500, 500}), rule(10), 1e-6);
  EXPECT_NEAR(wave({1500, 950}), rule(1), 1e-6);  // dry: the minimum depth, 1 m
  p.min_depth_m = 4;
  EXPECT_NEAR(SizingOracle(d, p)({1500, 950}), rule(4), 1e-6);
  // The other order: the grid everywhere.
  p.bathymetry = {{grid}, {survey}};
  p.min_depth_m = 1;
  EXPECT_NEAR(SizingOracle(d, p)({500, 500}), rule(10), 1e-6);

  // A slope: d = 20 + x / 100, |grad d| = 0.01.
  const std::string slope = write_tif(dir.file("slope.tif"), -100, 1100, 50, 44, 24,
                                      [](double x, double) { return 20 + x / 100; });
  SizingParams q;
  q.automatic = false;
  q.bathymetry = {{slope}};
  q.slope_factor = 10;
  SizingOracle steep(d, q);
  for (double x : {300.0, 1000.0, 1700.0})
    EXPECT_NEAR(steep({x, 500}), 2 * M_PI * (20 + x / 100) / (10 * 0.01), 1e-3) << x;
  // Neither rule: an error naming what is missing.
  q.slope_factor = 0;
  const Error e = error_of([&] { SizingOracle o(d, q); });
  EXPECT_EQ(e.error_class(), ErrorClass::usage);
  EXPECT_NE(std::string(e.what()).find("--wavelength-period"), std::string::npos) << e.what();
}

// --size-expr in d, the depth: sizes by depth bands (OceanMesh2D's limits by depth),
// holding where a raster gives a depth; other places keep their other sources.
TEST(SizingField, AnExpressionInTheDepthHoldsWhereARasterGivesOne) {
  TempDir dir;
  const Domain d = rectangle(2000, 1000);
  // Depths 10 + x / 100 over the west half (x < 1000) only.
  const std::string west = write_tif(dir.file("west.tif"), 0, 1000, 50, 20, 20,
                                     [](double x, double) { return 10 + x / 100; });
  SizingParams p;
  p.automatic = false;
  p.bathymetry = {{west}};
  p.expression = "d < 12 ? 50 : 5 * d";
  p.hmax_m = 300;
  EXPECT_TRUE(expression_uses_depth(p.expression));
  EXPECT_TRUE(sizing_reads_depths(p));
  SizingOracle oracle(d, p);
  EXPECT_NEAR(oracle({100, 500}), 50, 1e-9);        // 11 m deep
  EXPECT_NEAR(oracle({500, 500}), 5 * 15.0, 1e-6);  // 15 m deep
  EXPECT_NEAR(oracle({1500, 500}), 300, 1e-9);      // no depth: hmax
  // With x too, and another source beside it: the minimum where both hold.
  p.expression = "d + x / 10";
  p.constant_m = 100;
  SizingOracle both(d, p);
  EXPECT_NEAR(both({200, 500}), 12 + 20, 1e-6);
  EXPECT_NEAR(both({1500, 500}), 100, 1e-9);

  // Errors: d without depths; depths that no rule or expression reads; a size under 0,
  // with the depth that gave it.
  SizingParams no_depths;
  no_depths.automatic = false;
  no_depths.expression = "2 * d";
  Error e = error_of([&] { SizingOracle o(d, no_depths); });
  EXPECT_EQ(e.error_class(), ErrorClass::usage);
  EXPECT_NE(std::string(e.what()).find("--bathymetry"), std::string::npos) << e.what();
  SizingParams unread = p;
  unread.expression = "x + 10";
  EXPECT_FALSE(expression_uses_depth(unread.expression));
  EXPECT_FALSE(sizing_reads_depths(unread));
  e = error_of([&] { SizingOracle o(d, unread); });
  EXPECT_NE(std::string(e.what()).find("--size-expr in d"), std::string::npos) << e.what();
  SizingParams negative = p;
  negative.expression = "18 - d";
  SizingOracle o(d, negative);
  e = error_of([&] { o({900, 500}); });
  EXPECT_NE(std::string(e.what()).find("(d = 19"), std::string::npos) << e.what();
  EXPECT_FALSE(expression_uses_depth("d *"));  // does not parse: the oracle says so
}

TEST(SizingField, TimeStepRuleRaisesSizesToItsFloorOverEverySourceButLocalOnes) {
  TempDir dir;
  // 20 km x 10 km, depths from 5 m (x = 0) to 2005 m (x = 20 km); automatic sizes of
  // 100 to 400 m. At 4 s and a Courant number of 0.5 the floor passes 400 m 1.6 km from
  // the shallow edge.
  const Domain d = rectangle(20000, 10000);
  const std::string depths = write_tif(dir.file("depth.tif"), -500, 10500, 250, 84, 44,
                                       [](double x, double) { return 5 + std::max(0.0, x) / 10; });
  SizingParams p;
  p.hmin_m = 100;
  p.hmax_m = 400;
  p.bathymetry = {{depths}};
  p.time_step_s = 4;
  p.courant = 0.5;
  const SizingOracle oracle(d, p);
  auto floor_at = [](double x, double courant) {
    return kTimeStepMargin * 4 * std::sqrt(kGravity * (5 + x / 10)) / courant;
  };
  // The rule is a bound, not a source: the sizing stays automatic, and the summary says so.
  ASSERT_EQ(oracle.summary().sources.size(), 1u);
  EXPECT_EQ(oracle.summary().sources[0], "automatic (local feature size)");
  EXPECT_DOUBLE_EQ(oracle.summary().time_step_s, 4.0);
  // Deep water: the floor, above hmax; shallow water: the automatic sizes.
  EXPECT_NEAR(oracle({15000, 5000}), floor_at(15000, 0.5), 1e-3);
  EXPECT_GT(oracle({15000, 5000}), 1000.0);
  EXPECT_NEAR(oracle.time_step_floor({15000, 5000}), floor_at(15000, 0.5), 1e-3);
  EXPECT_LT(floor_at(1000, 0.5), 400.0);
  EXPECT_DOUBLE_EQ(oracle({1000, 5000}), 400.0);
  // Courant 1 halves it.
  SizingParams q = p;
  q.courant = 1.0;
  EXPECT_NEAR(SizingOracle(d, q).time_step_floor({15000, 5000}), floor_at(15000, 1.0), 1e-3);

  // On the background mesh: no vertex under the floor after gradation, and the floor
  // sets the sizes in the deep half.
  const BackgroundMesh mesh = mesh_for(d, oracle);
  const SizingField f = sample_sizing_field(mesh, oracle, p.gradation);
  std::size_t set = 0;
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    const double floor = floor_at(mesh.points[v].x, 0.5);
    ASSERT_GE(f.size_m[v], floor * (1 - 1e-4)) << v;
    set += f.size_m[v] <= floor * (1 + 1e-4);
  }
  EXPECT_GT(f.num_set_by_time_step, mesh.points.size() / 2);
  EXPECT_NEAR(static_cast<double>(set), static_cast<double>(f.num_set_by_time_step),
              0.01 * mesh.points.size());
  EXPECT_NEAR(f.max_time_step_size_m, floor_at(20000, 0.5), 0.02 * floor_at(20000, 0.5));

  // A local refinement (a failed tiling's cone) stays under it.
  SizingParams r = p;
  r.refinements.push_back({{15000, 5000}, 0.0, 100.0});
  const SizingOracle refined(d, r);
  EXPECT_NEAR(refined({15000, 5000}), 100.0, 1e-9);
  EXPECT_NEAR(refined.time_step_floor({15000, 5000}), 100.0, 1e-9);

  // Usage errors: no depths, a non-positive Courant number.
  SizingParams none = p;
  none.bathymetry.clear();
  const Error e = error_of([&] { SizingOracle o(d, none); });
  EXPECT_EQ(e.error_class(), ErrorClass::usage);
  EXPECT_NE(std::string(e.what()).find("--time-step needs depths"), std::string::npos) << e.what();
  SizingParams zero = p;
  zero.courant = 0;
  EXPECT_EQ(error_of([&] { SizingOracle o(d, zero); }).error_class(), ErrorClass::usage);
}

// Sizes in metres are the ground's: on World Mercator from the equator to 70 N, --size
// 10 km is 10 km times the scale in the CRS (twice that at 60 N), and the automatic
// hmax's area is the ground's. With ground_sizes off (--size-scale crs), the CRS's metres.
// A domain whose scale stays within kGroundScaleTolerance of 1 keeps its sizes exactly.
TEST(SizingField, SizesAreTheGroundsTimesTheCrsScale) {
  const CrsInfo wgs = parse_crs("EPSG:4326", "src"), mercator = parse_crs("EPSG:3395", "dst");
  Ring outer{{0, 0}, {10, 0}, {10, 70}, {0, 70}};
  Ring dense;  // lon/lat edges densified, so that the planar ring follows them
  for (std::size_t i = 0; i < outer.size(); ++i)
    for (int k = 0; k < 20; ++k) {
      const Point2 &a = outer[i], &b = outer[(i + 1) % outer.size()];
      dense.push_back({a.x + (b.x - a.x) * k / 20, a.y + (b.y - a.y) * k / 20});
    }
  ASSERT_EQ(CrsTransform(wgs, mercator).transform(dense), -1);
  Domain d;
  d.polygons.push_back({dense, {}});
  d.crs_wkt = mercator.wkt;
  d.crs_name = mercator.name;
  auto at = [&](double lon, double lat) {
    Point2 p{lon, lat};
    EXPECT_TRUE(CrsTransform(wgs, mercator).transform(p));
    return p;
  };
  const double k60 = std::sqrt(1 - 0.00669438 * 0.75) / 0.5;

  SizingParams p;
  p.automatic = false;
  p.constant_m = 10000.0;
  const SizingOracle ground(d, p);
  EXPECT_TRUE(ground.summary().scale_applied);
  EXPECT_NEAR(ground.summary().scale_min, 1.0, 1e-6);
  EXPECT_NEAR(ground(at(5, 0.5)), 10000.0, 10.0);
  EXPECT_NEAR(ground(at(5, 60)) / (10000.0 * k60), 1.0, 1e-3);
  p.ground_sizes = false;
  const SizingOracle crs(d, p);
  EXPECT_FALSE(crs.summary().scale_applied);
  EXPECT_EQ(crs(at(5, 60)), 10000.0);

  // The automatic hmax: about 2000 quads of it on the ground, far fewer in the CRS.
  SizingParams automatic;
  const SizingOracle a(d, automatic);
  const double ground_area = 6.66e12;  // 10 x 70 degrees: R^2 (pi / 18) sin 70, about
  EXPECT_NEAR(a.summary().hmax_m / std::sqrt(ground_area / 2000.0), 1.0, 0.03);
  EXPECT_NEAR(a(at(5, 60)) / a(at(5, 1)), k60, 0.3) << "the same sizes on the ground";

  // 100 km of UTM round its central meridian: the scale is 0.9996 to 0.9997, not applied.
  Domain utm;
  utm.polygons.push_back(
      {{{450000, 4950000}, {550000, 4950000}, {550000, 5050000}, {450000, 5050000}}, {}});
  utm.crs_wkt = parse_crs("EPSG:32631", "dst").wkt;
  utm.crs_name = "utm";
  p.ground_sizes = true;
  const SizingOracle u(utm, p);
  EXPECT_FALSE(u.summary().scale_applied);
  EXPECT_LT(u.summary().scale_min, 0.9997);
  EXPECT_EQ(u({500000, 5000000}), 10000.0);

  // A mesh of sizes (--size-mesh) of 10 x 10 degree quads over the Mercator domain: its
  // sides are longest in the CRS at 60 to 70 N (a node's mean side about 1,800 km there),
  // on the ground at the equator (about 1,110 km). Without --hmax, its largest size on the
  // ground bounds the sizes off it.
  TempDir dir;
  const std::string mesh_path = dir.file("sizes.gr3");
  {
    std::ofstream gr3(mesh_path);
    gr3 << "sizes\n7 16\n";
    for (int j = 0; j <= 7; ++j)
      for (int i = 0; i <= 1; ++i) {
        const Point2 q = at(10.0 * i, 10.0 * j);
        gr3 << 2 * j + i + 1 << " " << std::setprecision(12) << q.x << " " << q.y << " 0\n";
      }
    for (int j = 0; j < 7; ++j)
      gr3 << j + 1 << " 4 " << 2 * j + 1 << " " << 2 * j + 2 << " " << 2 * j + 4 << " " << 2 * j + 3
          << "\n";
  }
  SizingParams m;
  m.automatic = false;
  m.size_mesh_path = mesh_path;
  m.size_mesh_crs = "EPSG:3395";
  const SizingOracle sized(d, m);
  EXPECT_GT(sized.summary().hmax_m, 1.0e6);
  EXPECT_LT(sized.summary().hmax_m, 1.25e6);
}
