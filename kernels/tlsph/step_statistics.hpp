// Per-step reduction: the maxima the time step needs (seed 000 eq. 38) and a
// health check (non-finite values, particles outside the scene's bounds),
// in one pass over the particles.
#pragma once
#include "kernels/core/vec.hpp"

namespace mfsd {

template <class Real>
struct StepStatistics {
  Real max_speed2;
  Real max_acceleration2;
  Index first_bad;  // smallest index of a non-finite or escaped particle, or n
};

template <class Real>
struct StepStatisticsCombine {
  MFSD_HD StepStatistics<Real> operator()(const StepStatistics<Real>& a, const StepStatistics<Real>& b) const {
    return StepStatistics<Real>{math::max(a.max_speed2, b.max_speed2),
                                math::max(a.max_acceleration2, b.max_acceleration2),
                                math::min(a.first_bad, b.first_bad)};
  }
};

template <int D, class Real>
struct StepStatisticsFunctor {
  const Vec<D, Real>* reference_position;
  const Vec<D, Real>* displacement;
  const Vec<D, Real>* velocity;
  const Vec<D, Real>* acceleration;
  Vec<D, Real> lower, upper;  // scene bounds
  Index n;

  MFSD_HD StepStatistics<Real> operator()(Index i) const {
    const Vec<D, Real> v = velocity[i], a = acceleration[i];
    const Vec<D, Real> x = reference_position[i] + displacement[i];
    const Real v2 = squared_norm(v), a2 = squared_norm(a);
    bool ok = math::isfinite(v2) && math::isfinite(a2);
    for (int k = 0; k < D; ++k) ok = ok && x.v[k] >= lower.v[k] && x.v[k] <= upper.v[k];  // false for NaN
    return StepStatistics<Real>{ok ? v2 : Real(0), ok ? a2 : Real(0), ok ? n : i};
  }
};

}  // namespace mfsd
