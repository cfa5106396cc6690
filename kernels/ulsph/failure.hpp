// Tensile failure of ULSPH particles (seed 002 section 5.9; formulations.md
// section 3, "Failure"): a particle fails when its negative pressure (tensile
// stress) exceeds a threshold; from then on its pressure is not allowed below
// zero (it still resists compression). The flag is a per-particle state that
// is never cleared.
//
// Decisions where the seed is silent: the test is -p > threshold with the
// threshold a positive stress; the clamp applies already in the evaluation
// that detects the failure (the particle cannot carry the tension that broke
// it); the shear stress of a failed particle is left to the caller.
#pragma once
#include "kernels/core/config.hpp"
#include "kernels/core/math.hpp"

namespace mfsd::ulsph {

// True when the pressure p is a tension beyond the threshold (seed 002 section 5.9).
template <class Real>
MFSD_HD inline bool exceeds_tensile_threshold(Real p, Real threshold) {
  return -p > threshold;  // seed 002 section 5.9: negative pressure above the threshold
}

// The failure flag after seeing pressure p: once failed, always failed.
template <class Real>
MFSD_HD inline unsigned char update_failure(unsigned char failed, Real p, Real threshold) {
  return (failed || exceeds_tensile_threshold(p, threshold)) ? 1 : 0;  // seed 002 section 5.9
}

// The pressure a particle may carry: a failed particle takes no tension.
template <class Real>
MFSD_HD inline Real failed_pressure(Real p, unsigned char failed) {
  return failed ? math::max(p, Real(0)) : p;  // seed 002 section 5.9: p >= 0 after failure
}

// Failure models plugged into the pressure functor (equation_of_state.hpp) at
// compile time: a body without failure carries no flag and no test.
struct NoFailure {
  template <class Real>
  MFSD_HD Real operator()(Index, Real p) const {
    return p;
  }
};

template <class Real>
struct TensileFailure {
  Real threshold;         // tensile pressure at failure (> 0)
  unsigned char* failed;  // per particle, 1 once failed

  MFSD_HD Real operator()(Index i, Real p) const {
    const unsigned char f = update_failure(failed[i], p, threshold);
    failed[i] = f;
    return failed_pressure(p, f);
  }
};

}  // namespace mfsd::ulsph
