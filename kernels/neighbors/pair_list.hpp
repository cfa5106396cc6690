// View of a CSR neighbour list with the per-pair data every SPH method reads
// (design.md, "Neighbour search"), laid out for streaming: per pair one
// index, one vector and one scalar,
//   grad_ij    = V_j dW/dr(r_ij) e_ij      (= V_j grad_i W_ij),
//   stretch_ij = V_j dW/dr(r_ij) / r_ij,
// with e_ij = (x_i - x_j)/r_ij, r_ij = |x_i - x_j| and dW/dr < 0, evaluated
// in the configuration the list was built in: the reference configuration
// (TLSPH, built once, V = V0) or the current one (ULSPH, rebuilt every
// advection step, V = m/rho). Everything else follows from these two:
// |V_j dW| = |grad|, V_j dW = -|grad|, and x_i - x_j = grad / stretch.
// Per particle: gradient_sum_i = sum_j grad_ij (zero inside a full support).
// beta_ij = W(r)/W(0) only for the paper form of the GENOG limiter.
#pragma once
#include "kernels/core/vec.hpp"

namespace mfsd {

// The pair loops prefetch the fields of the neighbour this many pairs ahead;
// the neighbour array carries as many extra entries (index 0) at its end
// (times the slice height in the sliced layout).
constexpr int kPairPrefetchDistance = 16;

// One row's pairs: the k-th is at first + k * stride. Compressed rows (CSR)
// have stride 1; the sliced layout (sliced ELLPACK, issue 24 item 3) stores
// the rows of a slice of `stride` consecutive particles interleaved, so that
// the k-th pairs of the slice's rows are adjacent: on the GPU a warp whose
// threads take consecutive rows reads them in one coalesced transaction.
struct PairRow {
  PairIndex first;
  Index count;
  Index stride;
  MFSD_HD PairIndex at(Index k) const { return first + PairIndex(k) * stride; }
};

template <int D, class Real>
struct PairList {
  const PairIndex* offsets;  // CSR: size n + 1, pairs of i are [offsets[i], offsets[i+1]); sliced: row i's first
  const Index* neighbor;
  const Vec<D, Real>* grad;
  const Real* stretch;
  const Vec<D, Real>* gradient_sum;  // per particle
  const Real* beta;                  // null unless a stage needs it
  const Index* count = nullptr;      // sliced: each row's pair count; null for CSR
  Index stride = 1;                  // sliced: the slice height

  MFSD_HD PairRow row(Index i) const {
    if (count) return PairRow{offsets[i], count[i], stride};
    return PairRow{offsets[i], Index(offsets[i + 1] - offsets[i]), 1};
  }
};

}  // namespace mfsd
