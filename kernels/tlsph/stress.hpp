// Per-particle stress stage of TLSPH, fused with the first half step of the
// position-based Verlet scheme (F += dt/2 dF/dt, u += dt/2 v; seed 000 eq. 35)
// so that F is read and written once. Computes, from F, dF/dt and B0, the
// matrices the force stage sums over pairs, specialized on the material and
// the hourglass variant:
//   none      : M = (tau + tau_d) F^{-T} B0                       (seed 000 eq. 3, 20)
//   laplacian : M = tau_r F^{-T} B0,
//               tau_r = tau_vol I - zeta/d c tr(b) I + tau_d     (seed 003 eq. 28)
//               s = zeta c, c = G J^{-2/d}                       (seed 003 eq. 27)
//   genog     : M = tau_r F^{-T} B0,
//               tau_r = tau_vol I - 1/d c tr(b) I + tau_d        (seed 000 eq. 25)
//               S = c b F^{-T} B0 = c F B0,  F^{-1}              (seed 000 eq. 32)
//               stored as Q = M + S and S (acceleration.hpp).
// Plastic materials (j2_plastic.hpp) first run the return mapping at the half
// step's F (seed 000 Appendix A: the plastic algorithm at n + 1/2) and put the
// elastic b_e in place of b (seed 000 section 3.2):
//   none      : tau = tau_vol I + G dev(b_bar_e) + tau_d
//   genog     : tau_r = tau_vol I - G tr(b_bar_e)/3 I + tau_d,
//               S = c b_e F^{-T} B0 = G b_bar_e F^{-T} B0  (c = |b_e|^{-1/3} G, eq. 25)
// (3 x 3 tensors, in-plane blocks in plane strain). The Laplacian form of
// seed 003 is defined for elastic bodies only; the solver refuses the pair.
// B0 is symmetric, so P B0^T = P B0. With correction_in_force = false, B0 is
// left out of the force sums (only dF/dt uses it), as in the authors' code.
#pragma once
#include <type_traits>

#include "kernels/core/mat.hpp"
#include "kernels/materials/holzapfel_ogden.hpp"
#include "kernels/materials/j2_plastic.hpp"
#include "kernels/materials/material_interface.hpp"
#include "kernels/tlsph/damping.hpp"
#include "kernels/tlsph/genog_neighbor_record.hpp"
#include "kernels/tlsph/hourglass.hpp"

namespace mfsd {

template <int D, class Real, class Material, class Hourglass>
struct StressFunctor {
  Material material;
  KelvinVoigtDamping<Real> damping;
  Real zeta;
  bool correction_in_force;
  Real half_dt;  // 0 computes the stress without moving the state
  Mat<D, Real>* deformation_gradient;
  Vec<D, Real>* displacement;
  const Vec<D, Real>* velocity;
  const Mat<D, Real>* rate;
  const Mat<D, Real>* correction;
  Mat<D, Real>* force_stress;                  // M, or Q = M + S (genog)
  Real* shear_coefficient;                     // s (laplacian)
  Mat<D, Real>* shear_stress;                  // S (genog)
  Mat<D, Real>* inverse_F;                     // F^{-1} (genog)
  GenogNeighborRecord<Real>* neighbor_record;  // 3-D genog on the CPU, else null
  J2State<Real>* plastic_state;                // plastic materials, else null
  Real* damping_work;                          // with Kelvin-Voigt damping: its work per V0, else null
  Real* stiffening = nullptr;                  // stiffening materials: current / reference longitudinal modulus
  Real* active_work = nullptr;                 // materials with an active stress: its work on the body per V0

  static constexpr bool plastic = IsPlastic<Material>::value;
  static_assert(!(plastic && std::is_same<Hourglass, HourglassLaplacian>::value),
                "the Laplacian hourglass form is defined for elastic bodies only (seed 003)");
  static_assert(plastic || IsIsotropic<Material>::value || !std::is_same<Hourglass, HourglassLaplacian>::value,
                "the Laplacian hourglass form is defined for isotropic elastic bodies only (seed 003)");

  MFSD_HD void operator()(Index i) const {
    const Mat<D, Real> dF = rate[i];
    const Mat<D, Real> F = deformation_gradient[i] + dF * half_dt;  // eq. 35
    deformation_gradient[i] = F;
    displacement[i] += velocity[i] * half_dt;
    const Mat<D, Real> F_inv = inverse(F);
    const Mat<D, Real> tau_d = damping.stress(F, dF);
    // The damping stress's work over the step, V0 P_d : dF/dt dt = V0 tau_d : (dF/dt F^{-1}) dt.
    if (damping_work) damping_work[i] += Real(2) * half_dt * ddot(tau_d, dF * F_inv);
    Mat<D, Real> tau;
    [[maybe_unused]] Mat<D, Real> S;
    if constexpr (plastic) {
      J2State<Real> state = plastic_state[i];
      const J2Stress<Real> p = material.update(F, state, Real(2) * half_dt);  // Algorithm 1 at n + 1/2
      plastic_state[i] = state;
      const Mat<D, Real> be = leading_block<D>(p.be_bar);
      tau = tau_d;
      if constexpr (std::is_same<Hourglass, HourglassNone>::value) {
        tau += be * material.G;
        tau.add_diagonal(p.volumetric - material.G * trace(p.be_bar) / Real(3));  // tau_vol + G dev(b_bar_e)
      } else {
        tau.add_diagonal(p.volumetric - material.G * trace(p.be_bar) / Real(3));  // tau_r
        S = mul_transposed(be * material.G, F_inv);                               // G b_bar_e F^{-T}
        if (correction_in_force) S = S * correction[i];
        shear_stress[i] = S;
        if (!neighbor_record) inverse_F[i] = F_inv;
      }
    } else {
      // The material at particle i (material_interface.hpp; Holzapfel-Ogden:
      // f0, s0 and T_a of the particle, seed 000 eq. 17-19).
      const auto m = material.at(i);
      using Point = std::decay_t<decltype(m)>;
      if constexpr (Stiffens<Point>::value)
        if (stiffening) stiffening[i] = m.stiffening(F);
      // The active stress's work on the body over the step is -V0 tau_a : (dF/dt F^{-1}) dt.
      if constexpr (HasActiveWork<Point>::value)
        if (active_work) active_work[i] -= m.active_work(F, dF * F_inv, Real(2) * half_dt);
      if constexpr (std::is_same<Hourglass, HourglassNone>::value) {
        tau = m.kirchhoff(F) + tau_d;
      } else if constexpr (std::is_same<Hourglass, HourglassLaplacian>::value) {
        const Real J = det(F);
        const Real c = material.shear_coefficient(J);
        const Real tr_b = ddot(F, F);  // tr(F F^T)
        tau = tau_d;
        tau.add_diagonal(material.volumetric_kirchhoff(J) - zeta / Real(D) * c * tr_b);  // eq. 28
        shear_coefficient[i] = zeta * c;                                                 // eq. 27
      } else {  // genog: tau_s = c b, tau_r = tau - c b (seed 000 eq. 25)
        const KirchhoffSplit<D, Real> split = m.genog_split(F);
        tau = split.remainder + tau_d;
        S = F * split.coefficient;  // c b F^{-T} = c F
        if (correction_in_force) S = S * correction[i];
        shear_stress[i] = S;
        if (!neighbor_record) inverse_F[i] = F_inv;
      }
    }
    Mat<D, Real> M = mul_transposed(tau, F_inv);  // tau F^{-T}
    if (correction_in_force) M = M * correction[i];
    if constexpr (std::is_same<Hourglass, HourglassGenog>::value) {
      M += S;
      if constexpr (D == 3) {
        if (neighbor_record) {
          neighbor_record[i].set(M, F_inv, displacement[i]);
          return;
        }
      }
    }
    force_stress[i] = M;
  }
};

}  // namespace mfsd
