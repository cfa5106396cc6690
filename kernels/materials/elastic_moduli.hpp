// Elastic moduli from Young's modulus and Poisson's ratio (formulations.md 0):
//   G = E / (2 (1 + nu)),  K = E / (3 (1 - 2 nu)),  lambda = K - 2G/3.
#pragma once
#include "kernels/core/config.hpp"

namespace mfsd {

struct ElasticModuli {
  double youngs_modulus;
  double poisson_ratio;
  double shear() const { return youngs_modulus / (2.0 * (1.0 + poisson_ratio)); }
  double bulk() const { return youngs_modulus / (3.0 * (1.0 - 2.0 * poisson_ratio)); }
  double lame_lambda() const { return bulk() - 2.0 * shear() / 3.0; }
};

}  // namespace mfsd
