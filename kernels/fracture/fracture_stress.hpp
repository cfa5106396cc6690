// The stress stage of a fracturing body (standard TLSPH form, seed 001
// eq. 55; hourglass "none"), fused with the first half step of the
// position-based Verlet scheme for F, u and the phase field s:
//   F += dt/2 dF/dt,  u += dt/2 v,  s += dt/2 ds/dt            (seed 000 eq. 35)
//   s >  s_l: tau = s^2 tau_plus + tau_minus (tension_split.hpp, seed 001 eq. 18, 31),
//             H = max(H, psi_plus)                               (eq. 8)
//   s <= s_l: F = I, no stress                                   (eq. 63)
//   M = (tau + tau_d) F^{-T} B0                                  (seed 000 eq. 20)
// The elastic energy the degradation releases, psi_plus (s_n^2 - s^2), and the
// energy a particle holds when it is frozen, are accumulated per V0 as the
// fracture dissipation that closes the energy balance (docs/theory.md).
#pragma once
#include "kernels/core/mat.hpp"
#include "kernels/fracture/phase_field.hpp"
#include "kernels/fracture/tension_split.hpp"
#include "kernels/tlsph/damping.hpp"
#include "kernels/tlsph/observables.hpp"

namespace mfsd {

template <int D, class Real, class Material>
struct FractureStressFunctor {
  Material material;
  KelvinVoigtDamping<Real> damping;
  FractureParameters<Real> fracture;
  bool correction_in_force;
  Real half_dt;  // 0 computes the stress without moving the state
  Mat<D, Real>* deformation_gradient;
  Vec<D, Real>* displacement;
  const Vec<D, Real>* velocity;
  const Mat<D, Real>* rate;
  const Mat<D, Real>* correction;
  Mat<D, Real>* force_stress;  // M
  Real* damping_work;          // with Kelvin-Voigt damping, else null
  PhaseFieldViews<Real> phase;

  MFSD_HD void operator()(Index i) const {
    const Mat<D, Real> dF = rate[i];
    const Mat<D, Real> F_old = deformation_gradient[i];
    Mat<D, Real> F = F_old + dF * half_dt;  // eq. 35
    displacement[i] += velocity[i] * half_dt;
    const Real s_old = math::min(math::max(phase.s[i], Real(0)), Real(1));
    const Real s_half = phase.s[i] + half_dt * phase.rate[i];
    phase.s[i] = s_half;  // as computed: the phase-field pass recovers s_n from it
    const Real s = math::min(math::max(s_half, Real(0)), Real(1));
    const TensionSplit<D, Real> split = tension_split(material, F);
    Mat<D, Real> tau;
    if (s <= fracture.s_limit) {  // seed 001 eq. 63: F frozen to I
      // The energy it held at the start of the step is given up (no work is
      // done on a particle without stress).
      phase.released[i] += tension_split(material, F_old).energy(s_old);
      phase.tensile_energy[i] = Real(0);
      F = Mat<D, Real>::identity();
      tau = Mat<D, Real>::zero();
    } else {
      phase.history[i] = math::max(phase.history[i], split.psi_plus);  // eq. 8
      phase.tensile_energy[i] = split.psi_plus;
      phase.released[i] += split.psi_plus * (s_old * s_old - s * s);
      tau = split.kirchhoff(s);  // eq. 18 / 31
    }
    deformation_gradient[i] = F;
    const Mat<D, Real> F_inv = inverse(F);
    const Mat<D, Real> tau_d = damping.stress(F, dF);
    if (damping_work) damping_work[i] += Real(2) * half_dt * ddot(tau_d, dF * F_inv);
    Mat<D, Real> M = mul_transposed(tau + tau_d, F_inv);  // tau F^{-T}
    if (correction_in_force) M = M * correction[i];
    force_stress[i] = M;
  }
};

// Degraded von Mises stress, J and von Mises strain of a fracturing body.
template <int D, class Real, class Material>
struct FractureObservablesFunctor {
  Material material;
  const Mat<D, Real>* deformation_gradient;
  const Real* s;
  Real* von_mises_stress;
  Real* jacobian;
  Real* strain;
  MFSD_HD void operator()(Index i) const {
    const Mat<D, Real> F = deformation_gradient[i];
    const Real J = det(F);
    von_mises_stress[i] = von_mises(tension_split(material, F).kirchhoff(s[i]) * (Real(1) / J));
    jacobian[i] = J;
    strain[i] = von_mises_strain(F);
  }
};

// Energies of a fracturing body: those of EnergyFunctor with the degraded
// strain energy (eq. 7), the released energy and the crack surface energy.
template <int D, class Real, class Material>
struct FractureEnergyFunctor {
  EnergyFunctor<D, Real, Material> base;
  ReferencePairs<D, Real> pairs;
  const Mat<D, Real>* correction;
  FractureParameters<Real> fracture;
  PhaseFieldViews<Real> phase;
  MFSD_HD EnergySums operator()(Index i) const {
    EnergySums e = base(i);
    const double V0 = double(base.volume[i]);
    e.strain = V0 * double(tension_split(base.material, base.deformation_gradient[i]).energy(phase.s[i]));
    e.fracture = V0 * double(phase.released[i]);
    e.surface = V0 * double(crack_surface_density(pairs, correction[i], phase.s, fracture, i));
    return e;
  }
};

}  // namespace mfsd
