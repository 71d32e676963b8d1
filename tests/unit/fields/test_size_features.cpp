// The --refine features' sizes: FeatureSizes against a plain computation over a lattice
// of points (inside polygons by the even-odd rule, distances to every segment and
// point), and the reader's messages for bad files.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>

#include "core/error.h"
#include "fields/size_features.h"
#include "gis/read_size_features.h"
#include "support/test_support.h"

using namespace isoquad;
using namespace isoquad::test;

namespace {

double plain_distance(const SizeFeature& f, const Point2& p) {
  bool in = false;
  for (const auto& ring : f.rings)
    for (std::size_t i = 0; i + 1 < ring.size(); ++i) {
      const Point2 &a = ring[i], &b = ring[i + 1];
      if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y))
        in = !in;
    }
  if (in) return 0.0;
  double d = INFINITY;
  for (const auto* parts : {&f.rings, &f.lines})
    for (const auto& line : *parts)
      for (std::size_t i = 0; i + 1 < line.size(); ++i)
        d = std::min(d, distance_to_segment(p, line[i], line[i + 1]));
  for (const Point2& q : f.points) d = std::min(d, distance(p, q));
  return d;
}

}  // namespace

TEST(FeatureSizes, TheSmallestGradedSizeOfAnyFeature) {
  std::vector<SizeFeature> features(3);
  // A square with a square hole, size 500.
  features[0].size_m = 500;
  features[0].rings = {{{0, 0}, {4000, 0}, {4000, 4000}, {0, 4000}, {0, 0}},
                       {{1000, 1000}, {1000, 3000}, {3000, 3000}, {3000, 1000}, {1000, 1000}}};
  // A long polyline of 100 segments (several runs), size 800.
  features[1].size_m = 800;
  features[1].lines.emplace_back();
  for (int i = 0; i <= 100; ++i)
    features[1].lines[0].push_back({6000.0 + 200 * i, 1000.0 + 300 * std::sin(0.3 * i)});
  // Two points, size 300.
  features[2].size_m = 300;
  features[2].points = {{-3000, 9000}, {15000, -4000}};
  const double k = 0.2, h0 = 3000;
  const FeatureSizes sizes(features, k);
  int below = 0;
  for (int i = -40; i <= 140; ++i)
    for (int j = -40; j <= 80; ++j) {
      const Point2 p{250.0 * i + 7, 250.0 * j + 3};
      double want = h0;
      for (const SizeFeature& f : features)
        want = std::min(want, f.size_m + k * plain_distance(f, p));
      ASSERT_NEAR(sizes.limit(p, h0), want, 1e-9) << p.x << " " << p.y;
      below += want < h0;
    }
  EXPECT_GT(below, 1000);
  EXPECT_EQ(sizes.limit({2000, 2000}, h0), 500 + k * 1000);  // in the hole: 1000 m from the square
  EXPECT_EQ(sizes.limit({500, 500}, h0), 500);               // inside
  EXPECT_EQ(sizes.limit({500, 500}, 400), 400);              // never above h
}

namespace {

// Many features (the grid's cells hold few of them): points, small squares and short
// lines scattered over 100 km, sizes 200 to 1,000 m, and with `widths` widths of 0 to
// 3,000 m.
std::vector<SizeFeature> scattered_features(bool widths) {
  std::vector<SizeFeature> features(400);
  std::uint32_t seed = 12345;
  auto uniform = [&seed](double a, double b) {
    seed = seed * 1664525u + 1013904223u;
    return a + (b - a) * (seed >> 8) / double(1u << 24);
  };
  for (std::size_t k = 0; k < features.size(); ++k) {
    SizeFeature& f = features[k];
    f.size_m = uniform(200, 1000);
    const Point2 c{uniform(0, 100000), uniform(0, 100000)};
    if (k % 3 == 0) f.points = {c};
    if (k % 3 == 1) f.rings = {{c, {c.x + 800, c.y}, {c.x + 800, c.y + 800}, {c.x, c.y + 800}, c}};
    if (k % 3 == 2) f.lines = {{c, {c.x + uniform(-3000, 3000), c.y + uniform(-3000, 3000)}}};
    if (widths && k % 2 == 0) f.width_m = uniform(0, 3000);
  }
  return features;
}

// FeatureSizes against the plain minimum of size + K max(0, distance - width / 2) on
// a lattice of points, for h 2,500 and 700 m.
void expect_the_plain_minimum(const std::vector<SizeFeature>& features) {
  const double k = 0.3, h0 = 2500;
  const FeatureSizes sizes(features, k);
  for (int i = -10; i <= 110; ++i)
    for (int j = -10; j <= 110; ++j) {
      const Point2 p{1000.0 * i + 13, 1000.0 * j + 29};
      for (double h : {h0, 700.0}) {
        double want = h;
        for (const SizeFeature& f : features)
          want =
              std::min(want, f.size_m + k * std::max(0.0, plain_distance(f, p) - 0.5 * f.width_m));
        ASSERT_NEAR(sizes.limit(p, h), want, 1e-9) << p.x << " " << p.y << " " << h;
      }
    }
}

}  // namespace

TEST(FeatureSizes, ManyFeaturesThroughTheGridGiveThePlainMinimum) {
  expect_the_plain_minimum(scattered_features(false));
}

TEST(FeatureSizes, AWidthHoldsTheSizeWithinHalfOfItThenItGrows) {
  expect_the_plain_minimum(scattered_features(true));
  // A line of size 100 and width 1,000: 100 up to 500 m from it, then growing by K.
  std::vector<SizeFeature> one(1);
  one[0].size_m = 100;
  one[0].width_m = 1000;
  one[0].lines = {{{0, 0}, {10000, 0}}};
  const FeatureSizes sizes(one, 0.2);
  EXPECT_EQ(sizes.limit({5000, 499}, 3000), 100);
  EXPECT_NEAR(sizes.limit({5000, -1500}, 3000), 100 + 0.2 * 1000, 1e-9);
  EXPECT_NEAR(sizes.limit({-700, 0}, 3000), 100 + 0.2 * 200, 1e-9);  // beyond its end
  EXPECT_EQ(sizes.limit({5000, 20000}, 3000), 3000);
}

TEST(FeatureSizes, TheReaderNamesWhatIsWrong) {
  TempDir dir;
  auto file = [&dir](const std::string& name, const std::string& properties,
                     const std::string& crs = "") {
    const std::string path = dir.file(name);
    write_file(path, R"({"type":"FeatureCollection",)" + crs +
                         R"("features":[{"type":"Feature","properties":)" + properties +
                         R"(,"geometry":{"type":"Point","coordinates":[1,2]}}]})");
    return path;
  };
  const SizeFeatures ok =
      read_size_features(file("ok.geojson", R"({"size":250,"name":"x"})"), "", "size", "--refine");
  EXPECT_EQ(ok.features.at(0).width_m, 0);
  const SizeFeatures wide = read_size_features(file("wide.geojson", R"({"size":250,"w":3000})"), "",
                                               "size", "--refine", "w");
  EXPECT_EQ(wide.features.at(0).width_m, 3000);
  ASSERT_EQ(ok.features.size(), 1u);
  EXPECT_EQ(ok.features[0].size_m, 250);
  EXPECT_EQ(ok.features[0].points.size(), 1u);
  EXPECT_TRUE(ok.crs.geographic);
  auto message = [](const std::function<void()>& f, ErrorClass cls) {
    try {
      f();
    } catch (const Error& e) {
      EXPECT_EQ(e.error_class(), cls) << e.what();
      return std::string(e.what());
    }
    ADD_FAILURE() << "no error";
    return std::string();
  };
  const std::string no_field = file("a.geojson", R"({"h":250,"name":"x"})");
  EXPECT_NE(
      message([&] { read_size_features(no_field, "", "size", "--refine"); }, ErrorClass::usage)
          .find("has no attribute 'size' for the sizes (attributes: h, name)"),
      std::string::npos);
  const std::string negative = file("b.geojson", R"({"size":-5})");
  EXPECT_NE(
      message([&] { read_size_features(negative, "", "size", "--refine"); }, ErrorClass::input)
          .find("feature 0 has size '-5'; sizes are positive numbers of metres"),
      std::string::npos);
  const std::string narrow = file("n.geojson", R"({"size":5,"w":-1})");
  EXPECT_NE(
      message([&] { read_size_features(narrow, "", "size", "--refine", "w"); }, ErrorClass::input)
          .find("feature 0 has w '-1'; widths are numbers of metres, 0 or more"),
      std::string::npos);
  EXPECT_NE(message([&] { read_size_features(narrow, "", "size", "--refine", "width"); },
                    ErrorClass::usage)
                .find("has no attribute 'width' for the widths (attributes: size, w)"),
            std::string::npos);
  const std::string text = file("c.geojson", R"({"size":"big"})");
  EXPECT_NE(message([&] { read_size_features(text, "", "size", "--refine"); }, ErrorClass::input)
                .find("has size 'big'"),
            std::string::npos);
  EXPECT_NE(
      message([&] { read_size_features(no_field, "nope", "size", "--refine"); }, ErrorClass::usage)
          .find("no layer 'nope'"),
      std::string::npos);
  EXPECT_NE(
      message([&] { read_size_features(dir.file("missing.geojson"), "", "size", "--refine"); },
              ErrorClass::input)
          .find("missing.geojson"),
      std::string::npos);
}
