// Holzapfel-Ogden material (seed 000 section 3.3, eq. 12-17) with the active
// stress of electrophysiologically driven muscle (seed 000 section 3.4,
// eq. 18-19). Strain energy per reference volume (eq. 12):
//   W = a/(2b) {exp[b(I1 - 3)] - 1} - a ln J + lambda/2 (ln J)^2
//     + sum_{i=f,s} a_i/(2b_i) {exp[b_i (I_ii - 1)^2] - 1}
//     + a_fs/(2b_fs) {exp[b_fs I_fs^2] - 1},
// I1 = tr C, I_ff = f0.C f0, I_ss = s0.C s0, I_fs = f0.C s0 (eq. 13-14). The
// -1 inside the first braces (a constant) makes W(I) = 0; each term of the
// form a/(2b) (exp(b x) - 1) tends to a x / 2 as b -> 0 (seed 000 Table 3 has
// b_f = 0), evaluated as a/2 expm1(b x)/b. Kirchhoff stress (eq. 17):
//   tau = (lambda ln J - a) I + c b,  c = a exp[b(I1 - 3)]
//       + 2 a_f (I_ff - 1) exp[b_f (I_ff - 1)^2] (F f0) (x) (F f0)
//       + 2 a_s (I_ss - 1) exp[b_s (I_ss - 1)^2] (F s0) (x) (F s0)
//       + a_fs I_fs exp[b_fs I_fs^2] [(F f0) (x) (F s0) + (F s0) (x) (F f0)]
//       + T_a (F f0) (x) (F f0)                                   (eq. 18-19)
// (eq. 17 prints "a exp[b(I1 - 3)] I"; F I F^T = b, as the GENOG split
// tau_s = c b with c = a exp[b(I1 - 3)] of seed 000 section 4 states.)
// f0, s0 and T_a are per particle; the fibres are material directions, so
// they turn with F. In 2-D (plane strain) the out-of-plane stretch is 1:
// I1 = tr C + 1 and the directions lie in the plane.
#pragma once
#include "kernels/core/mat.hpp"
#include "kernels/materials/material_interface.hpp"

namespace mfsd {

template <class Real>
struct HolzapfelOgdenParameters {
  Real lambda;    // Lame parameter of the ln J terms
  Real a, b;      // isotropic (stress, dimensionless)
  Real af, bf;    // fibre
  Real as, bs;    // sheet
  Real afs, bfs;  // fibre-sheet coupling
};

namespace detail {
// a/(2b) {exp(b x) - 1}, and its limit a x / 2 at b = 0.
template <class Real>
MFSD_HD inline Real exp_energy(Real a, Real b, Real x) {
  if (b == Real(0)) return Real(0.5) * a * x;
  return Real(0.5) * a * math::expm1(b * x) / b;
}
}  // namespace detail

// The material at one particle: its directions and active tension.
template <int D, class Real>
struct HolzapfelOgdenPoint {
  HolzapfelOgdenParameters<Real> p;
  Vec<D, Real> f0, s0;     // unit reference directions
  Real active_tension;     // T_a (eq. 19), 0 for a passive body
  Real reference_modulus;  // longitudinal_modulus at F = I without T_a (the c0 the time step uses)

  // I1 of the 3-D C (plane strain adds the unit out-of-plane stretch).
  MFSD_HD static Real first_invariant(const Mat<D, Real>& F) { return ddot(F, F) + Real(3 - D); }

  // c = a exp[b(I1 - 3)], the coefficient of b in tau (GENOG tau_s = c b, seed 000 section 4).
  MFSD_HD Real shear_coefficient(const Mat<D, Real>& F) const {
    return p.a * math::exp(p.b * (first_invariant(F) - Real(3)));
  }

  // tau - c b: everything but the isotropic exponential's c b (GENOG tau_r).
  MFSD_HD Mat<D, Real> kirchhoff_remainder(const Mat<D, Real>& F) const {
    const Real J = det(F);
    const Vec<D, Real> f = F * f0, s = F * s0;  // fibres in the current configuration
    const Real Iff = dot(f, f), Iss = dot(s, s), Ifs = dot(f, s);
    const Real ef = Iff - Real(1), es = Iss - Real(1);
    Mat<D, Real> tau = Mat<D, Real>::diagonal(p.lambda * math::log(J) - p.a);                 // eq. 17, 1st term
    tau += outer(f, f) * (Real(2) * p.af * ef * math::exp(p.bf * ef * ef) + active_tension);  // eq. 17, 19
    tau += outer(s, s) * (Real(2) * p.as * es * math::exp(p.bs * es * es));
    const Mat<D, Real> fs = outer(f, s);
    tau += (fs + transpose(fs)) * (p.afs * Ifs * math::exp(p.bfs * Ifs * Ifs));
    return tau;
  }

  MFSD_HD Mat<D, Real> kirchhoff(const Mat<D, Real>& F) const {
    return kirchhoff_remainder(F) + mul_transposed(F, F) * shear_coefficient(F);
  }

  // GENOG's split tau = tau_r + c b, c = a exp[b(I1 - 3)] (seed 000 eq. 25).
  MFSD_HD KirchhoffSplit<D, Real> genog_split(const Mat<D, Real>& F) const {
    return {kirchhoff_remainder(F), shear_coefficient(F)};
  }

  // The active stress's work over dt per V0 at the rate L = dF/dt F^{-1}:
  // tau_a : L dt with tau_a = T_a f (x) f, f = F f0 (eq. 19), so T_a f . L f dt.
  MFSD_HD Real active_work(const Mat<D, Real>& F, const Mat<D, Real>& L, Real dt) const {
    const Vec<D, Real> f = F * f0;
    return dt * active_tension * dot(f, L * f);
  }

  // The stiffening the time step follows: current over reference longitudinal modulus.
  MFSD_HD Real stiffening(const Mat<D, Real>& F) const { return longitudinal_modulus(F) / reference_modulus; }

  // W per reference volume (eq. 12, passive part; the active stress does
  // work but stores no energy).
  MFSD_HD Real strain_energy_density(const Mat<D, Real>& F) const {
    const Real lnJ = math::log(det(F));
    const Vec<D, Real> f = F * f0, s = F * s0;
    const Real ef = dot(f, f) - Real(1), es = dot(s, s) - Real(1), Ifs = dot(f, s);
    return detail::exp_energy(p.a, p.b, first_invariant(F) - Real(3)) - p.a * lnJ + Real(0.5) * p.lambda * lnJ * lnJ +
           detail::exp_energy(p.af, p.bf, ef * ef) + detail::exp_energy(p.as, p.bs, es * es) +
           detail::exp_energy(p.afs, p.bfs, Ifs * Ifs);
  }

  // Longitudinal modulus in the stiffest direction, from the small-strain
  // tangent at the current invariants (theory.md, "Holzapfel-Ogden"):
  //   lambda + 2 b c + 2 c                                  (isotropic part)
  //   + 4 a_i exp[b_i e_i^2] (1 + 2 b_i e_i^2) I_ii          (i = f, s; e_i = I_ii - 1)
  // At F = I: lambda + 2ab + 2a + 4 max(a_f, a_s) under the max over the two families.
  MFSD_HD Real longitudinal_modulus(const Mat<D, Real>& F) const {
    const Real c = shear_coefficient(F);
    const Vec<D, Real> f = F * f0, s = F * s0;
    const Real Iff = dot(f, f), Iss = dot(s, s);
    const Real ef = Iff - Real(1), es = Iss - Real(1);
    const Real kf = Real(4) * p.af * math::exp(p.bf * ef * ef) * (Real(1) + Real(2) * p.bf * ef * ef) * Iff;
    const Real ks = Real(4) * p.as * math::exp(p.bs * es * es) * (Real(1) + Real(2) * p.bs * es * es) * Iss;
    return p.lambda + Real(2) * p.b * c + Real(2) * c + math::max(kf, ks) + math::fabs(active_tension);
  }
};

// The body's material: constants and the per-particle fields (indexed by the
// global particle index, like every field the stress stage reads).
template <int D, class Real>
struct HolzapfelOgden {
  HolzapfelOgdenParameters<Real> p;
  Real reference_modulus;      // longitudinal_modulus at F = I without T_a (the c0 the time step uses)
  const Vec<D, Real>* fibre;   // f0 per particle
  const Vec<D, Real>* sheet;   // s0 per particle
  const Real* active_tension;  // k V_m per particle (seed 000 eq. 43), null for a passive body
  Real activation;             // the ramp's factor in [0, 1] at this step's time: T_a = activation k V_m
  double ramp_time = -1;       // T_a grows over this time (s); < 0: no active stress

  MFSD_HD HolzapfelOgdenPoint<D, Real> at(Index i) const {
    return HolzapfelOgdenPoint<D, Real>{p, fibre[i], sheet[i],
                                        active_tension ? activation * active_tension[i] : Real(0), reference_modulus};
  }

  // Before a step at time t: T_a = k V_m min(t / ramp_time, 1).
  MFSD_HD void set_time(double t) {
    if (ramp_time >= 0) activation = Real(ramp_time > 0 ? (t / ramp_time < 1.0 ? t / ramp_time : 1.0) : 1.0);
  }
};

}  // namespace mfsd
