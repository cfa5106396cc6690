// Eigen-decomposition of a symmetric matrix, A = Q diag(lambda) Q^T, with the
// eigenvectors in the columns of Q (orthonormal). Cyclic Jacobi rotations:
// branch-light, no recursion, accurate to round-off for D = 2 and 3.
#pragma once
#include "kernels/core/mat.hpp"

namespace mfsd {

template <int D, class Real>
struct SymmetricEigen {
  Vec<D, Real> values;
  Mat<D, Real> vectors;  // column k is the eigenvector of values[k]
};

namespace detail {
// One Jacobi rotation annihilating A(p,q); accumulates the rotation into Q.
template <int D, class Real>
MFSD_HD inline void jacobi_rotate(Mat<D, Real>& A, Mat<D, Real>& Q, int p, int q) {
  const Real apq = A.m[p][q];
  if (apq == Real(0)) return;
  const Real theta = (A.m[q][q] - A.m[p][p]) / (Real(2) * apq);
  // t = tan of the rotation angle, the smaller root for stability.
  const Real sign = theta >= Real(0) ? Real(1) : Real(-1);
  const Real t = sign / (math::fabs(theta) + math::sqrt(theta * theta + Real(1)));
  const Real c = Real(1) / math::sqrt(t * t + Real(1));
  const Real s = t * c;
  for (int k = 0; k < D; ++k) {  // A <- A J
    const Real akp = A.m[k][p], akq = A.m[k][q];
    A.m[k][p] = c * akp - s * akq;
    A.m[k][q] = s * akp + c * akq;
  }
  for (int k = 0; k < D; ++k) {  // A <- J^T A
    const Real apk = A.m[p][k], aqk = A.m[q][k];
    A.m[p][k] = c * apk - s * aqk;
    A.m[q][k] = s * apk + c * aqk;
  }
  A.m[p][q] = A.m[q][p] = Real(0);
  for (int k = 0; k < D; ++k) {  // Q <- Q J
    const Real qkp = Q.m[k][p], qkq = Q.m[k][q];
    Q.m[k][p] = c * qkp - s * qkq;
    Q.m[k][q] = s * qkp + c * qkq;
  }
}
}  // namespace detail

// Only the symmetric part of A is used.
template <int D, class Real>
MFSD_HD inline SymmetricEigen<D, Real> eigen_symmetric(const Mat<D, Real>& A_in) {
  Mat<D, Real> A;
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) A.m[a][b] = Real(0.5) * (A_in.m[a][b] + A_in.m[b][a]);
  Mat<D, Real> Q = Mat<D, Real>::identity();
  Real scale = Real(0);
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) scale += A.m[a][b] * A.m[a][b];
  const Real tiny = scale * Real(1e-30);
  // Cyclic sweeps; quadratic convergence, 3-5 sweeps reach round-off.
  for (int sweep = 0; sweep < 12; ++sweep) {
    Real off = Real(0);
    for (int p = 0; p < D; ++p)
      for (int q = p + 1; q < D; ++q) off += A.m[p][q] * A.m[p][q];
    if (off <= tiny) break;
    for (int p = 0; p < D; ++p)
      for (int q = p + 1; q < D; ++q) detail::jacobi_rotate(A, Q, p, q);
  }
  SymmetricEigen<D, Real> r;
  for (int a = 0; a < D; ++a) r.values.v[a] = A.m[a][a];
  r.vectors = Q;
  return r;
}

// Q diag(lambda) Q^T.
template <int D, class Real>
MFSD_HD inline Mat<D, Real> compose_symmetric(const Vec<D, Real>& lambda, const Mat<D, Real>& Q) {
  Mat<D, Real> R = Mat<D, Real>::zero();
  for (int k = 0; k < D; ++k)
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) R.m[a][b] += Q.m[a][k] * lambda.v[k] * Q.m[b][k];
  return R;
}

}  // namespace mfsd
