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
    if constexpr (genog && D == 3) {
      genog_particle_3d(i);
      return;
    }
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
      const Index ahead = pairs.neighbor[p + kPairPrefetchDistance];
      prefetch(&force_stress[ahead]);
      if constexpr (laplacian || genog) prefetch(&displacement[ahead]);
      if constexpr (genog) prefetch(&inverse_F[ahead]);
      const Vec<D, Real> g = pairs.grad[p];
      sum += force_stress[j] * g;  // eq. 20 (M_j part); M_i part below
      if constexpr (laplacian) {
        const Vec<D, Real> t = g + (ui - displacement[j]) * pairs.stretch[p];
        sum += t * (si + shear_coefficient[j]);  // seed 003 eq. 27
      }
      if constexpr (genog) {
        const Vec<D, Real> t = g + (ui - displacement[j]) * pairs.stretch[p];
        const Vec<D, Real> h = (Finv_i + inverse_F[j]) * t * Real(0.5) - g;  // dW V0 e_hat, eq. 31
        const Real h2 = squared_norm(h), g2 = squared_norm(g);
        if (h2 > GenogWeight<Real>::threshold * GenogWeight<Real>::threshold * g2) {
          const Real phi = genog_weight(math::sqrt(h2 / g2), pairs.beta ? pairs.beta[p] : Real(0));
          sum += (Si + shear_stress[j]) * h * phi;  // eq. 32, phi e_hat part
        }
      }
    }
    finish(i, sum);
  }

 private:
  MFSD_HD void finish(Index i, const Vec<D, Real>& sum) const {
    const Vec<D, Real> a = (force_stress[i] * pairs.gradient_sum[i] + sum) * inv_rho0 + body_acceleration;
    acceleration[i] = a;
    velocity[i] += a * dt;  // eq. 36
  }

  // genog in 3-D: the same sums in two passes over the pairs. The first pass
  // sums Q_j g_ij and tests phi_ij > 0 on squares, written on scalars with
  // (F_i^{-1} + F_j^{-1}) t as 9 adds and 9 multiplies (1.4x faster than the
  // same arithmetic on Vec/Mat temporaries; docs/performance.md). Only a
  // particle with an active pair (rare in an orderly distribution) takes the
  // second pass, which adds phi_ij (S_i + S_j) h_ij.
  MFSD_HD void genog_particle_3d(Index i) const {
    const Real* Q = &force_stress[0].m[0][0];
    const Real* Fv = &inverse_F[0].m[0][0];
    const Real* U = &displacement[0].v[0];
    const Real* G = &pairs.grad[0].v[0];
    const Real* K = pairs.stretch;
    const Index* J = pairs.neighbor;
    const Mat<D, Real> Fi = inverse_F[i];
    const Vec<D, Real> ui = displacement[i];
    const Real f00 = Fi.m[0][0], f01 = Fi.m[0][1], f02 = Fi.m[0][2];
    const Real f10 = Fi.m[1][0], f11 = Fi.m[1][1], f12 = Fi.m[1][2];
    const Real f20 = Fi.m[2][0], f21 = Fi.m[2][1], f22 = Fi.m[2][2];
    const Real u0 = ui.v[0], u1 = ui.v[1], u2 = ui.v[2];
    const Real thr2 = GenogWeight<Real>::threshold * GenogWeight<Real>::threshold;
    const PairIndex begin = pairs.offsets[i], end = pairs.offsets[i + 1];
    Real s0 = Real(0), s1 = Real(0), s2 = Real(0);
    bool active = false;
    for (PairIndex p = begin; p < end; ++p) {
      const PairIndex j9 = PairIndex(J[p]) * 9, j3 = PairIndex(J[p]) * 3;
      {  // the neighbour kPairPrefetchDistance pairs ahead: 72-byte matrices span two lines
        const PairIndex ahead = PairIndex(J[p + kPairPrefetchDistance]);
        prefetch(Q + ahead * 9);
        prefetch(Q + ahead * 9 + 8);
        prefetch(Fv + ahead * 9);
        prefetch(Fv + ahead * 9 + 8);
        prefetch(U + ahead * 3);
      }
      const Real g0 = G[3 * p], g1 = G[3 * p + 1], g2 = G[3 * p + 2], k = K[p];
      s0 += Q[j9] * g0 + Q[j9 + 1] * g1 + Q[j9 + 2] * g2;  // eq. 20, 32: Q_j g_ij
      s1 += Q[j9 + 3] * g0 + Q[j9 + 4] * g1 + Q[j9 + 5] * g2;
      s2 += Q[j9 + 6] * g0 + Q[j9 + 7] * g1 + Q[j9 + 8] * g2;
      const Real t0 = g0 + (u0 - U[j3]) * k, t1 = g1 + (u1 - U[j3 + 1]) * k, t2 = g2 + (u2 - U[j3 + 2]) * k;
      // h = 1/2 (F_i^{-1} + F_j^{-1}) t - g  (eq. 31 times V0_j dW)
      const Real h0 = Real(0.5) * ((f00 + Fv[j9]) * t0 + (f01 + Fv[j9 + 1]) * t1 + (f02 + Fv[j9 + 2]) * t2) - g0;
      const Real h1 = Real(0.5) * ((f10 + Fv[j9 + 3]) * t0 + (f11 + Fv[j9 + 4]) * t1 + (f12 + Fv[j9 + 5]) * t2) - g1;
      const Real h2 = Real(0.5) * ((f20 + Fv[j9 + 6]) * t0 + (f21 + Fv[j9 + 7]) * t1 + (f22 + Fv[j9 + 8]) * t2) - g2;
      active |= h0 * h0 + h1 * h1 + h2 * h2 > thr2 * (g0 * g0 + g1 * g1 + g2 * g2);
    }
    Vec<D, Real> sum;
    sum.v[0] = s0;
    sum.v[1] = s1;
    sum.v[2] = s2;
    if (active) {
      const Mat<D, Real> Si = shear_stress[i];
      for (PairIndex p = begin; p < end; ++p) {
        const Index j = pairs.neighbor[p];
        const Vec<D, Real> g = pairs.grad[p];
        const Vec<D, Real> t = g + (ui - displacement[j]) * pairs.stretch[p];
        const Vec<D, Real> h = (Fi + inverse_F[j]) * t * Real(0.5) - g;
        const Real h2 = squared_norm(h), g2 = squared_norm(g);
        if (h2 > thr2 * g2) {
          const Real phi = genog_weight(math::sqrt(h2 / g2), pairs.beta ? pairs.beta[p] : Real(0));
          sum += (Si + shear_stress[j]) * h * phi;  // eq. 32, phi e_hat part
        }
      }
    }
    finish(i, sum);
  }
};

}  // namespace mfsd
