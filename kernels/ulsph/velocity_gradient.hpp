// Kernel-gradient correction and velocity gradient of ULSPH (seed 002 eq. 20-21;
// formulations.md section 3, "Velocity gradient"), rebuilt with the neighbours
// in the current configuration:
//   A_i = -sum_j (x_i - x_j) (x) grad W_ij V_j = -sum_j grad_ij (x) grad_ij / stretch_ij,
//   B_i = A_i^{-1}                                                   (seed 002 eq. 21)
// (x_i - x_j = grad_ij / stretch_ij, pair_list.hpp; A_i is symmetric, ~I inside a
// full support), and
//   L_i = -sum_j (v_i - v_j) (x) (B_i grad_ij)                       (seed 002 eq. 20)
//       = -(v_i (x) G_i - sum_j v_j (x) grad_ij) B_i^T,   G_i = gradient_sum_i,
// so that L_ab = dv_a/dx_b (formulations.md section 3: not its transpose). A
// linear field v = M x + c gives L_i = M exactly at every particle whose A_i is
// invertible, surface particles included.
#pragma once
#include "kernels/core/mat.hpp"
#include "kernels/neighbors/pair_list.hpp"

namespace mfsd::ulsph {

// The moment matrix A_i whose inverse is the correction B_i.
template <int D, class Real>
MFSD_HD inline Mat<D, Real> correction_moment(const PairList<D, Real>& pairs, Index i) {
  Mat<D, Real> A = Mat<D, Real>::zero();
  for (PairIndex k = pairs.offsets[i]; k < pairs.offsets[i + 1]; ++k) {
    const Vec<D, Real> g = pairs.grad[k];
    if (pairs.stretch[k] == Real(0)) continue;   // a pair at the edge of the support, or moved out of it
    const Real w = -Real(1) / pairs.stretch[k];  // -(x_i - x_j) = -grad/stretch
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) A.m[a][b] += w * g.v[a] * g.v[b];  // seed 002 eq. 21
  }
  return A;
}

// B_i = A_i^{-1} (seed 002 eq. 21). Fallback: where det(A_i) < min_determinant
// (or is not a number) -- fewer than D independent neighbour directions, a
// particle alone or on a line of particles -- B_i = I, the uncorrected kernel
// gradient, and the function returns true so that the host can count them.
template <int D, class Real>
MFSD_HD inline bool correction_matrix(const PairList<D, Real>& pairs, Index i, Real min_determinant, Mat<D, Real>& B) {
  const Mat<D, Real> A = correction_moment(pairs, i);
  const Real d = det(A);
  if (!(d >= min_determinant)) {  // also catches NaN
    B = Mat<D, Real>::identity();
    return true;
  }
  B = inverse(A);
  return false;
}

// The uncorrected L~_i = -sum_j (v_i - v_j) (x) grad_ij: the gradient whose
// stress power V tau : L~ the shear force of eq. 18 does as work.
template <int D, class Real>
MFSD_HD inline Mat<D, Real> uncorrected_velocity_gradient(const PairList<D, Real>& pairs, const Vec<D, Real>* velocity,
                                                          Index i) {
  Mat<D, Real> sum = Mat<D, Real>::zero();  // sum_j v_j (x) grad_ij
  for (PairIndex k = pairs.offsets[i]; k < pairs.offsets[i + 1]; ++k) {
    prefetch(&velocity[pairs.neighbor[k + kPairPrefetchDistance]]);
    const Vec<D, Real> vj = velocity[pairs.neighbor[k]];
    const Vec<D, Real> g = pairs.grad[k];
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) sum.m[a][b] += vj.v[a] * g.v[b];
  }
  const Vec<D, Real> vi = velocity[i], G = pairs.gradient_sum[i];
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) sum.m[a][b] -= vi.v[a] * G.v[b];  // now -sum_j (v_i - v_j) (x) grad_ij
  return sum;
}

// L_i = -sum_j (v_i - v_j) (x) (B_i grad_ij) = L~_i B_i^T, L_ab = dv_a/dx_b (seed 002 eq. 20).
template <int D, class Real>
MFSD_HD inline Mat<D, Real> velocity_gradient(const PairList<D, Real>& pairs, const Vec<D, Real>* velocity,
                                              const Mat<D, Real>& B, Index i) {
  return mul_transposed(uncorrected_velocity_gradient(pairs, velocity, i), B);  // seed 002 eq. 20: (.) B_i^T
}

// correction[i] = B_i; fallback[i] = 1 where B_i = I was used (may be null).
template <int D, class Real>
struct CorrectionMatrixFunctor {
  PairList<D, Real> pairs;
  Mat<D, Real>* correction;
  unsigned char* fallback;
  Real min_determinant = Real(1e-3);  // det(A) ~ 1 in a full support, ~1/2^D at a corner

  MFSD_HD void operator()(Index i) const {
    Mat<D, Real> B;
    const bool f = correction_matrix(pairs, i, min_determinant, B);
    correction[i] = B;
    if (fallback) fallback[i] = f ? 1 : 0;
  }
};

// velocity_gradient[i] = L_i.
template <int D, class Real>
struct VelocityGradientFunctor {
  PairList<D, Real> pairs;
  const Vec<D, Real>* velocity;
  const Mat<D, Real>* correction;
  Mat<D, Real>* velocity_gradient;

  MFSD_HD void operator()(Index i) const {
    velocity_gradient[i] = ulsph::velocity_gradient(pairs, velocity, correction[i], i);
  }
};

}  // namespace mfsd::ulsph
