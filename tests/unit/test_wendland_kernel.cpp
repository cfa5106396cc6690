// Wendland C2 kernel: unit integral (2-D, 3-D), dW is the derivative of W,
// and lattice sums: sum V W close to 1 and sum V grad W = 0 in the bulk.
#include <gtest/gtest.h>

#include <cmath>

#include "kernels/core/vec.hpp"
#include "kernels/sph/wendland_c2.hpp"

using namespace mfsd;

TEST(WendlandC2, IntegratesToOneIn2D) {
  const auto k = WendlandC2<2, double>::make(0.7);
  // integral over the disc r < 2h of W(r) 2 pi r dr (Simpson's rule)
  const int n = 2000;
  const double R = k.cutoff(), dr = R / n;
  double s = 0;
  for (int i = 0; i <= n; ++i) {
    const double r = i * dr, w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
    s += w * k.W(r) * 2 * M_PI * r;
  }
  EXPECT_NEAR(s * dr / 3, 1.0, 1e-10);
}

TEST(WendlandC2, IntegratesToOneIn3D) {
  const auto k = WendlandC2<3, double>::make(1.3);
  const int n = 2000;
  const double R = k.cutoff(), dr = R / n;
  double s = 0;
  for (int i = 0; i <= n; ++i) {
    const double r = i * dr, w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
    s += w * k.W(r) * 4 * M_PI * r * r;
  }
  EXPECT_NEAR(s * dr / 3, 1.0, 1e-10);
}

TEST(WendlandC2, DerivativeMatchesFiniteDifference) {
  const auto k = WendlandC2<3, double>::make(0.5);
  for (double r = 0.01; r < 1.0; r += 0.037) {
    const double fd = (k.W(r + 1e-6) - k.W(r - 1e-6)) / 2e-6;
    EXPECT_NEAR(k.dW(r), fd, 1e-5 * std::abs(k.W(0.0) / k.h));
    EXPECT_LE(k.dW(r), 0.0);
  }
  EXPECT_EQ(k.W(k.cutoff()), 0.0);
  EXPECT_EQ(k.dW(k.cutoff() * 1.01), 0.0);
}

// On a square lattice with h = 1.15 dp (the TLSPH default) the discrete
// partition of unity holds to a few percent (sum V W = 1.023 in 2-D) and the
// gradient sum vanishes by symmetry.
TEST(WendlandC2, LatticeSumsIn2D) {
  const double dp = 0.1;
  const auto k = WendlandC2<2, double>::make(1.15 * dp);
  double sum = 0;
  Vec<2, double> grad = Vec<2, double>::zero();
  for (int i = -5; i <= 5; ++i)
    for (int j = -5; j <= 5; ++j) {
      const Vec<2, double> x{{0.5 * dp - (i + 0.5) * dp, 0.5 * dp - (j + 0.5) * dp}};  // x_0 - x_j
      const double r = norm(x);
      sum += dp * dp * k.W(r);
      if (r > 0) grad += x * (dp * dp * k.dW(r) / r);
    }
  EXPECT_NEAR(sum, 1.0, 0.03);
  EXPECT_NEAR(grad[0], 0.0, 1e-12);
  EXPECT_NEAR(grad[1], 0.0, 1e-12);
}

TEST(WendlandC2, LatticeSumsIn3D) {
  const double dp = 0.2;
  const auto k = WendlandC2<3, double>::make(1.15 * dp);
  double sum = 0;
  for (int i = -4; i <= 4; ++i)
    for (int j = -4; j <= 4; ++j)
      for (int l = -4; l <= 4; ++l) sum += dp * dp * dp * k.W(dp * std::sqrt(double(i * i + j * j + l * l)));
  EXPECT_NEAR(sum, 1.0, 0.03);
}
