#include "fields/cross_field.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "mesh/background_mesh.h"
#include "unit/mesh/test_domains.h"

using namespace isoquad;
using namespace isoquad::test;

namespace {

constexpr double kDeg = kPi / 180.0;

BackgroundMesh mesh_of(const Domain& d, double max_edge_m) {
  BackgroundMeshParams p;
  p.max_edge_m = [max_edge_m](const Point2&) { return max_edge_m; };
  return build_background_mesh(d, p);
}

double direction_rad(const BackgroundMesh& m, int a, int b) {
  return std::atan2(m.points[b].y - m.points[a].y, m.points[b].x - m.points[a].x);
}

// Largest deviation, degrees, of the cross at each chain vertex from the cross of its
// two chain edges (the middle of the two edge crosses, which is exact for a smooth
// boundary discretised by a polygon).
double max_boundary_deviation_deg(const BackgroundMesh& m, const CrossField& field) {
  double worst = 0.0;
  for (const BoundaryChain& chain : m.chains) {
    const std::size_t n = chain.vertices.size();
    for (std::size_t k = 0; k < n; ++k) {
      const int prev = chain.vertices[(k + n - 1) % n], v = chain.vertices[k],
                next = chain.vertices[(k + 1) % n];
      const double a = direction_rad(m, prev, v), b = direction_rad(m, v, next);
      const double expected = a + 0.5 * cross_rotation_rad(a, b);
      worst = std::max(worst, std::abs(cross_rotation_rad(expected, field.angle_rad[v])) / kDeg);
    }
  }
  return worst;
}

int total_index_quarters(const std::vector<Singularity>& s) {
  int total = 0;
  for (const Singularity& x : s) total += x.index_quarters;
  return total;
}

// Largest cross rotation, degrees, across an edge whose triangles are both farther than
// `clearance_m` from every singular triangle.
double max_edge_rotation_away_from_singularities_deg(const BackgroundMesh& m,
                                                     const CrossField& field,
                                                     const std::vector<Singularity>& s,
                                                     double clearance_m) {
  double worst = 0.0;
  for (int f = 0; f < static_cast<int>(m.triangles.size()); ++f) {
    const Point2 c = centroid(m, f);
    bool near = false;
    for (const Singularity& x : s) near = near || distance(c, x.position) < clearance_m;
    if (near) continue;
    const auto& t = m.triangles[f];
    for (int i = 0; i < 3; ++i)
      worst = std::max(worst, std::abs(cross_rotation_rad(field.angle_rad[t[i]],
                                                          field.angle_rad[t[(i + 1) % 3]])) /
                                  kDeg);
  }
  return worst;
}

}  // namespace

TEST(CrossField, RotationIsTheSmallestModuloAQuarterTurn) {
  EXPECT_NEAR(cross_rotation_rad(0.0, 89 * kDeg), -1 * kDeg, 1e-12);
  EXPECT_NEAR(cross_rotation_rad(89 * kDeg, 0.0), 1 * kDeg, 1e-12);
  EXPECT_NEAR(cross_rotation_rad(10 * kDeg, 200 * kDeg), 10 * kDeg, 1e-12);
  EXPECT_NEAR(cross_rotation_rad(0.0, -30 * kDeg), -30 * kDeg, 1e-12);
}

TEST(CrossField, SquareIsAxisAligned) {
  const BackgroundMesh m = mesh_of(square_domain(1000.0), 40.0);
  const CrossField field = boundary_aligned_cross_field(m);
  ASSERT_EQ(field.angle_rad.size(), m.points.size());
  double worst = 0.0;
  for (double a : field.angle_rad) {
    EXPECT_GE(a, 0.0);
    EXPECT_LT(a, kPi / 2);
    worst = std::max(worst, std::abs(cross_rotation_rad(0.0, a)) / kDeg);
  }
  EXPECT_LT(worst, 1.0);
  EXPECT_TRUE(cross_field_singularities(m, field).empty());
}

TEST(CrossField, RotatedSquareFollowsItsSides) {
  Domain d;
  const double c = std::cos(30 * kDeg), s = std::sin(30 * kDeg);
  const Domain square = square_domain(1000.0);
  Ring ring;
  for (const Point2& q : square.polygons[0].outer)
    ring.push_back({c * q.x - s * q.y, s * q.x + c * q.y});
  d.polygons.push_back({ring, {}});
  const BackgroundMesh m = mesh_of(d, 50.0);
  const CrossField field = boundary_aligned_cross_field(m);
  for (double a : field.angle_rad) EXPECT_NEAR(a, 30 * kDeg, 1 * kDeg);
}

TEST(CrossField, DiskIsTangentWithFourQuarterSingularities) {
  const BackgroundMesh m = mesh_of(disk_domain(1000.0, 128), 40.0);
  const CrossField field = boundary_aligned_cross_field(m);
  EXPECT_LT(max_boundary_deviation_deg(m, field), 1.0);
  const std::vector<Singularity> s = cross_field_singularities(m, field);
  // Poincare-Hopf: the indices sum to the Euler characteristic of the disk, 1.
  EXPECT_EQ(total_index_quarters(s), 4);
  EXPECT_EQ(s.size(), 4u);
  for (const Singularity& x : s) EXPECT_EQ(x.index_quarters, 1);
  const double worst = max_edge_rotation_away_from_singularities_deg(m, field, s, 400.0);
  EXPECT_LT(worst, 10.0);
}

TEST(CrossField, AnnulusIsTangentToBothRingsWithZeroTotalIndex) {
  const BackgroundMesh m = mesh_of(annulus_domain(1000.0, 300.0, 128), 40.0);
  const CrossField field = boundary_aligned_cross_field(m);
  EXPECT_LT(max_boundary_deviation_deg(m, field), 1.0);
  const std::vector<Singularity> s = cross_field_singularities(m, field);
  // Euler characteristic of the annulus: 0.
  EXPECT_EQ(total_index_quarters(s), 0);
  const double worst = max_edge_rotation_away_from_singularities_deg(m, field, s, 200.0);
  EXPECT_LT(worst, 10.0);
}

TEST(CrossField, ConstantFieldIsReproduced) {
  const BackgroundMesh m = mesh_of(l_domain(500.0), 50.0);
  const CrossField field = constant_cross_field(m, 100.0);  // = 10 degrees as a cross
  ASSERT_EQ(field.angle_rad.size(), m.points.size());
  for (double a : field.angle_rad) EXPECT_NEAR(a, 10 * kDeg, 1e-12);
  EXPECT_TRUE(cross_field_singularities(m, field).empty());
  EXPECT_NEAR(cross_angle_at(m, field, 0, {0.2, 0.3, 0.5}), 10 * kDeg, 1e-12);
  EXPECT_NEAR(constant_cross_field(m, -30.0).angle_rad[0], 60 * kDeg, 1e-12);
}

TEST(CrossField, InterpolationAveragesCrossesNotAngles) {
  const BackgroundMesh m = mesh_of(square_domain(100.0), 50.0);
  CrossField field = constant_cross_field(m, 0.0);
  const auto& t = m.triangles[0];
  field.angle_rad[t[0]] = 85 * kDeg;  // the same cross as -5 degrees
  field.angle_rad[t[1]] = 5 * kDeg;
  field.angle_rad[t[2]] = 5 * kDeg;
  // Averaging angles would give about 31.7 degrees; the crosses agree near 1.7 degrees.
  const double a = cross_angle_at(m, field, 0, {1.0 / 3, 1.0 / 3, 1.0 / 3});
  EXPECT_NEAR(cross_rotation_rad(0.0, a) / kDeg, 1.67, 0.1);
  EXPECT_NEAR(cross_angle_at(m, field, 0, {1.0, 0.0, 0.0}), 85 * kDeg, 1e-12);
}

TEST(CrossField, LShapeIsAlignedWithTheAxes) {
  // Every boundary edge is axis-aligned, so the smoothest field is constant.
  const BackgroundMesh m = mesh_of(l_domain(500.0), 25.0);
  const CrossField field = boundary_aligned_cross_field(m);
  for (double a : field.angle_rad) EXPECT_LT(std::abs(cross_rotation_rad(0.0, a)), 1 * kDeg);
}

TEST(CrossField, ConformalRotationPutsSingularitiesWhereTheSizesGrade) {
  // A square, axis-aligned on its sides, with sizes that grade by a factor of e^2
  // towards a bump at (700, 600): log h = -2 exp(-r^2 / 150^2). Without the rotation
  // the field is the constant axis-aligned one; with it, singularities appear, all near
  // the bump (where the Laplacian of log h is large), of total index 0 (the square's
  // field has none), and the field away from the bump stays aligned with the sides.
  const BackgroundMesh m = mesh_of(square_domain(1000.0), 20.0);
  std::vector<double> bump(m.points.size());
  for (std::size_t v = 0; v < m.points.size(); ++v) {
    const double dx = m.points[v].x - 700.0, dy = m.points[v].y - 600.0;
    bump[v] = 100.0 * std::exp(-2.0 * std::exp(-(dx * dx + dy * dy) / (150.0 * 150.0)));
  }
  EXPECT_TRUE(cross_field_singularities(m, boundary_aligned_cross_field(m, bump, 0.0)).empty());

  const CrossField field = boundary_aligned_cross_field(m, bump, 1.0);
  const std::vector<Singularity> s = cross_field_singularities(m, field);
  EXPECT_GE(s.size(), 2u);
  EXPECT_EQ(total_index_quarters(s), 0);
  for (const Singularity& x : s)
    EXPECT_LT(distance(x.position, {700.0, 600.0}), 300.0) << x.position.x << " " << x.position.y;
  double worst_far = 0.0;
  for (std::size_t v = 0; v < m.points.size(); ++v)
    if (distance(m.points[v], {700.0, 600.0}) > 500.0)
      worst_far = std::max(worst_far, std::abs(cross_rotation_rad(0.0, field.angle_rad[v])) / kDeg);
  EXPECT_LT(worst_far, 10.0);
}
