// MeshNodeField: a mesh's node values read as a depth source. A linear function on the
// nodes is sampled exactly inside (quads cut in two, a triangle beside them), at the
// nearest boundary point just outside, NaN far off; a .ll is transformed from lon/lat;
// RasterStack takes a mesh among its rasters; a mesh without values is refused; the mean
// of the nodes in a square (--depth-average).
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "gis/crs.h"
#include "gis/mesh_field.h"
#include "support/test_support.h"

using namespace isoquad;
using namespace isoquad::test;

namespace {

double linear(double x, double y) {
  return 3 * x + 2 * y + 1;
}

// Two quads (0..200 x 0..100, times `scale`, from x0, y0) and a triangle to their right,
// node values f(x, y).
std::string grid_gr3(double (*f)(double, double), double x0 = 0, double y0 = 0,
                     double scale = 1.0) {
  const double xs[] = {0, 100, 200, 0, 100, 200, 300};
  const double ys[] = {0, 0, 0, 100, 100, 100, 50};
  std::string text = "grid\n3 7\n";
  for (int i = 0; i < 7; ++i) {
    const double x = x0 + xs[i] * scale, y = y0 + ys[i] * scale;
    text += std::to_string(i + 1) + " " + std::to_string(x) + " " + std::to_string(y) + " " +
            std::to_string(f(x, y)) + "\n";
  }
  return text + "1 4 1 2 5 4\n2 4 2 3 6 5\n3 3 3 7 6\n";
}

double shifted(double lon, double lat) {
  return 1000 * (lon - 3) + 10 * (lat - 45);
}

}  // namespace

TEST(MeshNodeField, LinearInsideNearestBoundaryJustOutsideNanFarOff) {
  TempDir dir;
  write_file(dir.file("hgrid.gr3"), grid_gr3(linear));
  const CrsInfo utm = parse_crs("EPSG:32631", "test");
  const MeshNodeField f(dir.file("hgrid.gr3"), "--bathymetry", utm);
  for (const Point2 p : {Point2{10, 10}, Point2{150, 70}, Point2{199.5, 1}, Point2{250, 50},
                         Point2{100, 100}, Point2{0, 0}})
    EXPECT_NEAR(f.sample(p), linear(p.x, p.y), 1e-9) << p.x << " " << p.y;
  // 5 m below the bottom side: the value on it.
  EXPECT_NEAR(f.sample({50, -5}), linear(50, 0), 1e-9);
  EXPECT_TRUE(std::isnan(f.sample({50, -1000})));
  EXPECT_TRUE(std::isnan(f.sample({5000, 50})));
}

// With an extent, the elements far from it are not kept: a box round the left quad
// (0..100 x 0..100, widened by a quarter of 100 m) keeps the two quads (the second
// touches it) and drops the triangle beyond x = 200; the values inside are the same. A
// box far off keeps none: NaN.
TEST(MeshNodeField, OnlyTheElementsNearTheExtentAreKept) {
  TempDir dir;
  write_file(dir.file("hgrid.gr3"), grid_gr3(linear));
  const CrsInfo utm = parse_crs("EPSG:32631", "test");
  const MeshNodeField all(dir.file("hgrid.gr3"), "--bathymetry", utm);
  const MeshNodeField near(dir.file("hgrid.gr3"), "--bathymetry", utm, "",
                           MeshNodeField::Values::nodes, std::array<double, 4>{0, 0, 100, 100});
  for (const Point2 p : {Point2{10, 10}, Point2{150, 70}, Point2{100, 100}})
    EXPECT_EQ(near.sample(p), all.sample(p)) << p.x << " " << p.y;
  EXPECT_NEAR(all.sample({295, 50}), linear(295, 50), 1e-9);
  EXPECT_TRUE(std::isnan(near.sample({295, 50})));  // (more than a cell off the two quads)
  EXPECT_EQ(near.max_value(), linear(200, 100));    // the triangle's far node gone
  const MeshNodeField none(dir.file("hgrid.gr3"), "--bathymetry", utm, "",
                           MeshNodeField::Values::nodes,
                           std::array<double, 4>{10000, 10000, 10100, 10100});
  EXPECT_TRUE(std::isnan(none.sample({50, 50})));
  EXPECT_TRUE(std::isnan(none.mean_over({50, 50}, 100)));
}

TEST(MeshNodeField, LonLatNodesTransformedAndStackedWithRasters) {
  TempDir dir;
  // hgrid.ll: the same grid in degrees from 3 E 45 N (EPSG:4326 by its extension).
  write_file(dir.file("hgrid.ll"), grid_gr3(shifted, 3, 45, 1e-3));
  const CrsInfo utm = parse_crs("EPSG:32631", "test");
  const CrsInfo wgs84 = parse_crs("EPSG:4326", "test");
  const CrsTransform to_utm(wgs84, utm);
  Point2 node{3.1, 45.1};  // the fifth node
  ASSERT_TRUE(to_utm.transform(node));
  const MeshNodeField f(dir.file("hgrid.ll"), "--bathymetry", utm);
  EXPECT_NEAR(f.sample(node), shifted(3.1, 45.1), 1e-6);
  const RasterStack stack({DepthRaster{dir.file("hgrid.ll"), false}}, utm);
  EXPECT_NEAR(stack.sample(node), shifted(3.1, 45.1), 1e-6);
  const RasterStack elevations({DepthRaster{dir.file("hgrid.ll"), true}}, utm);
  EXPECT_NEAR(elevations.sample(node), -shifted(3.1, 45.1), 1e-6);
}

TEST(MeshNodeField, AMeshWithoutValuesIsRefused) {
  TempDir dir;
  write_file(dir.file("m.msh"),
             "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n"
             "$EndNodes\n$Elements\n1\n1 2 2 0 1 1 2 3\n$EndElements\n");
  try {
    check_raster(dir.file("m.msh"), "--bathymetry");
    FAIL() << "a .msh has no depths";
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), ErrorClass::input);
    EXPECT_NE(std::string(e.what()).find("the mesh's nodes have no depths or bed levels"),
              std::string::npos)
        << e.what();
  }
}

// --size-mesh: each node's mean side length, linear between nodes; the largest of them.
TEST(MeshNodeField, ElementSizesAreTheNodesMeanSides) {
  TempDir dir;
  write_file(dir.file("hgrid.gr3"), grid_gr3(linear));
  const CrsInfo utm = parse_crs("EPSG:32631", "test");
  const MeshNodeField f(dir.file("hgrid.gr3"), "--size-mesh", utm, "",
                        MeshNodeField::Values::element_sizes);
  EXPECT_NEAR(f.sample({0, 0}), 100.0, 1e-9);
  EXPECT_NEAR(f.sample({60, 40}), 100.0, 1e-9);  // inside the first quad, every node 100
  const double slant = std::hypot(100.0, 50.0);
  EXPECT_NEAR(f.sample({300, 50}), slant, 1e-9);                   // the triangle's tip
  EXPECT_NEAR(f.sample({200, 0}), (100 + 100 + slant) / 3, 1e-9);  // three sides
  EXPECT_NEAR(f.max_value(), slant, 1e-9);
}

// --depth-average on a finer grid: the mean of its nodes in the square, where it holds
// four or more; the value between them where it holds fewer.
TEST(MeshNodeField, MeanOverTheSquareOfAFinerGrid) {
  TempDir dir;
  // 21 x 21 nodes 10 m apart, 4 and 6 in a checkerboard (a grid of 5 m with noise).
  const int n = 21;
  std::string text =
      "fine\n" + std::to_string((n - 1) * (n - 1)) + " " + std::to_string(n * n) + "\n";
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      text += std::to_string(j * n + i + 1) + " " + std::to_string(10 * i) + " " +
              std::to_string(10 * j) + " " + ((i + j) % 2 ? "4" : "6") + "\n";
  int e = 0;
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i + 1;
      text += std::to_string(++e) + " 4 " + std::to_string(a) + " " + std::to_string(a + 1) + " " +
              std::to_string(a + n + 1) + " " + std::to_string(a + n) + "\n";
    }
  write_file(dir.file("fine.gr3"), text);
  const MeshNodeField f(dir.file("fine.gr3"), "--bathymetry", parse_crs("EPSG:32631", "test"));
  EXPECT_NEAR(f.sample({100, 100}), 6, 1e-12);
  EXPECT_NEAR(f.mean_over({100, 100}, 50), 5.0, 0.01);                   // 121 nodes, 61 of 6
  EXPECT_NEAR(f.mean_over({102, 100}, 6), f.sample({102, 100}), 1e-12);  // one node
  EXPECT_NEAR(f.mean_over({102, 100}, 0), f.sample({102, 100}), 1e-12);
  EXPECT_TRUE(std::isnan(f.mean_over({-500, 100}, 50)));
}
