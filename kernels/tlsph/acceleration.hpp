// Force stage of TLSPH, fused with the velocity update: particle acceleration
// from the stress stage's matrices, gathered over the reference neighbours
// (no atomics), then v += dt a (seed 000 eq. 36). With g_ij = V0_j grad0_i W_ij
// and G_i = sum_j g_ij (reference_pairs.hpp):
//   a_i = 1/rho0_i sum_j (M_i + M_j) g_ij                          (seed 000 eq. 20)
//       = 1/rho0_i (M_i G_i + sum_j M_j g_ij)
// plus the shear term of the hourglass variant:
//   laplacian: + 1/rho0_i sum_j (s_i + s_j) (r_ij / r0_ij) V0_j dW0_ij (seed 003 eq. 27)
//   genog    : + 1/rho0_i sum_j (S_i + S_j) (e0_ij + phi_ij e_hat_ij) V0_j dW0_ij
//                                                                      (seed 000 eq. 32)
//     e_hat_ij = 1/2 (F_i^{-1} + F_j^{-1}) r_ij / r0_ij - e0_ij         (seed 000 eq. 31)
// and body forces. In pair data, V0_j dW0 r_ij / r0_ij = g_ij + (u_i - u_j) stretch_ij
// =: t_ij, and V0_j dW0 e_hat_ij = 1/2 (F_i^{-1} + F_j^{-1}) t_ij - g_ij =: h_ij, so
// |e_hat_ij| = |h_ij| / |g_ij|. For genog the stress stage stores Q = M + S, and
//   a_i = 1/rho0_i (Q_i G_i + sum_j Q_j g_ij + sum_{phi_ij > 0} phi_ij (S_i + S_j) h_ij);
// phi_ij = 0 unless |e_hat_ij| > 0.05, which is tested on squares (no root) and
// is rare in an orderly particle distribution.
#pragma once
#include <type_traits>

#include "kernels/core/mat.hpp"
#include "kernels/tlsph/hourglass.hpp"
#include "kernels/tlsph/reference_pairs.hpp"

namespace mfsd {

// phi_ij of the GENOG correction (seed 000 eq. 32-33, or the capped form),
// from |e_hat_ij| > 0.05.
template <class Real>
struct GenogWeight {
  GenogLimiter limiter;
  Real alpha_d;  // alpha * d (paper form)

  static constexpr Real threshold = Real(0.05);

  MFSD_HD Real operator()(Real e_hat_norm, Real beta) const {
    const Real excess = e_hat_norm - threshold;
    if (limiter == GenogLimiter::paper)
      return alpha_d * beta * math::clamp(excess, Real(0), Real(1));  // eq. 33
    return math::min(Real(10) * math::max(excess, Real(0)), Real(1));
  }
};

template <int D, class Real, class Hourglass>
struct AccelerationFunctor {
  ReferencePairs<D, Real> pairs;
  const Mat<D, Real>* force_stress;     // M (none, laplacian) or Q = M + S (genog)
  const Real* shear_coefficient;        // s (laplacian)
  const Mat<D, Real>* shear_stress;     // S (genog)
  const Mat<D, Real>* inverse_F;        // F^{-1} (genog)
  const Vec<D, Real>* displacement;     // u
  Real inv_rho0;
  Vec<D, Real> body_acceleration;       // gravity
  GenogWeight<Real> genog_weight;
  Real dt;                              // velocity update v += dt a; 0 leaves v alone
  Vec<D, Real>* acceleration;
  Vec<D, Real>* velocity;

  static constexpr bool laplacian = std::is_same<Hourglass, HourglassLaplacian>::value;
  static constexpr bool genog = std::is_same<Hourglass, HourglassGenog>::value;

  MFSD_HD void operator()(Index i) const {
    Vec<D, Real> sum = Vec<D, Real>::zero();  // sum_j Q_j g_ij (+ laplacian and genog terms)
    [[maybe_unused]] Vec<D, Real> ui;
    [[maybe_unused]] Real si;
    [[maybe_unused]] Mat<D, Real> Si, Finv_i;
    if constexpr (laplacian || genog) ui = displacement[i];
    if constexpr (laplacian) si = shear_coefficient[i];
    if constexpr (genog) {
      Si = shear_stress[i];
      Finv_i = inverse_F[i];
    }
    const PairIndex begin = pairs.offsets[i], end = pairs.offsets[i + 1];
    for (PairIndex p = begin; p < end; ++p) {
      const Index j = pairs.neighbor[p];
      const Vec<D, Real> g = pairs.grad[p];
      sum += force_stress[j] * g;  // eq. 20 (M_j part); M_i part below
      if constexpr (laplacian) {
        const Vec<D, Real> t = g + (ui - displacement[j]) * pairs.stretch[p];
        sum += t * (si + shear_coefficient[j]);  // seed 003 eq. 27
      }
      if constexpr (genog) {
        const Vec<D, Real> t = g + (ui - displacement[j]) * pairs.stretch[p];
        const Vec<D, Real> h = (Finv_i * t + inverse_F[j] * t) * Real(0.5) - g;  // dW V0 e_hat, eq. 31
        const Real h2 = squared_norm(h), g2 = squared_norm(g);
        if (h2 > GenogWeight<Real>::threshold * GenogWeight<Real>::threshold * g2) {
          const Real phi = genog_weight(math::sqrt(h2 / g2), pairs.beta ? pairs.beta[p] : Real(0));
          sum += (Si + shear_stress[j]) * h * phi;  // eq. 32, phi e_hat part
        }
      }
    }
    const Vec<D, Real> a = (force_stress[i] * pairs.gradient_sum[i] + sum) * inv_rho0 + body_acceleration;
    acceleration[i] = a;
    velocity[i] += a * dt;  // eq. 36
  }
};

}  // namespace mfsd
