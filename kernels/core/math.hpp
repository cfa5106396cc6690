// Scalar math usable on host and device for float and double. Kernels call
// these instead of std:: functions, which lack device overloads.
#pragma once
#include <cmath>

#include "kernels/core/config.hpp"

namespace mfsd::math {

#define MFSD_UNARY(name, fname)                                       \
  MFSD_HD MFSD_FORCEINLINE float name(float x) { return ::fname(x); } \
  MFSD_HD MFSD_FORCEINLINE double name(double x) { return ::name(x); }
MFSD_UNARY(sqrt, sqrtf)
MFSD_UNARY(cbrt, cbrtf)
MFSD_UNARY(fabs, fabsf)
MFSD_UNARY(exp, expf)
MFSD_UNARY(expm1, expm1f)
MFSD_UNARY(log, logf)
MFSD_UNARY(log10, log10f)
MFSD_UNARY(sin, sinf)
MFSD_UNARY(cos, cosf)
MFSD_UNARY(tan, tanf)
MFSD_UNARY(asin, asinf)
MFSD_UNARY(acos, acosf)
MFSD_UNARY(atan, atanf)
MFSD_UNARY(sinh, sinhf)
MFSD_UNARY(cosh, coshf)
MFSD_UNARY(tanh, tanhf)
MFSD_UNARY(floor, floorf)
MFSD_UNARY(ceil, ceilf)
#undef MFSD_UNARY

MFSD_HD MFSD_FORCEINLINE float pow(float x, float y) { return ::powf(x, y); }
MFSD_HD MFSD_FORCEINLINE double pow(double x, double y) { return ::pow(x, y); }
MFSD_HD MFSD_FORCEINLINE float atan2(float y, float x) { return ::atan2f(y, x); }
MFSD_HD MFSD_FORCEINLINE double atan2(double y, double x) { return ::atan2(y, x); }

#if defined(__CUDA_ARCH__)
MFSD_HD MFSD_FORCEINLINE bool isfinite(float x) { return ::isfinite(x); }
MFSD_HD MFSD_FORCEINLINE bool isfinite(double x) { return ::isfinite(x); }
#else
MFSD_HD MFSD_FORCEINLINE bool isfinite(float x) { return std::isfinite(x); }
MFSD_HD MFSD_FORCEINLINE bool isfinite(double x) { return std::isfinite(x); }
#endif

template <class T>
MFSD_HD MFSD_FORCEINLINE T min(T a, T b) {
  return b < a ? b : a;
}
template <class T>
MFSD_HD MFSD_FORCEINLINE T max(T a, T b) {
  return a < b ? b : a;
}
template <class T>
MFSD_HD MFSD_FORCEINLINE T clamp(T x, T lo, T hi) {
  return x < lo ? lo : (hi < x ? hi : x);
}
template <class T>
MFSD_HD MFSD_FORCEINLINE T sqr(T x) {
  return x * x;
}

template <class Real>
inline constexpr Real pi = Real(3.14159265358979323846);

}  // namespace mfsd::math
