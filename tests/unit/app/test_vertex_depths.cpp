// The vertices' depths (app/vertex_depths.h): rasters in priority order, the vertices
// without a depth filled from the nearest with one, the minimum depth.
#include "app/vertex_depths.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <optional>

#include "core/error.h"
#include "gis/crs.h"
#include "gis/gdal_env.h"
#include "gis/map_scale.h"
#include "support/test_support.h"
#include "support/write_raster.h"

using namespace isoquad;
using namespace isoquad::test;

namespace {

// A GeoTIFF without a CRS (so in the query CRS) of nx x ny pixels of 50 m from (x0, y1)
// down and right, with value(x, y) at the pixel centres (NaN: nodata).
std::string write_raster(const TempDir& dir, const std::string& name, double x0, double y1, int nx,
                         int ny, const std::function<double(double, double)>& value) {
  return write_geotiff(dir.file(name), x0, y1, 50, nx, ny, 0, value);
}

// (nx + 1) x (ny + 1) vertices 100 m apart from (x0, 0), quads counter-clockwise.
void add_grid(QuadMesh& m, double x0, int nx, int ny) {
  const int first = static_cast<int>(m.points.size());
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) m.points.push_back({x0 + 100.0 * i, 100.0 * j});
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = first + j * (nx + 1) + i;
      m.quads.push_back({a, a + 1, a + nx + 2, a + nx + 1});
    }
}

QuadMesh grid() {
  QuadMesh m;
  add_grid(m, 0, 10, 5);  // x 0..1000, y 0..500
  return m;
}

const CrsInfo kNoCrs{};

// West: x up to 500 m, depth 10 + y / 100 (linear in y: bilinear sampling is exact).
std::string west(const TempDir& dir) {
  return write_raster(dir, "west.tif", -50, 550, 11, 12,
                      [](double, double y) { return 10 + y / 100; });
}
// Everywhere on the grid, depth 100 + y / 100.
std::string whole(const TempDir& dir) {
  return write_raster(dir, "whole.tif", -50, 550, 22, 12,
                      [](double, double y) { return 100 + y / 100; });
}

}  // namespace

TEST(VertexDepths, TheFirstRasterWithADepthGivesIt) {
  TempDir dir;
  const QuadMesh m = grid();
  const RasterStack survey_first({{west(dir)}, {whole(dir)}}, kNoCrs);
  const VertexDepths d = vertex_depths(survey_first, m, std::nullopt);
  for (std::size_t v = 0; v < m.points.size(); ++v) {
    const Point2 p = m.points[v];
    EXPECT_NEAR(d.depth[v], (p.x <= 500 ? 10 : 100) + p.y / 100, 1e-4) << p.x << " " << p.y;
  }
  EXPECT_EQ(d.num_filled, 0u);
  EXPECT_EQ(d.num_raised, 0u);
  EXPECT_NEAR(d.min_m, 10, 1e-4);
  EXPECT_NEAR(d.max_m, 105, 1e-4);
  const RasterStack whole_first({{whole(dir)}, {west(dir)}}, kNoCrs);
  for (double z : vertex_depths(whole_first, m, std::nullopt).depth) EXPECT_GE(z, 100 - 1e-4);
}

// Elevations (positive up, as GEBCO's) are read as depths, in the same priority list;
// the dry vertices are counted.
// --depth-average: a grid ten times finer than the quads, waves of 30 m over a slope,
// read as each vertex's mean over a square as wide as its quads (100 m): within the
// waves' leftover of a tenth, where the bilinear samples are off by a quarter of them
// or more.
TEST(VertexDepths, AveragedDepthsAreMeansOverEachVertexsSquare) {
  TempDir dir;
  const QuadMesh m = grid();
  auto truth = [](double y) { return 50 + y / 100; };
  const std::string fine = write_geotiff(
      dir.file("fine.tif"), -100, 600, 10, 120, 70, 0,
      [&](double x, double y) { return truth(y) + 10 * std::cos(2 * M_PI * x / 30); });
  const RasterStack stack({{fine}}, kNoCrs);
  const VertexDepths sampled = vertex_depths(stack, m, std::nullopt);
  const VertexDepths averaged = vertex_depths(stack, m, std::nullopt, true);
  EXPECT_FALSE(sampled.averaged);
  EXPECT_TRUE(averaged.averaged);
  double worst_sampled = 0.0, worst_averaged = 0.0;
  for (std::size_t v = 0; v < m.points.size(); ++v) {
    const double t = truth(m.points[v].y);
    worst_sampled = std::max(worst_sampled, std::abs(sampled.depth[v] - t));
    worst_averaged = std::max(worst_averaged, std::abs(averaged.depth[v] - t));
  }
  EXPECT_GE(worst_sampled, 2.5 - 1e-4);
  EXPECT_LE(worst_averaged, 1.0 + 1e-4);
  // A raster of cells wider than the squares gives its bilinear values.
  const RasterStack coarse({{whole(dir)}}, kNoCrs);
  QuadMesh small;
  small.points = {{100, 100}, {130, 100}, {130, 130}, {100, 130}};
  small.quads = {{0, 1, 2, 3}};
  const VertexDepths c = vertex_depths(coarse, small, std::nullopt, true);
  for (std::size_t v = 0; v < 4; ++v) EXPECT_NEAR(c.depth[v], coarse.sample(small.points[v]), 1e-9);
}

TEST(VertexDepths, ElevationRastersAreReadAsDepths) {
  TempDir dir;
  const QuadMesh m = grid();
  // West: elevations -(10 + y / 100), so depths 10 + y / 100; then the whole grid's
  // depths 100 + y / 100.
  const std::string west_elevation = write_raster(dir, "west_z.tif", -50, 550, 11, 12,
                                                  [](double, double y) { return -(10 + y / 100); });
  const RasterStack stack({{west_elevation, true}, {whole(dir), false}}, kNoCrs);
  EXPECT_EQ(stack.paths_text(),
            "--elevation '" + west_elevation + "', --bathymetry '" + whole(dir) + "'");
  const VertexDepths d = vertex_depths(stack, m, std::nullopt);
  for (std::size_t v = 0; v < m.points.size(); ++v) {
    const Point2 p = m.points[v];
    EXPECT_NEAR(d.depth[v], (p.x <= 500 ? 10 : 100) + p.y / 100, 1e-4) << p.x << " " << p.y;
  }
  EXPECT_EQ(d.num_dry, 0u);
  // The same raster given as depths: the west is dry (6 x 6 vertices at x <= 500).
  const VertexDepths wrong =
      vertex_depths(RasterStack({{west_elevation, false}, {whole(dir)}}, kNoCrs), m, 5.0);
  EXPECT_EQ(wrong.num_dry, 36u);
  EXPECT_EQ(wrong.num_raised, 36u);
}

TEST(VertexDepths, NodataFallsThroughToTheNextRaster) {
  TempDir dir;
  const QuadMesh m = grid();
  // A hole of nodata over x in [300, 700]: sampling next to it gives none either.
  const std::string holed =
      write_raster(dir, "holed.tif", -50, 550, 22, 12,
                   [](double x, double y) { return x > 300 && x < 700 ? NAN : 100 + y / 100; });
  const std::string flat =
      write_raster(dir, "flat.tif", -50, 550, 22, 12, [](double, double) { return 7.0; });
  const VertexDepths d = vertex_depths(RasterStack({{holed}, {flat}}, kNoCrs), m, std::nullopt);
  int from_flat = 0;
  for (std::size_t v = 0; v < m.points.size(); ++v) {
    const Point2 p = m.points[v];
    if (p.x >= 300 && p.x <= 700) {
      EXPECT_NEAR(d.depth[v], 7.0, 1e-6);
    }
    if (p.x <= 200 || p.x >= 800) {
      EXPECT_NEAR(d.depth[v], 100 + p.y / 100, 1e-4);
    }
    from_flat += d.depth[v] == 7.0;
  }
  EXPECT_GE(from_flat, 5 * 6);
  EXPECT_EQ(d.num_filled, 0u);
}

TEST(VertexDepths, VerticesWithoutADepthTakeTheNearestAlongTheEdges) {
  TempDir dir;
  const QuadMesh m = grid();
  const VertexDepths d = vertex_depths(RasterStack({{west(dir)}}, kNoCrs), m, std::nullopt);
  // East of 500 m each vertex takes the depth of the vertex at 500 m on its row.
  for (std::size_t v = 0; v < m.points.size(); ++v)
    EXPECT_NEAR(d.depth[v], 10 + m.points[v].y / 100, 1e-4) << v;
  EXPECT_EQ(d.num_filled, 5u * 6u);
  EXPECT_NEAR(d.max_fill_distance_m, 500, 1e-9);
}

TEST(VertexDepths, APartOfTheMeshOffTheRastersTakesTheNearestDepth) {
  TempDir dir;
  QuadMesh m = grid();
  add_grid(m, 3000, 2, 2);  // x 3000..3200, y 0..200: no raster reaches it
  const VertexDepths d = vertex_depths(RasterStack({{whole(dir)}}, kNoCrs), m, std::nullopt);
  // From the vertex with a depth nearest (3000, 0): (1000, 0), depth 100.
  for (std::size_t v = 66; v < m.points.size(); ++v) EXPECT_NEAR(d.depth[v], 100, 1e-4) << v;
  EXPECT_EQ(d.num_filled, 9u);
  EXPECT_NEAR(d.max_fill_distance_m, 2000 + 200 + 200, 1e-9);
}

TEST(VertexDepths, ShallowDepthsAreRaisedToTheMinimum) {
  TempDir dir;
  const QuadMesh m = grid();
  const VertexDepths d = vertex_depths(RasterStack({{whole(dir)}}, kNoCrs), m, 102.0);
  std::size_t raised = 0;
  for (std::size_t v = 0; v < m.points.size(); ++v) {
    const double asked = 100 + m.points[v].y / 100;
    EXPECT_NEAR(d.depth[v], std::max(asked, 102.0), 1e-4);
    raised += asked < 102.0 - 1e-6;
  }
  EXPECT_EQ(raised, 2u * 11u);  // the rows at y = 0 and 100
  EXPECT_EQ(d.num_raised, raised);
  EXPECT_NEAR(d.min_m, 102, 1e-12);
}

TEST(VertexDepths, ARasterThatMissesTheMeshIsAnError) {
  TempDir dir;
  const std::string far =
      write_raster(dir, "far.tif", 50000, 50550, 10, 10, [](double, double) { return 5.0; });
  try {
    vertex_depths(RasterStack({{far}}, kNoCrs), grid(), std::nullopt);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), ErrorClass::input);
    EXPECT_NE(std::string(e.what()).find("far.tif"), std::string::npos) << e.what();
  }
}

TEST(VertexDepths, TimeStepsAreTheWidthOverTheCelerity) {
  QuadMesh m = grid();  // 100 m squares; the last column narrowed to 50 m
  for (Point2& p : m.points)
    if (p.x > 999) p.x = 950;
  std::vector<double> depth(m.points.size());
  for (std::size_t v = 0; v < m.points.size(); ++v) depth[v] = 10 + m.points[v].y / 10;  // 10..60
  // The quads of the first row: dry (every vertex at 0 or shallower).
  for (std::size_t v = 0; v < m.points.size(); ++v)
    if (m.points[v].y < 150) depth[v] = m.points[v].y < 50 ? -2.0 : 0.0;
  const TimeSteps t = courant_time_steps(m, depth);
  ASSERT_EQ(t.per_quad_s.size(), m.quads.size());
  for (std::size_t q = 0; q < m.quads.size(); ++q) {
    const auto& c = m.quads[q];
    double deepest = depth[c[0]];
    for (int v : c) deepest = std::max(deepest, depth[v]);
    const double width = m.points[c[1]].x - m.points[c[0]].x;  // <= 100 m tall
    if (deepest <= 0) {
      EXPECT_TRUE(std::isnan(t.per_quad_s[q])) << q;
    } else {
      EXPECT_NEAR(t.per_quad_s[q], std::min(width, 100.0) / std::sqrt(9.81 * deepest), 1e-9) << q;
    }
  }
  // The narrow column at the deepest row sets it: 50 m in 60 m of water.
  EXPECT_NEAR(t.min_s, 50 / std::sqrt(9.81 * 60), 1e-9);
  EXPECT_NEAR(t.width_m, 50, 1e-9);
  EXPECT_NEAR(t.depth_m, 60, 1e-9);
  EXPECT_EQ(m.quads[t.limiting_quad][0], 4 * 11 + 9);  // the top row's last quad
  EXPECT_GT(t.median_s, t.min_s);

  // At a Courant number of 0.7 every time step is 0.7 times as long; against a target,
  // the wet quads under it are counted.
  const double target = t.median_s;
  const TimeSteps c = courant_time_steps(m, depth, 0.7, target * 0.7);
  std::size_t wet = 0, under = 0;
  for (std::size_t q = 0; q < m.quads.size(); ++q) {
    if (std::isnan(t.per_quad_s[q])) {
      EXPECT_TRUE(std::isnan(c.per_quad_s[q]));
      continue;
    }
    EXPECT_NEAR(c.per_quad_s[q], 0.7 * t.per_quad_s[q], 1e-12) << q;
    ++wet;
    under += t.per_quad_s[q] < target;
  }
  EXPECT_DOUBLE_EQ(c.courant, 0.7);
  EXPECT_EQ(c.num_wet, wet);
  EXPECT_EQ(t.num_wet, wet);
  EXPECT_EQ(c.num_under_target, under);
  EXPECT_GT(under, 0u);
  EXPECT_LT(under, wet);
  EXPECT_EQ(t.num_under_target, 0u);  // no target
  EXPECT_NEAR(c.min_s, 0.7 * t.min_s, 1e-12);
}

// Where the sizes are the ground's, so are the widths: the same quads on World Mercator
// at 60 N, whose scale is about 2, allow half the time step they would in its metres.
TEST(VertexDepths, TimeStepsTakeTheWidthsOnTheGround) {
  QuadMesh m = grid();  // 100 m squares from the origin
  const CrsInfo mercator = parse_crs("EPSG:3395", "test");
  Point2 at60{0, 60};
  ASSERT_TRUE(CrsTransform(parse_crs("EPSG:4326", "test"), mercator).transform(at60));
  for (Point2& p : m.points) p.y += at60.y;
  const std::vector<double> depth(m.points.size(), 40.0);
  const MapScale scale(mercator, {-1000, at60.y - 1000, 2000, at60.y + 2000}, 8);
  const double k = scale.at({500, at60.y + 500});
  ASSERT_NEAR(k, 2.0, 0.01);
  const TimeSteps crs = courant_time_steps(m, depth);
  const TimeSteps ground = courant_time_steps(m, depth, 1.0, 0.0, &scale);
  for (std::size_t q = 0; q < m.quads.size(); ++q)
    EXPECT_NEAR(ground.per_quad_s[q] * scale.at(quad_centroid(m, static_cast<int>(q))),
                crs.per_quad_s[q], 1e-9)
        << q;
  EXPECT_NEAR(ground.width_m * k, crs.width_m, 0.01 * crs.width_m);
}
