// Fixed-size vector Vec<D, Real> for host and device code: D = 2 or 3 for
// positions and velocities, up to kMaxSmallSize for the small systems of
// meshfree methods (RKPM's linear basis in 3-D: D + 1 = 4).
#pragma once
#include "kernels/core/config.hpp"
#include "kernels/core/math.hpp"

namespace mfsd {

// The largest Vec / Mat size: RKPM's quadratic basis in 2-D has 6 terms,
// its linear basis in 3-D 4; beyond 8 a fixed-size type in registers stops
// paying (a kernel then wants shared memory or a library).
inline constexpr int kMaxSmallSize = 8;

template <int D, class Real>
struct Vec {
  static_assert(D >= 1 && D <= kMaxSmallSize, "Vec<D>: 1 <= D <= kMaxSmallSize");
  Real v[D];

  MFSD_HD static Vec zero() {
    Vec r;
    for (int a = 0; a < D; ++a) r.v[a] = Real(0);
    return r;
  }
  MFSD_HD static Vec constant(Real c) {
    Vec r;
    for (int a = 0; a < D; ++a) r.v[a] = c;
    return r;
  }
  MFSD_HD Real& operator[](int a) { return v[a]; }
  MFSD_HD const Real& operator[](int a) const { return v[a]; }

  MFSD_HD Vec& operator+=(const Vec& o) {
    for (int a = 0; a < D; ++a) v[a] += o.v[a];
    return *this;
  }
  MFSD_HD Vec& operator-=(const Vec& o) {
    for (int a = 0; a < D; ++a) v[a] -= o.v[a];
    return *this;
  }
  MFSD_HD Vec& operator*=(Real s) {
    for (int a = 0; a < D; ++a) v[a] *= s;
    return *this;
  }
};

template <int D, class Real>
MFSD_HD inline Vec<D, Real> operator+(Vec<D, Real> a, const Vec<D, Real>& b) {
  return a += b;
}
template <int D, class Real>
MFSD_HD inline Vec<D, Real> operator-(Vec<D, Real> a, const Vec<D, Real>& b) {
  return a -= b;
}
template <int D, class Real>
MFSD_HD inline Vec<D, Real> operator-(Vec<D, Real> a) {
  for (int k = 0; k < D; ++k) a.v[k] = -a.v[k];
  return a;
}
template <int D, class Real>
MFSD_HD inline Vec<D, Real> operator*(Vec<D, Real> a, Real s) {
  return a *= s;
}
template <int D, class Real>
MFSD_HD inline Vec<D, Real> operator*(Real s, Vec<D, Real> a) {
  return a *= s;
}
template <int D, class Real>
MFSD_HD inline Vec<D, Real> operator/(Vec<D, Real> a, Real s) {
  return a *= (Real(1) / s);
}

template <int D, class Real>
MFSD_HD inline Real dot(const Vec<D, Real>& a, const Vec<D, Real>& b) {
  Real s = a.v[0] * b.v[0];
  for (int k = 1; k < D; ++k) s += a.v[k] * b.v[k];
  return s;
}
template <int D, class Real>
MFSD_HD inline Real squared_norm(const Vec<D, Real>& a) {
  return dot(a, a);
}
template <int D, class Real>
MFSD_HD inline Real norm(const Vec<D, Real>& a) {
  return math::sqrt(dot(a, a));
}
template <class Real>
MFSD_HD inline Vec<3, Real> cross(const Vec<3, Real>& a, const Vec<3, Real>& b) {
  return Vec<3, Real>{
      {a.v[1] * b.v[2] - a.v[2] * b.v[1], a.v[2] * b.v[0] - a.v[0] * b.v[2], a.v[0] * b.v[1] - a.v[1] * b.v[0]}};
}

// Conversion between precisions (host set-up in double, kernels in Real).
template <class To, int D, class From>
MFSD_HD inline Vec<D, To> cast(const Vec<D, From>& a) {
  Vec<D, To> r;
  for (int k = 0; k < D; ++k) r.v[k] = To(a.v[k]);
  return r;
}

}  // namespace mfsd
