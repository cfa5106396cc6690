// Rate of the deformation gradient (seed 000 eq. 22; seed 003 eq. 22):
//   dF_i/dt = sum_j V0_j (v_j - v_i) (x) grad0_i W_ij  B0_i.
// Exact for linear velocity fields (v = L X gives dF/dt = L).
#pragma once
#include "kernels/core/mat.hpp"
#include "kernels/tlsph/reference_pairs.hpp"

namespace mfsd {

template <int D, class Real>
struct DeformationRateFunctor {
  ReferencePairs<D, Real> pairs;
  const Vec<D, Real>* velocity;
  const Mat<D, Real>* correction;  // B0
  Mat<D, Real>* rate;              // dF/dt

  MFSD_HD void operator()(Index i) const {
    const Vec<D, Real> vi = velocity[i];
    Mat<D, Real> sum = Mat<D, Real>::zero();
    for (PairIndex p = pairs.offsets[i]; p < pairs.offsets[i + 1]; ++p) {
      const Vec<D, Real> dv = velocity[pairs.neighbor[p]] - vi;
      const Vec<D, Real> g = pairs.e0[p] * pairs.dwv[p];  // V0_j grad0_i W_ij
      for (int a = 0; a < D; ++a)
        for (int b = 0; b < D; ++b) sum.m[a][b] += dv.v[a] * g.v[b];
    }
    rate[i] = sum * correction[i];
  }
};

}  // namespace mfsd
