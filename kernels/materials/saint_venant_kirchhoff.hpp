// Saint Venant-Kirchhoff material (seed 003 eq. 5; seed 001 eq. 10):
//   E = (C - I)/2,  S = lambda tr(E) I + 2 G E,  tau = F S F^T,
//   W = lambda/2 tr(E)^2 + G E:E.
// For the hourglass-controlled forms the volumetric Kirchhoff term is
// K J (J - 1) and c = G J^{-2/d}, as the authors' code does for linear and
// SVK materials (formulations.md section 1).
#pragma once
#include "kernels/core/mat.hpp"
#include "kernels/materials/material_interface.hpp"

namespace mfsd {

template <int D, class Real>
struct SaintVenantKirchhoff {
  Real K;       // bulk modulus
  Real G;       // shear modulus
  Real lambda;  // first Lame parameter (3-D value, also in plane strain)

  MFSD_HD Real volumetric_kirchhoff(Real J) const { return K * J * (J - Real(1)); }
  MFSD_HD Real shear_coefficient(Real J) const { return G * math::pow(J, Real(-2) / Real(D)); }

  // The material at particle i: the same at every particle (material_interface.hpp).
  MFSD_HD const SaintVenantKirchhoff& at(Index) const { return *this; }
  // GENOG's split tau = tau_r + c b (seed 000 eq. 25).
  MFSD_HD KirchhoffSplit<D, Real> genog_split(const Mat<D, Real>& F) const { return isotropic_genog_split(*this, F); }

  MFSD_HD Mat<D, Real> green_lagrange(const Mat<D, Real>& F) const {
    Mat<D, Real> E = transpose(F) * F;
    E.add_diagonal(Real(-1));
    return E * Real(0.5);
  }

  MFSD_HD Mat<D, Real> kirchhoff(const Mat<D, Real>& F) const {
    const Mat<D, Real> E = green_lagrange(F);
    Mat<D, Real> S = E * (Real(2) * G);
    S.add_diagonal(lambda * trace(E));
    return mul_transposed(F * S, F);  // F S F^T
  }

  MFSD_HD Real strain_energy_density(const Mat<D, Real>& F) const {
    const Mat<D, Real> E = green_lagrange(F);
    const Real trE = trace(E);
    return Real(0.5) * lambda * trE * trE + G * ddot(E, E);
  }
};

}  // namespace mfsd
