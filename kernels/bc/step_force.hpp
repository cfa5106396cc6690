// A force added to a particle after the force stage (loads, contact), like
// the internal force: v += dt f/m and a += f/m (so that the time step sees
// it). Its power is taken at the mid-step velocity
// v_mid = v^n + dt/2 (a + f/m), v^n = v - dt a, so that the work sums of
// energies.csv close the balance to second order in dt.
#pragma once
#include "kernels/core/vec.hpp"

namespace mfsd {

// Returns the power f . v_mid, in Real (float runs do no double arithmetic
// per step; docs/floating-point.md).
template <int D, class Real>
MFSD_HD inline Real add_step_force(const Vec<D, Real>& f, Real mass, Real dt, Vec<D, Real>& velocity,
                                   Vec<D, Real>& acceleration) {
  const Vec<D, Real> a_f = f * (Real(1) / mass);
  const Vec<D, Real> v_old = velocity - acceleration * dt;  // v^n
  const Vec<D, Real> v_mid = v_old + (acceleration + a_f) * (Real(0.5) * dt);
  velocity += a_f * dt;
  acceleration += a_f;
  Real power = Real(0);
  for (int a = 0; a < D; ++a) power += f.v[a] * v_mid.v[a];
  return power;
}

}  // namespace mfsd
