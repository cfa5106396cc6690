// Pressure acceleration of ULSPH with the dissipation of a linearised acoustic
// Riemann solver (seed 002 eq. 15-17; formulations.md section 3, "Pressure
// acceleration" and "Riemann dissipation"):
//   a_p,i = -(1/rho_i) sum_j (p_i + p_j) dW_ij V_j e_ij
//         + (1/rho_i) sum_j Z ((v_i - v_j) . e_ij) dW_ij V_j e_ij,   Z = rho0 c0,
// i.e. -(2/rho_i) sum_j p*_ij grad_ij with p*_ij = (p_i + p_j)/2 + (Z/2) u_ij the
// linearised inter-particle Riemann pressure, u_ij = -(v_i - v_j) . e_ij the
// approach speed of the pair (seed 002 eq. 16-17 linearised, no limiter).
// In pair data (pair_list.hpp) grad_ij = dW_ij V_j e_ij and dW_ij V_j = -|grad_ij|:
//   ((v_i - v_j) . e_ij) dW_ij V_j e_ij = -((v_i - v_j) . grad_ij) grad_ij / |grad_ij|.
// Both terms are central and antisymmetric under i <-> j once multiplied by
// m_i = rho_i V_i (V_i V_j dW_ij appears in both), so they conserve linear and
// angular momentum. Approaching particles ((v_i - v_j) . e_ij < 0) are pushed
// apart: the dissipation term is then along +e_ij for i.
#pragma once
#include "kernels/core/vec.hpp"
#include "kernels/neighbors/pair_list.hpp"

namespace mfsd::ulsph {

template <int D, class Real>
MFSD_HD inline Vec<D, Real> pressure_acceleration(const PairList<D, Real>& pairs, const Vec<D, Real>* velocity,
                                                  const Real* pressure, Real rho_i, Real impedance, Index i,
                                                  Vec<D, Real>* riemann = nullptr) {
  const Real p_i = pressure[i];
  const Vec<D, Real> v_i = velocity[i];
  Vec<D, Real> sum = Vec<D, Real>::zero(), dissipation = Vec<D, Real>::zero();
  for (PairIndex k = pairs.offsets[i]; k < pairs.offsets[i + 1]; ++k) {
    const Index j = pairs.neighbor[k];
    const Index ahead = pairs.neighbor[k + kPairPrefetchDistance];
    prefetch(&velocity[ahead]);
    prefetch(&pressure[ahead]);
    const Vec<D, Real> g = pairs.grad[k];
    const Real g2 = squared_norm(g);
    const Real inv_g = g2 > Real(0) ? Real(1) / math::sqrt(g2) : Real(0);  // 0 only for coincident particles
    const Real u = dot(v_i - velocity[j], g) * inv_g;                      // -(v_i - v_j) . e_ij
    // seed 002 eq. 15: -(p_i + p_j) grad_ij (pressure) - Z u grad_ij (Riemann dissipation)
    sum += g * (-(p_i + pressure[j]));
    dissipation -= g * (impedance * u);
  }
  if (riemann) *riemann = dissipation / rho_i;  // the dissipative part alone (its work: energies.csv `damping`)
  return (sum + dissipation) / rho_i;           // seed 002 eq. 15: 1/rho_i
}

// acceleration[i] = a_p,i (written, not added: the first term of the force stage;
// shear and hourglass terms are added to it, shear_stress.hpp and gnog.hpp).
template <int D, class Real>
struct PressureAccelerationFunctor {
  PairList<D, Real> pairs;
  const Vec<D, Real>* velocity;
  const Real* density;
  const Real* pressure;
  Real impedance;  // Z = rho0 c0 of the body
  Vec<D, Real>* acceleration;

  MFSD_HD void operator()(Index i) const {
    acceleration[i] = pressure_acceleration(pairs, velocity, pressure, density[i], impedance, i);
  }
};

}  // namespace mfsd::ulsph
