// Spectral norm of F^{-1}, i.e. 1 / (smallest principal stretch of F): how
// much faster than c0 a wave crosses the reference configuration where the
// body is compressed most (the Lagrangian wave speed along a direction whose
// stretch is lambda is about c0 / lambda). Computed as the square root of the
// largest eigenvalue of F^{-1} F^{-T} (closed form: 2-D quadratic, 3-D
// trigonometric solution of the characteristic cubic), which is well
// conditioned where it matters (a large eigenvalue).
#pragma once
#include "kernels/core/mat.hpp"

namespace mfsd {

template <class Real>
MFSD_HD inline Real largest_eigenvalue_symmetric(const Mat<2, Real>& A) {
  const Real m = Real(0.5) * (A.m[0][0] + A.m[1][1]);
  const Real d = Real(0.5) * (A.m[0][0] - A.m[1][1]);
  return m + math::sqrt(d * d + A.m[0][1] * A.m[1][0]);
}

template <class Real>
MFSD_HD inline Real largest_eigenvalue_symmetric(const Mat<3, Real>& A) {
  const Real off = A.m[0][1] * A.m[0][1] + A.m[0][2] * A.m[0][2] + A.m[1][2] * A.m[1][2];
  const Real q = trace(A) / Real(3);
  const Real d0 = A.m[0][0] - q, d1 = A.m[1][1] - q, d2 = A.m[2][2] - q;
  const Real p2 = d0 * d0 + d1 * d1 + d2 * d2 + Real(2) * off;
  const Real p = math::sqrt(p2 / Real(6));
  // A multiple of I, or so close to one that p^3 below would underflow (ahead
  // of a wave front the SPH sums leave F = I + 1e-160 and the like, and
  // det(B)/p^3 became 0/0): the largest eigenvalue lies in [q - p, q + 2 p].
  if (!(p > Real(1e-6) * math::fabs(q))) return q + Real(2) * p;
  Mat<3, Real> B = A;
  B.add_diagonal(-q);
  const Real r = math::clamp(det(B) / (Real(2) * p * p * p), Real(-1), Real(1));
  return q + Real(2) * p * math::cos(math::acos(r) / Real(3));
}

template <int D, class Real>
MFSD_HD inline Real inverse_stretch(const Mat<D, Real>& F) {
  const Mat<D, Real> F_inv = inverse(F);
  return math::sqrt(math::max(largest_eigenvalue_symmetric(mul_transposed(F_inv, F_inv)), Real(0)));
}

}  // namespace mfsd
