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

#if defined(__x86_64__)
namespace paired_math_detail {
inline void split(__m128d r, double& ra, double& rb) {
  ra = _mm_cvtsd_f64(r);
  rb = _mm_cvtsd_f64(_mm_unpackhi_pd(r, r));
}
}  // namespace paired_math_detail
#endif

// ea = exp(a), eb = exp(b), exactly as std::exp gives them in this process.
inline void exp_pair(double a, double b, double& ea, double& eb) {
#if defined(__x86_64__)
  paired_math_detail::split(Sleef_cinz_expd2_u10sse2(_mm_set_pd(b, a)), ea, eb);
#else
  ea = Sleef_cinz_expd1_u10purec(a);
  eb = Sleef_cinz_expd1_u10purec(b);
#endif
}

// la = log(a), lb = log(b), exactly as std::log gives them in this process.
inline void log_pair(double a, double b, double& la, double& lb) {
#if defined(__x86_64__)
  paired_math_detail::split(Sleef_cinz_logd2_u35sse2(_mm_set_pd(b, a)), la, lb);
#else
  la = Sleef_cinz_logd1_u35purec(a);
  lb = Sleef_cinz_logd1_u35purec(b);
#endif
}

// ta = atan2(ya, xa), tb = atan2(yb, xb), exactly as std::atan2 gives them in this process.
inline void atan2_pair(double ya, double xa, double yb, double xb, double& ta, double& tb) {
#if defined(__x86_64__)
  paired_math_detail::split(Sleef_cinz_atan2d2_u35sse2(_mm_set_pd(yb, ya), _mm_set_pd(xb, xa)), ta,
                            tb);
#else
  ta = Sleef_cinz_atan2d1_u35purec(ya, xa);
  tb = Sleef_cinz_atan2d1_u35purec(yb, xb);
#endif
}

}  // namespace isoquad
