// Determinant, inverse and linear solve of a small Mat<N, Real> of any size
// (kernels/core/mat.hpp) by Gauss-Jordan elimination with partial pivoting,
// in registers, for host and device code: RKPM's moment matrices
// (../shared/reference/rkpm.md), which are symmetric positive definite when
// the support holds enough particles and near singular when it does not.
// Each returns whether the matrix was invertible: a pivot smaller than
// `tiny` times the largest entry of its column marks it singular (the caller
// then falls back, as RKPM's quasi-linear fallback does). Mat<2> and Mat<3>
// keep their closed forms in mat.hpp for the tensors of mechanics.
#pragma once
#include "kernels/core/mat.hpp"

namespace mfsd {

// x with A x = b; false (x unchanged) when A is singular to `tiny`.
template <int N, class Real>
MFSD_HD inline bool solve(Mat<N, Real> A, Vec<N, Real> b, Vec<N, Real>& x, Real tiny = Real(1e-12)) {
  for (int c = 0; c < N; ++c) {
    int p = c;
    Real best = math::fabs(A.m[c][c]), scale = Real(0);
    for (int r = c; r < N; ++r) {
      const Real v = math::fabs(A.m[r][c]);
      scale = math::max(scale, v);
      if (v > best) best = v, p = r;
    }
    if (!(best > tiny * scale) || best == Real(0)) return false;
    if (p != c) {
      for (int k = 0; k < N; ++k) {
        const Real t = A.m[c][k];
        A.m[c][k] = A.m[p][k];
        A.m[p][k] = t;
      }
      const Real t = b.v[c];
      b.v[c] = b.v[p];
      b.v[p] = t;
    }
    const Real inv = Real(1) / A.m[c][c];
    for (int r = 0; r < N; ++r) {
      if (r == c) continue;
      const Real f = A.m[r][c] * inv;
      if (f == Real(0)) continue;
      for (int k = c; k < N; ++k) A.m[r][k] -= f * A.m[c][k];
      b.v[r] -= f * b.v[c];
    }
  }
  for (int r = 0; r < N; ++r) x.v[r] = b.v[r] / A.m[r][r];
  return true;
}

// A^-1 into `inverse_out`; false (unchanged) when A is singular to `tiny`.
template <int N, class Real>
MFSD_HD inline bool try_inverse(Mat<N, Real> A, Mat<N, Real>& inverse_out, Real tiny = Real(1e-12)) {
  Mat<N, Real> R = Mat<N, Real>::identity();
  for (int c = 0; c < N; ++c) {
    int p = c;
    Real best = math::fabs(A.m[c][c]), scale = Real(0);
    for (int r = c; r < N; ++r) {
      const Real v = math::fabs(A.m[r][c]);
      scale = math::max(scale, v);
      if (v > best) best = v, p = r;
    }
    if (!(best > tiny * scale) || best == Real(0)) return false;
    if (p != c)
      for (int k = 0; k < N; ++k) {
        Real t = A.m[c][k];
        A.m[c][k] = A.m[p][k];
        A.m[p][k] = t;
        t = R.m[c][k];
        R.m[c][k] = R.m[p][k];
        R.m[p][k] = t;
      }
    const Real inv = Real(1) / A.m[c][c];
    for (int k = 0; k < N; ++k) {
      A.m[c][k] *= inv;
      R.m[c][k] *= inv;
    }
    for (int r = 0; r < N; ++r) {
      if (r == c) continue;
      const Real f = A.m[r][c];
      if (f == Real(0)) continue;
      for (int k = 0; k < N; ++k) {
        A.m[r][k] -= f * A.m[c][k];
        R.m[r][k] -= f * R.m[c][k];
      }
    }
  }
  inverse_out = R;
  return true;
}

// det A by elimination with partial pivoting (0 for an exactly singular A).
template <int N, class Real>
MFSD_HD inline Real det_by_elimination(Mat<N, Real> A) {
  Real d = Real(1);
  for (int c = 0; c < N; ++c) {
    int p = c;
    for (int r = c + 1; r < N; ++r)
      if (math::fabs(A.m[r][c]) > math::fabs(A.m[p][c])) p = r;
    if (A.m[p][c] == Real(0)) return Real(0);
    if (p != c) {
      for (int k = 0; k < N; ++k) {
        const Real t = A.m[c][k];
        A.m[c][k] = A.m[p][k];
        A.m[p][k] = t;
      }
      d = -d;
    }
    d *= A.m[c][c];
    for (int r = c + 1; r < N; ++r) {
      const Real f = A.m[r][c] / A.m[c][c];
      for (int k = c; k < N; ++k) A.m[r][k] -= f * A.m[c][k];
    }
  }
  return d;
}

}  // namespace mfsd
