// The force stage of acceleration.hpp in the half-pair loop strategy
// (host/backend/cpu.hpp, half_pair_for; issue 24): each reference pair once,
// from the row of its smaller index. With g_ij = V0_j grad0_i W_ij the pair
// terms are antisymmetric up to the volumes: g_ji = -(V0_i / V0_j) g_ij, and
// likewise t_ji (laplacian) and h_ji (genog: e_hat_ji = -e_hat_ij, so phi_ji =
// phi_ij), so in momentum units (rho0 V0 a) the pair gives
//   to i:  V0_i (Q_j g_ij + c_ij),    to j: -V0_i (Q_i g_ij + c_ij),
// c_ij the shear term of the hourglass variant (seed 003 eq. 27; seed 000
// eq. 32), and the Q_i G_i term of each particle (seed 000 eq. 20) is added at
// the end. The genog test and correction are evaluated once per pair: no
// second pass. Results equal the full gather's to round-off.
#pragma once
#include "kernels/neighbors/half_pair_sink.hpp"
#include "kernels/tlsph/acceleration.hpp"

namespace mfsd {

// P: how the half list stores its pair data (Real, or float in a double run:
// --pair-precision float, issue 24 item 4); the arithmetic is in Real.
template <int D, class Real, class Hourglass, class P = Real>
struct AccelerationHalfFunctor {
  AccelerationFunctor<D, Real, Hourglass> f;  // fields and the finish (f.pairs: the full list, for G_i)
  ReferencePairs<D, P> half;                  // each row's pairs with j > i (reference_neighbor_list.hpp)
  const Real* volume;                         // V0

  using Acc = Vec<D, Real>;
  static constexpr bool laplacian = AccelerationFunctor<D, Real, Hourglass>::laplacian;
  static constexpr bool genog = AccelerationFunctor<D, Real, Hourglass>::genog;
  static constexpr bool packed = genog && D == 3;  // 3-D genog may read the neighbour record

  MFSD_HD Mat<D, Real> Q(Index j) const {
    if constexpr (packed)
      if (f.neighbor_record) return f.neighbor_record[j].Q();
    return f.force_stress[j];
  }
  MFSD_HD Mat<D, Real> F_inv(Index j) const {
    if constexpr (packed)
      if (f.neighbor_record) return f.neighbor_record[j].F_inv();
    return f.inverse_F[j];
  }

  // Row i's pairs with j > i.
  MFSD_HD void operator()(Index i, const HalfPairSink<Acc>& sink) const {
#if !defined(__CUDACC__)
    if constexpr (packed) {
      if (f.neighbor_record) {
        row_packed(i, sink);
        return;
      }
    }
#endif
    row(i, sink);
  }

  MFSD_HD void finish(Index i, const Acc& total) const { f.finish(i, Q(i), total * (Real(1) / volume[i])); }

 private:
  MFSD_HD void row(Index i, const HalfPairSink<Acc>& sink) const {
    const ReferencePairs<D, P>& pairs = half;
    const Real Vi = volume[i];
    const Mat<D, Real> Qi = Q(i);
    [[maybe_unused]] Vec<D, Real> ui;
    [[maybe_unused]] Real si;
    [[maybe_unused]] Mat<D, Real> Si, Fi;
    if constexpr (laplacian || genog) ui = f.displacement[i];
    if constexpr (laplacian) si = f.shear_coefficient[i];
    if constexpr (genog) {
      Si = f.shear_stress[i];
      Fi = F_inv(i);
    }
    constexpr Real thr2 = GenogWeight<Real>::threshold * GenogWeight<Real>::threshold;
    Acc sum = Acc::zero();
    const PairIndex end = pairs.offsets[i + 1];
    for (PairIndex p = pairs.offsets[i]; p < end; ++p) {
      const Index j = pairs.neighbor[p];
      {
        const Index ahead = pairs.neighbor[p + kPairPrefetchDistance];
        if constexpr (packed) {
          if (f.neighbor_record) {
            const char* r = reinterpret_cast<const char*>(f.neighbor_record + ahead);
            for (unsigned off = 0; off < sizeof(GenogNeighborRecord<Real>); off += 64) prefetch(r + off);
          } else {
            prefetch(&f.force_stress[ahead]);
          }
        } else {
          prefetch(&f.force_stress[ahead]);
        }
        prefetch(&sink.acc[ahead < sink.hi ? ahead : i]);
      }
      const Vec<D, Real> g = cast<Real>(pairs.grad[p]);
      const Real stretch = Real(pairs.stretch[p]);
      Vec<D, Real> own = Q(j) * g;  // eq. 20: Q_j g_ij for i
      Vec<D, Real> other = Qi * g;  // and Q_i g_ij for j
      if constexpr (laplacian) {
        const Vec<D, Real> t = g + (ui - f.displacement[j]) * stretch;
        const Vec<D, Real> c = t * (si + f.shear_coefficient[j]);  // seed 003 eq. 27
        own += c;
        other += c;
      }
      if constexpr (genog) {
        const Vec<D, Real> h = scaled_e_hat(Fi, F_inv(j), ui, f.displacement[j], g, stretch);  // eq. 31
        const Real h2 = squared_norm(h), g2 = squared_norm(g);
        if (h2 > thr2 * g2) {
          const Real phi = f.genog_weight(math::sqrt(h2 / g2), pairs.beta ? Real(pairs.beta[p]) : Real(0));
          const Vec<D, Real> c = (Si + f.shear_stress[j]) * f.genog_weight.correction(g, h, phi, g2);  // eq. 32
          own += c;
          other += c;
        }
      }
      sum += own;
      sink.add(j, other * (-Vi));
    }
    sink.add(i, sum * Vi);
  }

#if !defined(__CUDACC__)
  // 3-D genog from the packed neighbour record on 4-wide vectors (as the full
  // gather's first pass, acceleration.hpp): Q_j g, Q_i g and
  // (F_i^{-1} + F_j^{-1}) t are three vector FMAs each; the rare active pair
  // takes the scalar correction.
  void row_packed(Index i, const HalfPairSink<Acc>& sink) const {
    typedef Real V4 __attribute__((vector_size(4 * sizeof(Real))));
    auto load = [](const Real* p) {
      V4 v;
      __builtin_memcpy(&v, p, sizeof v);
      return v;
    };
    const ReferencePairs<D, P>& pairs = half;
    const GenogNeighborRecord<Real>* R = f.neighbor_record;
    const GenogNeighborRecord<Real>& ri = R[i];
    const V4 qi0 = load(ri.q[0]), qi1 = load(ri.q[1]), qi2 = load(ri.q[2]);
    const V4 fi0 = load(ri.f[0]), fi1 = load(ri.f[1]), fi2 = load(ri.f[2]);
    const V4 u_i = load(ri.u);
    const Real Vi = volume[i];
    constexpr Real thr2 = GenogWeight<Real>::threshold * GenogWeight<Real>::threshold;
    const P* G = &pairs.grad[0].v[0];
    const P* K = pairs.stretch;
    const Index* J = pairs.neighbor;
    V4 own = {Real(0), Real(0), Real(0), Real(0)};
    const PairIndex end = pairs.offsets[i + 1];
    for (PairIndex p = pairs.offsets[i]; p < end; ++p) {
      const Index j = J[p];
      const GenogNeighborRecord<Real>& r = R[j];
      {  // the record kPairPrefetchDistance pairs ahead (224 bytes in double), and its sum
        const Index ahead = J[p + kPairPrefetchDistance];
        const char* a = reinterpret_cast<const char*>(R + ahead);
        for (unsigned off = 0; off < sizeof(GenogNeighborRecord<Real>); off += 64) prefetch(a + off);
        prefetch(&sink.acc[ahead < sink.hi ? ahead : i]);
      }
      const Real g0 = G[3 * p], g1 = G[3 * p + 1], g2 = G[3 * p + 2], k = K[p];
      V4 to_i = load(r.q[0]) * g0 + load(r.q[1]) * g1 + load(r.q[2]) * g2;  // eq. 20, 32: Q_j g_ij
      V4 to_j = qi0 * g0 + qi1 * g1 + qi2 * g2;                             // and Q_i g_ij
      const V4 g = {g0, g1, g2, Real(0)};
      const V4 t = g + (u_i - load(r.u)) * k;
      const V4 hs = (fi0 + load(r.f[0])) * t[0] + (fi1 + load(r.f[1])) * t[1] + (fi2 + load(r.f[2])) * t[2];
      const V4 h = hs * Real(0.5) - g;  // eq. 31 times V0_j dW
      const V4 d = h * h - g * g * thr2;
      if (d[0] + d[1] + d[2] > Real(0)) {  // phi_ij > 0: eq. 32's phi e_hat part
        const Vec<D, Real> gv{{g0, g1, g2}}, hv{{h[0], h[1], h[2]}};
        const Real h2v = squared_norm(hv), g2v = squared_norm(gv);
        const Real phi = f.genog_weight(math::sqrt(h2v / g2v), pairs.beta ? Real(pairs.beta[p]) : Real(0));
        const Vec<D, Real> c = (f.shear_stress[i] + f.shear_stress[j]) * f.genog_weight.correction(gv, hv, phi, g2v);
        const V4 cv = {c.v[0], c.v[1], c.v[2], Real(0)};
        to_i += cv;
        to_j += cv;
      }
      own += to_i;
      Vec<D, Real>& aj = j < sink.hi ? sink.acc[j] : sink.remote[j - sink.hi];
      aj.v[0] -= Vi * to_j[0];
      aj.v[1] -= Vi * to_j[1];
      aj.v[2] -= Vi * to_j[2];
    }
    sink.add(i, Vec<D, Real>{{Vi * own[0], Vi * own[1], Vi * own[2]}});
  }
#endif
};

}  // namespace mfsd
