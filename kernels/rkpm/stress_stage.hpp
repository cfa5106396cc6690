// RKPM stress stage (rkpm.md 5.2 stage 2; seed 004 section 7, eq. 25-26):
// per node L, a gather over row L with the operators of the configuration
// they were built in (x^n):
//   L_n = sum_I (du_I - du_L) (x) grad~Psi_I(x_L)           (rkpm.md 4.1)
//   Hughes-Winget: Deps, Q; sigma_tr = Q sigma Q^T + C:Deps   (rkpm.md 4.2)
//   return mapping (J2, Drucker-Prager) and damage           (rkpm.md 4.3-4.4)
//   F_cell <- (I + L_n) F_cell, re-celled when cond > kappa  (rkpm.md 3.2)
//   NSNI stress gradients sigma^(i) and tau^(i) = sum_j Theta_ij sigma^(j)  (rkpm.md 3.5, 4.5)
// and the internal and plastic work. du_I: the nodes' displacement since the
// operators' configuration.
#pragma once
#include "kernels/rkpm/hughes_winget.hpp"
#include "kernels/rkpm/node_operator.hpp"
#include "kernels/rkpm/stress_update.hpp"

namespace mfsd::rkpm {

// NSNI stress gradients sigma^(i) (or tau^(i)), in-plane D x D each.
template <int D, class Real>
struct StressGradient {
  Mat<D, Real> g[D];
};

enum class LawKind : int { elastic, j2, drucker_prager };

// The hypo-elastic law of a body (seed 004 section 7): elastic moduli, the
// plastic model and the damage law.
struct StressLaw {
  LawKind kind = LawKind::elastic;
  double K = 0, mu = 0;
  J2Hardening j2{0, 0, 0};
  DruckerPragerCone dp{0, 0, 0, 0, 0, 0};
  DamageLaw damage;
};

template <int D>
MFSD_HD inline Mat<D, double> in_plane(const Mat<3, double>& A) {
  Mat<D, double> r;
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) r.m[a][b] = A.m[a][b];
  return r;
}

// The moduli of the NSNI stress-gradient update (rkpm.md 4.5, switch
// `nsni_moduli`): elastic, or the tangent of the step's return mapping,
//   C:e = K tr(e) I + 2 mu_perp (dev e - (n:e) n) + 2 mu_flow (n:e) n,
// n the unit deviatoric flow direction. J2 radial return: mu_perp = mu theta,
// theta = 1 - 3 mu deps_p / q_tr, mu_flow = mu H/(3 mu + H) (Simo & Hughes
// 1998, the consistent tangent). Drucker-Prager: on the cone mu_perp =
// mu q_bar/q_bar_tr, mu_flow = 0 (perfectly plastic; the dilatant coupling of
// p and q is left out), at the cut-off K = 0, at the corner also
// mu_perp = mu q_cap/q_bar_tr, at the apex all 0. With the elastic moduli
// sigma^(i) keeps growing where the material flows: a footing on perfectly
// plastic soil then never reaches a limit load (docs/theory.md).
struct GradientModuli {
  double K, mu_perp, mu_flow;
  Mat<3, double> n;                // unit deviatoric direction (zero where unused)
  double deviatoric_return = 1.0;  // s = theta s_tr of the return: applied to the gradients' deviators too
  MFSD_HD static GradientModuli elastic(double K, double mu) {
    return GradientModuli{K, mu, mu, Mat<3, double>::zero(), 1.0};
  }
  template <int D>
  MFSD_HD Mat<D, double> apply(const Mat<D, double>& e) const {
    Mat<3, double> e3 = Mat<3, double>::zero();
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) e3.m[a][b] = e.m[a][b];  // plane strain: e_33 = 0
    const double ne = ddot(n, e3);
    Mat<3, double> s = (deviator(e3) - n * ne) * (2.0 * mu_perp) + n * (2.0 * mu_flow * ne);
    s.add_diagonal(K * trace(e3));
    return in_plane<D>(s);
  }
};

// The consistency projection of the NSNI stress gradients (`nsni_moduli:
// consistent`): where a node flows plastically in the step, its neighbourhood
// stays on the yield surface f(sigma(x)) = 0, so the stress gradients obey
// f_sigma : sigma^(i) = 0 (perfect plasticity) and the trial gradients
// (rotated + C:Deps^(i)) are returned along the plastic flow C:g_sigma:
//   sigma^(i) <- sigma^(i) - C:g_sigma (f_sigma : sigma^(i)) / (f_sigma:C:g_sigma + H)
// (the continuum elasto-plastic tangent applied to the whole gradient, not only
// to its increment: the elastic gradient stored before yield is returned too).
// J2: f_sigma = sqrt(3/2) n, C:g_sigma = 2 mu sqrt(3/2) n, denominator 3 mu + H
// (a fraction H/(3 mu + H) of the normal part stays each step: hardening).
// Drucker-Prager cone: f_sigma = n/sqrt2 + alpha_bar I/3, C:g_sigma =
// sqrt2 mu n + K beta_bar I, denominator mu + K alpha_bar beta_bar (rkpm.md 4.4);
// tension cut-off: the mean part removed; apex and corner: all removed. In
// plane strain the contraction runs over the in-plane components only (the
// gradient of sigma_33 is not carried; exact where n_33 = 0, e.g. phi = 0 at
// the limit load). Unlike the return's algorithmic tangent it keeps the
// gradients orthogonal to the flow, which carry the stabilization.
struct GradientReturn {
  enum Mode : int { none, project, zero };
  int mode = none;
  Mat<3, double> flow = Mat<3, double>::zero();    // C:g_sigma
  Mat<3, double> normal = Mat<3, double>::zero();  // f_sigma
  double inv_denominator = 0.0;
  template <int D>
  MFSD_HD void apply(Mat<D, double>& g) const {
    if (mode == zero) g = Mat<D, double>::zero();
    if (mode != project) return;
    double r = 0.0;
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) r += normal.m[a][b] * g.m[a][b];
    g += in_plane<D>(flow) * (-r * inv_denominator);
  }
};

MFSD_HD inline Mat<3, double> unit_deviator(const Mat<3, double>& sigma) {
  const Mat<3, double> s = deviator(sigma);
  const double norm_s = math::sqrt(ddot(s, s));
  return norm_s > 0.0 ? s * (1.0 / norm_s) : Mat<3, double>::zero();
}

template <int D, class Real>
struct StressFunctor {
  PairList<D, Real> rows;
  NodeFields<D, Real> nodes;  // positions and supports of the operators' configuration
  const NodeOperator<D, Real>* op;
  const ImplicitGradient<D, Real>* nsni;  // null: SNNI
  const Vec<D, Real>* increment;          // du since the operators' configuration
  const Real* initial_volume;             // V0
  const Vec<D, Real>* cell_lo;
  const Vec<D, Real>* cell_hi;
  Mat<D, Real>* cell_map;                    // F_cell, updated
  Mat<3, Real>* stress;                      // sigma_bar (effective Cauchy), updated
  Real* plastic_strain;                      // null for elastic bodies
  Real* damage;                              // null without a damage law
  StressGradient<D, Real>* stress_gradient;  // sigma^(i) (NSNI)
  StressGradient<D, Real>* nsni_stress;      // tau^(i) = sum_j Theta_ij (1 - D) sigma^(j)
  Real* internal_work;                       // J, accumulated
  Real* plastic_work;                        // J, accumulated (null: elastic)
  StressLaw law;
  double nsni_scale;       // c_s
  bool tangent_moduli;     // NSNI stress gradients with the return's tangent (else elastic)
  bool consistent_moduli;  // NSNI stress gradients returned to the yield surface's tangent plane
  double recell_condition;
  bool box_cells;
  double dt;

  MFSD_HD void operator()(Index L) const {
    const NodeOperator<D, Real>& o = op[L];
    const Vec<D, Real> xL = nodes.position[L];
    const Vec<D, double> duL = cast<double>(increment[L]);
    const double inv_V = 1.0 / double(o.volume);
    const double inv_abar = double(o.inv_abar);
    Mat<D, double> Ln = Mat<D, double>::zero();
    Mat<D, double> de[D];
    for (int i = 0; i < D; ++i) de[i] = Mat<D, double>::zero();
    const PairRow row = rows.row(L);
    for (Index k = 0; k < row.count; ++k) {
      const Index I = rows.neighbor[row.at(k)];
      const Vec<D, Real> xI = nodes.position[I];
      const Vec<D, double> d = cast<double>(xL - xI);
      const double aI = double(nodes.support[I]);
      const Vec<D, double> du = cast<double>(increment[I]) - duL;
      const Vec<D, double> grad =
          smoothed_gradient_volume(o, I, d, aI, nodes.is_singular(I), nodes.box, 0, (Vec<D, double>*)nullptr) * inv_V;
      Ln += outer(du, grad);  // rkpm.md 4.1: L_n = sum (du_I - du_L) (x) grad~Psi_I
      if (nsni) {
        const KernelSample<D> s = kernel<D>(d, aI, false, nodes.box);
        if (!(s.w > 0.0)) continue;
        const Mat<D, double> P = implicit_second_derivatives(nsni[L], basis<D>(d, inv_abar), s, inv_abar);
        // rkpm.md 4.5: Deps^(i)_ab = 1/2 sum_I (du_Ia Psi_I,bi + du_Ib Psi_I,ai)
        for (int i = 0; i < D; ++i)
          for (int a = 0; a < D; ++a)
            for (int b = 0; b < D; ++b) de[i].m[a][b] += 0.5 * (du.v[a] * P.m[b][i] + du.v[b] * P.m[a][i]);
      }
    }
    const HughesWingetIncrement inc = hughes_winget<D>(Ln);  // seed 004 eq. 25-26
    const Mat<3, double> sigma_n = cast<double>(stress[L]);
    Mat<3, double> sigma = elastic_predictor(sigma_n, inc.rotation, inc.strain, law.K, law.mu);
    double eps_p = plastic_strain ? double(plastic_strain[L]) : 0.0;
    double deps_p = 0.0;
    double plastic_power = 0.0;  // sigma:Deps_p of the step
    GradientModuli moduli = GradientModuli::elastic(law.K, law.mu);
    GradientReturn gradient_return;
    if (law.kind == LawKind::j2) {
      const double q_tr = von_mises(sigma);
      const Mat<3, double> n = unit_deviator(sigma);
      deps_p = j2_radial_return(sigma, eps_p, law.j2);
      plastic_power = von_mises(sigma) * deps_p;
      if (deps_p > 0.0 && consistent_moduli) {  // GradientReturn, J2
        const double root = math::sqrt(1.5);
        gradient_return = {GradientReturn::project, n * (2.0 * law.mu * root), n * root,
                           1.0 / (3.0 * law.mu + law.j2.hardening)};
      }
      if (deps_p > 0.0 && tangent_moduli)
        moduli = GradientModuli{law.K, law.mu * (1.0 - 3.0 * law.mu * deps_p / q_tr),
                                law.mu * law.j2.hardening / (3.0 * law.mu + law.j2.hardening), n,
                                1.0 - 3.0 * law.mu * deps_p / q_tr};
    } else if (law.kind == LawKind::drucker_prager) {
      const double q_tr = sqrt_j2(sigma);
      const Mat<3, double> n = unit_deviator(sigma);
      const DruckerPragerReturn r = drucker_prager_return(sigma, law.dp);
      if (consistent_moduli && r.branch == DpBranch::cone) {  // GradientReturn, Drucker-Prager cone
        const double root = math::sqrt(2.0);
        Mat<3, double> flow = n * (root * law.mu), normal = n * (1.0 / root);
        flow.add_diagonal(law.K * law.dp.beta_bar);
        normal.add_diagonal(law.dp.alpha_bar / 3.0);
        gradient_return = {GradientReturn::project, flow, normal,
                           1.0 / (law.mu + law.K * law.dp.alpha_bar * law.dp.beta_bar)};
      } else if (consistent_moduli && r.branch == DpBranch::tension_cutoff) {  // p = T: mean part removed
        gradient_return = {GradientReturn::project, Mat<3, double>::diagonal(law.K),
                           Mat<3, double>::diagonal(1.0 / 3.0), 1.0 / law.K};
      } else if (consistent_moduli && r.branch != DpBranch::elastic) {  // apex, corner: the stress is a point
        gradient_return.mode = GradientReturn::zero;
      }
      if (tangent_moduli && r.branch != DpBranch::elastic) {
        const double ratio = q_tr > 0.0 ? sqrt_j2(sigma) / q_tr : 0.0;
        const bool cone = r.branch == DpBranch::cone;
        const bool cutoff = r.branch == DpBranch::tension_cutoff;
        moduli = GradientModuli{cone ? law.K : 0.0, cutoff ? law.mu : law.mu * ratio, cutoff ? law.mu : 0.0, n,
                                cutoff ? 1.0 : ratio};
      }
      // rkpm.md 4.4: Deps_p = dgamma s/(2 q_bar) + deps_pv I/3, so sigma:Deps_p =
      // q_bar dgamma + p deps_pv; the equivalent plastic strain grows by dgamma/sqrt(3).
      deps_p = r.dgamma / math::sqrt(3.0);
      eps_p += deps_p;
      plastic_power = sqrt_j2(sigma) * r.dgamma + mean_stress(sigma) * r.deps_pv;
    }
    const double D_n = damage ? double(damage[L]) : 0.0;
    double Dm = D_n;
    if (damage) Dm = update_damage(law.damage, D_n, eps_p, deps_p, sigma, dt > 0.0 ? deps_p / dt : 0.0);
    // Cell map and volumes (rkpm.md 4.1, 3.2).
    const Mat<D, double> F_n = cast<double>(cell_map[L]);
    Mat<D, double> F = (Mat<D, double>::identity() + Ln) * F_n;
    if (condition_number<D>(F) > recell_condition) F = recell<D>(F);
    const double V0 = double(initial_volume[L]);
    const double V_mid = 0.5 * (det(F_n) + det(F)) * V0;
    // Internal work 1/2 (sigma_n + sigma_n+1):Deps V_n+1/2 (rkpm.md 4.2), nominal stresses.
    const Mat<3, double> nominal_n = damage ? nominal_stress(sigma_n, D_n, law.damage) : sigma_n;
    const Mat<3, double> nominal = damage ? nominal_stress(sigma, Dm, law.damage) : sigma;
    double work = 0.5 * ddot(nominal_n + nominal, inc.strain) * V_mid;
    if (plastic_work) plastic_work[L] += Real(plastic_power * V_mid);
    if (stress_gradient) {
      // rkpm.md 4.5: sigma^(i) <- sum_e Q_ie Q sigma^(e) Q^T + c_s C:Deps^(i)
      const Mat<D, double> Q = in_plane<D>(inc.rotation);
      Mat<D, double> rotated[D];
      for (int e = 0; e < D; ++e) rotated[e] = mul_transposed(Q * cast<double>(stress_gradient[L].g[e]), Q);
      // Theta = J F Theta0 F^T, Theta0_kk = V0 (lo_k^3 + hi_k^3)/(3 l_k) (rkpm.md 3.5)
      const Mat<D, double> Fm = box_cells ? box_map<D>(F) : F;
      Mat<D, double> theta0 = Mat<D, double>::zero();
      for (int k = 0; k < D; ++k) {
        const double lo = double(cell_lo[L].v[k]), hi = double(cell_hi[L].v[k]);
        theta0.m[k][k] = V0 * (lo * lo * lo + hi * hi * hi) / (3.0 * (lo + hi));
      }
      const Mat<D, double> theta = mul_transposed(Fm * theta0, Fm) * det(Fm);
      const double scale = damage ? (is_failed(Dm, law.damage) ? 0.0 : 1.0 - Dm) : 1.0;
      Mat<D, double> next[D];
      for (int i = 0; i < D; ++i) {
        next[i] = moduli.apply<D>(de[i]) * nsni_scale;
        for (int e = 0; e < D; ++e) next[i] += rotated[e] * Q.m[i][e];
        if (moduli.deviatoric_return < 1.0) {  // the return's radial scaling, also on the gradients
          const double p = trace(next[i]) / D;
          next[i].add_diagonal(-p);
          next[i] *= moduli.deviatoric_return;
          next[i].add_diagonal(p);
        }
        gradient_return.apply<D>(next[i]);
        stress_gradient[L].g[i] = cast<Real>(next[i]);
      }
      for (int i = 0; i < D; ++i) {
        Mat<D, double> tau = Mat<D, double>::zero();
        for (int j = 0; j < D; ++j) tau += next[j] * (theta.m[i][j] * scale);
        // The stabilization's work, 1/2 (tau_n + tau_n+1):Deps^(i) (rkpm.md 3.5).
        work += 0.5 * ddot(cast<double>(nsni_stress[L].g[i]) + tau, de[i]);
        nsni_stress[L].g[i] = cast<Real>(tau);
      }
    }
    internal_work[L] += Real(work);
    cell_map[L] = cast<Real>(F);
    stress[L] = cast<Real>(sigma);
    if (plastic_strain) plastic_strain[L] = Real(eps_p);
    if (damage) damage[L] = Real(Dm);
  }
};

}  // namespace mfsd::rkpm
