// The elementary functions every isoquad executable brings (src/core/portable_math.cpp):
// they are the ones the process calls and exports (so that PROJ, GEOS and GDAL call
// them too), they are SLEEF's deterministic builds, and their values are libm's to a
// few ulp, special values and the edges of the range included.
#include <dlfcn.h>
#include <gtest/gtest.h>
#include <sleef.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "core/paired_math.h"

namespace {

// Arguments the compiler cannot fold.
double opaque(double x) {
  volatile double v = x;
  return v;
}

std::uint64_t bits(double x) {
  std::uint64_t u;
  std::memcpy(&u, &x, sizeof u);
  return u;
}

// Relative error against a long double reference, in units of the double's epsilon.
double ulps(double got, long double want) {
  if (want == 0) return got == 0 ? 0 : std::numeric_limits<double>::infinity();
  return static_cast<double>(std::fabs((static_cast<long double>(got) - want) / want)) /
         std::numeric_limits<double>::epsilon();
}

}  // namespace

TEST(PortableMath, TheProcessCallsAndExportsItsOwnFunctions) {
  // What a shared library linked to the executable binds to: the first definition in
  // the global scope, the executable's when it exports it.
  for (const char* name : {"exp", "log", "pow", "sin", "cos", "sincos", "atan2", "atan", "asinh",
                           "sinh", "log1p", "expf", "sinf"}) {
    void* global = dlsym(RTLD_DEFAULT, name);
    void* next = dlsym(RTLD_NEXT, name);  // the one after the executable: libm's
    ASSERT_NE(global, nullptr) << name;
    EXPECT_NE(global, next) << name << " is libm's";
  }
  for (double x : {0.1, 0.7, 1.3, 2.9, 12.5, -3.3, 100.25}) {
    const double v = opaque(x);
    EXPECT_EQ(bits(std::exp(v)), bits(Sleef_cinz_expd1_u10purec(v))) << x;
    EXPECT_EQ(bits(std::sin(v)), bits(Sleef_cinz_sind1_u35purec(v))) << x;
    EXPECT_EQ(bits(std::atan2(v, 0.3)), bits(Sleef_cinz_atan2d1_u35purec(v, 0.3))) << x;
    EXPECT_EQ(bits(std::log(std::fabs(v))), bits(Sleef_cinz_logd1_u35purec(std::fabs(v)))) << x;
    EXPECT_EQ(bits(std::pow(std::fabs(v), 1.7)), bits(Sleef_cinz_powd1_u10purec(std::fabs(v), 1.7)))
        << x;
  }
}

TEST(PortableMath, ValuesAreLibmsToAFewUlp) {
  struct Case {
    const char* name;
    double (*f)(double);
    long double (*ref)(long double);
    double lo, hi;
  };
  const std::vector<Case> cases = {
      {"sin", [](double x) { return std::sin(x); }, sinl, -20, 20},
      {"cos", [](double x) { return std::cos(x); }, cosl, -20, 20},
      {"tan", [](double x) { return std::tan(x); }, tanl, -1.5, 1.5},
      {"asin", [](double x) { return std::asin(x); }, asinl, -1, 1},
      {"acos", [](double x) { return std::acos(x); }, acosl, -1, 1},
      {"atan", [](double x) { return std::atan(x); }, atanl, -50, 50},
      {"exp", [](double x) { return std::exp(x); }, expl, -700, 700},
      {"exp2", [](double x) { return std::exp2(x); }, exp2l, -1000, 1000},
      {"expm1", [](double x) { return std::expm1(x); }, expm1l, -5, 5},
      {"log", [](double x) { return std::log(x); }, logl, 1e-300, 1e300},
      {"log2", [](double x) { return std::log2(x); }, log2l, 1e-300, 1e300},
      {"log10", [](double x) { return std::log10(x); }, log10l, 1e-300, 1e300},
      {"log1p", [](double x) { return std::log1p(x); }, log1pl, -0.9, 1e308},
      {"sinh", [](double x) { return std::sinh(x); }, sinhl, -710, 710},
      {"cosh", [](double x) { return std::cosh(x); }, coshl, -710, 710},
      {"tanh", [](double x) { return std::tanh(x); }, tanhl, -20, 20},
      {"asinh", [](double x) { return std::asinh(x); }, asinhl, -1e300, 1e300},
      {"acosh", [](double x) { return std::acosh(x); }, acoshl, 1, 1e300},
      {"atanh", [](double x) { return std::atanh(x); }, atanhl, -0.99, 0.99},
      {"erf", [](double x) { return std::erf(x); }, erfl, -5, 5},
  };
  for (const Case& c : cases) {
    double worst = 0, at = 0;
    const int n = 20000;
    for (int i = 0; i <= n; ++i) {
      // Spread over the range, geometrically where it spans many orders of magnitude.
      const double t = static_cast<double>(i) / n;
      double x;
      if (c.lo > 0 && c.hi / c.lo > 1e6) {
        x = c.lo * std::pow(c.hi / c.lo, t);
      } else if (c.hi - c.lo > 1e6) {
        const double m = std::max(-c.lo, c.hi), s = 2 * t - 1;
        x = (s < 0 ? -1 : 1) * std::pow(m, std::fabs(s));
      } else {
        x = c.lo + (c.hi - c.lo) * t;
      }
      x = std::max(c.lo, std::min(c.hi, x));
      const double got = c.f(opaque(x));
      const long double want = c.ref(static_cast<long double>(x));
      if (!std::isfinite(static_cast<double>(want))) continue;  // beyond the doubles
      ASSERT_TRUE(std::isfinite(got)) << c.name << "(" << x << ") = " << got;
      const double e = ulps(got, want);
      if (e > worst) worst = e, at = x;
    }
    EXPECT_LE(worst, 4.0) << c.name << ": " << worst << " ulp at " << at;
  }
}

TEST(PortableMath, SpecialValues) {
  const double inf = std::numeric_limits<double>::infinity();
  const double z = opaque(0.0), nz = opaque(-0.0), one = opaque(1.0);
  EXPECT_EQ(std::log(z), -inf);
  EXPECT_TRUE(std::isnan(std::log(-one)));
  EXPECT_EQ(std::exp(-inf * one), 0.0);
  EXPECT_EQ(std::exp(inf * one), inf);
  EXPECT_EQ(std::exp(opaque(1000.0)), inf);
  EXPECT_EQ(std::atan2(z, nz), M_PI);
  EXPECT_EQ(std::atan2(nz, nz), -M_PI);
  EXPECT_TRUE(std::signbit(std::atan2(nz, one)));
  EXPECT_EQ(std::pow(z, z), 1.0);
  EXPECT_EQ(std::pow(opaque(-2.0), opaque(3.0)), -8.0);
  EXPECT_TRUE(std::isnan(std::pow(opaque(-8.0), opaque(1.0 / 3.0))));
  EXPECT_EQ(std::sinh(-inf * one), -inf);
  EXPECT_EQ(std::cosh(-inf * one), inf);
  EXPECT_EQ(std::asinh(-inf * one), -inf);
  EXPECT_TRUE(std::isnan(std::sinh(std::nan("") * one)));
  EXPECT_TRUE(std::isnan(std::log1p(std::nan("") * one)));
  EXPECT_TRUE(std::isnan(std::acosh(opaque(0.5))));
  double s = 0, c = 0;
  for (double x : {0.3, 2.0, -7.5, 1e6}) {
    sincos(opaque(x), &s, &c);
    EXPECT_NEAR(s, std::sin(x), 4e-16 * std::fabs(std::sin(x)) + 1e-300) << x;
    EXPECT_NEAR(c, std::cos(x), 4e-16 * std::fabs(std::cos(x)) + 1e-300) << x;
  }
}

// core/paired_math.h: two values at once (SLEEF's SSE2 builds on x86-64), bit for bit
// what the process's std::exp, std::log and std::atan2 give one at a time, over the
// whole range, with the special values; the angle sweeps' energy depends on it.
TEST(PortableMath, PairsGiveTheBitsOfSingleCalls) {
  std::uint64_t state = 88172645463325252ull;
  auto uniform = [&](double lo, double hi) {
    state ^= state << 13, state ^= state >> 7, state ^= state << 17;
    return lo + (hi - lo) * static_cast<double>(state >> 11) / 9007199254740992.0;
  };
  const double inf = std::numeric_limits<double>::infinity(), nan = std::nan("");
  std::vector<double> xs = {
      0.0,     -0.0,   1.0,    -1.0, 709.78, 709.79, -745.2,
      -745.13, 1e-300, 5e-324, inf,  -inf,   nan,    std::numeric_limits<double>::max()};
  for (int i = 0; i < 200000; ++i) {
    xs.push_back(uniform(-750, 750));
    xs.push_back(uniform(-40, 40));
    xs.push_back(std::ldexp(uniform(0.5, 1), static_cast<int>(uniform(-1070, 1024))));
  }
  int compared = 0;
  for (std::size_t i = 0; i + 1 < xs.size(); ++i) {
    const double a = opaque(xs[i]), b = opaque(xs[xs.size() - 1 - i]);
    double ea, eb, la, lb, ta, tb;
    isoquad::exp_pair(a, b, ea, eb);
    isoquad::log_pair(a, b, la, lb);
    isoquad::atan2_pair(a, b, b, a, ta, tb);
    ASSERT_EQ(bits(ea), bits(std::exp(a))) << a;
    ASSERT_EQ(bits(eb), bits(std::exp(b))) << b;
    ASSERT_EQ(bits(la), bits(std::log(a))) << a;
    ASSERT_EQ(bits(lb), bits(std::log(b))) << b;
    ASSERT_EQ(bits(ta), bits(std::atan2(a, b))) << a << " " << b;
    ASSERT_EQ(bits(tb), bits(std::atan2(b, a))) << b << " " << a;
    ++compared;
  }
  EXPECT_GT(compared, 600000);
}
