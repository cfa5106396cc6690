// The crack tip of a fracturing body: among the particles with s below a
// threshold (0.5), the one that reaches furthest along the crack's direction
// d from its origin o (the notch's tip), measured in the reference
// configuration: reach_i = (X_i - o) . d. A max-reduction over the body.
#pragma once
#include "kernels/core/vec.hpp"

namespace mfsd {

template <class Real>
struct CrackTip {
  Real reach;   // -huge when no particle is broken
  Index index;  // the tip particle
};

template <class Real>
struct CrackTipMax {
  MFSD_HD CrackTip<Real> operator()(const CrackTip<Real>& a, const CrackTip<Real>& b) const {
    if (a.reach != b.reach) return a.reach > b.reach ? a : b;
    return a.index < b.index ? a : b;  // ties: the lower index, so the result does not depend on the order
  }
};

template <int D, class Real>
struct CrackTipFunctor {
  const Vec<D, Real>* reference_position;
  const Real* s;
  Vec<D, Real> origin, direction;
  Real threshold;
  MFSD_HD CrackTip<Real> operator()(Index i) const {
    if (!(s[i] < threshold)) return CrackTip<Real>{Real(-1e30), i};
    return CrackTip<Real>{dot(reference_position[i] - origin, direction), i};
  }
};

}  // namespace mfsd
