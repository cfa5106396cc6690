// Generalized non-hourglass (GNOG) penalty of ULSPH (seed 002 eq. 27-35;
// formulations.md section 3, "GNOG penalty"). The non-affine part of the pair
// velocity, what the particle-wise linear fields L_i, L_j do not predict,
//   v_tilde_ij = (v_i - v_j) - 1/2 (L_i + L_j) (x_i - x_j)          (seed 002 eq. 27-28)
// drives an accumulated penalty acceleration (a state variable, never reset)
//   a_h,i += dt sum_j 1/2 (xi_i + xi_j) G v_tilde_ij dW_ij V_j / (rho_i r_ij)   (eq. 29, 35)
// with xi_i = xi kappa_i (eq. 33-34; kappa from shear_stress.hpp, 1 for elastic
// bodies; xi = 4 elastic, 0.2 J2, formulations.md section 3). In pair data
// (pair_list.hpp) dW_ij V_j / r_ij = stretch_ij and (x_i - x_j) stretch_ij = grad_ij, so
//   v_tilde_ij dW_ij V_j / r_ij = (v_i - v_j) stretch_ij - 1/2 (L_i + L_j) grad_ij,
// with no division. stretch_ij < 0: the penalty opposes v_tilde_ij. v_tilde_ij is
// antisymmetric in i <-> j, so with V_i = m_i / rho_i the pair terms of m_i da_h,i
// cancel (linear momentum). A rigid motion v = W x + c (W skew) has L = W and
// v_tilde = 0 -- only with L_ab = dv_a/dx_b, not with its transpose.
//
// Variant `gnog_amc` (formulations.md section 3, an option): v_tilde_ij is
// projected on e_ij, (v_tilde_ij . e_ij) e_ij, making each pair force central
// (angular momentum conserved by the increment), and the accumulated a_h is
// rotated with the particle spin before each increment (rotate_with_spin).
#pragma once
#include <type_traits>

#include "kernels/core/mat.hpp"
#include "kernels/neighbors/pair_list.hpp"

namespace mfsd::ulsph {

struct GnogStandard {};                   // scene hourglass `gnog`
struct GnogAngularMomentumConserving {};  // scene hourglass `gnog_amc`

// v_tilde_ij stretch_ij = (v_i - v_j) stretch_ij - 1/2 (L_i + L_j) grad_ij (seed 002 eq. 28 times dW V_j / r).
template <int D, class Real>
MFSD_HD inline Vec<D, Real> scaled_non_affine_velocity(const Vec<D, Real>& v_i, const Vec<D, Real>& v_j,
                                                       const Mat<D, Real>& L_i, const Mat<D, Real>& L_j,
                                                       const Vec<D, Real>& grad, Real stretch) {
  return (v_i - v_j) * stretch - (L_i + L_j) * grad * Real(0.5);  // seed 002 eq. 27-28
}

// v_tilde_ij itself (seed 002 eq. 28), x_i - x_j = grad / stretch.
template <int D, class Real>
MFSD_HD inline Vec<D, Real> non_affine_velocity(const Vec<D, Real>& v_i, const Vec<D, Real>& v_j,
                                                const Mat<D, Real>& L_i, const Mat<D, Real>& L_j,
                                                const Vec<D, Real>& grad, Real stretch) {
  return scaled_non_affine_velocity(v_i, v_j, L_i, L_j, grad, stretch) / stretch;
}

// One pair's bracket of eq. 29 and 35, (kappa_i + kappa_j) [v_tilde_ij stretch_ij],
// projected on e_ij with GnogAngularMomentumConserving.
template <int D, class Real, class Variant>
MFSD_HD inline Vec<D, Real> gnog_pair_term(const Vec<D, Real>& v_i, const Vec<D, Real>& v_j, const Mat<D, Real>& L_i,
                                           const Mat<D, Real>& L_j, const Vec<D, Real>& g, Real stretch, Real kappa_i,
                                           Real kappa_j) {
  Vec<D, Real> s = scaled_non_affine_velocity(v_i, v_j, L_i, L_j, g, stretch);
  if constexpr (std::is_same<Variant, GnogAngularMomentumConserving>::value) {
    const Real g2 = squared_norm(g);
    s = g2 > Real(0) ? g * (dot(s, g) / g2) : Vec<D, Real>::zero();  // (s . e_ij) e_ij, formulations.md 3 (amc)
  }
  return s * (kappa_i + kappa_j);  // seed 002 eq. 35: (xi_i + xi_j) = xi (kappa_i + kappa_j)
}

// d a_h,i / dt = sum_j 1/2 (xi_i + xi_j) G v_tilde_ij dW_ij V_j / (rho_i r_ij)
//             = xi G / (2 rho_i) sum_j (kappa_i + kappa_j) [v_tilde_ij stretch_ij]   (seed 002 eq. 29, 33, 35)
// kappa may be null (elastic body: kappa = 1). With GnogAngularMomentumConserving
// the bracket is projected on e_ij (= on grad_ij).
template <int D, class Real, class Variant = GnogStandard>
MFSD_HD inline Vec<D, Real> gnog_penalty_rate(const PairList<D, Real>& pairs, const Vec<D, Real>* velocity,
                                              const Mat<D, Real>* velocity_gradient, const Real* kappa, Real xi,
                                              Real shear_modulus, Real rho_i, Index i) {
  const Vec<D, Real> v_i = velocity[i];
  const Mat<D, Real> L_i = velocity_gradient[i];
  const Real kappa_i = kappa ? kappa[i] : Real(1);
  Vec<D, Real> sum = Vec<D, Real>::zero();
  for (PairIndex k = pairs.offsets[i]; k < pairs.offsets[i + 1]; ++k) {
    const Index j = pairs.neighbor[k];
    const Index ahead = pairs.neighbor[k + kPairPrefetchDistance];
    prefetch(&velocity[ahead]);
    prefetch(&velocity_gradient[ahead]);
    sum += gnog_pair_term<D, Real, Variant>(v_i, velocity[j], L_i, velocity_gradient[j], pairs.grad[k],
                                            pairs.stretch[k], kappa_i, kappa ? kappa[j] : Real(1));
  }
  return sum * (Real(0.5) * xi * shear_modulus / rho_i);  // seed 002 eq. 29: G / rho_i
}

// The axial vector omega of Omega = skew L (Omega v = omega x v): the particle's
// angular velocity. In 2-D only omega_z = (L_yx - L_xy)/2.
template <class Real>
MFSD_HD inline Vec<3, Real> spin_vector(const Mat<3, Real>& L) {
  return Vec<3, Real>{
      {Real(0.5) * (L.m[2][1] - L.m[1][2]), Real(0.5) * (L.m[0][2] - L.m[2][0]), Real(0.5) * (L.m[1][0] - L.m[0][1])}};
}

// a rotated by the spin of L over dt (gnog_amc, formulations.md section 3):
// 2-D: plane rotation by theta = omega_z dt.
template <class Real>
MFSD_HD inline Vec<2, Real> rotate_with_spin(const Vec<2, Real>& a, const Mat<2, Real>& L, Real dt) {
  const Real theta = Real(0.5) * (L.m[1][0] - L.m[0][1]) * dt;
  const Real c = math::cos(theta), s = math::sin(theta);
  return Vec<2, Real>{{c * a.v[0] - s * a.v[1], s * a.v[0] + c * a.v[1]}};
}
// 3-D: Rodrigues, axis k = omega/|omega|, theta = |omega| dt:
//   R a = a cos(theta) + (k x a) sin(theta) + k (k . a)(1 - cos(theta)).
template <class Real>
MFSD_HD inline Vec<3, Real> rotate_with_spin(const Vec<3, Real>& a, const Mat<3, Real>& L, Real dt) {
  const Vec<3, Real> omega = spin_vector(L);
  const Real w = norm(omega);
  if (!(w > Real(0))) return a;
  const Vec<3, Real> k = omega / w;
  const Real theta = w * dt;
  const Real c = math::cos(theta), s = math::sin(theta);
  return a * c + cross(k, a) * s + k * (dot(k, a) * (Real(1) - c));  // Rodrigues
}

// a_h,i (state) += dt d a_h,i/dt -- after rotating it with the spin for
// gnog_amc -- and, when acceleration is not null, acceleration[i] += a_h,i
// (after the pressure and shear terms; the authors' code adds the updated a_h).
template <int D, class Real, class Variant = GnogStandard>
struct GnogPenaltyFunctor {
  PairList<D, Real> pairs;
  const Vec<D, Real>* velocity;
  const Mat<D, Real>* velocity_gradient;
  const Real* density;
  const Real* kappa;   // null: elastic body, kappa = 1
  Real xi;             // 4 elastic, 0.2 J2 (gnog); 2 (gnog_amc)
  Real shear_modulus;  // G
  Real dt;
  Vec<D, Real>* hourglass_acceleration;  // a_h, never reset
  Vec<D, Real>* acceleration;            // may be null

  MFSD_HD void operator()(Index i) const {
    Vec<D, Real> a_h = hourglass_acceleration[i];
    if constexpr (std::is_same<Variant, GnogAngularMomentumConserving>::value)
      a_h = rotate_with_spin(a_h, velocity_gradient[i], dt);
    a_h += gnog_penalty_rate<D, Real, Variant>(pairs, velocity, velocity_gradient, kappa, xi, shear_modulus, density[i],
                                               i) *
           dt;  // seed 002 eq. 29: integrated over time
    hourglass_acceleration[i] = a_h;
    if (acceleration) acceleration[i] += a_h;
  }
};

}  // namespace mfsd::ulsph
