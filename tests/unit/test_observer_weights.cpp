// Observer interpolation (issue 28; host/output/observer_weights.hpp): the
// Shepard average keeps constants exactly, the linear correction keeps
// linear fields exactly where Shepard does not, and the weights are the
// kernel formula's.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "host/output/observer_weights.hpp"

namespace mfsd {
namespace {

// A 2-D lattice of spacing dp on [0, 1] x [0, 0.4], each particle moved by up
// to 0.2 dp (a disordered cloud), with volumes dp^2.
struct Cloud {
  std::vector<double> x, V;
};
Cloud perturbed_lattice(double dp) {
  Cloud c;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.2 * dp, 0.2 * dp);
  for (double X = 0.5 * dp; X < 1.0; X += dp)
    for (double Y = 0.5 * dp; Y < 0.4; Y += dp) {
      c.x.push_back(X + jitter(rng));
      c.x.push_back(Y + jitter(rng));
      c.V.push_back(dp * dp);
    }
  return c;
}

const std::vector<std::vector<double>> kPoints = {{0.5, 0.2}, {0.31, 0.13}, {0.02, 0.2}, {0.99, 0.01}};

TEST(ObserverWeights, ShepardKeepsAConstantExactly) {
  const Cloud c = perturbed_lattice(0.02);
  const auto w = observer_weights(kPoints, c.x, c.V, nullptr, 2, 0.05, false);
  const std::vector<double> f(c.V.size(), 3.25);
  for (size_t p = 0; p < kPoints.size(); ++p) EXPECT_NEAR(observe(w[p], f, 1)[0], 3.25, 1e-14) << p;
}

TEST(ObserverWeights, LinearCorrectionKeepsALinearFieldExactlyWhereShepardDoesNot) {
  const Cloud c = perturbed_lattice(0.02);
  std::vector<double> f;
  for (size_t j = 0; j < c.V.size(); ++j) f.push_back(2.0 + 3.0 * c.x[2 * j] - 1.5 * c.x[2 * j + 1]);
  const auto linear = observer_weights(kPoints, c.x, c.V, nullptr, 2, 0.05, true);
  const auto shepard = observer_weights(kPoints, c.x, c.V, nullptr, 2, 0.05, false);
  double shepard_error_at_edges = 0;
  for (size_t p = 0; p < kPoints.size(); ++p) {
    const double exact = 2.0 + 3.0 * kPoints[p][0] - 1.5 * kPoints[p][1];
    EXPECT_NEAR(observe(linear[p], f, 1)[0], exact, 1e-12) << p;
    if (p >= 2) shepard_error_at_edges = std::max(shepard_error_at_edges, std::fabs(observe(shepard[p], f, 1)[0] - exact));
  }
  // At the edges (points 2 and 3) the one-sided Shepard average is biased by
  // a fraction of the radius times the gradient.
  EXPECT_GT(shepard_error_at_edges, 1e-3);
}

TEST(ObserverWeights, WeightsAreTheNormalisedKernelTimesVolume) {
  // Three particles at distances 0, 0.5 r and 0.9 r of the point, one beyond r.
  const double r = 2.0;
  const std::vector<double> x = {1.0, 1.0, 2.0, 1.0, 1.0, 2.8, 4.5, 1.0};
  const std::vector<double> V = {1.0, 2.0, 0.5, 1.0};
  const auto w = observer_weights({{1.0, 1.0}}, x, V, nullptr, 2, r, false);
  auto W = [](double q) { return std::pow(1.0 - q, 4) * (1.0 + 4.0 * q); };  // Wendland C2
  const double w0 = W(0.0) * 1.0, w1 = W(0.5) * 2.0, w2 = W(0.9) * 0.5, sum = w0 + w1 + w2;
  ASSERT_EQ(w[0].size(), 3u);
  const std::vector<double> f = {10.0, 20.0, 30.0, 1000.0};
  EXPECT_NEAR(observe(w[0], f, 1)[0], (10.0 * w0 + 20.0 * w1 + 30.0 * w2) / sum, 1e-13);
}

TEST(ObserverWeights, APointSeenByNoParticleIsNaN) {
  const Cloud c = perturbed_lattice(0.02);
  const auto w = observer_weights({{5.0, 5.0}}, c.x, c.V, nullptr, 2, 0.05, true);
  EXPECT_TRUE(std::isnan(observe(w[0], std::vector<double>(c.V.size(), 1.0), 1)[0]));
}

TEST(ObserverWeights, OnlyTheChosenBodysParticlesCount) {
  const std::vector<double> x = {0.0, 0.0, 0.1, 0.0};
  const std::vector<double> V = {1.0, 1.0};
  const std::vector<unsigned char> use = {0, 1};
  const auto w = observer_weights({{0.0, 0.0}}, x, V, &use, 2, 1.0, false);
  EXPECT_EQ(observe(w[0], {5.0, 7.0}, 1)[0], 7.0);
}

}  // namespace
}  // namespace mfsd
