// Finite-strain J2 plasticity on the isochoric elastic left Cauchy-Green
// tensor b_bar_e (seed 000 Appendix A, Algorithm 1; formulations.md section 2:
// the return mapping of Simo, with b_bar_e in place of b in the neo-Hookean
// deviatoric stress tau_dev = G dev(b_bar_e)). One material point, one step;
// the caller (j2_plastic.hpp) keeps C_p^{-1} and the equivalent plastic strain
// alpha per particle and forms the trial
//   b_bar_e^trial = F_bar C_p^{-1} F_bar^T,  F_bar = J^{-1/3} F^{n+1/2}
// (the same as f_bar b_bar_e^n f_bar^T with the relative deformation f).
// Always 3 x 3: plane-strain bodies embed F with F_33 = 1 and keep the
// out-of-plane component of b_bar_e, which plastic flow changes.
//
//   s_tr = G dev(b_tr),  f_tr = |s_tr| - sqrt(2/3) sigma_Y(alpha_n)        (eq. A.1)
//   elastic if f_tr <= 0; otherwise, with G_bar = G tr(b_tr)/3 and n = s_tr/|s_tr|,
//   find dgamma >= 0 with
//     r(dgamma) = |s_tr| - 2 G_bar dgamma - sqrt(2/3) sigma_Y(alpha_n + sqrt(2/3) dgamma) = 0
//   (linear hardening: dgamma = f_tr / (2 (G_bar + H/3)), Algorithm 1 step 9),
//   s = s_tr - 2 G_bar dgamma n,  alpha = alpha_n + sqrt(2/3) dgamma,
//   b_bar_e = s / G + I_e I  with I_e chosen so that det(b_bar_e) = 1.
// Algorithm 1 writes b_e = tau / G_bar + tr(b_tr)/d I; dividing by G (Simo)
// keeps tau_dev = G dev(b_bar_e) consistent with the returned s, and fixing I_e
// by det(b_bar_e) = 1 keeps the plastic flow isochoric exactly (both differ
// from Algorithm 1 by O(elastic strain), negligible for metals). The update
// integrates the flow to first order on b_bar_e, so alpha = sum sqrt(2/3) dgamma
// exceeds the plastic log strain by a fraction of order the elastic strain
// (0.56 % in uniaxial tension to a stretch of 1.3 with tau/E = 0.8 %,
// tests/unit/test_j2_return_mapping.cpp); an exponential-map return would not.
#pragma once
#include <type_traits>

#include "kernels/core/mat.hpp"

namespace mfsd {

// sigma_Y(alpha) = sigma_y + H alpha (perfect plasticity: H = 0).
template <class Real>
struct LinearHardening {
  Real sigma_y, H;
  MFSD_HD Real yield(Real alpha) const { return sigma_y + H * alpha; }
  MFSD_HD Real slope(Real) const { return H; }
};

// sigma_Y(alpha) = sigma_y + H alpha + (sigma_inf - sigma_y)(1 - exp(-delta alpha))
// (seed 000 Table 7; formulations.md section 2).
template <class Real>
struct SaturationHardening {
  Real sigma_y, H, sigma_inf, delta;
  MFSD_HD Real yield(Real alpha) const {
    return sigma_y + H * alpha + (sigma_inf - sigma_y) * (Real(1) - math::exp(-delta * alpha));
  }
  MFSD_HD Real slope(Real alpha) const { return H + (sigma_inf - sigma_y) * delta * math::exp(-delta * alpha); }
};

// Viscoplastic Herschel-Bulkley flow (seed 000 section 5.7, Table 8; formulations.md
// section 2): no flow below the yield radius, above it the rate
//   dgamma/dt = ((|s| - sqrt(2/3) sigma_y) / eta)^(1/n),
// i.e. the returned |s| = sqrt(2/3) sigma_y + eta (dgamma/dt)^n: a rate-dependent
// radius of the yield surface (n > 1 thickens, as the oobleck of Table 8).
template <class Real>
struct HerschelBulkley {
  Real sigma_y, eta, n;
  static constexpr bool rate_dependent = true;
};

// The radius of the yield surface, sqrt(2/3) sigma_Y, once the step's
// multiplier is x, and its derivative in x; dt is the step (used by rate laws).
template <class Real, class Hardening>
MFSD_HD inline Real flow_radius(const Hardening& h, Real alpha_n, Real x, Real) {
  const Real c = math::sqrt(Real(2) / Real(3));
  return c * h.yield(alpha_n + c * x);
}
template <class Real, class Hardening>
MFSD_HD inline Real flow_radius_slope(const Hardening& h, Real alpha_n, Real x, Real) {
  return Real(2) / Real(3) * h.slope(alpha_n + math::sqrt(Real(2) / Real(3)) * x);
}
template <class Real>
MFSD_HD inline Real flow_radius(const HerschelBulkley<Real>& h, Real, Real x, Real dt) {
  return math::sqrt(Real(2) / Real(3)) * h.sigma_y + h.eta * math::pow(x / dt, h.n);
}
template <class Real>
MFSD_HD inline Real flow_radius_slope(const HerschelBulkley<Real>& h, Real, Real x, Real dt) {
  if (!(x > Real(0))) return h.n > Real(1) ? Real(0) : (h.n == Real(1) ? h.eta / dt : Real(1e30));
  return h.eta * h.n * math::pow(x / dt, h.n - Real(1)) / dt;
}

// Seed 001's J2 (eq. 41-51): linear hardening sigma_y + H e_p on its
// equivalent plastic strain, with its own return (j2_mandel_return below).
template <class Real>
struct Seed001Hardening {
  Real sigma_y, H;
  static constexpr bool mandel = true;
  MFSD_HD Real yield(Real e) const { return sigma_y + H * e; }
};

template <class Law, class = void>
struct IsMandel : std::false_type {};
template <class Law>
struct IsMandel<Law, std::void_t<decltype(Law::mandel)>> : std::bool_constant<Law::mandel> {};

template <class Law, class = void>
struct IsRateDependent : std::false_type {};
template <class Law>
struct IsRateDependent<Law, std::void_t<decltype(Law::rate_dependent)>> : std::bool_constant<Law::rate_dependent> {};

template <class Real>
struct J2Update {
  Mat<3, Real> be_bar;  // updated isochoric elastic left Cauchy-Green tensor
  Mat<3, Real> s;       // deviatoric Kirchhoff stress G dev(be_bar)
  Real alpha;           // equivalent plastic strain
  Real dgamma;          // plastic multiplier of the step (0: elastic)
  int iterations;       // of the consistency solve (0: closed form or elastic)
};

// The consistency condition r(dgamma) = 0 on [0, |s_tr| / (2 G_bar)], where r
// decreases (sigma_Y non-decreasing): Newton steps kept inside a shrinking
// bracket, bisection when a step leaves it; converged to |r| <= 1e-12 |s_tr|
// (1e-6 in float).
template <class Real, class Hardening>
MFSD_HD inline Real j2_consistency(Real s_norm, Real G_bar, Real alpha_n, const Hardening& h, int& iterations,
                                   Real dt = Real(0)) {
  const Real tol = (sizeof(Real) == 8 ? Real(1e-12) : Real(1e-6)) * s_norm;
  Real lo = Real(0), hi = s_norm / (Real(2) * G_bar);
  Real x = Real(0);
  iterations = 0;
  for (int k = 0; k < 100; ++k) {
    ++iterations;
    const Real r = s_norm - Real(2) * G_bar * x - flow_radius(h, alpha_n, x, dt);
    if (math::fabs(r) <= tol) break;
    if (r > 0)
      lo = x;
    else
      hi = x;
    const Real dr = -Real(2) * G_bar - flow_radius_slope(h, alpha_n, x, dt);
    Real next = x - r / dr;
    if (!(next > lo && next < hi)) next = Real(0.5) * (lo + hi);
    x = next;
  }
  return x;
}

// Seed 001's return on the plastic metric C_p with the Mandel stress
// (eq. 46-51), written on b_bar_e = F_bar C_p^{-1} F_bar^T. For isotropic
// elasticity M_dev = G dev(C_bar_e) is a rotation of s = G dev(b_bar_e), so
// sigma_eq = sqrt(3/2) |s| (eq. 42; the invariant tr(M_dev^2): the paper's
// C_e = C C_p^{-1} of eq. 33 is not symmetric) and
//   dgamma = (sigma_eq_tr - sigma_Y(e_n)) / (3 G + H sqrt(2/3))      (eq. 48)
//   e_p    = e_n + sqrt(2/3) dgamma                                   (eq. 49)
//   s      = (1 - 3 G dgamma / sigma_eq_tr) s_tr                      (eq. 47)
// The flow rule C_p <- C_p + 2 dgamma N C_p (eq. 50, N = 3/(2 sigma_eq) M_dev
// with the mixed C_e of eq. 33, for which N C_p = 3/(2 sigma_eq) G (C_bar -
// tr(C_bar C_p^{-1})/3 C_p) is symmetric) reads, pushed forward with F_bar,
//   b_bar_e = [(1 - k tr(b_tr)/3) b_tr^{-1} + k I]^{-1},  k = 3 G dgamma / sigma_eq_tr,
// and the projection det C_p = 1 (eq. 51) is det b_bar_e = 1. The stress of
// the updated state, G dev(b_bar_e), which the stress stage uses, differs from
// the returned s (eq. 47) by O(dgamma x elastic strain): 3.7e-3 of the
// overshoot for aluminium (tests/unit/test_j2_return_mapping.cpp). Note the conventions:
// e_p grows by sqrt(2/3) dgamma while sigma_eq falls by 3 G dgamma, so per unit
// of the usual equivalent plastic strain (seed 000's alpha) e_p grows by
// sqrt(2/3) and H acts as sqrt(2/3) H. J2Update::dgamma holds the Kirchhoff-space
// multiplier (|s_tr| - |s|) / (2 G_bar) of seed 000's form, from which
// J2Plastic::plastic_work takes the dissipation.
template <class Real>
MFSD_HD inline J2Update<Real> j2_mandel_return(const Mat<3, Real>& be_bar_trial, Real e_n, Real G,
                                               const Seed001Hardening<Real>& h) {
  const Real c = math::sqrt(Real(2) / Real(3));
  const Mat<3, Real> s_tr = deviator(be_bar_trial) * G;
  const Real s_norm = frobenius_norm(s_tr);
  const Real sigma_tr = s_norm / c;  // sqrt(3/2) |s|
  const Real f_tr = sigma_tr - h.yield(e_n);
  if (f_tr <= Real(0)) return J2Update<Real>{be_bar_trial, s_tr, e_n, Real(0), 0};
  const Real dgamma = f_tr / (Real(3) * G + h.H * c);  // eq. 48
  const Real k = Real(3) * G * dgamma / sigma_tr;      // eq. 47, 50
  const Mat<3, Real> s = s_tr * (Real(1) - k);         // eq. 47
  Mat<3, Real> m = inverse(be_bar_trial) * (Real(1) - k * trace(be_bar_trial) / Real(3));
  m.add_diagonal(k);
  Mat<3, Real> be = inverse(m);         // eq. 50
  be *= Real(1) / math::cbrt(det(be));  // eq. 51
  const Real G_bar = G * trace(be_bar_trial) / Real(3);
  return J2Update<Real>{be, s, e_n + c * dgamma, (s_norm - frobenius_norm(s)) / (Real(2) * G_bar), 0};
}

// Seed 000's return (Algorithm 1, the header above). dt: the time since the
// previous return mapping (rate-dependent laws only; with dt = 0 they do not flow).
template <class Real, class Hardening>
MFSD_HD inline J2Update<Real> j2_simo_return(const Mat<3, Real>& be_bar_trial, Real alpha_n, Real G, const Hardening& h,
                                             Real dt) {
  const Real c = math::sqrt(Real(2) / Real(3));
  const Mat<3, Real> s_tr = deviator(be_bar_trial) * G;
  const Real s_norm = frobenius_norm(s_tr);
  const Real f_tr = s_norm - flow_radius(h, alpha_n, Real(0), dt);  // eq. A.1
  bool elastic = f_tr <= Real(0);
  if constexpr (IsRateDependent<Hardening>::value) elastic = elastic || !(dt > Real(0));
  if (elastic) return J2Update<Real>{be_bar_trial, s_tr, alpha_n, Real(0), 0};
  const Real I_tr = trace(be_bar_trial) / Real(3);
  const Real G_bar = G * I_tr;
  int iterations = 0;
  const Real dgamma = j2_consistency(s_norm, G_bar, alpha_n, h, iterations, dt);
  const Mat<3, Real> s = s_tr * (Real(1) - Real(2) * G_bar * dgamma / s_norm);
  // b_bar_e = A + x I with A = s / G (traceless) and det = 1:
  //   x^3 - 1/2 tr(A^2) x + det(A) - 1 = 0, Newton from the trial's I_tr.
  const Mat<3, Real> A = s * (Real(1) / G);
  const Real p = Real(0.5) * ddot(A, A), q = det(A) - Real(1);
  Real x = I_tr;
  for (int k = 0; k < 20; ++k) {
    const Real r = x * x * x - p * x + q, dr = Real(3) * x * x - p;
    const Real dx = r / dr;
    x -= dx;
    if (math::fabs(dx) <= Real(1e-15) * x) break;
  }
  Mat<3, Real> be = A;
  be.add_diagonal(x);
  return J2Update<Real>{be, s, alpha_n + c * dgamma, dgamma, iterations};
}

template <class Real, class Hardening>
MFSD_HD inline J2Update<Real> j2_return_mapping(const Mat<3, Real>& be_bar_trial, Real alpha_n, Real G,
                                                const Hardening& h, Real dt = Real(0)) {
  if constexpr (IsMandel<Hardening>::value)
    return j2_mandel_return(be_bar_trial, alpha_n, G, h);
  else
    return j2_simo_return(be_bar_trial, alpha_n, G, h, dt);
}

}  // namespace mfsd
