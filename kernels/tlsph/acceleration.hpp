// Force stage of TLSPH: particle acceleration from the stress stage's
// matrices, gathered over the reference neighbours (no atomics):
//   a_i = 1/rho0_i sum_j (M_i + M_j) grad0_i W_ij V0_j                 (seed 000 eq. 20)
// plus the shear term of the hourglass variant:
//   laplacian: + 1/rho0_i sum_j (s_i + s_j) (r_ij / r0_ij) dW0_ij V0_j (seed 003 eq. 27)
//   genog    : + 1/rho0_i sum_j (S_i + S_j) (e0_ij + phi_ij e_hat_ij) dW0_ij V0_j
//                                                                      (seed 000 eq. 32)
//     e_hat_ij = 1/2 (F_i^{-1} + F_j^{-1}) r_ij / r0_ij - e0_ij         (seed 000 eq. 31)
// and body forces. r_ij / r0_ij = e0_ij + (u_i - u_j) / r0_ij.
#pragma once
#include <type_traits>

#include "kernels/core/mat.hpp"
#include "kernels/tlsph/hourglass.hpp"
#include "kernels/tlsph/reference_pairs.hpp"

namespace mfsd {

// phi_ij of the GENOG correction (seed 000 eq. 32-33, or the capped form).
template <class Real>
struct GenogWeight {
  GenogLimiter limiter;
  Real alpha_d;  // alpha * d (paper form)

  MFSD_HD Real operator()(Real e_hat_norm, Real beta) const {
    const Real excess = e_hat_norm - Real(0.05);
    if (limiter == GenogLimiter::paper)
      return alpha_d * beta * math::clamp(excess, Real(0), Real(1));  // eq. 33
    return math::min(Real(10) * math::max(excess, Real(0)), Real(1));
  }
};

template <int D, class Real, class Hourglass>
struct AccelerationFunctor {
  ReferencePairs<D, Real> pairs;
  const Mat<D, Real>* force_stress;     // M
  const Real* shear_coefficient;        // s (laplacian)
  const Mat<D, Real>* shear_stress;     // S (genog)
  const Mat<D, Real>* inverse_F;        // F^{-1} (genog)
  const Vec<D, Real>* displacement;     // u
  Real inv_rho0;
  Vec<D, Real> body_acceleration;       // gravity
  GenogWeight<Real> genog_weight;
  Vec<D, Real>* acceleration;

  MFSD_HD void operator()(Index i) const {
    const Mat<D, Real> Mi = force_stress[i];
    Vec<D, Real> force = Vec<D, Real>::zero();
    [[maybe_unused]] Vec<D, Real> ui;
    [[maybe_unused]] Real si;
    [[maybe_unused]] Mat<D, Real> Si, Finv_i;
    if constexpr (!std::is_same<Hourglass, HourglassNone>::value) ui = displacement[i];
    if constexpr (std::is_same<Hourglass, HourglassLaplacian>::value) si = shear_coefficient[i];
    if constexpr (std::is_same<Hourglass, HourglassGenog>::value) {
      Si = shear_stress[i];
      Finv_i = inverse_F[i];
    }
    const PairIndex begin = pairs.offsets[i], end = pairs.offsets[i + 1];
    for (PairIndex p = begin; p < end; ++p) {
      const Index j = pairs.neighbor[p];
      const Vec<D, Real> e0 = pairs.e0[p];
      const Real dwv = pairs.dwv[p];
      force += (Mi + force_stress[j]) * (e0 * dwv);  // eq. 20
      if constexpr (std::is_same<Hourglass, HourglassLaplacian>::value) {
        const Vec<D, Real> r_over_r0 = e0 + (ui - displacement[j]) * pairs.inv_r0[p];
        force += r_over_r0 * ((si + shear_coefficient[j]) * dwv);  // seed 003 eq. 27
      }
      if constexpr (std::is_same<Hourglass, HourglassGenog>::value) {
        const Vec<D, Real> r_over_r0 = e0 + (ui - displacement[j]) * pairs.inv_r0[p];
        const Vec<D, Real> e_hat = (Finv_i + inverse_F[j]) * r_over_r0 * Real(0.5) - e0;  // eq. 31
        const Real phi = genog_weight(norm(e_hat), pairs.beta ? pairs.beta[p] : Real(0));
        force += (Si + shear_stress[j]) * ((e0 + e_hat * phi) * dwv);  // eq. 32
      }
    }
    acceleration[i] = force * inv_rho0 + body_acceleration;
  }
};

}  // namespace mfsd
