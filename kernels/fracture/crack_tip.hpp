// The crack tip of a fracturing body: among the particles with s below a
// threshold (0.5), the one that reaches furthest along the crack's direction
// d from its origin o (the notch's tip), measured in the reference
// configuration: reach_i = (X_i - o) . d. A max-reduction over the body.
// Particles of equal reach (a lattice's column across the crack) are told
// apart by their reference positions, the lowest first in x, then y, then
// z: the tip does not depend on the particles' order, which differs between
// a single process and the ranks of a distributed run.
#pragma once
#include "kernels/core/vec.hpp"

namespace mfsd {

template <class Real>
struct CrackTip {
  Real reach;   // -huge when no particle is broken
  Index index;  // the tip particle
  Real X[3];    // its reference position (ties), zero beyond the dimension
};

// a before b: the further reach, then the lower reference position.
template <class Real>
MFSD_HD inline bool crack_tip_before(const CrackTip<Real>& a, const CrackTip<Real>& b) {
  if (a.reach != b.reach) return a.reach > b.reach;
  for (int k = 0; k < 3; ++k)
    if (a.X[k] != b.X[k]) return a.X[k] < b.X[k];
  return a.index < b.index;
}

template <class Real>
struct CrackTipMax {
  MFSD_HD CrackTip<Real> operator()(const CrackTip<Real>& a, const CrackTip<Real>& b) const {
    return crack_tip_before(a, b) ? a : b;
  }
};

template <int D, class Real>
struct CrackTipFunctor {
  const Vec<D, Real>* reference_position;
  const Real* s;
  Vec<D, Real> origin, direction;
  Real threshold;
  MFSD_HD CrackTip<Real> operator()(Index i) const {
    CrackTip<Real> t{Real(-1e30), i, {Real(0), Real(0), Real(0)}};
    if (!(s[i] < threshold)) return t;
    t.reach = dot(reference_position[i] - origin, direction);
    for (int k = 0; k < D; ++k) t.X[k] = reference_position[i].v[k];
    return t;
  }
};

}  // namespace mfsd
