// View of the total-Lagrangian reference neighbour list (CSR) with the
// per-pair reference data computed once (design.md, "Neighbour search"):
//   e0_ij    = (X_i - X_j)/|X_i - X_j|   unit vector from j to i,
//   dwv_ij   = V0_j dW/dr(|X_i - X_j|)   (< 0),
//   inv_r0   = 1/|X_i - X_j|,
//   beta_ij  = W(|X_ij|)/W(0)           (GENOG weight, seed 000 eq. 32).
// grad0_i W_ij V0_j = dwv_ij e0_ij.
#pragma once
#include "kernels/core/vec.hpp"

namespace mfsd {

template <int D, class Real>
struct ReferencePairs {
  const PairIndex* offsets;  // size n + 1; pairs of i are [offsets[i], offsets[i+1])
  const Index* neighbor;
  const Vec<D, Real>* e0;
  const Real* dwv;
  const Real* inv_r0;
  const Real* beta;  // null unless a stage needs it
};

}  // namespace mfsd
