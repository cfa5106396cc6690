// Hourglass indicator of a particle (validation.md, "Stability measures"):
// the mean over its reference neighbours of |e_hat_ij|,
//   e_hat_ij = 1/2 (F_i^{-1} + F_j^{-1}) r_ij / r0_ij - e0_ij   (seed 000 eq. 31),
// zero for any linear deformation, large for zigzag (hourglass) patterns.
#pragma once
#include "kernels/core/mat.hpp"
#include "kernels/tlsph/reference_pairs.hpp"

namespace mfsd {

// F^{-1} per particle (scratch for the indicator).
template <int D, class Real>
struct InverseDeformationFunctor {
  const Mat<D, Real>* deformation_gradient;
  Mat<D, Real>* inverse_F;
  MFSD_HD void operator()(Index i) const { inverse_F[i] = inverse(deformation_gradient[i]); }
};

template <int D, class Real>
struct HourglassIndicatorFunctor {
  ReferencePairs<D, Real> pairs;
  const Mat<D, Real>* inverse_F;
  const Vec<D, Real>* displacement;
  Real* indicator;

  MFSD_HD void operator()(Index i) const {
    const PairIndex begin = pairs.offsets[i], end = pairs.offsets[i + 1];
    const Vec<D, Real> ui = displacement[i];
    const Mat<D, Real> Fi_inv = inverse_F[i];
    Real sum = Real(0);
    for (PairIndex p = begin; p < end; ++p) {
      const Index j = pairs.neighbor[p];
      const Vec<D, Real> e0 = pairs.e0[p];
      const Vec<D, Real> r_over_r0 = e0 + (ui - displacement[j]) * pairs.inv_r0[p];
      sum += norm((Fi_inv + inverse_F[j]) * r_over_r0 * Real(0.5) - e0);
    }
    indicator[i] = end > begin ? sum / Real(end - begin) : Real(0);
  }
};

}  // namespace mfsd
