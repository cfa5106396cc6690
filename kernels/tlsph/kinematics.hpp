// Position-based Verlet pieces (seed 000 eq. 35-37; seed 003 eq. 30-32) that
// are not fused into a pair stage: the half steps live in the stress stage
// (stress.hpp) and the deformation-rate stage (deformation_rate.hpp), the
// velocity update in the force stage (acceleration.hpp). Positions are stored
// as displacements u = x - X: in single precision the small increments dt v
// are then kept with full relative accuracy.
#pragma once
#include "kernels/core/mat.hpp"

namespace mfsd {

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
