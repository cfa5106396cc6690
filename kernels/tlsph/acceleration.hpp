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
#include "kernels/tlsph/e_hat.hpp"
#include "kernels/tlsph/genog_active_pairs.hpp"
#include "kernels/tlsph/genog_neighbor_record.hpp"
#include "kernels/tlsph/hourglass.hpp"
#include "kernels/tlsph/reference_pairs.hpp"

namespace mfsd {

// phi_ij of the GENOG correction (seed 000 eq. 32-33, or the capped form),
// from |e_hat_ij| > 0.05.
template <class Real>
struct GenogWeight {
  GenogLimiter limiter;
  Real alpha_d;  // alpha * d (paper form)
  GenogForm form = GenogForm::vector;

  static constexpr Real threshold = Real(0.05);

  MFSD_HD Real operator()(Real e_hat_norm, Real beta) const {
    const Real excess = e_hat_norm - threshold;
    if (limiter == GenogLimiter::paper) return alpha_d * beta * math::clamp(excess, Real(0), Real(1));  // eq. 33
    return math::min(Real(10) * math::max(excess, Real(0)), Real(1));
  }

  // What an active pair adds to the sum besides its (S_i + S_j) g part, in
  // units of (S_i + S_j): with g = V0_j dW e0 and h = V0_j dW e_hat,
  //   vector (eq. 32): phi h
  //   dyadic: (c (x) c) g - g = (g + phi h)(1 + phi h.g / g.g) - g, since
  //           c . e0 = 1 + phi e_hat . e0 (c = e0 + phi e_hat, grad W = dW e0).
  template <int D>
  MFSD_HD Vec<D, Real> correction(const Vec<D, Real>& g, const Vec<D, Real>& h, Real phi, Real g2) const {
    if (form == GenogForm::vector) return h * phi;
    const Real c = phi * dot(h, g) / g2;
    return h * phi + (g + h * phi) * c;
  }
};

template <int D, class Real, class Hourglass>
struct AccelerationFunctor {
  ReferencePairs<D, Real> pairs;
  const Mat<D, Real>* force_stress;                  // M (none, laplacian) or Q = M + S (genog)
  const Real* shear_coefficient;                     // s (laplacian)
  const Mat<D, Real>* shear_stress;                  // S (genog)
  const Mat<D, Real>* inverse_F;                     // F^{-1} (genog)
  const Vec<D, Real>* displacement;                  // u
  const GenogNeighborRecord<Real>* neighbor_record;  // 3-D genog on the CPU: Q, F^{-1}, u packed
  Real inv_rho0;
  Vec<D, Real> body_acceleration;  // gravity
  GenogWeight<Real> genog_weight;
  Real dt;  // velocity update v += dt a; 0 leaves v alone
  Vec<D, Real>* acceleration;
  Vec<D, Real>* velocity;

  static constexpr bool laplacian = std::is_same<Hourglass, HourglassLaplacian>::value;
  static constexpr bool genog = std::is_same<Hourglass, HourglassGenog>::value;

  MFSD_HD void operator()(Index i) const {
    if constexpr (genog && D == 3)
      genog_particle_3d(i);
    else
      particle(i);
  }

 private:
  // none, laplacian, and genog in 2-D: one pass over the pairs.
  MFSD_HD void particle(Index i) const {
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
    const PairRow r = pairs.row(i);
    for (Index k = 0; k < r.count; ++k) {
      const PairIndex p = r.at(k);
      const Index j = pairs.neighbor[p];
      const Index ahead = pairs.neighbor[r.at(k + kPairPrefetchDistance)];
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
        const Vec<D, Real> h = scaled_e_hat(Finv_i, inverse_F[j], ui, displacement[j], g, pairs.stretch[p]);  // eq. 31
        const Real h2 = squared_norm(h), g2 = squared_norm(g);
        if (h2 > GenogWeight<Real>::threshold * GenogWeight<Real>::threshold * g2) {
          const Real phi = genog_weight(math::sqrt(h2 / g2), pairs.beta ? pairs.beta[p] : Real(0));
          sum += (Si + shear_stress[j]) * genog_weight.correction(g, h, phi, g2);  // eq. 32, phi e_hat part
        }
      }
    }
    finish(i, sum);
  }

  MFSD_HD void finish(Index i, const Vec<D, Real>& sum) const { finish(i, force_stress[i], sum); }

 public:
  // a_i from sum = sum_j (Q_j g_ij + shear terms), and v += dt a.
  MFSD_HD void finish(Index i, const Mat<D, Real>& Qi, const Vec<D, Real>& sum) const {
    const Vec<D, Real> a = (Qi * pairs.gradient_sum[i] + sum) * inv_rho0 + body_acceleration;
    acceleration[i] = a;
    velocity[i] += a * dt;  // eq. 36
  }

 private:
  // First pass on scalars: sum_j Q_j g_ij into s, and whether some pair may
  // have phi_ij > 0 (the test of GenogActivePairs, a little looser than the
  // second pass's); with a record (host), which pairs.
  MFSD_HD bool genog_first_pass(const Mat<D, Real>& Fi, const Vec<D, Real>& ui, const PairRow& row, Real& s0_out,
                                Real& s1_out, Real& s2_out, GenogActivePairs<Real>* record = nullptr) const {
    const Real* Q = &force_stress[0].m[0][0];
    const Real* Fv = &inverse_F[0].m[0][0];
    const Real* U = &displacement[0].v[0];
    const Real* G = &pairs.grad[0].v[0];
    const Real* K = pairs.stretch;
    const Index* J = pairs.neighbor;
    const Real f00 = Fi.m[0][0], f01 = Fi.m[0][1], f02 = Fi.m[0][2];
    const Real f10 = Fi.m[1][0], f11 = Fi.m[1][1], f12 = Fi.m[1][2];
    const Real f20 = Fi.m[2][0], f21 = Fi.m[2][1], f22 = Fi.m[2][2];
    const Real u0 = ui.v[0], u1 = ui.v[1], u2 = ui.v[2];
    const Real thr2 = GenogActivePairs<Real>::loose_threshold2;  // the second pass tests 0.05^2
    Real s0 = Real(0), s1 = Real(0), s2 = Real(0);
    bool active = false;
    for (Index n = 0; n < row.count; ++n) {
      const PairIndex p = row.at(n);
      const PairIndex j9 = PairIndex(J[p]) * 9, j3 = PairIndex(J[p]) * 3;
      {  // the neighbour kPairPrefetchDistance pairs ahead: 72-byte matrices span two lines
        const PairIndex ahead = PairIndex(J[row.at(n + kPairPrefetchDistance)]);
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
      const Real excess = h0 * h0 + h1 * h1 + h2 * h2 - thr2 * (g0 * g0 + g1 * g1 + g2 * g2);
      active |= excess > Real(0);
      if (record) record->put(n, excess);
    }
    s0_out = s0;
    s1_out = s1;
    s2_out = s2;
    return active;
  }

#if !defined(__CUDACC__)
  // The same first pass on 4-wide vectors (GCC vector extensions; the
  // compiler maps them to SSE/AVX registers), reading the packed neighbour
  // record: Q_j g and (F_i^{-1} + F_j^{-1}) t are three vector FMAs each.
  bool genog_first_pass_packed(const Mat<D, Real>& Fi, const Vec<D, Real>& ui, const PairRow& row, Real& s0_out,
                               Real& s1_out, Real& s2_out, GenogActivePairs<Real>& record) const {
    typedef Real V4 __attribute__((vector_size(4 * sizeof(Real))));
    auto load = [](const Real* p) {
      V4 v;
      __builtin_memcpy(&v, p, sizeof v);
      return v;
    };
    const V4 fi0 = {Fi.m[0][0], Fi.m[1][0], Fi.m[2][0], Real(0)};
    const V4 fi1 = {Fi.m[0][1], Fi.m[1][1], Fi.m[2][1], Real(0)};
    const V4 fi2 = {Fi.m[0][2], Fi.m[1][2], Fi.m[2][2], Real(0)};
    const V4 u_i = {ui.v[0], ui.v[1], ui.v[2], Real(0)};
    const Real thr2 = GenogActivePairs<Real>::loose_threshold2;  // the second pass tests 0.05^2
    const Real* G = &pairs.grad[0].v[0];
    const Real* K = pairs.stretch;
    const Index* J = pairs.neighbor;
    const GenogNeighborRecord<Real>* R = neighbor_record;
    V4 acc = {Real(0), Real(0), Real(0), Real(0)};
    bool active = false;
    for (Index n = 0; n < row.count; ++n) {
      const PairIndex p = row.at(n);
      const GenogNeighborRecord<Real>& r = R[J[p]];
      {  // the record kPairPrefetchDistance pairs ahead (224 bytes in double)
        const char* ahead = reinterpret_cast<const char*>(R + J[row.at(n + kPairPrefetchDistance)]);
        for (unsigned off = 0; off < sizeof(GenogNeighborRecord<Real>); off += 64) prefetch(ahead + off);
      }
      const Real g0 = G[3 * p], g1 = G[3 * p + 1], g2 = G[3 * p + 2], k = K[p];
      acc += load(r.q[0]) * g0 + load(r.q[1]) * g1 + load(r.q[2]) * g2;  // eq. 20, 32: Q_j g_ij
      const V4 g = {g0, g1, g2, Real(0)};
      const V4 t = g + (u_i - load(r.u)) * k;
      const V4 s = (fi0 + load(r.f[0])) * t[0] + (fi1 + load(r.f[1])) * t[1] + (fi2 + load(r.f[2])) * t[2];
      const V4 h = s * Real(0.5) - g;  // eq. 31 times V0_j dW
      const V4 d = h * h - g * g * thr2;
      const Real excess = d[0] + d[1] + d[2];
      active |= excess > Real(0);
      record.put(n, excess);
    }
    s0_out = acc[0];
    s1_out = acc[1];
    s2_out = acc[2];
    return active;
  }
#endif

  // phi_ij (S_i + S_j) h_ij of pair p when it is active (eq. 32, the phi e_hat part).
  MFSD_HD void genog_correction(PairIndex p, const Mat<D, Real>& Fi, const Vec<D, Real>& ui, const Mat<D, Real>& Si,
                                Vec<D, Real>& sum) const {
    const Real thr2 = GenogWeight<Real>::threshold * GenogWeight<Real>::threshold;
    const Index j = pairs.neighbor[p];
    const Vec<D, Real> g = pairs.grad[p];
    const Mat<D, Real> Fj = neighbor_record ? neighbor_record[j].F_inv() : inverse_F[j];
    const Vec<D, Real> h = scaled_e_hat(Fi, Fj, ui, displacement[j], g, pairs.stretch[p]);
    const Real h2 = squared_norm(h), g2 = squared_norm(g);
    if (h2 > thr2 * g2) {
      const Real phi = genog_weight(math::sqrt(h2 / g2), pairs.beta ? pairs.beta[p] : Real(0));
      sum += (Si + shear_stress[j]) * genog_weight.correction(g, h, phi, g2);  // eq. 32, phi e_hat part
    }
  }

  // genog in 3-D: the same sums in two passes over the pairs. The first pass
  // sums Q_j g_ij and tests phi_ij > 0 on squares, written on scalars with
  // (F_i^{-1} + F_j^{-1}) t as 9 adds and 9 multiplies (1.4x faster than the
  // same arithmetic on Vec/Mat temporaries; docs/performance.md). Only a
  // particle with an active pair takes the second pass, which adds
  // phi_ij (S_i + S_j) h_ij: on CPU threads over the pairs the first pass
  // recorded (GenogActivePairs; all of them in a row longer than its
  // capacity), on the GPU over all pairs. The record holds every pair the
  // second pass's own test can accept, so the sums are those of a full second
  // pass, to round-off: a particle whose pairs only pass the looser test takes
  // the second pass and adds nothing, and a pair at the threshold, where
  // phi_ij = 0, may fall either way where the compiler contracts the first
  // pass's arithmetic differently.
  MFSD_HD void genog_particle_3d(Index i) const {
    const Mat<D, Real> Fi = neighbor_record ? neighbor_record[i].F_inv() : inverse_F[i];
    const Vec<D, Real> ui = displacement[i];
    const PairRow row = pairs.row(i);
    Real s0, s1, s2;
    bool active;
#if !defined(__CUDACC__)
    GenogActivePairs<Real> record;
    if (neighbor_record)
      active = genog_first_pass_packed(Fi, ui, row, s0, s1, s2, record);
    else
      active = genog_first_pass(Fi, ui, row, s0, s1, s2, &record);
#else
    active = genog_first_pass(Fi, ui, row, s0, s1, s2);
#endif
    Vec<D, Real> sum;
    sum.v[0] = s0;
    sum.v[1] = s1;
    sum.v[2] = s2;
    if (active) {
      const Mat<D, Real> Si = shear_stress[i];
#if !defined(__CUDACC__)
      if (!record.overflowed(row.count))
        record.for_each(row.count, [&](PairIndex k) { genog_correction(row.at(Index(k)), Fi, ui, Si, sum); });
      else
#endif
        for (Index k = 0; k < row.count; ++k) genog_correction(row.at(k), Fi, ui, Si, sum);
    }
    finish(i, neighbor_record ? neighbor_record[i].Q() : force_stress[i], sum);
  }
};

}  // namespace mfsd
