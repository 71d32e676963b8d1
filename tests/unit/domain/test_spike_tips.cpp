// Spike tips sharper than a quad's corner may be: cut back square to min_width wide.
#include "domain/spike_tips.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace isoquad;

namespace {

// The smallest interior angle at a convex vertex of the domain, degrees.
double sharpest_convex_corner(const Domain& d) {
  double sharpest = 180.0;
  for (const Polygon& p : d.polygons) {
    std::vector<const Ring*> rings{&p.outer};
    for (const Ring& h : p.holes) rings.push_back(&h);
    for (const Ring* r : rings) {
      const std::size_t n = r->size();
      const double side = (signed_area(*r) > 0) == (r == &p.outer) ? 1.0 : -1.0;
      for (std::size_t i = 0; i < n; ++i) {
        const Point2 &a = (*r)[(i + n - 1) % n], &v = (*r)[i], &b = (*r)[(i + 1) % n];
        if (side * ((v.x - a.x) * (b.y - v.y) - (v.y - a.y) * (b.x - v.x)) <= 0) continue;
        const double ux = a.x - v.x, uy = a.y - v.y, wx = b.x - v.x, wy = b.y - v.y;
        const double c = (ux * wx + uy * wy) / (std::hypot(ux, uy) * std::hypot(wx, wy));
        sharpest = std::min(sharpest, std::acos(std::clamp(c, -1.0, 1.0)) * 180 / M_PI);
      }
    }
  }
  return sharpest;
}

// A 1 km square with a spike 600 m long on its right side, its base 40 m wide (a tip of
// 3.8 degrees), and with `island` a small island 2 m above the spike near its tip.
Domain square_with_spike(bool island_near) {
  Domain d;
  Polygon p;
  p.outer = {{0, 0}, {1000, 0}, {1000, 480}, {1600, 500}, {1000, 520}, {1000, 1000}, {0, 1000}};
  orient_polygon(p);
  d.polygons.push_back(p);
  if (island_near) {
    Polygon island;
    island.outer = {{1480, 506}, {1560, 506}, {1560, 520}, {1480, 520}};
    orient_polygon(island);
    d.polygons.push_back(island);
  }
  return d;
}

}  // namespace

TEST(SpikeTips, ASharpTipIsCutBackToTheWidth) {
  Domain d = square_with_spike(false);
  ASSERT_LT(sharpest_convex_corner(d), 4.0);
  const double before = area(d);
  SpikeParams params;
  params.min_width_m = 10.0;
  const SpikeResult r = cut_spike_tips(d, params);
  EXPECT_EQ(r.num_cut, 1u);
  // The tip triangle: 10 m wide at 150 m from the tip (the spike widens by 40 m in 600).
  EXPECT_NEAR(r.area_removed_m2, 0.5 * 10 * 150, 0.05 * 0.5 * 10 * 150);
  EXPECT_NEAR(before - area(d), r.area_removed_m2, 0.05 * r.area_removed_m2);
  ASSERT_EQ(d.polygons.size(), 1u);
  EXPECT_GT(sharpest_convex_corner(d), 45.0);  // the square's corners and the cut end's
  // Nothing is left beyond the cut, and the spike reaches it.
  double reach = 0;
  for (const Point2& q : d.polygons[0].outer) reach = std::max(reach, q.x);
  EXPECT_NEAR(reach, 1600 - 150, 1.0);
}

TEST(SpikeTips, WideCornersNotchesAndAnIslandNearbyStay) {
  // No cut at width 0; an island beside the spike, within the box the cut looks in, is
  // not touched; a sharp reflex corner (a notch into the domain) is no tip.
  Domain d = square_with_spike(true);
  const Domain original = d;
  EXPECT_EQ(cut_spike_tips(d, SpikeParams{}).num_cut, 0u);
  SpikeParams params;
  params.min_width_m = 10.0;
  const SpikeResult r = cut_spike_tips(d, params);
  EXPECT_EQ(r.num_cut, 1u);
  ASSERT_EQ(d.polygons.size(), 2u);
  EXPECT_NEAR(area(d.polygons[1]), 80.0 * 14.0, 1e-6);
  Domain notch;
  Polygon p;
  p.outer = {{0, 0}, {1000, 0}, {1000, 480}, {400, 500}, {1000, 520}, {1000, 1000}, {0, 1000}};
  orient_polygon(p);
  notch.polygons.push_back(p);
  const Domain notch_before = notch;
  EXPECT_EQ(cut_spike_tips(notch, params).num_cut, 0u);
  EXPECT_EQ(notch.polygons[0].outer, notch_before.polygons[0].outer);
}

TEST(SpikeTips, ASpitNarrowerThanTheWidthIsCutAtItsBase) {
  // At a width of 60 m the square cut would be 904 m from the tip, beyond the spike's
  // base (600 m, 40 m wide), where the square's side turns away: the spike goes whole.
  Domain d = square_with_spike(false);
  const double before = area(d);
  SpikeParams params;
  params.min_width_m = 60.0;
  const SpikeResult r = cut_spike_tips(d, params);
  EXPECT_EQ(r.num_cut, 0u);
  EXPECT_EQ(r.num_cut_at_base, 1u);
  EXPECT_NEAR(r.area_removed_m2, 0.5 * 40 * 600, 1e-6 * before);
  EXPECT_NEAR(before - area(d), r.area_removed_m2, 1e-6 * before);
  ASSERT_EQ(d.polygons.size(), 1u);
  EXPECT_GT(sharpest_convex_corner(d), 45.0);
  double reach = 0;
  for (const Point2& q : d.polygons[0].outer) reach = std::max(reach, q.x);
  EXPECT_NEAR(reach, 1000, 1e-9);

  // One side bends away nearer the tip: the cut goes through that bend, square across.
  Domain bent;
  Polygon p;
  p.outer = {{0, 0}, {1000, 0}, {1000, 480}, {1600, 500}, {1300, 510}, {1000, 700}, {0, 700}};
  orient_polygon(p);
  bent.polygons.push_back(p);
  ASSERT_LT(sharpest_convex_corner(bent), 15.0);
  const SpikeResult rb = cut_spike_tips(bent, params);
  EXPECT_EQ(rb.num_cut + rb.num_cut_at_base, 1u);
  EXPECT_EQ(rb.num_cut_at_base, 1u);
  EXPECT_GT(sharpest_convex_corner(bent), 45.0);
  for (const Point2& q : bent.polygons[0].outer) EXPECT_LE(q.x, 1300.5);

  // The same on a hole's ring: land poking 400 m into a lake, 40 m wide at its base.
  Domain lake;
  Polygon with_hole;
  with_hole.outer = {{0, 0}, {1000, 0}, {1000, 1000}, {0, 1000}};
  with_hole.holes.push_back({{200, 200}, {800, 200}, {800, 480}, {400, 500}, {800, 520}, {800, 800}, {200, 800}});
  orient_polygon(with_hole);
  lake.polygons.push_back(with_hole);
  ASSERT_LT(sharpest_convex_corner(lake), 6.0);
  const double lake_before = area(lake);
  const SpikeResult rl = cut_spike_tips(lake, params);
  EXPECT_EQ(rl.num_cut_at_base, 1u);
  EXPECT_NEAR(lake_before - area(lake), 0.5 * 40 * 400, 1e-6 * lake_before);
  ASSERT_EQ(lake.polygons.size(), 1u);
  ASSERT_EQ(lake.polygons[0].holes.size(), 1u);
  EXPECT_GT(sharpest_convex_corner(lake), 45.0);

  // Where the spike's base is under a quarter of the width wide, the cut would only move
  // the sharp corner to a shorter edge: the tip stays.
  Domain thin = square_with_spike(false);
  params.min_width_m = 200.0;
  const SpikeResult rt = cut_spike_tips(thin, params);
  EXPECT_EQ(rt.num_cut + rt.num_cut_at_base, 0u);
  EXPECT_LT(sharpest_convex_corner(thin), 4.0);
}
