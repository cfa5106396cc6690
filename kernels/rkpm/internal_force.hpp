// RKPM force stage (rkpm.md 5.2 stage 6; seed 004 eq. 21-22, 27-28): per
// node I, a gather over row I with the operators of the current configuration:
//   f~_I = sum_L V_L sigma_L grad~Psi_I(x_L)           (eq. 27, SNNI, eq. 23-24)
//   + S_I xi_I, the variational-consistency correction of the test gradient
//     xi_I = (B_I - g_I)/w_I                          (rkpm.md 3.4)
//   + sum_L sum_i tau^(i)_L Psi_I,.i(x_L)              (NSNI, rkpm.md 3.5)
//   M_I = sum_L m_L Psi_I(x_L)                         (row-sum mass, eq. 22a, 28)
// then the acceleration with gravity and mass-proportional damping, and the
// velocity over the step (rkpm.md 5.1; written for the drift-kick-drift step
// of host/solver/rkpm/, docs/theory.md "RKPM").
#pragma once
#include "kernels/rkpm/stress_stage.hpp"

namespace mfsd::rkpm {

// Guards of rkpm.md 3.3-3.4.
constexpr double kMassFloor = 0.1;               // M_I < 0.1 m_I: nodal mass
constexpr double kCorrectionWeightFloor = 1e-3;  // |w_I| < 1e-3 V_I: xi_I = 0

template <int D, class Real>
struct ForceFunctor {
  PairList<D, Real> rows;
  NodeFields<D, Real> nodes;
  const NodeOperator<D, Real>* op;
  const ImplicitGradient<D, Real>* nsni;       // null: SNNI
  const StressGradient<D, Real>* nsni_stress;  // tau^(i)
  const Mat<3, Real>* stress;                  // sigma_bar
  const Real* damage;                          // null: none
  DamageLaw damage_law;
  const unsigned char* surface;  // boundary face bits of each cell
  const unsigned char* status;   // operator status bits (1: regularized point)
  const Real* nodal_mass;        // m = rho0 V0
  Real* lumped_mass;             // M_I (out)
  Real* lumped_volume;           // M_I / rho0 (out): the conditions' mass (host/solver/rkpm/)
  const Real* density0;          // per node rho0
  Vec<D, Real>* velocity;        // v^n in, v^n+1 out (dt > 0)
  Vec<D, Real>* acceleration;    // (v^n+1 - v^n)/dt out
  Real* damping_work;            // J, accumulated (alpha_d > 0)
  Vec<D, Real> gravity;
  bool variational_correction;
  bool row_sum_mass;
  double alpha_d;                          // C = alpha_d M (seed 004 eq. 29)
  double dt;                               // 0 at set-up: masses only
  Vec<D, Real>* internal_force = nullptr;  // f_int (out) where given (tests: stiffness by differences)

  MFSD_HD Mat<D, double> nominal(Index L) const {
    const Mat<3, double> s = cast<double>(stress[L]);
    return in_plane<D>(damage ? nominal_stress(s, double(damage[L]), damage_law) : s);
  }

  MFSD_HD void operator()(Index I) const {
    const Vec<D, Real> xI = nodes.position[I];
    const double aI = double(nodes.support[I]);
    const bool singI = nodes.is_singular(I);
    Vec<D, double> f = Vec<D, double>::zero(), g = Vec<D, double>::zero(), B = Vec<D, double>::zero();
    Mat<D, double> S = Mat<D, double>::zero();
    double w = 0.0, M = 0.0;
    bool correct = variational_correction;
    const PairRow row = rows.row(I);
    for (Index k = 0; k < row.count; ++k) {
      const Index L = rows.neighbor[row.at(k)];
      const NodeOperator<D, Real>& o = op[L];
      const Vec<D, double> d = cast<double>(nodes.position[L] - xI);  // x_L - x_I
      const Vec<D, double> A =
          smoothed_gradient_volume(o, I, d, aI, singI, nodes.box, surface[L], &B);  // V_L grad~Psi_I(x_L)
      const double psi = shape_at(o, 2 * D, I, d, aI, singI, nodes.box);            // Psi_I(x_L)
      const Mat<D, double> sigma = nominal(L);
      f += sigma * A;  // eq. 27: V_L sigma_L grad~Psi_I(x_L)
      g += A;
      const double Vpsi = double(o.volume) * psi;
      w += Vpsi;
      S += sigma * Vpsi;
      M += double(nodal_mass[L]) * psi;  // eq. 22a: M_I = sum_L m_L Psi_I(x_L)
      if (status[L] & 1u) correct = false;
      if (damage && is_failed(double(damage[L]), damage_law)) correct = false;
      if (nsni) {
        const KernelSample<D> s = kernel<D>(d, aI, false, nodes.box);
        if (s.w > 0.0) {
          const double inv_abar = double(o.inv_abar);
          const Mat<D, double> P = implicit_second_derivatives(nsni[L], basis<D>(d, inv_abar), s, inv_abar);
          // rkpm.md 3.5: f_I,a += sum_i tau^(i)_L,ab Psi_I,bi(x_L)
          for (int i = 0; i < D; ++i) {
            const Mat<D, double> tau = cast<double>(nsni_stress[L].g[i]);
            for (int a = 0; a < D; ++a)
              for (int b = 0; b < D; ++b) f.v[a] += tau.m[a][b] * P.m[b][i];
          }
        }
      }
    }
    const double m = double(nodal_mass[I]);
    // rkpm.md 3.4: xi_I = (B_I - g_I)/w_I; f_I = f~_I + S_I xi_I.
    if (correct && math::fabs(w) >= kCorrectionWeightFloor * double(op[I].volume)) f += S * ((B - g) * (1.0 / w));
    if (!row_sum_mass || !(M >= kMassFloor * m)) M = m;
    if (internal_force) internal_force[I] = cast<Real>(f);
    lumped_mass[I] = Real(M);
    lumped_volume[I] = Real(M / double(density0[I]));
    if (!(dt > 0.0)) return;
    // M a = f_ext - f_int - alpha_d M v (rkpm.md 5.1), the damping on the
    // step's start velocity: then the reaction a velocity condition computes
    // from the velocity change, M (v_bar - v_n)/dt - M a, is exactly
    // f_int - f_ext + alpha_d M v (rkpm.md 6); the implicit form's
    // 1/(1 + alpha_d dt/2) would scale it (stable for alpha_d dt < 2, and
    // alpha_d = 2 omega_1 is far below the CFL's omega_max).
    const Vec<D, double> v0 = cast<double>(velocity[I]);
    const Vec<D, double> a = cast<double>(gravity) - f * (1.0 / M) - v0 * alpha_d;
    const Vec<D, double> v1 = v0 + a * dt;
    if (alpha_d > 0.0) damping_work[I] += Real(alpha_d * M * dot(v0, 0.5 * (v0 + v1)) * dt);
    velocity[I] = cast<Real>(v1);
    acceleration[I] = cast<Real>((v1 - v0) * (1.0 / dt));
  }
};

}  // namespace mfsd::rkpm
