// The axis-aligned box of a range of particles' current positions x = X + u,
// a reduction (the grid of a current-configuration search covers it).
#pragma once
#include "kernels/core/vec.hpp"

namespace mfsd {

template <int D, class Real>
struct BoundingBox {
  Vec<D, Real> lo, hi;
  MFSD_HD static BoundingBox empty() {
    return BoundingBox{Vec<D, Real>::constant(Real(1e30)), Vec<D, Real>::constant(Real(-1e30))};
  }
};

template <int D, class Real>
struct BoundingBoxCombine {
  MFSD_HD BoundingBox<D, Real> operator()(const BoundingBox<D, Real>& a, const BoundingBox<D, Real>& b) const {
    BoundingBox<D, Real> c;
    for (int k = 0; k < D; ++k) {
      c.lo.v[k] = math::min(a.lo.v[k], b.lo.v[k]);
      c.hi.v[k] = math::max(a.hi.v[k], b.hi.v[k]);
    }
    return c;
  }
};

template <int D, class Real>
struct BoundingBoxFunctor {
  const Vec<D, Real>* reference_position;
  const Vec<D, Real>* displacement;
  MFSD_HD BoundingBox<D, Real> operator()(Index i) const {
    const Vec<D, Real> x = reference_position[i] + displacement[i];
    return BoundingBox<D, Real>{x, x};
  }
};

}  // namespace mfsd
