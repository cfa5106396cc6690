// The step's last pass (RateHalfStepFunctor, deformation_rate.hpp) in the
// half-pair loop (host/backend/cpu.hpp, half_pair_reduce; issue 24): each
// reference pair once. dF_i/dt = sum_j (v_j - v_i) (x) g_ij B0_i (seed 000
// eq. 22), and with g_ji = -(V0_i / V0_j) g_ij particle j's term of the pair
// is (V0_i / V0_j) (v_j - v_i) (x) g_ij: in the volume-weighted sums
// W_k = V0_k sum_l (v_l - v_k) (x) g_kl both particles get
// V0_i (v_j - v_i) (x) g_ij, and dF_k/dt = W_k / V0_k B0_k.
#pragma once
#include <type_traits>

#include "kernels/neighbors/half_pair_sink.hpp"
#include "kernels/tlsph/deformation_rate.hpp"

namespace mfsd {

// The rows of the sums W_i = V0_i sum_j (f_j - f_i) (x) g_ij of a vector
// field f, each pair once; the two finishes below turn them into dF/dt.
// P: how the half list stores its pair data (acceleration_half.hpp).
template <int D, class Real, class P = Real>
struct HalfGradientRows {
  ReferencePairs<D, P> half;  // each row's pairs with j > i
  const Vec<D, Real>* field;  // f (the velocity, or a displacement for F = I + grad u)
  const Real* volume;         // V0

  using Acc = Mat<D, Real>;

  MFSD_HD void operator()(Index i, const HalfPairSink<Acc>& sink) const {
    if constexpr (std::is_same<Real, float>::value)
      row_scalar(i, sink);
    else
      row(i, sink);
  }

 private:
  // Two forms of one row, each the faster in one precision with g++ -O3
  // (bench/pair_loop_ab.py, bending column 84,672 particles, deformation_rate
  // stage half / full): the outer product as a Mat temporary added to both sums
  // (double 0.74, float 1.43: the float lanes are shuffled), and on scalars
  // written into the sums directly (double 1.05, float 0.80).
  MFSD_HD void row(Index i, const HalfPairSink<Acc>& sink) const {
    const Vec<D, Real> vi = field[i];
    const Real Vi = volume[i];
    Acc own = Acc::zero();
    for (PairIndex p = half.offsets[i]; p < half.offsets[i + 1]; ++p) {
      const Index j = half.neighbor[p];
      prefetch(&field[half.neighbor[p + kPairPrefetchDistance]]);
      const Vec<D, Real> d = (field[j] - vi) * Vi;
      const Vec<D, Real> g = cast<Real>(half.grad[p]);
      Acc x;
      for (int a = 0; a < D; ++a)
        for (int b = 0; b < D; ++b) x.m[a][b] = d.v[a] * g.v[b];
      own += x;
      sink.add(j, x);
    }
    sink.add(i, own);
  }

  MFSD_HD void row_scalar(Index i, const HalfPairSink<Acc>& sink) const {
    const Vec<D, Real> vi = field[i];
    const Real Vi = volume[i];
    Real own[D][D] = {};
    for (PairIndex p = half.offsets[i]; p < half.offsets[i + 1]; ++p) {
      const Index j = half.neighbor[p];
      prefetch(&field[half.neighbor[p + kPairPrefetchDistance]]);
      const Vec<D, Real> vj = field[j];
      const Vec<D, Real> g = cast<Real>(half.grad[p]);
      Real d[D];
      for (int a = 0; a < D; ++a) d[a] = (vj.v[a] - vi.v[a]) * Vi;
      Acc& aj = j < sink.hi ? sink.acc[j] : sink.remote[j - sink.hi];
      for (int a = 0; a < D; ++a)
        for (int b = 0; b < D; ++b) {
          const Real x = d[a] * g.v[b];
          own[a][b] += x;
          aj.m[a][b] += x;
        }
    }
    Acc& ai = sink.acc[i];
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) ai.m[a][b] += own[a][b];
  }
};

// The step's last pass: the rate, F and u at the half step, the statistics.
template <int D, class Real, class P = Real>
struct RateHalfStepHalfFunctor {
  RateHalfStepFunctor<D, Real> f;     // fields, the half step and the statistics
  HalfGradientRows<D, Real, P> rows;  // over f.velocity

  using Acc = Mat<D, Real>;

  MFSD_HD void operator()(Index i, const HalfPairSink<Acc>& sink) const { rows(i, sink); }

  MFSD_HD StepStatistics<Real> finish(Index i, const Acc& total) const {
    const Mat<D, Real> dF = total * (Real(1) / rows.volume[i]) * f.correction[i];
    f.rate[i] = dF;
    f.deformation_gradient[i] += dF * f.half_dt;
    f.displacement[i] += f.velocity[i] * f.half_dt;
    return f.statistics(i);
  }
};

// DeformationRateFunctor (deformation_rate.hpp) in the half-pair loop:
// rate_i = sum_j (f_j - f_i) (x) g_ij B0_i (seed 000 eq. 22).
template <int D, class Real, class P = Real>
struct DeformationRateHalfFunctor {
  HalfGradientRows<D, Real, P> rows;
  const Mat<D, Real>* correction;  // B0
  Mat<D, Real>* rate;

  using Acc = Mat<D, Real>;

  MFSD_HD void operator()(Index i, const HalfPairSink<Acc>& sink) const { rows(i, sink); }
  MFSD_HD void finish(Index i, const Acc& total) const { rate[i] = total * (Real(1) / rows.volume[i]) * correction[i]; }
};

}  // namespace mfsd
