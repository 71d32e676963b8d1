// Elementary functions of two arguments at once, bit for bit what one call each gives.
//
// The process's exp, log and atan2 are SLEEF's deterministic pure-C builds
// (core/portable_math.cpp). On x86-64, SLEEF's deterministic SSE2 builds (SSE2 is in
// every x86-64 CPU; "cinz": the same results on every platform and vector extension)
// give the same bits for two arguments in about the time of one: exp 5.5 against 20 ns
// a value here. The angle sweeps' energy, the smoothing's hottest code, calls exp six
// times per quad, atan2 three times and log twice.
#pragma once

#include <sleef.h>

#if defined(__x86_64__)
#include <emmintrin.h>
#endif

namespace isoquad {

// exp_pair: ea = exp(a), eb = exp(b); log_pair: la = log(a), lb = log(b); atan2_pair:
// ta = atan2(ya, xa), tb = atan2(yb, xb); each exactly as std::exp, std::log and
// std::atan2 give them in this process.
#if defined(__x86_64__)
namespace paired_math_detail {
inline void split(__m128d r, double& ra, double& rb) {
  ra = _mm_cvtsd_f64(r);
  rb = _mm_cvtsd_f64(_mm_unpackhi_pd(r, r));
}
inline __m128d two(double a, double b) {
  return _mm_set_pd(b, a);
}
}  // namespace paired_math_detail

inline void exp_pair(double a, double b, double& ea, double& eb) {
  using namespace paired_math_detail;
  split(Sleef_cinz_expd2_u10sse2(two(a, b)), ea, eb);
}
inline void log_pair(double a, double b, double& la, double& lb) {
  using namespace paired_math_detail;
  split(Sleef_cinz_logd2_u35sse2(two(a, b)), la, lb);
}
inline void atan2_pair(double ya, double xa, double yb, double xb, double& ta, double& tb) {
  using namespace paired_math_detail;
  split(Sleef_cinz_atan2d2_u35sse2(two(ya, yb), two(xa, xb)), ta, tb);
}
#else
inline void exp_pair(double a, double b, double& ea, double& eb) {
  ea = Sleef_cinz_expd1_u10purec(a), eb = Sleef_cinz_expd1_u10purec(b);
}
inline void log_pair(double a, double b, double& la, double& lb) {
  la = Sleef_cinz_logd1_u35purec(a), lb = Sleef_cinz_logd1_u35purec(b);
}
inline void atan2_pair(double ya, double xa, double yb, double xb, double& ta, double& tb) {
  ta = Sleef_cinz_atan2d1_u35purec(ya, xa), tb = Sleef_cinz_atan2d1_u35purec(yb, xb);
}
#endif

}  // namespace isoquad
