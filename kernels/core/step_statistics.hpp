// Per-step reduction: the maxima the time step needs (seed 000 eq. 38) and a
// health check (non-finite values, particles outside the scene's bounds),
// in one pass over the particles. With the deformed-configuration time step
// (solver.deformed_time_step) also the largest |F^{-1}| (inverse_stretch.hpp).
#pragma once
#include "kernels/core/inverse_stretch.hpp"
#include "kernels/core/vec.hpp"

namespace mfsd {

template <class Real>
struct StepStatistics {
  Real max_speed2;
  Real max_acceleration2;
  Real max_inverse_stretch;  // max |F^{-1}|_2, 0 unless requested
  Real max_stiffening;       // max current / reference modulus (Holzapfel-Ogden), 0 without
  Index first_bad;           // smallest index of a non-finite or escaped particle, or n
};

template <class Real>
struct StepStatisticsCombine {
  MFSD_HD StepStatistics<Real> operator()(const StepStatistics<Real>& a, const StepStatistics<Real>& b) const {
    return StepStatistics<Real>{math::max(a.max_speed2, b.max_speed2),
                                math::max(a.max_acceleration2, b.max_acceleration2),
                                math::max(a.max_inverse_stretch, b.max_inverse_stretch),
                                math::max(a.max_stiffening, b.max_stiffening), math::min(a.first_bad, b.first_bad)};
  }
};

template <int D, class Real>
struct StepStatisticsFunctor {
  const Vec<D, Real>* reference_position;
  const Vec<D, Real>* displacement;
  const Vec<D, Real>* velocity;
  const Vec<D, Real>* acceleration;
  const Mat<D, Real>* deformation_gradient;  // null: no inverse stretch
  const Real* stiffening;                    // null: no Holzapfel-Ogden body
  Vec<D, Real> lower, upper;                 // scene bounds
  Index n;
  const unsigned char* ghost = nullptr;  // distributed runs: ghosts (copies of other ranks' particles) count not

  MFSD_HD StepStatistics<Real> operator()(Index i) const {
    if (ghost && ghost[i]) return StepStatistics<Real>{Real(0), Real(0), Real(0), Real(0), n};
    const Vec<D, Real> v = velocity[i], a = acceleration[i];
    const Vec<D, Real> x = reference_position[i] + displacement[i];
    const Real v2 = squared_norm(v), a2 = squared_norm(a);
    bool ok = math::isfinite(v2) && math::isfinite(a2);
    for (int k = 0; k < D; ++k) ok = ok && x.v[k] >= lower.v[k] && x.v[k] <= upper.v[k];  // false for NaN
    Real s = Real(0);
    if (deformation_gradient) {
      s = inverse_stretch(deformation_gradient[i]);
      ok = ok && math::isfinite(s);
    }
    const Real k = stiffening ? stiffening[i] : Real(0);
    return StepStatistics<Real>{ok ? v2 : Real(0), ok ? a2 : Real(0), ok ? s : Real(0), ok ? k : Real(0), ok ? n : i};
  }
};

}  // namespace mfsd
