// Neo-Hookean material in volumetric-deviatoric Kirchhoff form
// (seed 000 eq. 4-8; seed 003 eq. 10-14):
//   W = K/2 [ (J^2 - 1)/2 - ln J ] + G/2 (tr(b_bar) - d),  b_bar = J^{-2/d} b,
//   tau = K/2 (J^2 - 1) I + G dev(b_bar).
// The hourglass-controlled forms split tau = tau_vol I + c (b - tr(b)/d I)
// with c = G J^{-2/d} = G |b|^{-1/d} (seed 000 eq. 25).
#pragma once
#include "kernels/core/mat.hpp"
#include "kernels/materials/material_interface.hpp"

namespace mfsd {

template <int D, class Real>
struct NeoHookean {
  Real K;  // bulk modulus
  Real G;  // shear modulus

  // Volumetric Kirchhoff stress K/2 (J^2 - 1) (seed 000 eq. 7).
  MFSD_HD Real volumetric_kirchhoff(Real J) const { return Real(0.5) * K * (J * J - Real(1)); }

  // J^{-2/d} without a general pow (3-D: cube root; 2-D: 1/J).
  MFSD_HD static Real isochoric_factor(Real J) {
    if constexpr (D == 2) {
      return Real(1) / J;
    } else {
      const Real c = math::cbrt(J);
      return Real(1) / (c * c);
    }
  }

  // c = G J^{-2/d} (seed 000 eq. 25, tau_s = c b).
  MFSD_HD Real shear_coefficient(Real J) const { return G * isochoric_factor(J); }

  // The material at particle i: the same at every particle (material_interface.hpp).
  MFSD_HD const NeoHookean& at(Index) const { return *this; }
  // GENOG's split tau = tau_r + c b (seed 000 eq. 25).
  MFSD_HD KirchhoffSplit<D, Real> genog_split(const Mat<D, Real>& F) const { return isotropic_genog_split(*this, F); }

  MFSD_HD Mat<D, Real> kirchhoff(const Mat<D, Real>& F) const {
    const Real J = det(F);
    Mat<D, Real> tau = deviator(mul_transposed(F, F)) * shear_coefficient(J);  // G dev(b_bar), eq. 8
    return tau.add_diagonal(volumetric_kirchhoff(J));                          // eq. 7
  }

  // Strain energy per reference volume (seed 000 eq. 4-6).
  MFSD_HD Real strain_energy_density(const Mat<D, Real>& F) const {
    const Real J = det(F);
    const Real tr_b_bar = trace(mul_transposed(F, F)) * isochoric_factor(J);
    return Real(0.5) * K * (Real(0.5) * (J * J - Real(1)) - math::log(J)) + Real(0.5) * G * (tr_b_bar - Real(D));
  }
};

}  // namespace mfsd
