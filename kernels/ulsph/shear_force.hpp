// Shear acceleration of ULSPH (seed 002 eq. 18-19; formulations.md section 3,
// "Shear acceleration"):
//   a_tau,i = (1/rho_i) sum_j (tau_i + tau_j) dW_ij V_j e_ij = (1/rho_i) sum_j (tau_i + tau_j) grad_ij
//           = (1/rho_i) (tau_i G_i + sum_j tau_j grad_ij),   G_i = gradient_sum_i.
// Symmetric form: m_i a_tau,i = sum_j V_i V_j dW_ij (tau_i + tau_j) e_ij is
// antisymmetric in i <-> j, so linear momentum is conserved. A uniform tau gives
// tau G_i, zero inside a full support; at a free end of a bar in tension
// (tau_xx > 0) G_i points into the body, so the end is pulled back.
#pragma once
#include "kernels/core/mat.hpp"
#include "kernels/neighbors/pair_list.hpp"

namespace mfsd::ulsph {

template <int D, class Real>
MFSD_HD inline Vec<D, Real> shear_acceleration(const PairList<D, Real>& pairs, const Mat<D, Real>* shear_stress,
                                               Real rho_i, Index i) {
  Vec<D, Real> sum = shear_stress[i] * pairs.gradient_sum[i];  // tau_i sum_j grad_ij
  for (PairIndex k = pairs.offsets[i]; k < pairs.offsets[i + 1]; ++k) {
    prefetch(&shear_stress[pairs.neighbor[k + kPairPrefetchDistance]]);
    sum += shear_stress[pairs.neighbor[k]] * pairs.grad[k];  // seed 002 eq. 18: tau_j grad_ij
  }
  return sum / rho_i;
}

// acceleration[i] += a_tau,i (after the pressure term, pressure_force.hpp).
template <int D, class Real>
struct ShearAccelerationFunctor {
  PairList<D, Real> pairs;
  const Real* density;
  const Mat<D, Real>* shear_stress;
  Vec<D, Real>* acceleration;

  MFSD_HD void operator()(Index i) const { acceleration[i] += shear_acceleration(pairs, shear_stress, density[i], i); }
};

}  // namespace mfsd::ulsph
