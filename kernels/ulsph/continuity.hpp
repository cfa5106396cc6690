// Continuity equation of ULSPH (seed 002 eq. 14; formulations.md section 3,
// "Continuity"):
//   drho_i/dt = rho_i sum_j (v_i - v_j) . e_ij dW_ij V_j
//             = rho_i sum_j (v_i - v_j) . grad_ij                (pair_list.hpp)
//             = rho_i (v_i . G_i - sum_j v_j . grad_ij),  G_i = gradient_sum_i.
// A uniform expansion v = c x gives drho_i/dt = -rho_i c tr(A_i) with
// A_i = -sum_j (x_i - x_j) (x) grad_ij (velocity_gradient.hpp), i.e.
// -rho_i c d inside a full support, where A_i ~ I.
#pragma once
#include "kernels/core/vec.hpp"
#include "kernels/neighbors/pair_list.hpp"

namespace mfsd::ulsph {

template <int D, class Real>
MFSD_HD inline Real density_rate(const PairList<D, Real>& pairs, const Vec<D, Real>* velocity, Real rho_i, Index i) {
  Real sum = Real(0);  // sum_j v_j . grad_ij
  for (PairIndex k = pairs.offsets[i]; k < pairs.offsets[i + 1]; ++k) {
    prefetch(&velocity[pairs.neighbor[k + kPairPrefetchDistance]]);
    sum += dot(velocity[pairs.neighbor[k]], pairs.grad[k]);
  }
  return rho_i * (dot(velocity[i], pairs.gradient_sum[i]) - sum);  // seed 002 eq. 14
}

// density_rate[i] = drho_i/dt.
template <int D, class Real>
struct DensityRateFunctor {
  PairList<D, Real> pairs;
  const Vec<D, Real>* velocity;
  const Real* density;
  Real* rate;

  MFSD_HD void operator()(Index i) const { rate[i] = density_rate(pairs, velocity, density[i], i); }
};

// rho_i += dt drho_i/dt, drho_i/dt at the current rho and v: the density half
// steps of the position-Verlet acoustic step (seed 002 eq. 24 and 26; the
// pipeline passes dt/2). Writes only rho_i, reads only velocities of the
// neighbours, so it runs in place.
template <int D, class Real>
struct ContinuityFunctor {
  PairList<D, Real> pairs;
  const Vec<D, Real>* velocity;
  Real* density;
  Real dt;

  MFSD_HD void operator()(Index i) const {
    const Real rho = density[i];
    density[i] = rho + dt * density_rate(pairs, velocity, rho, i);  // seed 002 eq. 24/26
  }
};

}  // namespace mfsd::ulsph
