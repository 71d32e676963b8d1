#include "domain/simplify_domain.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

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

namespace {

// Distance from p to the segment ab.
double to_segment(const Point2& p, const Point2& a, const Point2& b) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double t = std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
  return std::hypot(p.x - a.x - t * dx, p.y - a.y - t * dy);
}

// Distance from p to the ring's edges that lie left of x = 1500 (the U's left arm).
double to_left_arm(const Ring& ring, const Point2& p) {
  double d = 1e300;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Point2& a = ring[i];
    const Point2& b = ring[(i + 1) % ring.size()];
    if (a.x < 1500 && b.x < 1500) d = std::min(d, to_segment(p, a, b));
  }
  return d;
}

// Water shaped as a U round a slot of land 600 m wide and 4 km deep. The slot's left
// wall has a notch 300 m deep (within a tolerance of 350 m, so the simplification would
// straighten it); its right wall a cape whose tip reaches 20 m from where the straightened
// wall would run (580 m deep: it stays). The notch's two sides are 274 m from the tip.
Domain u_with_a_cape() {
  Domain d;
  d.polygons.push_back({{{0, 0}, {1000, 10}, {2000, -10}, {3000, 0}, {3000, 5000}, {1800, 5000},
                         {1800, 3100}, {1220, 3000}, {1800, 2900}, {1800, 1000}, {1200, 1000},
                         {1200, 2500}, {900, 3000}, {1200, 3500}, {1200, 5000}, {0, 5000}},
                        {}});
  return d;
}

}  // namespace

TEST(SimplifyDomain, KeepsTheGapAcrossAChannel) {
  // The Baltic at 1:10m: a bay's mouth of 280 m closed to 0.5 m at a tolerance of 385 m,
  // and the quads across it had sides of 0.4 m.
  const Point2 tip{1220, 3000};
  Domain without = u_with_a_cape();
  simplify_domain(without, {350.0, 0.0});
  EXPECT_LT(to_left_arm(without.polygons[0].outer, tip), 25.0) << "the premise: the notch goes";
  Domain with = u_with_a_cape();
  const SimplifyResult r = simplify_domain(with, {350.0, 350.0});
  EXPECT_GT(to_left_arm(with.polygons[0].outer, tip), 270.0);
  EXPECT_EQ(test::find_crossing(with), "");
  // The bottom's zig-zag of 10 m still goes: only the notch is kept.
  EXPECT_EQ(r.num_vertices_after, without.polygons[0].outer.size() + 1);
}

TEST(SimplifyDomain, KeepsTheGapToAnIsland) {
  // An island 300 m off a coast whose bay (250 m deep, within the tolerance) would be
  // cut across 50 m from the island's nearest corner.
  Domain d;
  Polygon p;
  p.outer = {{0, 0}, {4000, 0}, {5000, -250}, {6000, 0}, {10000, 0}, {10000, 10000}, {0, 10000}};
  p.holes.push_back({{4600, 50}, {4600, 450}, {5400, 450}, {5400, 50}});  // clockwise
  d.polygons.push_back(p);
  Domain without = d;
  simplify_domain(without, {300.0, 0.0});
  EXPECT_EQ(without.polygons[0].outer.size(), 4u) << "the premise: the bay goes";
  simplify_domain(d, {300.0, 300.0});
  EXPECT_EQ(d.polygons[0].outer.size(), 5u);  // the bay stays, its two corners at y = 0 go
  EXPECT_EQ(d.polygons[0].holes[0].size(), 4u);
}

TEST(SimplifyDomain, TheClearanceDoesNotHoldBackACoastsOwnNoise) {
  // A zig-zag's next vertices are as near as the noise, but on the same stretch of coast.
  for (double clearance : {0.0, 50.0, 200.0}) {
    Domain d;
    d.polygons.push_back({noisy_circle(0, 0, 1000, 400, 2), {}});
    const SimplifyResult r = simplify_domain(d, {50.0, clearance});
    EXPECT_LT(r.num_vertices_after, 60u) << "clearance " << clearance;
  }
}

TEST(SimplifyDomain, AShortSpitIsOneStretchOfCoast) {
  // A spit of land 60 m wide and 200 m long: its two sides are nearer than the clearance
  // but on one stretch of coast (round its tip, within the clearance), so they simplify
  // as without it. (Were they two banks, the tip could not be cut: the chord would pass
  // 57 m from the far corner of the spit's base, 60 m from the spit before.)
  auto domain = [] {
    Domain d;
    d.polygons.push_back({{{0, 0}, {4970, 0}, {4970, 200}, {5030, 200}, {5030, 0}, {10000, 0},
                           {10000, 10000}, {0, 10000}},
                          {}});
    return d;
  };
  Domain without = domain(), with = domain();
  simplify_domain(without, {100.0, 0.0});
  ASSERT_LT(without.polygons[0].outer.size(), 8u) << "the premise: the tip is cut";
  simplify_domain(with, {100.0, 300.0});
  EXPECT_EQ(with.polygons[0].outer, without.polygons[0].outer);
}

namespace {

// The smallest distance from a vertex of `a` to an edge of `b`, and from a vertex of `b`
// to an edge of `a`.
double gap_between(const Ring& a, const Ring& b) {
  auto one_way = [](const Ring& from, const Ring& to) {
    double d = 1e300;
    for (const Point2& p : from)
      for (std::size_t i = 0; i < to.size(); ++i)
        d = std::min(d, to_segment(p, to[i], to[(i + 1) % to.size()]));
    return d;
  };
  return std::min(one_way(a, b), one_way(b, a));
}

// The distance from p to the ring's edges.
double to_ring(const Point2& p, const Ring& ring) {
  double d = 1e300;
  for (std::size_t i = 0; i < ring.size(); ++i)
    d = std::min(d, to_segment(p, ring[i], ring[(i + 1) % ring.size()]));
  return d;
}

// The largest distance from a vertex of `original` to the ring `simplified`.
double departure(const Ring& original, const Ring& simplified) {
  double worst = 0;
  for (const Point2& p : original) worst = std::max(worst, to_ring(p, simplified));
  return worst;
}

}  // namespace

// A coast drawn far more finely than the tolerance (a vertex every 1.6 m, the tolerance
// 100 m) is thinned first and simplifies as the same coast drawn coarsely.
TEST(SimplifyDomain, ADenseRingSimplifiesAsACoarseOne) {
  Domain dense, coarse;
  dense.polygons.push_back({noisy_circle(0, 0, 10000, 40000, 2), {}});
  coarse.polygons.push_back({noisy_circle(0, 0, 10000, 400, 2), {}});
  const Ring original = dense.polygons[0].outer;
  const SimplifyResult rd = simplify_domain(dense, {100.0, 100.0});
  const SimplifyResult rc = simplify_domain(coarse, {100.0, 100.0});
  EXPECT_EQ(rd.num_vertices_before, 40000u);
  EXPECT_GE(rd.num_vertices_after, 0.8 * rc.num_vertices_after);
  EXPECT_LE(rd.num_vertices_after, 1.25 * rc.num_vertices_after);
  EXPECT_LE(departure(original, dense.polygons[0].outer), 100.0 + 1e-6);
  EXPECT_EQ(test::find_crossing(dense), "");
}

// Dense banks of a channel (a vertex every 2 m): a cape 155 m long on one reaches to
// 95.05 m of the other, where a notch 6 m wide and 10 m deep faces it. Thinned (within
// the tolerance of 100 m, each of its vertices with its neighbours within 25 m), the
// notch would go and the gap fall to 95 m; the thinning leaves the vertices near the cape
// to the simplification proper, which keeps the gap under its clearance of 100 m.
TEST(SimplifyDomain, TheThinningKeepsTheGapAcrossADenseChannel) {
  auto line = [](Ring& ring, Point2 from, Point2 to) {  // `from` and the points to `to`
    const int n = static_cast<int>(std::ceil(std::hypot(to.x - from.x, to.y - from.y) / 2.0));
    for (int i = 0; i < n; ++i)
      ring.push_back({from.x + (to.x - from.x) * i / n, from.y + (to.y - from.y) * i / n});
  };
  Polygon p;
  line(p.outer, {0, 0}, {1497, 0});
  line(p.outer, {1497, 0}, {1497, -10});
  line(p.outer, {1497, -10}, {1503, -10});
  line(p.outer, {1503, -10}, {1503, 0});
  line(p.outer, {1503, 0}, {3000, 0});
  p.outer.push_back({3000, 3000});
  p.outer.push_back({0, 3000});
  Ring hole{{1000, 250}, {1000, 2000}, {2000, 2000}};  // clockwise
  line(hole, {2000, 250}, {1530, 250});
  line(hole, {1530, 250}, {1500, 95});
  line(hole, {1500, 95}, {1470, 250});
  line(hole, {1470, 250}, {1000, 250});
  p.holes.push_back(hole);
  Domain d;
  d.polygons.push_back(p);
  ASSERT_EQ(test::find_crossing(d), "");
  const double before = gap_between(p.outer, hole);
  ASSERT_NEAR(before, 95.047, 0.001);
  simplify_domain(d, {100.0, 100.0});
  EXPECT_LT(d.polygons[0].outer.size() + d.polygons[0].holes[0].size(), 500u);  // thinned
  EXPECT_GE(gap_between(d.polygons[0].outer, d.polygons[0].holes[0]), before - 1e-6);
  EXPECT_EQ(test::find_crossing(d), "");
}

// Random coasts drawn finely (a vertex every 4 m, the tolerance and clearance 100 m): a
// wavy, rippled outer ring and islands 40 to 140 m in from it. Whatever the thinning and
// the simplification remove, no rings cross, every input vertex stays within the
// tolerance of its ring (the thinning's removed points count in the second pass's cost:
// dropped, a vertex here ends 101.9 m off), every island stays, and no vertex left comes
// nearer another ring than the clearance, or than it was.
TEST(SimplifyDomain, RandomDenseCoastsKeepTheirShapeAndGaps) {
  constexpr double kSpacing = 4.0, kTolerance = 100.0;
  for (unsigned seed = 1; seed <= 4; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    // A star-shaped ring round (cx, cy) of mean radius r, its radius varied by harmonics
    // of relative amplitude up to `wave` and by ripples 20 to 60 m long and up to 8 m
    // high (what the thinning may take off), a vertex every kSpacing metres or so.
    auto wavy = [&](double cx, double cy, double r, double wave) {
      std::vector<std::array<double, 3>> harmonics;  // order, relative amplitude, phase
      for (int k = 2; k <= 14; ++k)
        harmonics.push_back({double(k), wave * unit(rng) / k, 2 * M_PI * unit(rng)});
      for (int k = 0; k < 6; ++k)
        harmonics.push_back({std::round(2 * M_PI * r / (20 + 40 * unit(rng))), 8 * unit(rng) / r,
                             2 * M_PI * unit(rng)});
      const int n = static_cast<int>(2 * M_PI * r * 1.3 / kSpacing);
      Ring ring;
      for (int i = 0; i < n; ++i) {
        const double t = 2 * M_PI * i / n;
        double rr = r;
        for (const auto& h : harmonics) rr += r * h[1] * std::sin(h[0] * t + h[2]);
        ring.push_back({cx + rr * std::cos(t), cy + rr * std::sin(t)});
      }
      return ring;
    };
    Polygon p;
    p.outer = wavy(0, 0, 3000, 0.6);
    auto inside_outer = [&](const Point2& q) {  // even-odd test against the outer ring
      bool in = false;
      const Ring& o = p.outer;
      for (std::size_t i = 0, j = o.size() - 1; i < o.size(); j = i++)
        if ((o[i].y > q.y) != (o[j].y > q.y) &&
            q.x < (o[j].x - o[i].x) * (q.y - o[i].y) / (o[j].y - o[i].y) + o[i].x)
          in = !in;
      return in;
    };
    auto ring_distance = [](const Ring& a, const Ring& b) {  // vertex to vertex, every 2nd
      double d = 1e300;
      for (std::size_t i = 0; i < a.size(); i += 2)
        for (std::size_t j = 0; j < b.size(); j += 2)
          d = std::min(d, std::hypot(a[i].x - b[j].x, a[i].y - b[j].y));
      return d;
    };
    // Islands near the coast: each at a random bearing, its centre moved in from the
    // coast's vertex there by its radius and 40 to 140 m more.
    for (int tries = 0; tries < 200 && p.holes.size() < 8; ++tries) {
      const Point2 at = p.outer[static_cast<std::size_t>(unit(rng) * p.outer.size())];
      const double r = 80 + 170 * unit(rng), in = 1.3 * r + 40 + 100 * unit(rng);
      const double reach = std::hypot(at.x, at.y);
      Ring island = wavy(at.x * (1 - in / reach), at.y * (1 - in / reach), r, 0.3);
      bool fits = std::all_of(island.begin(), island.end(), inside_outer) &&
                  ring_distance(island, p.outer) > 20;
      for (const Ring& h : p.holes) fits = fits && ring_distance(island, h) > 20;
      if (!fits) continue;
      std::reverse(island.begin(), island.end());  // holes clockwise
      p.holes.push_back(std::move(island));
    }
    ASSERT_GE(p.holes.size(), 3u) << "seed " << seed;
    Domain d;
    d.polygons.push_back(p);
    ASSERT_EQ(test::find_crossing(d), "") << "seed " << seed;
    std::vector<const Ring*> before{&p.outer};
    for (const Ring& h : p.holes) before.push_back(&h);

    simplify_domain(d, {kTolerance, kTolerance});
    EXPECT_EQ(test::find_crossing(d), "") << "seed " << seed;
    ASSERT_EQ(d.polygons.size(), 1u);
    ASSERT_EQ(d.polygons[0].holes.size(), p.holes.size()) << "seed " << seed;
    std::vector<const Ring*> after{&d.polygons[0].outer};
    for (const Ring& h : d.polygons[0].holes) after.push_back(&h);
    std::size_t vertices = 0;
    for (std::size_t i = 0; i < after.size(); ++i) {
      vertices += after[i]->size();
      EXPECT_LE(departure(*before[i], *after[i]), kTolerance + 1e-6)
          << "seed " << seed << " ring " << i;
      // Each vertex left of another ring (an input vertex) is no nearer ring i than the
      // clearance, or than it was.
      for (std::size_t j = 0; j < after.size(); ++j) {
        if (j == i || ring_distance(*before[i], *before[j]) > 3 * kTolerance) continue;
        for (const Point2& v : *after[j]) {
          const double was = to_ring(v, *before[i]);
          EXPECT_GE(to_ring(v, *after[i]), std::min(was, kTolerance) - 1e-6)
              << "seed " << seed << ": vertex (" << v.x << ", " << v.y << ") of ring " << j
              << " to ring " << i;
        }
      }
    }
    EXPECT_LT(vertices, 2000u) << "seed " << seed;  // from about 8,000 to 14,000
  }
}
