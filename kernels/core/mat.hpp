// Fixed-size square matrix Mat<D, Real> (row-major) and the tensor
// operations of finite-strain mechanics: det, inverse, transpose, products,
// trace, deviator, outer and double-contraction products. D = 2 or 3 for
// tensors (closed-form det and inverse); any D up to kMaxSmallSize for the
// small systems of meshfree methods, such as RKPM's (D + 1) x (D + 1) moment
// matrices (det and inverse by Gauss-Jordan elimination with partial pivoting,
// kernels/core/small_solve.hpp).
#pragma once
#include "kernels/core/vec.hpp"

namespace mfsd {

template <int D, class Real>
struct Mat {
  static_assert(D >= 1 && D <= kMaxSmallSize, "Mat<D>: 1 <= D <= kMaxSmallSize");
  Real m[D][D];

  MFSD_HD static Mat zero() {
    Mat r;
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) r.m[a][b] = Real(0);
    return r;
  }
  MFSD_HD static Mat identity() { return diagonal(Real(1)); }
  MFSD_HD static Mat diagonal(Real s) {
    Mat r = zero();
    for (int a = 0; a < D; ++a) r.m[a][a] = s;
    return r;
  }
  MFSD_HD Real& operator()(int a, int b) { return m[a][b]; }
  MFSD_HD const Real& operator()(int a, int b) const { return m[a][b]; }

  MFSD_HD Mat& operator+=(const Mat& o) {
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) m[a][b] += o.m[a][b];
    return *this;
  }
  MFSD_HD Mat& operator-=(const Mat& o) {
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) m[a][b] -= o.m[a][b];
    return *this;
  }
  MFSD_HD Mat& operator*=(Real s) {
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) m[a][b] *= s;
    return *this;
  }
  // Adds s to the diagonal (A + s I).
  MFSD_HD Mat& add_diagonal(Real s) {
    for (int a = 0; a < D; ++a) m[a][a] += s;
    return *this;
  }
};

template <int D, class Real>
MFSD_HD inline Mat<D, Real> operator+(Mat<D, Real> a, const Mat<D, Real>& b) {
  return a += b;
}
template <int D, class Real>
MFSD_HD inline Mat<D, Real> operator-(Mat<D, Real> a, const Mat<D, Real>& b) {
  return a -= b;
}
template <int D, class Real>
MFSD_HD inline Mat<D, Real> operator*(Mat<D, Real> a, Real s) {
  return a *= s;
}
template <int D, class Real>
MFSD_HD inline Mat<D, Real> operator*(Real s, Mat<D, Real> a) {
  return a *= s;
}

// Matrix product A B.
template <int D, class Real>
MFSD_HD inline Mat<D, Real> operator*(const Mat<D, Real>& A, const Mat<D, Real>& B) {
  Mat<D, Real> C;
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) {
      Real s = A.m[a][0] * B.m[0][b];
      for (int k = 1; k < D; ++k) s += A.m[a][k] * B.m[k][b];
      C.m[a][b] = s;
    }
  return C;
}

// Matrix-vector product A v.
template <int D, class Real>
MFSD_HD inline Vec<D, Real> operator*(const Mat<D, Real>& A, const Vec<D, Real>& v) {
  Vec<D, Real> r;
  for (int a = 0; a < D; ++a) {
    Real s = A.m[a][0] * v.v[0];
    for (int k = 1; k < D; ++k) s += A.m[a][k] * v.v[k];
    r.v[a] = s;
  }
  return r;
}

template <int D, class Real>
MFSD_HD inline Mat<D, Real> transpose(const Mat<D, Real>& A) {
  Mat<D, Real> T;
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) T.m[a][b] = A.m[b][a];
  return T;
}

// A B^T without forming the transpose.
template <int D, class Real>
MFSD_HD inline Mat<D, Real> mul_transposed(const Mat<D, Real>& A, const Mat<D, Real>& B) {
  Mat<D, Real> C;
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) {
      Real s = A.m[a][0] * B.m[b][0];
      for (int k = 1; k < D; ++k) s += A.m[a][k] * B.m[b][k];
      C.m[a][b] = s;
    }
  return C;
}

// a (x) b, the dyadic product: (a (x) b)_kl = a_k b_l.
template <int D, class Real>
MFSD_HD inline Mat<D, Real> outer(const Vec<D, Real>& a, const Vec<D, Real>& b) {
  Mat<D, Real> C;
  for (int k = 0; k < D; ++k)
    for (int l = 0; l < D; ++l) C.m[k][l] = a.v[k] * b.v[l];
  return C;
}

template <int D, class Real>
MFSD_HD inline Real trace(const Mat<D, Real>& A) {
  Real s = A.m[0][0];
  for (int a = 1; a < D; ++a) s += A.m[a][a];
  return s;
}

// Deviator in the dimension of the problem: A - tr(A)/D I (formulations.md).
template <int D, class Real>
MFSD_HD inline Mat<D, Real> deviator(Mat<D, Real> A) {
  return A.add_diagonal(-trace(A) / Real(D));
}

// A : B = sum_kl A_kl B_kl.
template <int D, class Real>
MFSD_HD inline Real ddot(const Mat<D, Real>& A, const Mat<D, Real>& B) {
  Real s = Real(0);
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) s += A.m[a][b] * B.m[a][b];
  return s;
}

template <class Real>
MFSD_HD inline Real det(const Mat<2, Real>& A) {
  return A.m[0][0] * A.m[1][1] - A.m[0][1] * A.m[1][0];
}
template <class Real>
MFSD_HD inline Real det(const Mat<3, Real>& A) {
  return A.m[0][0] * (A.m[1][1] * A.m[2][2] - A.m[1][2] * A.m[2][1]) -
         A.m[0][1] * (A.m[1][0] * A.m[2][2] - A.m[1][2] * A.m[2][0]) +
         A.m[0][2] * (A.m[1][0] * A.m[2][1] - A.m[1][1] * A.m[2][0]);
}

// Inverse by the adjugate. The caller guarantees det(A) != 0.
template <class Real>
MFSD_HD inline Mat<2, Real> inverse(const Mat<2, Real>& A) {
  const Real inv_det = Real(1) / det(A);
  Mat<2, Real> R;
  R.m[0][0] = A.m[1][1] * inv_det;
  R.m[0][1] = -A.m[0][1] * inv_det;
  R.m[1][0] = -A.m[1][0] * inv_det;
  R.m[1][1] = A.m[0][0] * inv_det;
  return R;
}
template <class Real>
MFSD_HD inline Mat<3, Real> inverse(const Mat<3, Real>& A) {
  Mat<3, Real> R;
  R.m[0][0] = A.m[1][1] * A.m[2][2] - A.m[1][2] * A.m[2][1];
  R.m[0][1] = A.m[0][2] * A.m[2][1] - A.m[0][1] * A.m[2][2];
  R.m[0][2] = A.m[0][1] * A.m[1][2] - A.m[0][2] * A.m[1][1];
  R.m[1][0] = A.m[1][2] * A.m[2][0] - A.m[1][0] * A.m[2][2];
  R.m[1][1] = A.m[0][0] * A.m[2][2] - A.m[0][2] * A.m[2][0];
  R.m[1][2] = A.m[0][2] * A.m[1][0] - A.m[0][0] * A.m[1][2];
  R.m[2][0] = A.m[1][0] * A.m[2][1] - A.m[1][1] * A.m[2][0];
  R.m[2][1] = A.m[0][1] * A.m[2][0] - A.m[0][0] * A.m[2][1];
  R.m[2][2] = A.m[0][0] * A.m[1][1] - A.m[0][1] * A.m[1][0];
  const Real inv_det = Real(1) / (A.m[0][0] * R.m[0][0] + A.m[0][1] * R.m[1][0] + A.m[0][2] * R.m[2][0]);
  return R *= inv_det;
}

template <int D, class Real>
MFSD_HD inline Real frobenius_norm(const Mat<D, Real>& A) {
  return math::sqrt(ddot(A, A));
}

template <class To, int D, class From>
MFSD_HD inline Mat<D, To> cast(const Mat<D, From>& A) {
  Mat<D, To> R;
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) R.m[a][b] = To(A.m[a][b]);
  return R;
}

}  // namespace mfsd
