// Stress update of the semi-Lagrangian RKPM at one node (rkpm.md 4.2-4.4;
// seed 004 section 7): the Jaumann-rate elastic predictor with the
// Hughes-Winget rotation (hughes_winget.hpp), J2 plasticity with linear
// isotropic hardening (radial return), the damage laws and the nominal stress
// of a damaged or failed node, and Drucker-Prager plasticity with a tension
// cut-off (four-branch return) with its Mohr-Coulomb matches. Always on the
// full 3 x 3 effective stress sigma_bar (plane strain keeps sigma_33; the
// in-plane deviator would give the wrong yield surface, rkpm.md 4.2). Tension
// positive, p = tr(sigma)/3, s = dev(sigma) (3-D deviator), all in double.
//
// Decisions (rkpm.md leaves them open or is silent):
// - Damage acts on the nominal stress only (nominal_stress): the returns work
//   on sigma_bar, and a failed node keeps its sigma_bar. A failed node
//   (D >= D_c) carries sigma = min(p_bar, 0) I: no deviator, its compressive
//   effective pressure undegraded (as ULSPH's failed particles,
//   kernels/ulsph/failure.hpp), so failed material still resists closing.
// - Johnson-Cook: the temperature factor [1 + D5 theta*] is omitted (no
//   temperature state); rate* = max(rate/rate0, 1) (no ln of a vanishing rate
//   in quasi-static steps); sigma* = p/q of sigma_bar after the return (0 when
//   q = 0); eps_f <= 0 fails the node at once.
// - Drucker-Prager apex (branch 4) puts p = T* = min(T, k/alpha_bar), which is
//   the spec's k/alpha_bar whenever the cut-off is not effective. For
//   beta_bar >= 0 branch 4 is never reached with p_tr <= k/alpha_bar (the cone
//   return is then valid), so branch 1 (the corner with q_cap = 0) takes the
//   apex states; branch 4 is reachable with beta_bar < 0 only.
#pragma once
#include "kernels/core/mat.hpp"

namespace mfsd::rkpm {

// ---- invariants (rkpm.md notation) -----------------------------------------
MFSD_HD inline double mean_stress(const Mat<3, double>& sigma) { return trace(sigma) / 3.0; }  // p = tr sigma/3
// q = sqrt(3/2 s:s), the von Mises stress.
MFSD_HD inline double von_mises(const Mat<3, double>& sigma) {
  const Mat<3, double> s = deviator(sigma);
  return math::sqrt(1.5 * ddot(s, s));
}
// q_bar = sqrt(J2) = sqrt(s:s/2).
MFSD_HD inline double sqrt_j2(const Mat<3, double>& sigma) {
  const Mat<3, double> s = deviator(sigma);
  return math::sqrt(0.5 * ddot(s, s));
}

// ---- elastic predictor (rkpm.md 4.2) ----------------------------------------
// sigma_tr = Q sigma_n Q^T + lambda tr(Deps) I + 2 mu Deps, lambda = K - 2 mu/3.
// In Dienes' simple shear the error is 5.2e-4 mu (100 steps) and 5.2e-6 mu
// (1000) at gamma = 2 pi, but first order along the path (6.3e-2 and 6.3e-3 mu
// at gamma = pi): the midpoint increment is added unrotated, and its error
// cancels only over a full period (tests/unit/test_rkpm_stress_update.cpp).
MFSD_HD inline Mat<3, double> elastic_predictor(const Mat<3, double>& sigma_n, const Mat<3, double>& Q,
                                                const Mat<3, double>& deps, double K, double mu) {
  Mat<3, double> sigma = mul_transposed(Q * sigma_n, Q);   // Q sigma Q^T: seed 004 eq. 25 spin terms, Hughes-Winget
  sigma += deps * (2.0 * mu);                              // rkpm.md 4.2: + 2 mu Deps
  sigma.add_diagonal((K - 2.0 * mu / 3.0) * trace(deps));  // rkpm.md 4.2: + lambda tr(Deps) I
  return sigma;
}

// ---- J2, linear isotropic hardening (rkpm.md 4.3) ----------------------------
struct J2Hardening {
  double mu;            // shear modulus
  double yield_stress;  // sigma_y0
  double hardening;     // H (uniaxial tangent after yield E H/(E + H))
  MFSD_HD double yield(double eps_p) const { return yield_stress + hardening * eps_p; }
};

// f = q - (sigma_y0 + H eps_p).
MFSD_HD inline double j2_yield_function(const Mat<3, double>& sigma, double eps_p, const J2Hardening& m) {
  return von_mises(sigma) - m.yield(eps_p);  // rkpm.md 4.3
}

// Radial return of the trial stress sigma (in: sigma_tr, out: sigma_n+1) with
// eps_p (in: eps_p_n, out: eps_p_n+1); returns the plastic strain increment.
MFSD_HD inline double j2_radial_return(Mat<3, double>& sigma, double& eps_p, const J2Hardening& m) {
  const double p = trace(sigma) / 3.0;                   // rkpm.md 4.3
  Mat<3, double> s = deviator(sigma);                    // s_tr = dev sigma_tr
  const double q_tr = math::sqrt(1.5 * ddot(s, s));      // q_tr = sqrt(3/2 s_tr:s_tr)
  const double f = q_tr - m.yield(eps_p);                // f = q_tr - (sigma_y0 + H eps_p_n)
  if (!(f > 0.0) || !(q_tr > 0.0)) return 0.0;           // elastic
  const double deps_p = f / (3.0 * m.mu + m.hardening);  // rkpm.md 4.3; Simo & Hughes 1998 ch. 3
  s *= 1.0 - 3.0 * m.mu * deps_p / q_tr;                 // s = (1 - 3 mu deps_p/q_tr) s_tr
  eps_p += deps_p;                                       // eps_p += deps_p
  sigma = s;
  sigma.add_diagonal(p);  // sigma = p I + s (pressure linear)
  return deps_p;
}

// ---- damage (rkpm.md 4.3, switch `damage`) -----------------------------------
enum class DamageKind : int { none, linear, exponential, johnson_cook };

struct DamageLaw {
  DamageKind kind = DamageKind::none;
  double eps_D = 0.0;                             // linear, exponential: plastic strain at damage onset
  double eps_f = 1.0;                             // linear: plastic strain at full damage (> eps_D)
  double eps_r = 1.0;                             // exponential: decay strain (> 0)
  double D1 = 0.0, D2 = 0.0, D3 = 0.0, D4 = 0.0;  // johnson_cook constants (D5, temperature: omitted)
  double rate0 = 1.0;                             // johnson_cook: reference plastic strain rate (1/s)
  double critical = 0.99;                         // D_c: a node with D >= D_c has failed
  bool degrade_whole_tensor = true;  // (1 - D) sigma_bar; false: (1 - D) on deviator and tensile pressure only

  MFSD_HD static DamageLaw linear(double eps_D, double eps_f) {
    DamageLaw d;
    d.kind = DamageKind::linear;
    d.eps_D = eps_D;
    d.eps_f = eps_f;
    return d;
  }
  MFSD_HD static DamageLaw exponential(double eps_D, double eps_r) {
    DamageLaw d;
    d.kind = DamageKind::exponential;
    d.eps_D = eps_D;
    d.eps_r = eps_r;
    return d;
  }
  MFSD_HD static DamageLaw johnson_cook(double D1, double D2, double D3, double D4, double rate0) {
    DamageLaw d;
    d.kind = DamageKind::johnson_cook;
    d.D1 = D1;
    d.D2 = D2;
    d.D3 = D3;
    d.D4 = D4;
    d.rate0 = rate0;
    return d;
  }
};

// Johnson-Cook failure strain eps_f = [D1 + D2 exp(D3 sigma*)][1 + D4 ln rate*] (temperature term omitted).
MFSD_HD inline double johnson_cook_failure_strain(const DamageLaw& d, double triaxiality, double plastic_rate) {
  const double rate_star = math::max(plastic_rate / d.rate0, 1.0);  // decision: rate* >= 1 (header)
  return (d.D1 + d.D2 * math::exp(d.D3 * triaxiality)) *
         (1.0 + d.D4 * math::log(rate_star));  // rkpm.md 4.3; Johnson & Cook, EFM 21 (1985) 31-48
}

// D_n+1 from D_n, the updated eps_p, the step's deps_p, the returned effective
// stress sigma_bar (johnson_cook: sigma* = p/q) and the plastic rate deps_p/dt.
MFSD_HD inline double update_damage(const DamageLaw& d, double D_n, double eps_p, double deps_p,
                                    const Mat<3, double>& sigma_bar, double plastic_rate) {
  switch (d.kind) {
    case DamageKind::linear:  // rkpm.md 4.3: D = clamp((eps_p - eps_D)/(eps_f - eps_D), 0, 1)
      return math::max(D_n, math::clamp((eps_p - d.eps_D) / (d.eps_f - d.eps_D), 0.0, 1.0));
    case DamageKind::exponential:  // rkpm.md 4.3: D = 1 - exp(-<eps_p - eps_D>/eps_r)
      return math::max(D_n, -math::expm1(-math::max(eps_p - d.eps_D, 0.0) / d.eps_r));
    case DamageKind::johnson_cook: {  // rkpm.md 4.3: D += deps_p/eps_f
      if (!(deps_p > 0.0)) return D_n;
      const double q = von_mises(sigma_bar);
      const double triaxiality = q > 0.0 ? mean_stress(sigma_bar) / q : 0.0;  // sigma* = p/q
      const double eps_f = johnson_cook_failure_strain(d, triaxiality, plastic_rate);
      return eps_f > 0.0 ? math::min(D_n + deps_p / eps_f, 1.0) : 1.0;
    }
    default:
      return D_n;
  }
}

MFSD_HD inline bool is_failed(double D, const DamageLaw& d) { return D >= d.critical; }  // rkpm.md 4.3: D >= D_c

// The stress the node carries: (1 - D) sigma_bar (default), or (1 - D) on the
// deviator and a tensile pressure only; a failed node min(p_bar, 0) I.
MFSD_HD inline Mat<3, double> nominal_stress(const Mat<3, double>& sigma_bar, double D, const DamageLaw& d) {
  const double p = trace(sigma_bar) / 3.0;
  if (is_failed(D, d)) return Mat<3, double>::diagonal(math::min(p, 0.0));  // rkpm.md 4.3: s = 0, p compressive only
  if (d.degrade_whole_tensor) return sigma_bar * (1.0 - D);                 // rkpm.md 4.3 default: (1 - D) sigma_bar
  Mat<3, double> sigma = deviator(sigma_bar) * (1.0 - D);                   // rkpm.md 4.3 option
  sigma.add_diagonal(p > 0.0 ? (1.0 - D) * p : p);
  return sigma;
}

// ---- Drucker-Prager, tension cut-off, apex (rkpm.md 4.4) ---------------------
struct DruckerPragerCone {
  double K, mu;      // bulk and shear moduli
  double alpha_bar;  // friction: f = q_bar + alpha_bar p - k
  double beta_bar;   // dilatancy: g = q_bar + beta_bar p (beta_bar = alpha_bar: associative)
  double k;          // cohesion (damage-degraded by the caller)
  double T;          // tension cut-off, p <= T (damage-degraded by the caller; +inf: none)
};

enum class DpBranch : int { elastic, cone, apex, tension_cutoff, tension_corner };

struct DruckerPragerReturn {
  DpBranch branch;
  double deps_pv;  // plastic volumetric strain increment (p_tr - p)/K (tension positive)
  double dgamma;   // deviatoric multiplier (q_bar_tr - q_bar)/mu (= Delta lambda on the cone)
};

// f = q_bar + alpha_bar p - k.
MFSD_HD inline double drucker_prager_yield(const Mat<3, double>& sigma, double alpha_bar, double k) {
  return sqrt_j2(sigma) + alpha_bar * mean_stress(sigma) - k;  // rkpm.md 4.4
}

// Four-branch return of the trial stress sigma (in: sigma_tr, out: sigma_n+1),
// perfectly plastic; rkpm.md 4.4; de Souza Neto, Peric & Owen 2008 (DP return).
MFSD_HD inline DruckerPragerReturn drucker_prager_return(Mat<3, double>& sigma, const DruckerPragerCone& c) {
  const double p_tr = trace(sigma) / 3.0;
  Mat<3, double> s = deviator(sigma);
  const double q_tr = math::sqrt(0.5 * ddot(s, s));                                   // q_bar = sqrt(s:s/2)
  const double T_star = c.alpha_bar > 0.0 ? math::min(c.T, c.k / c.alpha_bar) : c.T;  // T* = min(T, k/alpha_bar)
  DruckerPragerReturn r{DpBranch::elastic, 0.0, 0.0};
  double p = p_tr, q = q_tr;
  if (p_tr > T_star) {  // step 1, tension
    p = T_star;
    const double q_cap = math::max(c.k - c.alpha_bar * T_star, 0.0);  // q_cap = max(k - alpha_bar T*, 0)
    if (q_tr <= q_cap) {
      r.branch = DpBranch::tension_cutoff;  // s = s_tr
    } else {
      r.branch = DpBranch::tension_corner;  // s = (q_cap/q_tr) s_tr (a projection)
      s *= q_cap / q_tr;
      q = q_cap;
    }
  } else {
    const double f_tr = q_tr + c.alpha_bar * p_tr - c.k;                    // step 2
    if (f_tr <= 0.0) return r;                                              // elastic: accept
    const double dlambda = f_tr / (c.mu + c.K * c.alpha_bar * c.beta_bar);  // step 3: cone
    if (q_tr >= c.mu * dlambda) {
      r.branch = DpBranch::cone;
      s *= 1.0 - c.mu * dlambda / q_tr;       // s = (1 - mu dlambda/q_tr) s_tr
      p = p_tr - c.K * c.beta_bar * dlambda;  // p = p_tr - K beta_bar dlambda
      q = q_tr - c.mu * dlambda;
    } else {
      r.branch = DpBranch::apex;  // step 4: s = 0, p = k/alpha_bar (= T*, header)
      s = Mat<3, double>::zero();
      p = T_star;
      q = 0.0;
    }
  }
  r.deps_pv = (p_tr - p) / c.K;
  r.dgamma = (q_tr - q) / c.mu;
  sigma = s;
  sigma.add_diagonal(p);
  return r;
}

// Mohr-Coulomb matches of sqrt(J2) + alpha I1 - k (alpha_bar = 3 alpha) from
// the friction angle phi (radians) and the cohesion c; rkpm.md 4.4; de Souza
// Neto, Peric & Owen 2008 (DP approximations to Mohr-Coulomb).
struct DruckerPragerMatch {
  double alpha_bar, k;
};
// Outer cone (through the compressive meridian: uniaxial compressive strength).
MFSD_HD inline DruckerPragerMatch mohr_coulomb_outer_cone(double phi, double c) {
  const double d = math::sqrt(3.0) * (3.0 - math::sin(phi));
  return {3.0 * 2.0 * math::sin(phi) / d, 6.0 * c * math::cos(phi) / d};  // alpha = 2 sin phi/(sqrt3 (3 - sin phi))
}
// Inner cone (through the tensile meridian: uniaxial tensile strength).
MFSD_HD inline DruckerPragerMatch mohr_coulomb_inner_cone(double phi, double c) {
  const double d = math::sqrt(3.0) * (3.0 + math::sin(phi));
  return {3.0 * 2.0 * math::sin(phi) / d, 6.0 * c * math::cos(phi) / d};  // rkpm.md 4.4: 3 + sin phi
}
// Plane strain (same collapse load as Mohr-Coulomb in plane strain).
MFSD_HD inline DruckerPragerMatch mohr_coulomb_plane_strain(double phi, double c) {
  const double t = math::tan(phi);
  const double d = math::sqrt(9.0 + 12.0 * t * t);
  return {3.0 * t / d, 3.0 * c / d};  // alpha = tan phi/sqrt(9 + 12 tan^2 phi), k = 3c/sqrt(...)
}

}  // namespace mfsd::rkpm
