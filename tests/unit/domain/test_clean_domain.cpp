// clean_domain: islands and holes under the least area dropped, measured as they are or,
// with an area factor (a map's (k_min / k)^2), as at the map's smallest scale.
#include "domain/clean_domain.h"

#include <gtest/gtest.h>

#include "core/error.h"

using namespace isoquad;

namespace {

Ring square(double x, double y, double side, bool clockwise = false) {
  Ring r{{x, y}, {x + side, y}, {x + side, y + side}, {x, y + side}};
  if (clockwise) std::swap(r[1], r[3]);
  return r;
}

// A 100 x 100 sea with two 10 x 10 holes (islands), at x = 10 and x = 80, and two
// 10 x 10 islands beside it, at x = 110 and x = 180 (components sorted by area).
Domain islands() {
  Domain d;
  d.polygons.push_back({square(0, 0, 100), {square(10, 10, 10, true), square(80, 10, 10, true)}});
  d.polygons.push_back({square(110, 0, 10), {}});
  d.polygons.push_back({square(180, 0, 10), {}});
  return d;
}

}  // namespace

TEST(CleanDomain, DropsIslandsAndHolesUnderTheLeastArea) {
  Domain d = islands();
  CleanParams p;
  p.min_island_area_m2 = p.min_hole_area_m2 = 99.0;
  CleanResult r = clean_domain(d, p);
  EXPECT_EQ(r.num_islands_dropped, 0u);
  EXPECT_EQ(r.num_holes_dropped, 0u);
  p.min_island_area_m2 = p.min_hole_area_m2 = 101.0;
  r = clean_domain(d, p);
  EXPECT_EQ(r.num_islands_dropped, 2u);
  EXPECT_EQ(r.num_holes_dropped, 2u);
  ASSERT_EQ(d.polygons.size(), 1u);
  EXPECT_TRUE(d.polygons[0].holes.empty());
}

TEST(CleanDomain, AnAreaFactorMeasuresThemAsAtTheSmallestScale) {
  // The scale doubles from x = 0 to x = 200: beyond x = 31 an island drawn 100 m2 is
  // under 75 m2 at the smallest scale, and dropped at the least area 75.
  Domain d = islands();
  CleanParams p;
  p.min_island_area_m2 = p.min_hole_area_m2 = 75.0;
  p.area_factor = [](const Point2& q) {
    const double k = 1.0 + q.x / 200.0;
    return 1.0 / (k * k);
  };
  const CleanResult r = clean_domain(d, p);
  // At x = 15 (factor 0.86) the hole stays; at x = 85 (0.49) it goes, and both
  // islands (0.40, 0.27).
  EXPECT_EQ(r.num_holes_dropped, 1u);
  EXPECT_EQ(r.num_islands_dropped, 2u);
  ASSERT_EQ(d.polygons.size(), 1u);
  ASSERT_EQ(d.polygons[0].holes.size(), 1u);
  EXPECT_EQ(d.polygons[0].holes[0][0].x, 10.0);
  // Nothing left: a clear error.
  p.area_factor = [](const Point2&) { return 1e-9; };
  Domain tiny = islands();
  EXPECT_THROW(clean_domain(tiny, p), Error);
}

// Nothing left: an input error that gives the least area and the largest component's, and
// says where the least area comes from by default.
TEST(CleanDomain, NothingLeftSaysHowLargeTheComponentsAre) {
  Domain d = islands();  // the largest 100 x 100 m, its holes not counted
  CleanParams p;
  p.min_island_area_m2 = 2e6;
  try {
    clean_domain(d, p);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), ErrorClass::input);
    const std::string what = e.what();
    EXPECT_NE(what.find("--min-island-area, 2 km2 (the largest: 0.01 km2)"), std::string::npos)
        << what;
    EXPECT_NE(what.find("the square of the size"), std::string::npos) << what;
  }
  // Given by the user, not the default: the default is not the one to blame.
  p.min_island_area_given = true;
  d = islands();
  try {
    clean_domain(d, p);
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("Give a --min-island-area under the largest component's area"),
              std::string::npos)
        << what;
    EXPECT_EQ(what.find("square of the size"), std::string::npos) << what;
  }
}
