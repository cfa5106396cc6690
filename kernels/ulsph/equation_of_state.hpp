// Equation of state of ULSPH bodies (seed 002 section 2.1; formulations.md
// section 3, "Pressure"): the weakly compressible linear law
//   p = K (rho / rho0 - 1)   (= c0^2 (rho - rho0) with c0^2 = K / rho0),
// with an optional failure model (failure.hpp) applied to the result.
#pragma once
#include "kernels/core/config.hpp"
#include "kernels/ulsph/failure.hpp"

namespace mfsd::ulsph {

template <class Real>
struct LinearEquationOfState {
  Real bulk_modulus;       // K
  Real reference_density;  // rho0

  MFSD_HD Real pressure(Real rho) const {
    return bulk_modulus * (rho / reference_density - Real(1));  // formulations.md section 3: p = K (rho/rho0 - 1)
  }
  // The inverse, rho(p) (initial conditions with a given pressure).
  MFSD_HD Real density(Real p) const { return reference_density * (Real(1) + p / bulk_modulus); }
};

// pressure[i] = p(density[i]), passed through the failure model (NoFailure or
// TensileFailure<Real>, failure.hpp), which may update the failure flag.
template <class Real, class Failure = NoFailure>
struct PressureFunctor {
  const Real* density;
  Real* pressure;
  LinearEquationOfState<Real> eos;
  Failure failure;

  MFSD_HD void operator()(Index i) const { pressure[i] = failure(i, eos.pressure(density[i])); }
};

}  // namespace mfsd::ulsph
