// Hourglass indicator of a particle (validation.md, "Stability measures"):
// the mean over its reference neighbours of |e_hat_ij|,
//   e_hat_ij = 1/2 (F_i^{-1} + F_j^{-1}) r_ij / r0_ij - e0_ij   (seed 000 eq. 31),
// zero for any linear deformation, large for zigzag (hourglass) patterns.
// From the pair data: |e_hat_ij| = |h_ij| / |g_ij| (acceleration.hpp); pairs
// with a zero kernel gradient (at the support edge) carry no direction and
// are left out of the mean. F^{-1} comes from a scratch field filled by
// InverseDeformationFunctor, or, where the run keeps none (3-D genog with the
// packed record on the CPU: the memory of a large run, issue 24 item 6), is
// inverted per pair from F at output times.
#pragma once
#include "kernels/core/mat.hpp"
#include "kernels/neighbors/half_pair_sink.hpp"
#include "kernels/tlsph/e_hat.hpp"
#include "kernels/tlsph/reference_pairs.hpp"

namespace mfsd {

// F^{-1} per particle (scratch for the indicator).
template <int D, class Real>
struct InverseDeformationFunctor {
  const Mat<D, Real>* deformation_gradient;
  Mat<D, Real>* inverse_F;
  MFSD_HD void operator()(Index i) const { inverse_F[i] = inverse(deformation_gradient[i]); }
};

// F_j^{-1}: from the scratch field where there is one, else inverted from F_j.
template <int D, class Real>
struct InverseOfF {
  const Mat<D, Real>* inverse_F;  // may be null
  const Mat<D, Real>* deformation_gradient;
  MFSD_HD Mat<D, Real> operator[](Index j) const { return inverse_F ? inverse_F[j] : inverse(deformation_gradient[j]); }
};

template <int D, class Real>
struct HourglassIndicatorFunctor {
  ReferencePairs<D, Real> pairs;
  InverseOfF<D, Real> inverse_F;
  const Vec<D, Real>* displacement;
  Real* indicator;

  MFSD_HD void operator()(Index i) const {
    const PairRow r = pairs.row(i);
    const Vec<D, Real> ui = displacement[i];
    const Mat<D, Real> Fi_inv = inverse_F[i];
    Real sum = Real(0);
    Index count = 0;
    for (Index k = 0; k < r.count; ++k) {
      const PairIndex p = r.at(k);
      const Index j = pairs.neighbor[p];
      const Vec<D, Real> g = pairs.grad[p];
      const Real g2 = squared_norm(g);
      if (g2 == Real(0)) continue;
      const Vec<D, Real> h = scaled_e_hat(Fi_inv, inverse_F[j], ui, displacement[j], g, pairs.stretch[p]);
      sum += math::sqrt(squared_norm(h) / g2);
      ++count;
    }
    indicator[i] = count > 0 ? sum / Real(count) : Real(0);
  }
};

// The same mean in the half-pair loop (issue 24; host/backend/cpu.hpp):
// |e_hat_ji| = |e_hat_ij| (e_hat_ji = -e_hat_ij), so each pair's value and
// its count go to both particles.
template <class Real>
struct SumCount {
  Real sum, count;
  MFSD_HD SumCount& operator+=(const SumCount& o) {
    sum += o.sum;
    count += o.count;
    return *this;
  }
};

template <int D, class Real, class P = Real>  // P: the half list's pair data (acceleration_half.hpp)
struct HourglassIndicatorHalfFunctor {
  ReferencePairs<D, P> half;  // each row's pairs with j > i
  InverseOfF<D, Real> inverse_F;
  const Vec<D, Real>* displacement;
  Real* indicator;

  MFSD_HD void operator()(Index i, const HalfPairSink<SumCount<Real>>& sink) const {
    const Vec<D, Real> ui = displacement[i];
    const Mat<D, Real> Fi_inv = inverse_F[i];
    SumCount<Real> own{Real(0), Real(0)};
    for (PairIndex p = half.offsets[i]; p < half.offsets[i + 1]; ++p) {
      const Index j = half.neighbor[p];
      const Vec<D, Real> g = cast<Real>(half.grad[p]);
      const Real g2 = squared_norm(g);
      if (g2 == Real(0)) continue;
      const Vec<D, Real> h = scaled_e_hat(Fi_inv, inverse_F[j], ui, displacement[j], g, Real(half.stretch[p]));
      const SumCount<Real> e{math::sqrt(squared_norm(h) / g2), Real(1)};
      own += e;
      sink.add(j, e);
    }
    sink.add(i, own);
  }

  MFSD_HD void finish(Index i, const SumCount<Real>& t) const {
    indicator[i] = t.count > Real(0) ? t.sum / t.count : Real(0);
  }
};

}  // namespace mfsd
