// Raw views of the fields every method keeps and every shared service
// (conditions and loads, walls, clamps, contact, probes, measure planes)
// reads and writes. Each method stores positions as displacements from the
// particles' initial positions, x = X + u, so that in single precision the
// small increments dt v keep their full relative accuracy; for TLSPH X is the
// reference configuration, for ULSPH only the start of the motion. The volume
// is the initial one: m = rho0 V0 in every method.
#pragma once
#include "kernels/core/vec.hpp"

namespace mfsd {

template <int D, class Real>
struct Kinematics {
  const Vec<D, Real>* reference_position;  // X
  Vec<D, Real>* displacement;              // u = x - X
  Vec<D, Real>* velocity;
  Vec<D, Real>* acceleration;
  const Real* volume;  // V0
  // Distributed runs (docs/distributed.md): 1 for a ghost, a copy of another
  // rank's particle that the shared services leave to its owner; else null.
  const unsigned char* ghost = nullptr;
};

}  // namespace mfsd
