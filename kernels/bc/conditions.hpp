// Boundary conditions and loads on selected particles (seed 001 section
// 3.3.2, "bcvel" and "bcforce"), one functor call per selected particle, each
// component either a constant or a user expression (kernels/expr) of the
// particle variables below. An expression that takes its 'skip' branch leaves
// that component alone. Both functors return a ConditionSums that the host
// reduces: the power for the energy balance, the force sum (the reaction of
// a velocity condition) and the first run-time expression error.
//
//   loads      after the force stage, at t + dt/2 with the half-step position
//              and the velocity after the internal-force update:
//                point        f_i = F / n        (F shared by the n selected particles)
//                traction     f_i = T A_i        (A_i: surface area the particle carries)
//                acceleration f_i = m_i a
//              v_i += dt f_i / m_i and a_i += f_i / m_i (so the time step sees it);
//              power f_i . v_mid with v_mid = v_i^n + dt/2 (a_int + a_ext).
//   velocity   in the boundary stage, at t + dt: v_i = value; the reaction is
//              the force that makes the change, R_i = m_i (value - v_i) / dt,
//              and its power R_i . v_mid with v_mid = (v_i^n + value) / 2.
//              dt = 0 (the set-up at t = 0) sets the velocity only.
#pragma once
#include "kernels/bc/step_force.hpp"
#include "kernels/core/mat.hpp"
#include "kernels/expr/interpreter.hpp"
#include "kernels/expr/particle_variables.hpp"

namespace mfsd {

// One component of a condition: not given, a constant, or a program.
template <class Real>
struct ComponentValue {
  enum Kind : int { none = 0, constant = 1, program = 2 };
  int kind;
  Real value;
  expr::ProgramView<Real> code;
};

struct ConditionError {
  Index particle;  // kNoConditionError when none
  int component;
  int pc;
  int status;  // expr::Status
};

constexpr Index kNoConditionError = Index(0x7fffffff);

// In Real like every per-step sum (docs/floating-point.md).
template <class Real>
struct ConditionSums {
  Real power;            // W (per unit thickness in 2-D)
  Real force[3];         // N: sum of applied forces (loads) or reactions (velocity)
  ConditionError error;  // the lowest-indexed particle with an error (kNoConditionError when none)

  MFSD_HD static ConditionSums zero() {
    return ConditionSums{Real(0), {Real(0), Real(0), Real(0)}, {kNoConditionError, 0, 0, 0}};
  }
};

struct ConditionSumsCombine {
  template <class Real>
  MFSD_HD ConditionSums<Real> operator()(const ConditionSums<Real>& a, const ConditionSums<Real>& b) const {
    ConditionSums<Real> r;
    r.power = a.power + b.power;
    for (int k = 0; k < 3; ++k) r.force[k] = a.force[k] + b.force[k];
    r.error = b.error.particle < a.error.particle ? b.error : a.error;
    return r;
  }
};

// Evaluates the given components at particle i (its variables from X, u, v
// and the time); returns false (and fills `error`) at the first run-time
// error. mask bit a: component a was set (not absent, not skipped).
template <int D, class Real>
MFSD_HD inline bool evaluate_components(const ComponentValue<Real> (&c)[3], const Vec<D, Real>& X,
                                        const Vec<D, Real>& u, const Vec<D, Real>& v, Real t, Real dt, Real dx, Index i,
                                        Real (&value)[3], int& mask, ConditionError& error) {
  Real vars[kParticleVariables];
  particle_variables<D, Real>(X, u, v, t, dt, dx, vars);
  mask = 0;
  for (int a = 0; a < D; ++a) {
    if (c[a].kind == ComponentValue<Real>::none) continue;
    if (c[a].kind == ComponentValue<Real>::constant) {
      value[a] = c[a].value;
      mask |= 1 << a;
      continue;
    }
    int pc = 0;
    const expr::Status st = expr::evaluate(c[a].code, vars, &value[a], &pc);
    if (st == expr::Status::skipped) continue;
    if (st != expr::Status::ok) {
      error = ConditionError{i, a, pc, int(st)};
      return false;
    }
    mask |= 1 << a;
  }
  return true;
}

// What loads and velocity conditions share: their selected particles, the
// components and the particle fields the expressions read.
template <int D, class Real>
struct SelectedComponents {
  const Index* particles;  // selected particles (current order)
  ComponentValue<Real> component[3];
  Real density;
  Real t, dt, dx;  // t: the evaluation time
  const Vec<D, Real>* reference_position;
  const Vec<D, Real>* displacement;
  const Real* volume;

  // The values of selected particle k (index i); false when none was set or
  // an expression failed (then `error` is filled).
  MFSD_HD bool evaluate(Index k, const Vec<D, Real>* velocity, Index& i, Real (&value)[3], int& mask,
                        ConditionError& error) const {
    i = particles[k];
    return evaluate_components<D, Real>(component, reference_position[i], displacement[i], velocity[i], t, dt, dx, i,
                                        value, mask, error) &&
           mask;
  }
  MFSD_HD Real mass(Index i) const { return density * volume[i]; }
};

// Adds to `s` the reaction of a constraint that changed a velocity component
// from v_before to v_after within the step (v_start: its value at t^n): the
// force m (v_after - v_before)/dt and its power at the mid-step velocity.
template <class Real>
MFSD_HD inline void add_reaction(ConditionSums<Real>& s, int a, Real m, Real v_start, Real v_before, Real v_after,
                                 Real dt) {
  const Real force = m * (v_after - v_before) / dt;
  s.force[a] += force;
  s.power += force * Real(0.5) * (v_start + v_after);
}

enum class LoadType : int { point, traction, acceleration };

template <int D, class Real>
struct LoadFunctor {
  SelectedComponents<D, Real> sel;  // t = t^n + dt/2
  const Real* area;                 // per selected particle (traction), else null
  LoadType type;
  Real share;  // 1 / n for point loads
  Vec<D, Real>* velocity;
  Vec<D, Real>* acceleration;

  MFSD_HD ConditionSums<Real> operator()(Index k) const {
    ConditionSums<Real> s = ConditionSums<Real>::zero();
    Index i;
    Real value[3] = {Real(0), Real(0), Real(0)};
    int mask = 0;
    if (!sel.evaluate(k, velocity, i, value, mask, s.error)) return s;
    const Real mass = sel.mass(i), dt = sel.dt;
    Vec<D, Real> f = Vec<D, Real>::zero();
    for (int a = 0; a < D; ++a) {
      if (!(mask & (1 << a))) continue;
      if (type == LoadType::point)
        f.v[a] = value[a] * share;  // seed 001 bcforce type 1 [N]
      else if (type == LoadType::traction)
        f.v[a] = value[a] * area[k];  // type 2 [N/m^2]
      else
        f.v[a] = value[a] * mass;  // type 3 [m/s^2]
    }
    s.power = add_step_force(f, mass, dt, velocity[i], acceleration[i]);
    for (int a = 0; a < D; ++a) s.force[a] = f.v[a];
    return s;
  }
};

// A time-dependent transmembrane potential (seed 000 eq. 19, 43): at the
// stress stage's time t, active_tension_i = k V_m(particle variables, t) for
// the particles [begin, begin + n) of a Holzapfel-Ogden body; 'skip' keeps the
// last value. The sums carry only the first run-time expression error.
template <int D, class Real>
struct ActiveTensionFunctor {
  ComponentValue<Real> potential[3];  // [0]: V_m; [1], [2]: none
  Real tension_per_potential;         // k (T_a = k V_m, seed 000 eq. 43)
  Real t, dt, dx;
  Index begin;
  const Vec<D, Real>* reference_position;
  const Vec<D, Real>* displacement;
  const Vec<D, Real>* velocity;
  Real* active_tension;

  MFSD_HD ConditionSums<Real> operator()(Index k) const {
    ConditionSums<Real> s = ConditionSums<Real>::zero();
    const Index i = begin + k;
    Real value[3] = {Real(0), Real(0), Real(0)};
    int mask = 0;
    if (!evaluate_components<D, Real>(potential, reference_position[i], displacement[i], velocity[i], t, dt, dx, i,
                                      value, mask, s.error))
      return s;
    if (mask & 1) active_tension[i] = tension_per_potential * value[0];
    return s;
  }
};

template <int D, class Real>
struct VelocityConditionFunctor {
  SelectedComponents<D, Real> sel;   // t = t^n + dt
  const Vec<D, Real>* acceleration;  // internal + loads, for v^n
  Vec<D, Real>* velocity;

  MFSD_HD ConditionSums<Real> operator()(Index k) const {
    ConditionSums<Real> s = ConditionSums<Real>::zero();
    Index i;
    Real value[3] = {Real(0), Real(0), Real(0)};
    int mask = 0;
    if (!sel.evaluate(k, velocity, i, value, mask, s.error)) return s;
    const Real dt = sel.dt;
    Vec<D, Real> v = velocity[i];
    for (int a = 0; a < D; ++a) {
      if (!(mask & (1 << a))) continue;
      if (dt > Real(0)) add_reaction(s, a, sel.mass(i), v.v[a] - acceleration[i].v[a] * dt, v.v[a], value[a], dt);
      v.v[a] = value[a];
    }
    velocity[i] = v;
    return s;
  }
};

// Rigid frictionless wall (plane through `point` with unit normal `normal`
// pointing into the allowed side), kinematic form: particle centres keep
// at least half a spacing from the plane. At the end of the step a particle
// will be at x^{n+1/2} + dt/2 v^{n+1} (seed 000 eq. 37), so the normal
// velocity is raised to v_n >= -2 g / dt, g = (x^{n+1/2} - point).n - dp/2:
// no penetration at the step's end, a perfectly plastic (restitution 0)
// impact, tangential velocity untouched. The reaction m (v_new - v_old)/dt
// and its power are summed like those of a velocity condition.
template <int D, class Real>
struct WallFunctor {
  Vec<D, Real> point, normal;
  Real half_dp;
  Real dt;
  Index begin;  // the body's particles [begin, begin + n)
  Real density;
  const Vec<D, Real>* reference_position;
  const Vec<D, Real>* displacement;
  const Vec<D, Real>* acceleration;
  const Real* volume;
  Vec<D, Real>* velocity;
  const unsigned char* ghost = nullptr;  // distributed runs: the owner's wall acts on a ghost

  MFSD_HD ConditionSums<Real> operator()(Index k) const {
    ConditionSums<Real> s = ConditionSums<Real>::zero();
    const Index i = begin + k;
    if (ghost && ghost[i]) return s;
    const Vec<D, Real> x = reference_position[i] + displacement[i];
    const Real gap = dot(x - point, normal) - half_dp;
    const Vec<D, Real> v = velocity[i];
    const Real vn = dot(v, normal), vn_min = -Real(2) * gap / dt;
    if (!(vn < vn_min)) return s;
    const Vec<D, Real> v_new = v + normal * (vn_min - vn);
    velocity[i] = v_new;
    const Real m = density * volume[i];
    for (int a = 0; a < D; ++a) add_reaction(s, a, m, v.v[a] - acceleration[i].v[a] * dt, v.v[a], v_new.v[a], dt);
    return s;
  }
};

// Clamp (formulations.md 1): the particle keeps its reference position and
// zero velocity; the reaction is the force that stops it, R_i = -m_i v_i / dt
// (its power is zero: the particle does not move). dt = 0 only clamps.
template <int D, class Real>
struct ClampReactionFunctor {
  const Index* particles;
  Real density;
  Real dt;
  const Real* volume;
  Vec<D, Real>* displacement;
  Vec<D, Real>* velocity;

  MFSD_HD ConditionSums<Real> operator()(Index k) const {
    ConditionSums<Real> s = ConditionSums<Real>::zero();
    const Index i = particles[k];
    if (dt > Real(0)) {
      const Real m = density * volume[i];
      for (int a = 0; a < D; ++a) s.force[a] = -m * velocity[i].v[a] / dt;
    }
    displacement[i] = Vec<D, Real>::zero();
    velocity[i] = Vec<D, Real>::zero();
    return s;
  }
};

}  // namespace mfsd
