// The variables a per-particle expression reads (conditions, loads, active
// potentials), in slot order; host/scene/particle_expressions.cpp compiles
// with the same table. Shared by every method: no solver's state is here.
#pragma once
#include "kernels/core/vec.hpp"

namespace mfsd {

enum ParticleVariable : int {
  var_x0,
  var_y0,
  var_z0,
  var_x,
  var_y,
  var_z,
  var_ux,
  var_uy,
  var_uz,
  var_vx,
  var_vy,
  var_vz,
  var_t,
  var_dt,
  var_dx,
  kParticleVariables
};

template <int D, class Real>
MFSD_HD inline void particle_variables(const Vec<D, Real>& X, const Vec<D, Real>& u, const Vec<D, Real>& v, Real t,
                                       Real dt, Real dx, Real* vars) {
  for (int a = 0; a < 3; ++a) {
    vars[var_x0 + a] = a < D ? X.v[a < D ? a : 0] : Real(0);
    vars[var_ux + a] = a < D ? u.v[a < D ? a : 0] : Real(0);
    vars[var_x + a] = vars[var_x0 + a] + vars[var_ux + a];
    vars[var_vx + a] = a < D ? v.v[a < D ? a : 0] : Real(0);
  }
  vars[var_t] = t;
  vars[var_dt] = dt;
  vars[var_dx] = dx;
}

}  // namespace mfsd
