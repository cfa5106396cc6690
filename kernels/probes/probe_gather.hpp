// Gathers of the probes' and measure planes' particles into small buffers
// that the host copies at output times (any method).
#pragma once
#include "kernels/core/vec.hpp"

namespace mfsd {

// Values per probe particle: x(D) u(D) v(D) von_mises J von_mises_strain plastic_strain s.
template <int D>
constexpr int kProbeValues = 3 * D + 5;

// Copies selected particles' fields into a small buffer (probes).
template <int D, class Real>
struct ProbeGatherFunctor {
  const Index* index;
  const Vec<D, Real>* reference_position;
  const Vec<D, Real>* displacement;
  const Vec<D, Real>* velocity;
  const Real* von_mises;         // the stress measures: null where a method has none
  const Real* jacobian;
  const Real* von_mises_strain;
  const Real* plastic_strain;  // null without plastic bodies
  const Real* phase_field;     // null without fracture
  Real* out;                   // per probe particle: x(D) u(D) v(D) vm J vm_strain plastic_strain s
  MFSD_HD void operator()(Index k) const {
    const Index i = index[k];
    Real* o = out + k * kProbeValues<D>;
    for (int a = 0; a < D; ++a) {
      o[a] = reference_position[i].v[a] + displacement[i].v[a];
      o[D + a] = displacement[i].v[a];
      o[2 * D + a] = velocity[i].v[a];
    }
    o[3 * D] = von_mises ? von_mises[i] : Real(0);
    o[3 * D + 1] = jacobian ? jacobian[i] : Real(1);
    o[3 * D + 2] = von_mises_strain ? von_mises_strain[i] : Real(0);
    o[3 * D + 3] = plastic_strain ? plastic_strain[i] : Real(0);
    o[3 * D + 4] = phase_field ? phase_field[i] : Real(1);
  }
};

// Displacement and force m a of measure-plane particles into a small buffer.
template <int D, class Real>
struct MeasureGatherFunctor {
  const Index* index;
  const Vec<D, Real>* displacement;
  const Vec<D, Real>* acceleration;
  const Real* volume;
  const Real* density;  // per measured particle (its body's rho0)
  Real* out;            // per particle: u(D) f(D)
  MFSD_HD void operator()(Index k) const {
    const Index i = index[k];
    Real* o = out + k * (2 * D);
    const Real m = density[k] * volume[i];
    for (int a = 0; a < D; ++a) {
      o[a] = displacement[i].v[a];
      o[D + a] = m * acceleration[i].v[a];
    }
  }
};

}  // namespace mfsd
