// View of the total-Lagrangian reference neighbour list (CSR) with the
// per-pair reference data computed once (design.md, "Neighbour search"),
// laid out for streaming: per pair one index, one vector and one scalar,
//   grad_ij    = V0_j dW/dr(r0_ij) e0_ij      (= V0_j grad0_i W_ij),
//   stretch_ij = V0_j dW/dr(r0_ij) / r0_ij,
// with e0_ij = (X_i - X_j)/r0_ij and r0_ij = |X_i - X_j|. Everything the
// stages need follows from these two: V0_j dW r_ij/r0_ij = grad + (u_i - u_j)
// stretch, |V0_j dW| = |grad|, and V0_j (X_j - X_i) = -grad / stretch.
// Per particle: gradient_sum_i = sum_j grad_ij (zero inside a full support),
// so that pair sums of the form sum_j (A_i + A_j) grad_ij need only A_j.
// beta_ij = W(r0)/W(0) only for the paper form of the GENOG limiter.
#pragma once
#include "kernels/core/vec.hpp"

namespace mfsd {

// The pair loops prefetch the fields of the neighbour this many pairs ahead;
// the neighbour array carries as many extra entries (index 0) at its end.
constexpr int kPairPrefetchDistance = 16;

template <int D, class Real>
struct ReferencePairs {
  const PairIndex* offsets;  // size n + 1; pairs of i are [offsets[i], offsets[i+1])
  const Index* neighbor;
  const Vec<D, Real>* grad;
  const Real* stretch;
  const Vec<D, Real>* gradient_sum;  // per particle
  const Real* beta;                  // null unless a stage needs it
};

}  // namespace mfsd
