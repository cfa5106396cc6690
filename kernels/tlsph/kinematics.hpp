// Position-based Verlet pieces (seed 000 eq. 35-37; seed 003 eq. 30-32).
// Positions are stored as displacements u = x - X: in single precision the
// small increments dt v are then kept with full relative accuracy.
#pragma once
#include "kernels/core/mat.hpp"

namespace mfsd {

// F += s dF/dt and u += s v, with s = dt/2 (eq. 35 and eq. 37).
template <int D, class Real>
struct HalfStepFunctor {
  Mat<D, Real>* deformation_gradient;
  const Mat<D, Real>* rate;
  Vec<D, Real>* displacement;
  const Vec<D, Real>* velocity;
  Real half_dt;

  MFSD_HD void operator()(Index i) const {
    Mat<D, Real> F = deformation_gradient[i];
    F += rate[i] * half_dt;
    deformation_gradient[i] = F;
    displacement[i] += velocity[i] * half_dt;
  }
};

// v += dt a (eq. 36).
template <int D, class Real>
struct VelocityUpdateFunctor {
  Vec<D, Real>* velocity;
  const Vec<D, Real>* acceleration;
  Real dt;

  MFSD_HD void operator()(Index i) const { velocity[i] += acceleration[i] * dt; }
};

// Clamp: constrained particles of a body keep their reference position and
// zero velocity; applied after the velocity update (formulations.md 1).
template <int D, class Real>
struct ClampFunctor {
  const Index* constrained;  // indices of constrained particles
  Vec<D, Real>* displacement;
  Vec<D, Real>* velocity;

  MFSD_HD void operator()(Index k) const {
    const Index i = constrained[k];
    displacement[i] = Vec<D, Real>::zero();
    velocity[i] = Vec<D, Real>::zero();
  }
};

}  // namespace mfsd
