// Per-particle stress stage of TLSPH. Computes, from F, dF/dt and B0, the
// matrices the force stage sums over pairs, specialized on the material and
// the hourglass variant:
//   none      : M = (tau + tau_d) F^{-T} B0                       (seed 000 eq. 3, 20)
//   laplacian : M = tau_r F^{-T} B0,
//               tau_r = tau_vol I - zeta/d c tr(b) I + tau_d     (seed 003 eq. 28)
//               s = zeta c, c = G J^{-2/d}                       (seed 003 eq. 27)
//   genog     : M = tau_r F^{-T} B0,
//               tau_r = tau_vol I - 1/d c tr(b) I + tau_d        (seed 000 eq. 25)
//               S = c b F^{-T} B0 = c F B0,  F^{-1}              (seed 000 eq. 32)
// B0 is symmetric, so P B0^T = P B0. With correction_in_force = false, B0 is
// left out of the force sums (only dF/dt uses it), as in the authors' code.
#pragma once
#include <type_traits>

#include "kernels/core/mat.hpp"
#include "kernels/tlsph/damping.hpp"
#include "kernels/tlsph/hourglass.hpp"

namespace mfsd {

template <int D, class Real, class Material, class Hourglass>
struct StressFunctor {
  Material material;
  KelvinVoigtDamping<Real> damping;
  Real zeta;
  bool correction_in_force;
  const Mat<D, Real>* deformation_gradient;
  const Mat<D, Real>* rate;
  const Mat<D, Real>* correction;
  Mat<D, Real>* force_stress;  // M
  Real* shear_coefficient;     // s (laplacian)
  Mat<D, Real>* shear_stress;  // S (genog)
  Mat<D, Real>* inverse_F;     // F^{-1} (genog)

  MFSD_HD void operator()(Index i) const {
    const Mat<D, Real> F = deformation_gradient[i];
    const Mat<D, Real> F_inv = inverse(F);
    const Mat<D, Real> tau_d = damping.stress(F, rate[i]);
    Mat<D, Real> tau;
    if constexpr (std::is_same<Hourglass, HourglassNone>::value) {
      tau = material.kirchhoff(F) + tau_d;
    } else {
      const Real J = det(F);
      const Real c = material.shear_coefficient(J);
      const Real tr_b = ddot(F, F);  // tr(F F^T)
      if constexpr (std::is_same<Hourglass, HourglassLaplacian>::value) {
        tau = tau_d;
        tau.add_diagonal(material.volumetric_kirchhoff(J) - zeta / Real(D) * c * tr_b);  // eq. 28
        shear_coefficient[i] = zeta * c;                                                   // eq. 27
      } else {
        tau = tau_d;
        tau.add_diagonal(material.volumetric_kirchhoff(J) - c * tr_b / Real(D));  // seed 000 tau_r
        const Mat<D, Real> S = F * c;                                             // c b F^{-T} = c F
        shear_stress[i] = correction_in_force ? S * correction[i] : S;
        inverse_F[i] = F_inv;
      }
    }
    const Mat<D, Real> P = mul_transposed(tau, F_inv);  // tau F^{-T}
    force_stress[i] = correction_in_force ? P * correction[i] : P;
  }
};

}  // namespace mfsd
