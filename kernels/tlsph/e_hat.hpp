// The GENOG pair deviation in the form the pair loops use (seed 000 eq. 31):
//   e_hat_ij = 1/2 (F_i^{-1} + F_j^{-1}) r_ij / r0_ij - e0_ij,
// scaled by V0_j dW/dr(r0) (reference_pairs.hpp): with g = V0_j dW e0 and
// t = g + (u_i - u_j) stretch = V0_j dW r_ij / r0_ij,
//   h_ij = 1/2 (F_i^{-1} + F_j^{-1}) t - g = V0_j dW e_hat_ij,  |e_hat| = |h| / |g|.
#pragma once
#include "kernels/core/mat.hpp"

namespace mfsd {

template <int D, class Real>
MFSD_HD inline Vec<D, Real> scaled_e_hat(const Mat<D, Real>& Finv_i, const Mat<D, Real>& Finv_j,
                                         const Vec<D, Real>& u_i, const Vec<D, Real>& u_j, const Vec<D, Real>& g,
                                         Real stretch) {
  const Vec<D, Real> t = g + (u_i - u_j) * stretch;
  return (Finv_i + Finv_j) * t * Real(0.5) - g;
}

}  // namespace mfsd
