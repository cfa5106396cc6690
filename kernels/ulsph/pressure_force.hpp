// Pressure acceleration of ULSPH with the dissipation of a linearised acoustic
// Riemann solver (seed 002 eq. 15-17; formulations.md section 3, "Pressure
// acceleration" and "Riemann dissipation"):
//   a_p,i = -(1/rho_i) sum_j (p_i + p_j) dW_ij V_j e_ij
//         + (1/rho_i) sum_j Z ((v_i - v_j) . e_ij) dW_ij V_j e_ij,   Z = rho0 c0,
// i.e. -(2/rho_i) sum_j p*_ij grad_ij with p*_ij = (p_i + p_j)/2 + (Z/2) u_ij the
// linearised inter-particle Riemann pressure, u_ij = -(v_i - v_j) . e_ij the
// approach speed of the pair (seed 002 eq. 16-17 linearised, no limiter by
// default: formulations.md 3 and the authors' code, DissipativeRiemannSolver).
// With `limiter` = eta / c0 > 0 the dissipation is that of the low-dissipation
// Riemann solver of seed 002's ref. [38] (Zhang, Hu and Adams 2017): Z u is
// scaled by min(eta max(u, 0) / c0, 1), so it acts on approaching pairs only
// and in proportion to how fast they approach (eta = 3 there).
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

// One pair's Riemann dissipation term of eq. 15, -Z u_ij grad_ij, with
// v_ij = v_i - v_j (u_ij = -(v_i - v_j) . e_ij, the approach speed) and the
// optional limiter of ref. [38].
template <int D, class Real>
MFSD_HD inline Vec<D, Real> riemann_dissipation_term(const Vec<D, Real>& g, const Vec<D, Real>& v_ij, Real impedance,
                                                     Real limiter) {
  const Real g2 = squared_norm(g);
  const Real inv_g = g2 > Real(0) ? Real(1) / math::sqrt(g2) : Real(0);  // 0 only for coincident particles
  const Real u = dot(v_ij, g) * inv_g;                                   // -(v_i - v_j) . e_ij
  Real zu = impedance * u;
  if (limiter > Real(0)) zu *= math::min(math::max(limiter * u, Real(0)), Real(1));  // ref. [38]'s limiter
  return g * (-zu);
}

template <int D, class Real>
MFSD_HD inline Vec<D, Real> pressure_acceleration(const PairList<D, Real>& pairs, const Vec<D, Real>* velocity,
                                                  const Real* pressure, Real rho_i, Real impedance, Real limiter,
                                                  Index i, Vec<D, Real>* riemann = nullptr) {
  const Real p_i = pressure[i];
  const Vec<D, Real> v_i = velocity[i];
  Vec<D, Real> sum = Vec<D, Real>::zero(), dissipation = Vec<D, Real>::zero();
  for (PairIndex k = pairs.offsets[i]; k < pairs.offsets[i + 1]; ++k) {
    const Index j = pairs.neighbor[k];
    const Index ahead = pairs.neighbor[k + kPairPrefetchDistance];
    prefetch(&velocity[ahead]);
    prefetch(&pressure[ahead]);
    const Vec<D, Real> g = pairs.grad[k];
    // seed 002 eq. 15: -(p_i + p_j) grad_ij (pressure) - Z u grad_ij (Riemann dissipation)
    sum += g * (-(p_i + pressure[j]));
    dissipation += riemann_dissipation_term(g, v_i - velocity[j], impedance, limiter);
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
  Real limiter;    // eta / c0 of the low-dissipation limiter; 0: none
  Vec<D, Real>* acceleration;

  MFSD_HD void operator()(Index i) const {
    acceleration[i] = pressure_acceleration(pairs, velocity, pressure, density[i], impedance, limiter, i);
  }
};

}  // namespace mfsd::ulsph
