// Kernel-gradient correction matrix, computed once in the reference
// configuration (seed 000 eq. 21; seed 003 eq. 21):
//   B0_i = ( sum_j V0_j (X_j - X_i) (x) grad0_i W_ij )^{-1}
//        = ( - sum_j grad_ij (x) grad_ij / stretch_ij )^{-1}   (symmetric,
// since V0_j (X_j - X_i) = -grad_ij / stretch_ij, reference_pairs.hpp).
// The solver takes the moment matrix from the search (reference_pair_fill.hpp,
// which sees every neighbour also where only a half-pair list is stored) and
// inverts it in place (CorrectionFromMomentFunctor); CorrectionMatrixFunctor
// forms it from a full list's rows. Near-singular cases (particles on a line,
// thin parts, isolated particles) are regularized: the eigenvalues of the
// symmetric matrix are floored at `eigenvalue_floor` before inversion, and the
// particle is flagged so that the host can report how many needed it. A full
// lattice support gives eigenvalues close to 1.
#pragma once
#include "kernels/core/eigen_symmetric.hpp"
#include "kernels/tlsph/reference_pairs.hpp"

namespace mfsd {

// A^{-1} with A's eigenvalues floored at `floor`; *floored tells whether the
// floor was applied.
template <int D, class Real>
MFSD_HD inline Mat<D, Real> regularized_inverse(const Mat<D, Real>& A, Real floor, bool* floored) {
  const SymmetricEigen<D, Real> eig = eigen_symmetric(A);
  Vec<D, Real> inv_lambda;
  *floored = false;
  for (int k = 0; k < D; ++k) {
    Real l = eig.values.v[k];
    if (!(l >= floor)) {  // also catches NaN
      l = floor;
      *floored = true;
    }
    inv_lambda.v[k] = Real(1) / l;
  }
  return compose_symmetric(inv_lambda, eig.vectors);
}

template <int D, class Real>
struct CorrectionMatrixFunctor {
  ReferencePairs<D, Real> pairs;
  Mat<D, Real>* correction;    // B0
  unsigned char* regularized;  // 1 where the floor was applied
  Real eigenvalue_floor;

  MFSD_HD void operator()(Index i) const {
    Mat<D, Real> A = Mat<D, Real>::zero();
    const PairRow r = pairs.row(i);
    for (Index k = 0; k < r.count; ++k) {
      const PairIndex p = r.at(k);
      const Vec<D, Real> g = pairs.grad[p];
      if (pairs.stretch[p] == Real(0)) continue;   // dW = 0 at the support edge
      const Real w = -Real(1) / pairs.stretch[p];  // r0 / (V0_j |dW|)
      for (int a = 0; a < D; ++a)
        for (int b = 0; b < D; ++b) A.m[a][b] += w * g.v[a] * g.v[b];
    }
    bool floored;
    correction[i] = regularized_inverse(A, eigenvalue_floor, &floored);
    regularized[i] = floored ? 1 : 0;
  }
};

// B0 in place of the moment matrix A_i that the search left in `correction`.
template <int D, class Real>
struct CorrectionFromMomentFunctor {
  Mat<D, Real>* correction;    // A on entry, B0 on exit
  unsigned char* regularized;  // 1 where the floor was applied
  Real eigenvalue_floor;

  MFSD_HD void operator()(Index i) const {
    bool floored;
    correction[i] = regularized_inverse(correction[i], eigenvalue_floor, &floored);
    regularized[i] = floored ? 1 : 0;
  }
};

}  // namespace mfsd
