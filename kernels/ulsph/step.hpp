// The fused passes of one ULSPH acoustic step (seed 002 section 3.3, eq. 30-34;
// formulations.md section 3, "Step"): a position-Verlet split in which each
// pass reads its neighbours' fields that no pass writes at the same time.
//   first half        u += dt/2 v, then (after a rebuild) rho += dt/2 drho/dt   (eq. 30, 14)
//   StressFunctor     p = K (rho/rho0 - 1) with tension failure; L (eq. 20-21);
//                     tau by the Jaumann rate and the J2 return (eq. 6-12)
//   ForceFunctor      a = pressure with Riemann dissipation (eq. 15-17) + shear
//                     (eq. 18) + the accumulated GNOG penalty (eq. 27-29) + g
//   VelocityFunctor   v += dt a                                                  (eq. 31)
//   second half       HalfStepFunctor at v^{n+1} (eq. 32), the numerical forces' work
// Positions are displacements u = x - X (host/solver/common/kinematics.hpp).
// The pair data (grad, stretch) stay those of the last neighbour rebuild
// (ulsph_pair_fill.hpp) through the acoustic sub-steps of an advection step.
#pragma once
#include <type_traits>

#include "kernels/core/mat.hpp"
#include "kernels/core/step_statistics.hpp"
#include "kernels/neighbors/pair_list.hpp"
#include "kernels/ulsph/continuity.hpp"
#include "kernels/ulsph/equation_of_state.hpp"
#include "kernels/ulsph/failure.hpp"
#include "kernels/ulsph/gnog.hpp"
#include "kernels/ulsph/pressure_force.hpp"
#include "kernels/ulsph/shear_force.hpp"
#include "kernels/ulsph/shear_stress.hpp"
#include "kernels/ulsph/velocity_gradient.hpp"

namespace mfsd::ulsph {

// No hourglass control (scene hourglass `none`, the SPH-OG of seed 002).
struct GnogNone {};

// rho and u through half a step at the current velocity (seed 002 eq. 30, 32).
template <int D, class Real>
struct HalfStepFunctor {
  PairList<D, Real> pairs;
  const Vec<D, Real>* velocity;
  Real* density;
  Vec<D, Real>* displacement;  // null: rho only
  Real half_dt;

  MFSD_HD void operator()(Index i) const {
    const Real rho = density[i];
    density[i] = rho + half_dt * density_rate(pairs, velocity, rho, i);  // seed 002 eq. 14
    if (displacement) displacement[i] += velocity[i] * half_dt;
  }
};

// u through half a step (the first half, before the pair data of the step are formed).
template <int D, class Real>
struct DisplacementHalfStepFunctor {
  const Vec<D, Real>* velocity;
  Vec<D, Real>* displacement;
  Real half_dt;
  MFSD_HD void operator()(Index i) const { displacement[i] += velocity[i] * half_dt; }
};

// The work of the numerical forces (Riemann dissipation and GNOG penalty,
// a_num) over one position half step, m a_num . v dt/2, taken from the
// particle's account: position Verlet moves it by dt/2 (v^n + v^{n+1}) over
// the step, v^{n+1} after contact and conditions (a clamped particle does not
// move, whatever its a_num).
template <int D, class Real>
struct NumericalWork {
  Vec<D, Real>* numerical_acceleration;
  const Real* mass;
  Real* dissipated_work;
  Real half_dt;
  MFSD_HD void operator()(Index i, const Vec<D, Real>& v) const {
    dissipated_work[i] -= mass[i] * half_dt * dot(numerical_acceleration[i], v);
  }
};

// The second half step, reduced to the time step's maxima and the health
// check of the particle (kernels/core/step_statistics.hpp).
template <int D, class Real>
struct SecondHalfStepFunctor {
  HalfStepFunctor<D, Real> half;
  StepStatisticsFunctor<D, Real> statistics;
  NumericalWork<D, Real> work;  // its second half, at v^{n+1}
  MFSD_HD StepStatistics<Real> operator()(Index i) const {
    half(i);
    work(i, half.velocity[i]);
    return statistics(i);
  }
};

// Pressure, velocity gradient and shear stress of one body's particles.
template <int D, class Real, class Failure>
struct StressFunctor {
  PairList<D, Real> pairs;
  const Vec<D, Real>* velocity;
  const Mat<D, Real>* correction;  // B (velocity_gradient.hpp)
  const Real* density;
  Real* pressure;
  Mat<D, Real>* velocity_gradient;
  Mat<D, Real>* shear_stress;
  Real* hardening;     // a of J2 bodies, else null
  Real* kappa;         // plastic scale of J2 bodies, else null
  Real* plastic_work;  // J2 bodies: += V (sigma_y + H a) da, else null
  const Real* mass;
  LinearEquationOfState<Real> eos;
  Failure failure;
  HypoelasticJ2<Real> model;
  Real dt;
  // solver.ulsph.energy_audit: += V tau : (L - L~) dt, the stress power the
  // shear force (eq. 18, with the uncorrected gradient) does not do; else null.
  Real* shear_mismatch = nullptr;

  MFSD_HD void operator()(Index i) const {
    pressure[i] = failure(i, eos.pressure(density[i]));  // seed 002 section 2.1, 5.9
    const Mat<D, Real> L_uncorrected = ulsph::uncorrected_velocity_gradient(pairs, velocity, i);
    const Mat<D, Real> L = mul_transposed(L_uncorrected, correction[i]);  // seed 002 eq. 20: L~ B_i^T
    velocity_gradient[i] = L;
    const ShearStressUpdate<D, Real> r =
        update_shear_stress(shear_stress[i], L, hardening ? hardening[i] : Real(0), model, dt);
    shear_stress[i] = r.shear_stress;
    if (shear_mismatch) shear_mismatch[i] += dt * mass[i] / density[i] * ddot(r.shear_stress, L - L_uncorrected);
    if (hardening) {
      // tau : d eps_p = |tau| dgamma = sqrt(2/3) R dgamma = (sigma_y + H a) da per unit volume
      if (plastic_work)
        plastic_work[i] += mass[i] / density[i] * (model.yield_stress + model.hardening_modulus * r.hardening) *
                           (r.hardening - hardening[i]);
      hardening[i] = r.hardening;
    }
    if (kappa) kappa[i] = r.kappa;
  }
};

// a = pressure + Riemann dissipation + shear + GNOG penalty + gravity of one
// body's particles. Variant: GnogNone, GnogStandard, GnogAngularMomentumConserving.
template <int D, class Real, class Variant>
struct ForceFunctor {
  PairList<D, Real> pairs;
  const Vec<D, Real>* velocity;
  const Real* density;  // rho_i the pair data were formed with (V_i = m_i/rho_i in grad_ji): momentum to round-off
  const Real* pressure;
  const Mat<D, Real>* shear_stress;
  const Mat<D, Real>* velocity_gradient;
  const Real* kappa;                     // null: kappa = 1
  Vec<D, Real>* hourglass_acceleration;  // a_h (null with GnogNone)
  Vec<D, Real>* acceleration;
  NumericalWork<D, Real> work;  // writes a_num (its numerical_acceleration is written here)
  Real impedance;               // Z = rho0 c0
  Real limiter;                 // eta / c0 of the Riemann dissipation's limiter; 0: none (pressure_force.hpp)
  Real xi;                      // GNOG coefficient of the body
  Real shear_modulus;
  Real dt;
  Vec<D, Real> gravity;

  // One pass over the row for the three pair sums, each summed as its own
  // function does (pressure_acceleration, shear_acceleration,
  // gnog_penalty_rate): the same numbers, one gather of each neighbour field.
  MFSD_HD void operator()(Index i) const {
    constexpr bool gnog = !std::is_same<Variant, GnogNone>::value;
    const Real rho = density[i];
    const Real p_i = pressure[i];
    const Vec<D, Real> v_i = velocity[i];
    const Real kappa_i = kappa ? kappa[i] : Real(1);
    Mat<D, Real> L_i = Mat<D, Real>::zero();
    if constexpr (gnog) L_i = velocity_gradient[i];
    Vec<D, Real> sum_p = Vec<D, Real>::zero(), dissipation = Vec<D, Real>::zero(), sum_h = Vec<D, Real>::zero();
    Vec<D, Real> sum_s = shear_stress[i] * pairs.gradient_sum[i];  // tau_i sum_j grad_ij
    for (PairIndex k = pairs.offsets[i]; k < pairs.offsets[i + 1]; ++k) {
      const Index j = pairs.neighbor[k];
      const Index ahead = pairs.neighbor[k + kPairPrefetchDistance];
      prefetch(&velocity[ahead]);
      prefetch(&pressure[ahead]);
      prefetch(&shear_stress[ahead]);
      if constexpr (gnog) prefetch(&velocity_gradient[ahead]);
      const Vec<D, Real> g = pairs.grad[k];
      const Vec<D, Real> v_j = velocity[j];
      sum_p += g * (-(p_i + pressure[j]));                                        // seed 002 eq. 15: pressure
      dissipation += riemann_dissipation_term(g, v_i - v_j, impedance, limiter);  // eq. 15-17: Riemann
      sum_s += shear_stress[j] * g;                                               // eq. 18: tau_j grad_ij
      if constexpr (gnog)
        sum_h += gnog_pair_term<D, Real, Variant>(v_i, v_j, L_i, velocity_gradient[j], g, pairs.stretch[k], kappa_i,
                                                  kappa ? kappa[j] : Real(1));  // eq. 29, 35
    }
    const Vec<D, Real> a_d = dissipation / rho;    // the Riemann dissipation's part of a
    Vec<D, Real> a = (sum_p + dissipation) / rho;  // seed 002 eq. 15: 1/rho_i
    a += sum_s / rho;                              // seed 002 eq. 18
    Vec<D, Real> a_numerical = a_d;
    if constexpr (gnog) {
      Vec<D, Real> a_h = hourglass_acceleration[i];
      if constexpr (std::is_same<Variant, GnogAngularMomentumConserving>::value)
        a_h = rotate_with_spin(a_h, L_i, dt);                      // formulations.md 3: a_h turns with the spin
      a_h += sum_h * (Real(0.5) * xi * shear_modulus / rho) * dt;  // seed 002 eq. 29: G / rho_i, accumulated
      hourglass_acceleration[i] = a_h;
      a += a_h;
      a_numerical += a_h;
    }
    acceleration[i] = a + gravity;
    work.numerical_acceleration[i] = a_numerical;
    work(i, velocity[i]);  // the first half of the step's work, at v^n (NumericalWork)
  }
};

// v += dt a (seed 002 eq. 31).
template <int D, class Real>
struct VelocityFunctor {
  const Vec<D, Real>* acceleration;
  Vec<D, Real>* velocity;
  Real dt;
  MFSD_HD void operator()(Index i) const { velocity[i] += acceleration[i] * dt; }
};

// The output measures: von Mises stress sqrt(3/2) |tau| (the pressure adds no
// deviator) and J = rho0 / rho of one body.
template <int D, class Real>
struct ObservablesFunctor {
  const Mat<D, Real>* shear_stress;
  const Real* density;
  Real reference_density;
  Real* von_mises;
  Real* jacobian;
  MFSD_HD void operator()(Index i) const {
    von_mises[i] = math::sqrt(Real(1.5)) * frobenius_norm(shear_stress[i]);
    jacobian[i] = reference_density / density[i];
  }
};

}  // namespace mfsd::ulsph
