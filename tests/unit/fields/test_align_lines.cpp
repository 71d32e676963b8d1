// Lines inside the domain that the cross field follows (--align).
#include "fields/align_lines.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/geometry.h"
#include "fields/cross_field.h"
#include "mesh/background_mesh.h"
#include "unit/mesh/test_domains.h"

using namespace isoquad;
using namespace isoquad::test;

namespace {

constexpr double kDeg = kPi / 180.0;
constexpr double kEdge = 40.0;

BackgroundMesh square_mesh() {
  BackgroundMeshParams p;
  p.max_edge_m = [](const Point2&) { return kEdge; };
  return build_background_mesh(square_domain(1000.0), p);
}

// A line through (500, 500) at `deg` degrees, `half` metres each way.
std::vector<Point2> line_at(double deg, double half) {
  const double c = std::cos(deg * kDeg), s = std::sin(deg * kDeg);
  return {{500 - half * c, 500 - half * s}, {500 + half * c, 500 + half * s}};
}

// Degrees from cross angle `a` to `deg`'s cross (the smallest rotation).
double off_deg(double a, double deg) {
  return std::abs(cross_rotation_rad(a, deg * kDeg)) / kDeg;
}

}  // namespace

TEST(AlignLines, TheVerticesNearestALineTakeItsDirectionAndTheBoundaryKeepsItsOwn) {
  const BackgroundMesh mesh = square_mesh();
  const std::vector<Point2> line = line_at(30.0, 300.0);
  const LineCrosses lc = line_crosses(mesh, {line, {{2000, 2000}, {3000, 2500}}});
  ASSERT_EQ(lc.line_inside.size(), 2u);
  EXPECT_TRUE(lc.line_inside[0]);
  EXPECT_FALSE(lc.line_inside[1]);  // wholly outside: nothing fixed by it
  // A chain of vertices along the 600 m line: at least one per edge length.
  EXPECT_GE(lc.num_fixed, static_cast<std::size_t>(600.0 / kEdge));
  std::size_t fixed = 0;
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    if (!lc.crosses.is_fixed[v]) continue;
    ++fixed;
    EXPECT_LT(distance_to_segment(mesh.points[v], line[0], line[1]), kEdge) << v;
    EXPECT_LT(mesh.boundary_chain_of_vertex[v], 0) << v;
    EXPECT_LT(off_deg(cross_angle_of(lc.crosses.uc[v], lc.crosses.us[v]), 30.0), 1e-9) << v;
  }
  EXPECT_EQ(fixed, lc.num_fixed);
}

TEST(AlignLines, ALineThatCrossesTheBoundaryFixesNoBoundaryVertex) {
  const BackgroundMesh mesh = square_mesh();
  const LineCrosses lc = line_crosses(mesh, {{{-200, 500}, {1200, 500}}});
  EXPECT_TRUE(lc.line_inside[0]);
  std::size_t fixed = 0;
  for (std::size_t v = 0; v < mesh.points.size(); ++v)
    if (lc.crosses.is_fixed[v]) {
      ++fixed;
      EXPECT_LT(mesh.boundary_chain_of_vertex[v], 0) << v;
      EXPECT_LT(std::abs(mesh.points[v].y - 500.0), kEdge) << v;
    }
  EXPECT_GE(fixed, static_cast<std::size_t>(900.0 / kEdge));
}

TEST(AlignLines, WhereLinesCrossAVertexTakesOneOfTheirCrosses) {
  // At 45 degrees apart the two crosses are opposite in 4 theta: a vertex reached by
  // both takes the one that reached it more often, or none, never a cross between.
  const BackgroundMesh mesh = square_mesh();
  const LineCrosses lc = line_crosses(mesh, {line_at(30.0, 300.0), line_at(75.0, 300.0)});
  ASSERT_GT(lc.num_fixed, 0u);
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    if (!lc.crosses.is_fixed[v]) continue;
    const double a = cross_angle_of(lc.crosses.uc[v], lc.crosses.us[v]);
    EXPECT_LT(std::min(off_deg(a, 30.0), off_deg(a, 75.0)), 1e-6) << v;
  }
}

TEST(AlignLines, TheFieldFollowsTheLineAndTurnsBetweenItAndTheBoundary) {
  // The square's boundary asks for 0 degrees, the line for 30: the smoothest field
  // holds 30 on the line's vertices and, by the maximum principle of the harmonic
  // solve in 4 theta, stays between the two everywhere.
  const BackgroundMesh mesh = square_mesh();
  const LineCrosses lc = line_crosses(mesh, {line_at(30.0, 300.0)});
  const CrossField plain = boundary_aligned_cross_field(mesh);
  const CrossField field = boundary_aligned_cross_field(mesh, {}, 0.0, &lc.crosses);
  double near_line = 0.0;
  int num_near = 0;
  const std::vector<Point2> line = line_at(30.0, 300.0);
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    const double a = cross_rotation_rad(0.0, field.angle_rad[v]) / kDeg;
    EXPECT_GE(a, -1e-6) << v;
    EXPECT_LE(a, 30.0 + 1e-6) << v;
    EXPECT_LT(off_deg(plain.angle_rad[v], 0.0), 1e-6) << v;  // without the line: 0
    if (lc.crosses.is_fixed[v]) {
      EXPECT_LT(off_deg(field.angle_rad[v], 30.0), 1e-9) << v;
    }
    if (distance_to_segment(mesh.points[v], line[0], line[1]) < 2 * kEdge)
      near_line += a, ++num_near;
  }
  ASSERT_GT(num_near, 0);
  EXPECT_GT(near_line / num_near, 25.0);
}
