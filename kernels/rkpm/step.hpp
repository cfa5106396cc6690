// The per-node updates of an RKPM step around its gathers (rkpm.md 5.2;
// host/solver/rkpm/rkpm_solver.hpp): the drifts of the nodes, the move to the
// next operators' configuration with the supports a = a~ h0 J^(1/d)
// (rkpm.md 1.2), and the energy sums of a body.
#pragma once
#include "kernels/rkpm/stress_stage.hpp"

namespace mfsd::rkpm {

// u += dt/2 v (the drifts of the drift-kick-drift step), and the same into
// the increment du since the operators' configuration: the stress stage
// reads du itself, never a difference of positions (which would lose
// |x|/|du| of its digits).
template <int D, class Real>
struct DriftFunctor {
  const Vec<D, Real>* velocity;
  Vec<D, Real>* displacement;
  Vec<D, Real>* increment;
  Real half_dt;
  MFSD_HD void operator()(Index i) const {
    const Vec<D, Real> d = velocity[i] * half_dt;
    displacement[i] += d;
    increment[i] += d;
  }
};

// x_ops = X + u, a = a~ h0 J^(1/d) (rkpm.md 5.2 stage 3).
template <int D, class Real>
struct MoveFunctor {
  const Vec<D, Real>* reference_position;
  const Vec<D, Real>* displacement;
  const Mat<D, Real>* cell_map;
  Vec<D, Real>* position;
  Vec<D, Real>* increment;  // du, zeroed: the next operators' configuration starts
  Real* support;
  double support_length;  // a~ h0 of the body
  MFSD_HD void operator()(Index i) const {
    position[i] = reference_position[i] + displacement[i];
    increment[i] = Vec<D, Real>::zero();
    support[i] = Real(support_length * math::pow(double(det(cell_map[i])), 1.0 / D));  // rkpm.md 1.2
  }
};

// MoveFunctor over all bodies, each with its a~ h0 (lengths[body]).
template <int D, class Real>
struct MoveAllFunctor {
  MoveFunctor<D, Real> f;
  const int* body;
  const double* lengths;
  MFSD_HD void operator()(Index i) const {
    MoveFunctor<D, Real> g = f;
    g.support_length = lengths[body[i]];
    g(i);
  }
};

// Small reductions of the solver (host/solver/rkpm/): a field's values,
// their maximum, and m g . u (the gravity's potential).
template <class Real>
struct ValueOf {
  const Real* v;
  MFSD_HD Real operator()(Index i) const { return v[i]; }
};
template <class Real>
struct MaxOf {
  MFSD_HD Real operator()(Real a, Real b) const { return a > b ? a : b; }
};
struct PlusDouble {
  MFSD_HD double operator()(double a, double b) const { return a + b; }
};
template <int D, class Real>
struct GravityPotentialFunctor {
  const Vec<D, Real>* u;
  const Real* m;
  Vec<D, Real> g;
  MFSD_HD double operator()(Index i) const { return double(m[i]) * double(dot(g, u[i])); }
};

struct EnergySums {
  double kinetic, internal, plastic, damping;
  double momentum[3];
};
struct EnergySumsPlus {
  MFSD_HD EnergySums operator()(const EnergySums& a, const EnergySums& b) const {
    return EnergySums{a.kinetic + b.kinetic,
                      a.internal + b.internal,
                      a.plastic + b.plastic,
                      a.damping + b.damping,
                      {a.momentum[0] + b.momentum[0], a.momentum[1] + b.momentum[1], a.momentum[2] + b.momentum[2]}};
  }
};

// 1/2 M v^2 and M v with the lumped mass, and the accumulated works.
template <int D, class Real>
struct EnergyFunctor {
  const Vec<D, Real>* velocity;
  const Real* lumped_mass;
  const Real* internal_work;
  const Real* plastic_work;  // null: elastic
  const Real* damping_work;  // null: no damping
  MFSD_HD EnergySums operator()(Index i) const {
    const double M = double(lumped_mass[i]);
    const Vec<D, double> v = cast<double>(velocity[i]);
    EnergySums s{0.5 * M * dot(v, v),
                 double(internal_work[i]),
                 plastic_work ? double(plastic_work[i]) : 0.0,
                 damping_work ? double(damping_work[i]) : 0.0,
                 {0, 0, 0}};
    for (int a = 0; a < D; ++a) s.momentum[a] = M * v.v[a];
    return s;
  }
};

// von Mises stress, pressure and J for the outputs.
template <int D, class Real>
struct ObservablesFunctor {
  const Mat<3, Real>* stress;
  const Real* damage;
  DamageLaw damage_law;
  const Mat<D, Real>* cell_map;
  Real* von_mises_out;
  Real* pressure_out;
  Real* jacobian_out;
  MFSD_HD void operator()(Index i) const {
    Mat<3, double> s = cast<double>(stress[i]);
    if (damage) s = nominal_stress(s, double(damage[i]), damage_law);
    von_mises_out[i] = Real(von_mises(s));
    pressure_out[i] = Real(-trace(s) / 3.0);  // positive in compression, as ULSPH's pressure
    jacobian_out[i] = Real(det(cell_map[i]));
  }
};

}  // namespace mfsd::rkpm
