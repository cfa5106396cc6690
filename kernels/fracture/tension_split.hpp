// Tension/compression split of the elastic energy for phase-field fracture
// (seed 001 eq. 7, 11-31): psi = s^2 psi_plus + psi_minus, and the Kirchhoff
// stress tau = s^2 tau_plus + tau_minus, so that only the tensile part is
// degraded and a crack never opens in compression.
//   Saint Venant-Kirchhoff, spectral split of E = Q diag(l) Q^T (eq. 11-18):
//     psi_+- = lambda/2 <tr E>_+-^2 + G tr(E_+- E_+-),
//     S_+- = lambda <tr E>_+- I + 2 G E_+-,  tau_+- = F S_+- F^T.
//   Neo-Hookean (mfsd's volumetric-deviatoric form, neo_hookean.hpp), split
//   on J (eq. 20-31): J >= 1 degrades volumetric and isochoric parts, J < 1
//   only the isochoric part (eq. 27, 31 in Kirchhoff form).
// In 2-D (plane strain) E_zz = 0 adds nothing to either part.
#pragma once
#include "kernels/core/eigen_symmetric.hpp"
#include "kernels/core/mat.hpp"
#include "kernels/materials/neo_hookean.hpp"
#include "kernels/materials/saint_venant_kirchhoff.hpp"

namespace mfsd {

template <int D, class Real>
struct TensionSplit {
  Mat<D, Real> tau_plus, tau_minus;  // Kirchhoff stress of each part
  Real psi_plus, psi_minus;          // energy per reference volume of each part
  // The degraded Kirchhoff stress and energy (seed 001 eq. 7, 18).
  MFSD_HD Mat<D, Real> kirchhoff(Real s) const { return tau_plus * (s * s) + tau_minus; }
  MFSD_HD Real energy(Real s) const { return s * s * psi_plus + psi_minus; }
};

template <int D, class Real>
MFSD_HD inline TensionSplit<D, Real> tension_split(const SaintVenantKirchhoff<D, Real>& m, const Mat<D, Real>& F) {
  const Mat<D, Real> E = m.green_lagrange(F);
  const SymmetricEigen<D, Real> eig = eigen_symmetric(E);  // eq. 13-15
  Vec<D, Real> lp, ln;
  for (int k = 0; k < D; ++k) {
    lp.v[k] = math::max(eig.values.v[k], Real(0));  // eq. 16
    ln.v[k] = math::min(eig.values.v[k], Real(0));
  }
  const Mat<D, Real> Ep = compose_symmetric(lp, eig.vectors), En = compose_symmetric(ln, eig.vectors);
  const Real trE = trace(E);
  const Real trp = math::max(trE, Real(0)), trn = math::min(trE, Real(0));
  TensionSplit<D, Real> r;
  r.psi_plus = Real(0.5) * m.lambda * trp * trp + m.G * ddot(Ep, Ep);   // eq. 11
  r.psi_minus = Real(0.5) * m.lambda * trn * trn + m.G * ddot(En, En);  // eq. 12
  Mat<D, Real> Sp = Ep * (Real(2) * m.G), Sn = En * (Real(2) * m.G);    // eq. 17
  Sp.add_diagonal(m.lambda * trp);
  Sn.add_diagonal(m.lambda * trn);
  r.tau_plus = mul_transposed(F * Sp, F);
  r.tau_minus = mul_transposed(F * Sn, F);
  return r;
}

template <int D, class Real>
MFSD_HD inline TensionSplit<D, Real> tension_split(const NeoHookean<D, Real>& m, const Mat<D, Real>& F) {
  const Real J = det(F);
  const Real iso = NeoHookean<D, Real>::isochoric_factor(J);
  const Mat<D, Real> b = mul_transposed(F, F);
  Mat<D, Real> tau_vol = Mat<D, Real>::diagonal(m.volumetric_kirchhoff(J));               // K/2 (J^2 - 1) I
  const Mat<D, Real> tau_iso = deviator(b) * (m.G * iso);                                 // G dev(b_bar)
  const Real psi_vol = Real(0.5) * m.K * (Real(0.5) * (J * J - Real(1)) - math::log(J));  // U(J), eq. 22
  const Real psi_iso = Real(0.5) * m.G * (trace(b) * iso - Real(D));                      // eq. 23
  TensionSplit<D, Real> r;
  if (J >= Real(1)) {  // eq. 20-21, 31 (J >= 1)
    r.tau_plus = tau_vol + tau_iso;
    r.tau_minus = Mat<D, Real>::zero();
    r.psi_plus = psi_vol + psi_iso;
    r.psi_minus = Real(0);
  } else {  // J < 1
    r.tau_plus = tau_iso;
    r.tau_minus = tau_vol;
    r.psi_plus = psi_iso;
    r.psi_minus = psi_vol;
  }
  return r;
}

}  // namespace mfsd
