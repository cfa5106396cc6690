// Rate of the deformation gradient (seed 000 eq. 22; seed 003 eq. 22):
//   dF_i/dt = sum_j V0_j (v_j - v_i) (x) grad0_i W_ij  B0_i
//           = (sum_j v_j (x) g_ij - v_i (x) G_i) B0_i      (reference_pairs.hpp).
// Exact for linear velocity fields (v = L X gives dF/dt = L).
#pragma once
#include "kernels/core/mat.hpp"
#include "kernels/core/step_statistics.hpp"
#include "kernels/tlsph/reference_pairs.hpp"

namespace mfsd {

template <int D, class Real>
MFSD_HD inline Mat<D, Real> deformation_rate(const ReferencePairs<D, Real>& pairs, const Vec<D, Real>* velocity,
                                             const Mat<D, Real>& B0, Index i) {
  Mat<D, Real> sum = Mat<D, Real>::zero();
  const PairRow r = pairs.row(i);
  for (Index k = 0; k < r.count; ++k) {
    const PairIndex p = r.at(k);
    prefetch(&velocity[pairs.neighbor[r.at(k + kPairPrefetchDistance)]]);
    const Vec<D, Real> vj = velocity[pairs.neighbor[p]];
    const Vec<D, Real> g = pairs.grad[p];
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) sum.m[a][b] += vj.v[a] * g.v[b];
  }
  const Vec<D, Real> vi = velocity[i], G = pairs.gradient_sum[i];
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) sum.m[a][b] -= vi.v[a] * G.v[b];
  return sum * B0;
}

template <int D, class Real>
struct DeformationRateFunctor {
  ReferencePairs<D, Real> pairs;
  const Vec<D, Real>* velocity;
  const Mat<D, Real>* correction;  // B0
  Mat<D, Real>* rate;              // dF/dt

  MFSD_HD void operator()(Index i) const { rate[i] = deformation_rate(pairs, velocity, correction[i], i); }
};

// The step's last pass over the particles, fused: dF/dt at the updated velocity,
// the second half step F += dt/2 dF/dt, u += dt/2 v (seed 000 eq. 37), and
// each particle's time-step statistics of the updated state (step_statistics.hpp),
// which the host combines with a reduction.
template <int D, class Real>
struct RateHalfStepFunctor {
  ReferencePairs<D, Real> pairs;
  const Vec<D, Real>* velocity;
  const Mat<D, Real>* correction;
  Mat<D, Real>* rate;
  Mat<D, Real>* deformation_gradient;
  Vec<D, Real>* displacement;
  Real half_dt;
  StepStatisticsFunctor<D, Real> statistics;  // reads the updated displacement

  MFSD_HD StepStatistics<Real> operator()(Index i) const {
    const Mat<D, Real> dF = deformation_rate(pairs, velocity, correction[i], i);
    rate[i] = dF;
    deformation_gradient[i] += dF * half_dt;
    displacement[i] += velocity[i] * half_dt;
    return statistics(i);
  }
};

}  // namespace mfsd
