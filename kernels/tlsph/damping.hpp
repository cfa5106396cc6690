// Kelvin-Voigt artificial damping stress (seed 003 eq. 23-24; seed 000 eq. 23-24):
//   tau_d = (chi/2) db/dt,  chi = rho0 c h / 2,  db/dt = dF F^T + F dF^T,
// i.e. tau_d = (rho0 h c / 2) E_dot with E_dot = (dF F^T + F dF^T)/2.
// `normal` and `shear` are factor * rho0 h c / 2 for the diagonal and the
// off-diagonal components: the papers use one sound speed for all
// (isotropic form); the authors' code uses the shear-wave speed on the
// off-diagonal ones (split form, formulations.md section 1).
#pragma once
#include "kernels/core/mat.hpp"

namespace mfsd {

template <class Real>
struct KelvinVoigtDamping {
  Real normal;  // factor * rho0 * h * c_normal / 2
  Real shear;   // factor * rho0 * h * c_shear / 2

  template <int D>
  MFSD_HD Mat<D, Real> stress(const Mat<D, Real>& F, const Mat<D, Real>& dF) const {
    const Mat<D, Real> a = mul_transposed(dF, F);  // dF F^T
    Mat<D, Real> tau;
    for (int r = 0; r < D; ++r)
      for (int c = 0; c < D; ++c) {
        const Real e_dot = Real(0.5) * (a.m[r][c] + a.m[c][r]);
        tau.m[r][c] = (r == c ? normal : shear) * e_dot;
      }
    return tau;
  }
};

}  // namespace mfsd
