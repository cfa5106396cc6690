// Finite-strain J2 elastoplastic material of seed 000 (section 3.2, eq. 9-11,
// Appendix A): neo-Hookean elasticity (eq. 7-8) on the elastic left
// Cauchy-Green tensor b_e = F C_p^{-1} F^T (eq. 11), with the return mapping
// of j2_return_mapping.hpp on its isochoric part b_bar_e. The per-particle
// state is the inverse plastic right Cauchy-Green tensor C_p^{-1} (reference
// configuration, det = 1, Algorithm 1 keeps the same variable), the equivalent
// plastic strain alpha and the plastic work per reference volume.
//
//   b_bar_e^trial = F_bar C_p^{-1} F_bar^T,  F_bar = J^{-1/3} F      (Algorithm 1 step 2)
//   return mapping -> b_bar_e, alpha                                 (steps 3-9)
//   C_p^{-1} = F_bar^{-1} b_bar_e F_bar^{-T}                         (step 9, last line)
//   tau = K/2 (J^2 - 1) I + G dev(b_bar_e)                           (eq. 7-8 with b_e for b)
//
// Plane strain (D = 2) embeds F with F_33 = 1: C_p^{-1}, b_bar_e and the
// deviator are 3 x 3 (the out-of-plane plastic strain is real), and the
// in-plane block of tau drives the 2-D forces.
//
// Plastic work (plastic_work below) is accumulated in the state so that
// kinetic + stored + plastic work balances the work done on the body
// (energies.csv).
#pragma once
#include <type_traits>

#include "kernels/core/mat.hpp"
#include "kernels/materials/j2_return_mapping.hpp"

namespace mfsd {

// Whether a material carries a plastic state (Material::plastic == true).
template <class M, class = void>
struct IsPlastic : std::false_type {};
template <class M>
struct IsPlastic<M, std::void_t<decltype(M::plastic)>> : std::bool_constant<M::plastic> {};

template <class Real>
struct J2State {
  Real cp_inv[6];  // C_p^{-1}: xx yy zz xy xz yz
  Real alpha;      // equivalent plastic strain
  Real work;       // plastic work per reference volume

  MFSD_HD static J2State initial() { return J2State{{Real(1), Real(1), Real(1), Real(0), Real(0), Real(0)}, 0, 0}; }

  MFSD_HD Mat<3, Real> plastic_metric_inverse() const {
    Mat<3, Real> c;
    c.m[0][0] = cp_inv[0];
    c.m[1][1] = cp_inv[1];
    c.m[2][2] = cp_inv[2];
    c.m[0][1] = c.m[1][0] = cp_inv[3];
    c.m[0][2] = c.m[2][0] = cp_inv[4];
    c.m[1][2] = c.m[2][1] = cp_inv[5];
    return c;
  }
  MFSD_HD void set_plastic_metric_inverse(const Mat<3, Real>& c) {
    cp_inv[0] = c.m[0][0];
    cp_inv[1] = c.m[1][1];
    cp_inv[2] = c.m[2][2];
    cp_inv[3] = Real(0.5) * (c.m[0][1] + c.m[1][0]);
    cp_inv[4] = Real(0.5) * (c.m[0][2] + c.m[2][0]);
    cp_inv[5] = Real(0.5) * (c.m[1][2] + c.m[2][1]);
  }
};

// F of a D-dimensional body as a 3 x 3 tensor (plane strain: F_33 = 1).
template <class Real>
MFSD_HD inline Mat<3, Real> embed3(const Mat<3, Real>& F) {
  return F;
}
template <class Real>
MFSD_HD inline Mat<3, Real> embed3(const Mat<2, Real>& F) {
  Mat<3, Real> r = Mat<3, Real>::identity();
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) r.m[a][b] = F.m[a][b];
  return r;
}

// The leading D x D block of a 3 x 3 tensor.
template <int D, class Real>
MFSD_HD inline Mat<D, Real> leading_block(const Mat<3, Real>& A) {
  Mat<D, Real> r;
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) r.m[a][b] = A.m[a][b];
  return r;
}

// What the stress stage needs of a plastic material point.
template <class Real>
struct J2Stress {
  Real J;
  Real volumetric;      // K/2 (J^2 - 1)
  Mat<3, Real> be_bar;  // isochoric elastic left Cauchy-Green tensor
};

template <int D, class Real, class Hardening>
struct J2Plastic {
  static constexpr bool plastic = true;
  Real K;  // bulk modulus
  Real G;  // shear modulus
  Hardening hardening;

  MFSD_HD Real volumetric_kirchhoff(Real J) const { return Real(0.5) * K * (J * J - Real(1)); }  // eq. 7

  // F_bar = J^{-1/3} F (3 x 3).
  MFSD_HD static Mat<3, Real> isochoric(const Mat<3, Real>& F3, Real J) { return F3 * (Real(1) / math::cbrt(J)); }

  // b_bar_e of the stored state at F, without a return mapping.
  MFSD_HD static Mat<3, Real> elastic_tensor(const Mat<3, Real>& F_bar, const J2State<Real>& s) {
    return mul_transposed(F_bar * s.plastic_metric_inverse(), F_bar);
  }

  // The return mapping at F (Algorithm 1): updates the state, returns the stress
  // parts. dt: time since the previous update (viscoplastic laws only).
  MFSD_HD J2Stress<Real> update(const Mat<D, Real>& F, J2State<Real>& state, Real dt = Real(0)) const {
    const Mat<3, Real> F3 = embed3(F);
    const Real J = det(F3);
    const Mat<3, Real> F_bar = isochoric(F3, J);
    Mat<3, Real> trial = elastic_tensor(F_bar, state);
    trial *= Real(1) / math::cbrt(det(trial));  // det = 1 against round-off drift of C_p^{-1}
    const J2Update<Real> r = j2_return_mapping(trial, state.alpha, G, hardening, dt);
    if (r.dgamma > Real(0)) {
      const Mat<3, Real> F_bar_inv = inverse(F_bar);
      state.set_plastic_metric_inverse(mul_transposed(F_bar_inv * r.be_bar, F_bar_inv));
      state.work += plastic_work(trial, r);
      state.alpha = r.alpha;
    }
    return J2Stress<Real>{J, volumetric_kirchhoff(J), r.be_bar};
  }

  // Plastic work of the step: the rate at which the return takes stored energy
  // W = G/2 (tr b_bar_e - 3) away, at the returned state, times dgamma. With
  // b_bar = A + x I (A traceless, det = 1), tr b_bar - 3 = |A|^2/2 - det A + O(|A|^4),
  // and A shrinking along itself at the rate 2 G_bar / G per unit dgamma:
  //   dW_p = dgamma I_tr G (|A|^2 - 3 det A) / |A|,  A = s / G.
  // (The energy difference between trial and returned state would be larger
  // by G_bar dgamma^2: the trial's overshoot, which the stress power never sees,
  // a first-order error in dt.)
  MFSD_HD Real plastic_work(const Mat<3, Real>& trial, const J2Update<Real>& r) const {
    const Mat<3, Real> A = r.s * (Real(1) / G);
    const Real a = frobenius_norm(A);
    if (!(a > Real(0))) return Real(0);
    return r.dgamma * (trace(trial) / Real(3)) * G * (a * a - Real(3) * det(A)) / a;
  }

  // Kirchhoff stress of the stored state at F (outputs): K/2 (J^2-1) I + G dev(b_bar_e).
  MFSD_HD Mat<D, Real> kirchhoff(const Mat<D, Real>& F, const J2State<Real>& state) const {
    const Mat<3, Real> F3 = embed3(F);
    const Real J = det(F3);
    Mat<3, Real> tau = deviator(elastic_tensor(isochoric(F3, J), state)) * G;
    tau.add_diagonal(volumetric_kirchhoff(J));
    return leading_block<D>(tau);
  }

  // Stored energy per reference volume: K/2 [(J^2 - 1)/2 - ln J] + G/2 (tr b_bar_e - 3) (eq. 4-6 with b_e).
  MFSD_HD Real strain_energy_density(const Mat<D, Real>& F, const J2State<Real>& state) const {
    const Mat<3, Real> F3 = embed3(F);
    const Real J = det(F3);
    const Real tr_be = trace(elastic_tensor(isochoric(F3, J), state));
    return Real(0.5) * K * (Real(0.5) * (J * J - Real(1)) - math::log(J)) + Real(0.5) * G * (tr_be - Real(3));
  }
};

}  // namespace mfsd
