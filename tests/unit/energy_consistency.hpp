// Test helper: a material's first Piola-Kirchhoff stress P = tau F^{-T}
// against the derivative of its strain energy density, P = dW/dF, by central
// finite differences (step eps) in each component of F.
#pragma once
#include <gtest/gtest.h>

#include "kernels/core/mat.hpp"

namespace mfsd::test {

template <int D, class Material>
void expect_energy_consistent(const Material& m, const Mat<D, double>& F, double eps, double tol) {
  const Mat<D, double> P = mul_transposed(m.kirchhoff(F), inverse(F));  // tau F^{-T}
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) {
      Mat<D, double> Fp = F, Fm = F;
      Fp.m[a][b] += eps;
      Fm.m[a][b] -= eps;
      const double dW = (m.strain_energy_density(Fp) - m.strain_energy_density(Fm)) / (2 * eps);
      EXPECT_NEAR(P.m[a][b], dW, tol) << "component " << a << b;
    }
}

}  // namespace mfsd::test
