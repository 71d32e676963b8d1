// The same elementary functions on every x86-64 CPU, for the whole process.
//
// glibc's libm picks, when a program starts, one of several builds of exp, log, pow,
// sin, cos, tan, atan, atan2, asin, acos and a few float functions: one for CPUs with
// FMA and AVX2, one for AVX, one for plain SSE2; the functions built on them (log10,
// log1p, expm1, sinh, erf and the like) follow. Their results differ in the last bit
// for about one argument in a thousand, and over a run of millions of calls
// that is enough to change a mesh: France at a uniform 3 km gave 57,472 quads on this
// machine and 57,471 with the SSE2 builds (GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2,-FMA,
// -AVX), and the domain of Corsica moved one vertex in its last bits. The same input
// must give the same files on a user's laptop and on the CI machine that checks them.
//
// So every executable defines these functions itself, as SLEEF's deterministic pure-C
// builds ("cinz": no FMA, the same result on every platform): the faster build where
// SLEEF has two (within 3.5 ulp of the exact value: sin, cos, atan2, log...), else the
// one within 1 ulp (exp, pow, expm1...). With the 1-ulp builds of atan2 and log too,
// France automatic took 17% more time than with glibc's functions; with these, 3 to 5%
// (and the smoothing's hottest calls now go two at a time: core/paired_math.h).
// The executable's definitions interpose libm's for the whole process: isoquad's code,
// and PROJ, GEOS, GDAL and CGAL as they call them (the linker exports them from the
// executable, as shared libraries it links use them). A CLI test runs the binary with
// and without glibc's other builds and compares the bytes. The functions that gave the
// same bits with every build (sqrt, hypot, cbrt, floor and the like, which are exact or
// built once) are left to glibc, and so are lgamma and tgamma (lgamma also sets
// signgam). Unlike glibc's, these never set errno; isoquad never reads it after one.
#include <sleef.h>

#define ISOQUAD_MATH1(name, T, sleef) \
  extern "C" T name(T x) noexcept {   \
    return sleef(x);                  \
  }
#define ISOQUAD_MATH2(name, T, sleef)    \
  extern "C" T name(T x, T y) noexcept { \
    return sleef(x, y);                  \
  }
#define ISOQUAD_SINCOS(name, T, sleef)             \
  extern "C" void name(T x, T* s, T* c) noexcept { \
    const auto r = sleef(x);                       \
    *s = r.x;                                      \
    *c = r.y;                                      \
  }

ISOQUAD_MATH1(sin, double, Sleef_cinz_sind1_u35purec)
ISOQUAD_MATH1(cos, double, Sleef_cinz_cosd1_u35purec)
ISOQUAD_MATH1(tan, double, Sleef_cinz_tand1_u35purec)
ISOQUAD_MATH1(asin, double, Sleef_cinz_asind1_u35purec)
ISOQUAD_MATH1(acos, double, Sleef_cinz_acosd1_u35purec)
ISOQUAD_MATH1(atan, double, Sleef_cinz_atand1_u35purec)
ISOQUAD_MATH1(exp, double, Sleef_cinz_expd1_u10purec)
ISOQUAD_MATH1(exp2, double, Sleef_cinz_exp2d1_u35purec)
ISOQUAD_MATH1(expm1, double, Sleef_cinz_expm1d1_u10purec)
ISOQUAD_MATH1(log, double, Sleef_cinz_logd1_u35purec)
ISOQUAD_MATH1(log2, double, Sleef_cinz_log2d1_u35purec)
ISOQUAD_MATH1(log10, double, Sleef_cinz_log10d1_u10purec)
ISOQUAD_MATH1(exp10, double, Sleef_cinz_exp10d1_u35purec)
ISOQUAD_MATH1(tanh, double, Sleef_cinz_tanhd1_u35purec)
ISOQUAD_MATH1(atanh, double, Sleef_cinz_atanhd1_u10purec)
ISOQUAD_MATH1(erf, double, Sleef_cinz_erfd1_u10purec)
ISOQUAD_MATH1(erfc, double, Sleef_cinz_erfcd1_u15purec)

// SLEEF's builds of these overflow before the result does (asinh and acosh above about
// 1.3e154, log1p near the largest double, sinh and cosh above about 709.7, where the
// results are still finite); there the identities below take over, exact to a few ulp
// (asinh x = log 2x + 1/(4x^2) + ..., log1p x = log x + 1/x - ...).
namespace {
constexpr double kLn2 = 0.69314718055994530942;
double exp_half_squared(double x) {  // e^|x| / 2 without overflowing before it must
  const double t = Sleef_cinz_expd1_u10purec(0.5 * __builtin_fabs(x));
  return 0.5 * t * t;
}
}  // namespace

extern "C" double log1p(double x) noexcept {
  return x > 1e300 ? Sleef_cinz_logd1_u35purec(x) : Sleef_cinz_log1pd1_u10purec(x);
}
extern "C" double asinh(double x) noexcept {
  if (__builtin_fabs(x) <= 1e150) return Sleef_cinz_asinhd1_u10purec(x);
  return __builtin_copysign(Sleef_cinz_logd1_u35purec(__builtin_fabs(x)) + kLn2, x);
}
extern "C" double acosh(double x) noexcept {
  return x > 1e150 ? Sleef_cinz_logd1_u35purec(x) + kLn2 : Sleef_cinz_acoshd1_u10purec(x);
}
extern "C" double sinh(double x) noexcept {
  if (__builtin_fabs(x) <= 709.0) return Sleef_cinz_sinhd1_u35purec(x);
  return __builtin_copysign(exp_half_squared(x), x);
}
extern "C" double cosh(double x) noexcept {
  return __builtin_fabs(x) <= 709.0 ? Sleef_cinz_coshd1_u35purec(x) : exp_half_squared(x);
}
ISOQUAD_MATH2(atan2, double, Sleef_cinz_atan2d1_u35purec)
ISOQUAD_MATH2(pow, double, Sleef_cinz_powd1_u10purec)
ISOQUAD_SINCOS(sincos, double, Sleef_cinz_sincosd1_u35purec)

ISOQUAD_MATH1(sinf, float, Sleef_cinz_sinf1_u35purec)
ISOQUAD_MATH1(cosf, float, Sleef_cinz_cosf1_u35purec)
ISOQUAD_MATH1(tanf, float, Sleef_cinz_tanf1_u35purec)
ISOQUAD_MATH1(expf, float, Sleef_cinz_expf1_u10purec)
ISOQUAD_MATH1(exp2f, float, Sleef_cinz_exp2f1_u35purec)
ISOQUAD_MATH1(logf, float, Sleef_cinz_logf1_u35purec)
ISOQUAD_MATH1(log2f, float, Sleef_cinz_log2f1_u35purec)

ISOQUAD_MATH2(atan2f, float, Sleef_cinz_atan2f1_u35purec)
ISOQUAD_MATH2(powf, float, Sleef_cinz_powf1_u10purec)
ISOQUAD_SINCOS(sincosf, float, Sleef_cinz_sincosf1_u35purec)
