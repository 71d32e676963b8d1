#include "domain/simplify_domain.h"

#include <gtest/gtest.h>

#include <cmath>

#include "support/ring_checks.h"

using namespace isoquad;

namespace {

// A ring around a circle with a zig-zag of amplitude `noise_m` on every other vertex.
Ring noisy_circle(double cx, double cy, double r, int n, double noise_m) {
  Ring ring;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * M_PI * i / n;
    const double rr = r + ((i % 2) ? noise_m : -noise_m);
    ring.push_back({cx + rr * std::cos(t), cy + rr * std::sin(t)});
  }
  return ring;
}

}  // namespace

TEST(SimplifyDomain, ZeroToleranceChangesNothing) {
  Domain d;
  d.polygons.push_back({noisy_circle(0, 0, 1000, 200, 5), {}});
  const Domain before = d;
  const SimplifyResult r = simplify_domain(d, {0.0});
  EXPECT_EQ(r.num_vertices_before, 200u);
  EXPECT_EQ(r.num_vertices_after, 200u);
  for (std::size_t i = 0; i < 200; ++i) EXPECT_EQ(d.polygons[0].outer[i], before.polygons[0].outer[i]);
}

TEST(SimplifyDomain, RemovesNoiseBelowTheTolerance) {
  Domain d;
  d.polygons.push_back({noisy_circle(0, 0, 1000, 400, 2), {}});
  const SimplifyResult r = simplify_domain(d, {50.0});
  EXPECT_LT(r.num_vertices_after, 60u);
  EXPECT_GE(r.num_vertices_after, 3u);
  // Every kept vertex is an input vertex, so within the noise of the circle.
  for (const Point2& p : d.polygons[0].outer) EXPECT_NEAR(std::hypot(p.x, p.y), 1000.0, 2.0 + 1e-9);
  EXPECT_GT(signed_area(d.polygons[0].outer), 0.0);
}

// A hole close to the outer ring: a large tolerance must not make them cross, and the
// hole must survive.
TEST(SimplifyDomain, NeverMakesRingsCross) {
  Domain d;
  Polygon p;
  p.outer = noisy_circle(0, 0, 1000, 300, 30);
  Ring hole = noisy_circle(0, 0, 960, 300, 30);
  std::reverse(hole.begin(), hole.end());
  p.holes.push_back(hole);
  d.polygons.push_back(p);
  ASSERT_EQ(test::find_crossing(d), "");
  for (double tol : {10.0, 100.0, 1000.0, 5000.0}) {
    Domain copy = d;
    simplify_domain(copy, {tol});
    EXPECT_EQ(test::find_crossing(copy), "") << "tolerance " << tol;
    ASSERT_EQ(copy.polygons[0].holes.size(), 1u);
    EXPECT_GE(copy.polygons[0].holes[0].size(), 3u);
    EXPECT_GT(area(copy.polygons[0]), 0.0);
  }
}

TEST(SimplifyDomain, IsDeterministic) {
  Domain a;
  a.polygons.push_back({noisy_circle(0, 0, 1000, 500, 7), {}});
  Domain b = a;
  simplify_domain(a, {20.0});
  simplify_domain(b, {20.0});
  ASSERT_EQ(a.polygons[0].outer.size(), b.polygons[0].outer.size());
  for (std::size_t i = 0; i < a.polygons[0].outer.size(); ++i)
    EXPECT_EQ(a.polygons[0].outer[i], b.polygons[0].outer[i]);
}
