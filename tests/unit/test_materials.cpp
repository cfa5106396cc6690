// Materials: Kirchhoff stress against closed forms (uniaxial stretch, simple
// shear), objectivity under rigid rotation, and consistency with the strain
// energy (P = dW/dF = tau F^{-T}, by finite differences), 2-D and 3-D.
#include <gtest/gtest.h>

#include <cmath>

#include "kernels/materials/elastic_moduli.hpp"
#include "kernels/materials/neo_hookean.hpp"
#include "kernels/materials/saint_venant_kirchhoff.hpp"
#include "kernels/tlsph/damping.hpp"
#include "tests/unit/energy_consistency.hpp"

using namespace mfsd;

namespace {
const ElasticModuli kModuli{17e6, 0.45};
template <int D>
NeoHookean<D, double> neo() {
  return {kModuli.bulk(), kModuli.shear()};
}
template <int D>
SaintVenantKirchhoff<D, double> svk() {
  return {kModuli.bulk(), kModuli.shear(), kModuli.lame_lambda()};
}
Mat<3, double> rotation(double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  const Mat<3, double> Rz{{{c, -s, 0}, {s, c, 0}, {0, 0, 1}}};
  const double c2 = std::cos(0.7), s2 = std::sin(0.7);
  const Mat<3, double> Rx{{{1, 0, 0}, {0, c2, -s2}, {0, s2, c2}}};
  return Rz * Rx;
}
}  // namespace

TEST(ElasticModuli, FromYoungAndPoisson) {
  const ElasticModuli m{2e6, 0.3};
  EXPECT_NEAR(m.shear(), 2e6 / 2.6, 1e-6);
  EXPECT_NEAR(m.bulk(), 2e6 / 1.2, 1e-6);
  EXPECT_NEAR(m.lame_lambda(), 2e6 * 0.3 / (1.3 * 0.4), 1e-6);
}

TEST(NeoHookean, UniaxialStretch3D) {
  const auto m = neo<3>();
  const double l = 1.3;
  const Mat<3, double> F{{{l, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  const auto tau = m.kirchhoff(F);
  const double K = m.K, G = m.G, vol = 0.5 * K * (l * l - 1), c = G * std::pow(l, -2.0 / 3.0);
  EXPECT_NEAR(tau.m[0][0], vol + c * (2 * l * l - 2) / 3, 1e-6 * K);
  EXPECT_NEAR(tau.m[1][1], vol + c * (1 - l * l) / 3, 1e-6 * K);
  EXPECT_NEAR(tau.m[2][2], tau.m[1][1], 1e-6 * K);
  EXPECT_NEAR(tau.m[0][1], 0.0, 1e-9);
}

TEST(NeoHookean, SimpleShearIsIsochoric) {
  const auto m = neo<3>();
  const double g = 0.4;
  const Mat<3, double> F{{{1, g, 0}, {0, 1, 0}, {0, 0, 1}}};
  const auto tau = m.kirchhoff(F);
  EXPECT_NEAR(tau.m[0][1], m.G * g, 1e-6 * m.G);
  EXPECT_NEAR(tau.m[0][0], m.G * 2 * g * g / 3, 1e-6 * m.G);
  EXPECT_NEAR(tau.m[1][1], -m.G * g * g / 3, 1e-6 * m.G);
  EXPECT_NEAR(trace(tau), 0.0, 1e-6 * m.G);  // J = 1: no pressure
}

TEST(NeoHookean, PlaneForm2D) {
  // 2-D deviator and J^{-2/2}: F = diag(l, 1): tau_xx - tau_yy = G/l (l^2 - 1).
  const auto m = neo<2>();
  const double l = 1.2;
  const Mat<2, double> F{{{l, 0}, {0, 1}}};
  const auto tau = m.kirchhoff(F);
  EXPECT_NEAR(tau.m[0][0] - tau.m[1][1], m.G / l * (l * l - 1), 1e-6 * m.G);
  EXPECT_NEAR(tau.m[0][0] + tau.m[1][1], m.K * (l * l - 1), 1e-6 * m.K);
}

TEST(SaintVenantKirchhoff, UniaxialStretch3D) {
  const auto m = svk<3>();
  const double l = 1.1, E = 0.5 * (l * l - 1);
  const Mat<3, double> F{{{l, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  const auto tau = m.kirchhoff(F);
  EXPECT_NEAR(tau.m[0][0], l * l * (m.lambda + 2 * m.G) * E, 1e-6 * m.K);
  EXPECT_NEAR(tau.m[1][1], m.lambda * E, 1e-6 * m.K);
}

TEST(Materials, RigidRotationGivesNoStressAndObjectivity) {
  const auto nh = neo<3>();
  const auto sv = svk<3>();
  const Mat<3, double> R = rotation(0.9);
  for (const auto& tau : {nh.kirchhoff(R), sv.kirchhoff(R)})
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) EXPECT_NEAR(tau.m[a][b], 0.0, 1e-8 * nh.K);
  const Mat<3, double> F{{{1.1, 0.2, 0.05}, {-0.1, 0.95, 0.1}, {0.03, 0.0, 1.02}}};
  const auto check = [&](auto m) {
    const auto rotated = m.kirchhoff(R * F);
    const auto expected = mul_transposed(R * m.kirchhoff(F), R);  // R tau R^T
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) EXPECT_NEAR(rotated.m[a][b], expected.m[a][b], 1e-7 * m.K);
    EXPECT_NEAR(m.strain_energy_density(R * F), m.strain_energy_density(F), 1e-8 * m.K);
  };
  check(nh);
  check(sv);
}

TEST(Materials, StressIsDerivativeOfStrainEnergy) {
  const Mat<3, double> F3{{{1.1, 0.2, 0.05}, {-0.1, 0.95, 0.1}, {0.03, 0.0, 1.02}}};
  const Mat<2, double> F2{{{1.05, 0.1}, {-0.2, 0.9}}};
  test::expect_energy_consistent<3>(neo<3>(), F3, 1e-6, 1e-6 * kModuli.bulk());
  test::expect_energy_consistent<3>(svk<3>(), F3, 1e-6, 1e-6 * kModuli.bulk());
  test::expect_energy_consistent<2>(neo<2>(), F2, 1e-6, 1e-6 * kModuli.bulk());
  test::expect_energy_consistent<2>(svk<2>(), F2, 1e-6, 1e-6 * kModuli.bulk());
}

TEST(Materials, DecompositionRecoversNeoHookeanStress) {
  // tau = tau_vol I + c (b - tr(b)/d I) (seed 000 eq. 7, 25).
  const auto m = neo<3>();
  const Mat<3, double> F{{{1.1, 0.2, 0.05}, {-0.1, 0.95, 0.1}, {0.03, 0.0, 1.02}}};
  const double J = det(F), c = m.shear_coefficient(J);
  Mat<3, double> tau = deviator(mul_transposed(F, F)) * c;
  tau.add_diagonal(m.volumetric_kirchhoff(J));
  const auto ref = m.kirchhoff(F);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) EXPECT_NEAR(tau.m[a][b], ref.m[a][b], 1e-6);
}

TEST(KelvinVoigtDamping, IsotropicAndSplitForms) {
  // tau_d = coefficient * (dF F^T + F dF^T)/2 ; F = I, dF = L gives sym(L).
  const Mat<3, double> I = Mat<3, double>::identity();
  const Mat<3, double> L{{{1, 2, 0}, {0, 3, 4}, {0, 0, 5}}};
  const KelvinVoigtDamping<double> iso{10, 10}, split{10, 2};
  const auto a = iso.stress<3>(I, L), b = split.stress<3>(I, L);
  EXPECT_DOUBLE_EQ(a.m[0][0], 10.0);
  EXPECT_DOUBLE_EQ(a.m[0][1], 10.0);  // 10 * (2 + 0)/2
  EXPECT_DOUBLE_EQ(a.m[1][0], 10.0);
  EXPECT_DOUBLE_EQ(b.m[1][2], 4.0);  // 2 * (4 + 0)/2
  EXPECT_DOUBLE_EQ(b.m[2][2], 50.0);
  // A rigid spin (skew dF at F = I) is not damped.
  const Mat<3, double> W{{{0, 1, 0}, {-1, 0, 0}, {0, 0, 0}}};
  const auto c = iso.stress<3>(I, W);
  for (int r = 0; r < 3; ++r)
    for (int s = 0; s < 3; ++s) EXPECT_DOUBLE_EQ(c.m[r][s], 0.0);
}
