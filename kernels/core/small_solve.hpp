// Determinant, inverse and linear solve of a small Mat<N, Real> of any size
// (kernels/core/mat.hpp) by Gauss-Jordan elimination with partial pivoting,
// in registers, for host and device code: RKPM's moment matrices
// (../shared/reference/rkpm.md), which are symmetric positive definite when
// the support holds enough particles and near singular when it does not.
// Each returns whether the matrix was invertible: a pivot not above `tiny`
// times the largest entry of the matrix marks it singular (the caller
// then falls back, as RKPM's quasi-linear fallback does). Mat<2> and Mat<3>
// keep their closed forms in mat.hpp for the tensors of mechanics.
#pragma once
#include "kernels/core/mat.hpp"

namespace mfsd {

// The largest |A_ij|: the scale a pivot is judged against.
template <int N, class Real>
MFSD_HD inline Real largest_entry(const Mat<N, Real>& A) {
  Real s = Real(0);
  for (int a = 0; a < N; ++a)
    for (int b = 0; b < N; ++b) s = math::max(s, math::fabs(A.m[a][b]));
  return s;
}

// The row r >= c with the largest |A_rc| (partial pivoting), or -1 when that
// entry is not above `threshold` (>= 0; a zero pivot never passes).
template <int N, class Real>
MFSD_HD inline int pivot_row(const Mat<N, Real>& A, int c, Real threshold) {
  int p = c;
  Real best = math::fabs(A.m[c][c]);
  for (int r = c + 1; r < N; ++r) {
    const Real v = math::fabs(A.m[r][c]);
    if (v > best) best = v, p = r;
  }
  return best > threshold ? p : -1;
}

template <int N, class Real>
MFSD_HD inline void swap_rows(Mat<N, Real>& A, int a, int b) {
  for (int k = 0; k < N; ++k) {
    const Real t = A.m[a][k];
    A.m[a][k] = A.m[b][k];
    A.m[b][k] = t;
  }
}

// x with A x = b; false (x unchanged) when A is singular to `tiny`.
template <int N, class Real>
MFSD_HD inline bool solve(Mat<N, Real> A, Vec<N, Real> b, Vec<N, Real>& x, Real tiny = Real(1e-12)) {
  const Real threshold = tiny * largest_entry(A);
  for (int c = 0; c < N; ++c) {
    const int p = pivot_row(A, c, threshold);
    if (p < 0) return false;
    if (p != c) {
      swap_rows(A, c, p);
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
  const Real threshold = tiny * largest_entry(A);
  for (int c = 0; c < N; ++c) {
    const int p = pivot_row(A, c, threshold);
    if (p < 0) return false;
    if (p != c) {
      swap_rows(A, c, p);
      swap_rows(R, c, p);
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
    const int p = pivot_row(A, c, Real(0));
    if (p < 0) return Real(0);
    if (p != c) {
      swap_rows(A, c, p);
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
