// Holzapfel-Ogden with active stress (seed 000 eq. 12-19): zero stress at
// F = I, closed forms in uniaxial stretch along and across the fibre and in
// simple shear in the fibre-sheet plane, P = dW/dF by finite differences
// (random F, oblique fibres, 2-D and 3-D), energy = work over a slow
// load-unload cycle, objectivity with fibres that turn with F, the GENOG
// split, and the active stress's direction and magnitude.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kernels/materials/holzapfel_ogden.hpp"
#include "tests/unit/energy_consistency.hpp"
#include "tests/unit/rotation.hpp"

using namespace mfsd;

namespace {
// seed 000 Table 4 (muscle, kPa), lambda from a bulk modulus of 100 a.
HolzapfelOgdenParameters<double> table4() {
  const double a = 0.059;
  return {100 * a - 2 * a / 3, a, 8.023, 18.472, 16.026, 2.841, 11.12, 0.216, 11.436};
}
Vec<3, double> unit(double x, double y, double z) {
  const double n = std::sqrt(x * x + y * y + z * z);
  return Vec<3, double>{{x / n, y / n, z / n}};
}
HolzapfelOgdenPoint<3, double> muscle(double Ta = 0) {
  return {table4(), Vec<3, double>{{1, 0, 0}}, Vec<3, double>{{0, 1, 0}}, Ta, 1.0};
}
double scale(const HolzapfelOgdenParameters<double>& p) { return p.lambda + p.a + p.af + p.as + p.afs; }

}  // namespace

TEST(HolzapfelOgden, ZeroStressAndEnergyAtIdentity) {
  const auto m = muscle();
  const Mat<3, double> tau = m.kirchhoff(Mat<3, double>::identity());
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) EXPECT_NEAR(tau.m[a][b], 0.0, 1e-15);
  EXPECT_NEAR(m.strain_energy_density(Mat<3, double>::identity()), 0.0, 1e-15);
}

// F = diag(l, 1, 1), f0 = e1: J = l, I1 = l^2 + 2, I_ff = l^2, I_ss = 1, I_fs = 0.
TEST(HolzapfelOgden, UniaxialStretchAlongTheFibre) {
  const auto m = muscle();
  const auto& p = m.p;
  const double l = 1.15;
  const Mat<3, double> F{{{l, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  const Mat<3, double> tau = m.kirchhoff(F);
  const double c = p.a * std::exp(p.b * (l * l - 1)), e = l * l - 1;
  const double iso = p.lambda * std::log(l) - p.a;
  EXPECT_NEAR(tau.m[0][0], iso + c * l * l + 2 * p.af * e * std::exp(p.bf * e * e) * l * l, 1e-12 * scale(p));
  EXPECT_NEAR(tau.m[1][1], iso + c, 1e-12 * scale(p));
  EXPECT_NEAR(tau.m[2][2], iso + c, 1e-12 * scale(p));
  EXPECT_NEAR(tau.m[0][1], 0.0, 1e-12 * scale(p));
}

// F = diag(1, l, 1), f0 = e1, s0 = e2: the fibre term vanishes, the sheet's acts.
TEST(HolzapfelOgden, UniaxialStretchAcrossTheFibre) {
  const auto m = muscle();
  const auto& p = m.p;
  const double l = 1.1;
  const Mat<3, double> F{{{1, 0, 0}, {0, l, 0}, {0, 0, 1}}};
  const Mat<3, double> tau = m.kirchhoff(F);
  const double c = p.a * std::exp(p.b * (l * l - 1)), e = l * l - 1;
  const double iso = p.lambda * std::log(l) - p.a;
  EXPECT_NEAR(tau.m[0][0], iso + c, 1e-12 * scale(p));
  EXPECT_NEAR(tau.m[1][1], iso + c * l * l + 2 * p.as * e * std::exp(p.bs * e * e) * l * l, 1e-12 * scale(p));
  EXPECT_NEAR(tau.m[2][2], iso + c, 1e-12 * scale(p));
  // The same stretch on a fibre-only material (a_s = 0) gives no anisotropic stress.
  auto fibre_only = m;
  fibre_only.p.as = 0;
  EXPECT_NEAR(fibre_only.kirchhoff(F).m[1][1], iso + c * l * l, 1e-12 * scale(p));
}

// F = I + g e1 (x) e2 (f0 = e1, s0 = e2): C = [[1, g, 0], [g, 1 + g^2, 0], [0, 0, 1]],
// J = 1, I1 = 3 + g^2, I_ff = 1, I_ss = 1 + g^2, I_fs = g; F f0 = e1, F s0 = (g, 1, 0).
TEST(HolzapfelOgden, SimpleShearInTheFibreSheetPlane) {
  const auto m = muscle();
  const auto& p = m.p;
  const double g = 0.3;
  const Mat<3, double> F{{{1, g, 0}, {0, 1, 0}, {0, 0, 1}}};
  const Mat<3, double> tau = m.kirchhoff(F);
  const double c = p.a * std::exp(p.b * g * g);
  const double ks = 2 * p.as * g * g * std::exp(p.bs * g * g * g * g);  // 2 a_s e_s exp(b_s e_s^2), e_s = g^2
  const double kfs = p.afs * g * std::exp(p.bfs * g * g);               // a_fs I_fs exp(b_fs I_fs^2)
  // b = F F^T = [[1 + g^2, g, 0], [g, 1, 0], [0, 0, 1]]
  EXPECT_NEAR(tau.m[0][1], c * g + ks * g + kfs, 1e-12 * scale(p));
  EXPECT_NEAR(tau.m[1][0], tau.m[0][1], 1e-15);
  EXPECT_NEAR(tau.m[0][0], -p.a + c * (1 + g * g) + ks * g * g + 2 * kfs * g, 1e-12 * scale(p));
  EXPECT_NEAR(tau.m[1][1], -p.a + c + ks, 1e-12 * scale(p));
  EXPECT_NEAR(tau.m[2][2], -p.a + c, 1e-12 * scale(p));
}

TEST(HolzapfelOgden, StressIsTheDerivativeOfTheEnergy) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.15, 0.15);
  auto p = table4();
  for (int k = 0; k < 20; ++k) {
    Mat<3, double> F = Mat<3, double>::identity();
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) F.m[a][b] += u(rng);
    const Vec<3, double> f0 = unit(1, 0.3 + u(rng), -0.2);
    Vec<3, double> s0 = unit(-0.3, 1, 0.1 + u(rng));
    s0 = s0 - f0 * dot(s0, f0);
    s0 = s0 * (1 / std::sqrt(dot(s0, s0)));
    const HolzapfelOgdenPoint<3, double> m{p, f0, s0, 0, 1.0};
    test::expect_energy_consistent<3>(m, F, 1e-7, 2e-6 * scale(p));
  }
  // b = 0 and b_f = 0 (seed 000 Table 3): the limits a x / 2 of the energy.
  p.b = 0;
  p.bf = 0;
  const HolzapfelOgdenPoint<3, double> m{p, unit(0, 0, 1), unit(1, 0, 0), 0, 1.0};
  test::expect_energy_consistent<3>(m, Mat<3, double>{{{1.1, 0.05, 0}, {0, 0.95, 0.1}, {0.02, 0, 1.2}}}, 1e-7,
                                    2e-6 * scale(p));
  // Plane strain: in-plane fibres, I1 = tr C + 1.
  const HolzapfelOgdenPoint<2, double> m2{table4(), Vec<2, double>{{0.6, 0.8}}, Vec<2, double>{{-0.8, 0.6}}, 0, 1.0};
  test::expect_energy_consistent<2>(m2, Mat<2, double>{{{1.08, 0.1}, {-0.05, 0.93}}}, 1e-7, 2e-6 * scale(p));
}

// Work = sum P : dF along a path out and back (midpoint rule, 4000 steps per
// leg) returns to zero, and equals W at the turning point.
TEST(HolzapfelOgden, EnergyEqualsWorkOverALoadUnloadCycle) {
  const HolzapfelOgdenPoint<3, double> m{table4(), unit(1, 1, 0), unit(-1, 1, 0.5), 0, 1.0};
  const Mat<3, double> target{{{1.2, 0.1, 0}, {0.05, 0.9, 0.1}, {0, -0.1, 1.05}}};
  auto F_at = [&](double s) { return Mat<3, double>::identity() + (target - Mat<3, double>::identity()) * s; };
  const int n = 4000;
  double work = 0;
  auto leg = [&](double from, double to) {
    for (int k = 0; k < n; ++k) {
      const double s0 = from + (to - from) * k / n, s1 = from + (to - from) * (k + 1) / n;
      const Mat<3, double> Fm = F_at(0.5 * (s0 + s1));
      work += ddot(mul_transposed(m.kirchhoff(Fm), inverse(Fm)), F_at(s1) - F_at(s0));
    }
  };
  leg(0, 1);
  const double W = m.strain_energy_density(target);
  EXPECT_GT(W, 0.01);
  EXPECT_NEAR(work, W, 1e-6 * W);
  leg(1, 0);
  EXPECT_NEAR(work, 0.0, 1e-9 * W);
}

// tau(QF) = Q tau(F) Q^T with the same reference fibres: they turn with F.
TEST(HolzapfelOgden, Objectivity) {
  const HolzapfelOgdenPoint<3, double> m{table4(), unit(1, 0.2, 0.1), unit(-0.2, 1, 0), 1.5, 1.0};
  const Mat<3, double> F{{{1.1, 0.05, 0.02}, {-0.03, 0.95, 0.1}, {0.04, 0, 1.08}}};
  const Mat<3, double> Q = test::rotation(Point3{0.3, -0.5, 0.8}, 1.1);
  const Mat<3, double> expected = mul_transposed(Q * m.kirchhoff(F), Q);
  const Mat<3, double> got = m.kirchhoff(Q * F);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) EXPECT_NEAR(got.m[a][b], expected.m[a][b], 1e-12 * scale(m.p));
}

TEST(HolzapfelOgden, GenogSplitAddsUpToTheStress) {
  const HolzapfelOgdenPoint<3, double> m{table4(), unit(0, 1, 1), unit(1, 0, 0), -2.0, 1.0};
  const Mat<3, double> F{{{1.05, 0.1, 0}, {0, 0.9, -0.05}, {0.1, 0, 1.1}}};
  const double c = m.shear_coefficient(F);
  EXPECT_NEAR(c, m.p.a * std::exp(m.p.b * (ddot(F, F) - 3)), 1e-15);
  const Mat<3, double> sum = m.kirchhoff_remainder(F) + mul_transposed(F, F) * c;
  const Mat<3, double> tau = m.kirchhoff(F);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) EXPECT_NEAR(sum.m[a][b], tau.m[a][b], 1e-13 * scale(m.p));
}

// tau_active = T_a (F f0) (x) (F f0) (seed 000 eq. 19): along the current
// fibre, magnitude T_a |F f0|^2; nothing across it.
TEST(HolzapfelOgden, ActiveStressDirectionAndMagnitude) {
  const Vec<3, double> f0 = unit(1, 1, 0);
  const HolzapfelOgdenPoint<3, double> passive{table4(), f0, unit(-1, 1, 0), 0, 1.0};
  HolzapfelOgdenPoint<3, double> active = passive;
  active.active_tension = -15.0;  // T_a = -0.5 V_m at V_m = 30 mV
  const Mat<3, double> F{{{1.1, 0.2, 0}, {0, 0.95, 0}, {0, 0.1, 1.02}}};
  const Mat<3, double> d = active.kirchhoff(F) - passive.kirchhoff(F);
  const Vec<3, double> f = F * f0;
  const double lf2 = dot(f, f);
  const Vec<3, double> n = f * (1 / std::sqrt(lf2));
  EXPECT_NEAR(dot(n, d * n), -15.0 * lf2, 1e-12 * 15);
  Vec<3, double> t = unit(0, 0, 1);
  t = t - n * dot(t, n);
  t = t * (1 / std::sqrt(dot(t, t)));
  EXPECT_NEAR(dot(t, d * t), 0.0, 1e-12 * 15);
  EXPECT_NEAR(dot(t, d * n), 0.0, 1e-12 * 15);
  // At F = I: T_a f0 (x) f0.
  const Mat<3, double> d0 = active.kirchhoff(Mat<3, double>::identity());
  EXPECT_NEAR(d0.m[0][0], -7.5, 1e-12);
  EXPECT_NEAR(d0.m[0][1], -7.5, 1e-12);
  EXPECT_NEAR(d0.m[2][2], 0.0, 1e-12);
}

TEST(HolzapfelOgden, LongitudinalModulusAtRest) {
  const auto m = muscle();
  const auto& p = m.p;
  EXPECT_NEAR(m.longitudinal_modulus(Mat<3, double>::identity()),
              p.lambda + 2 * p.a * p.b + 2 * p.a + 4 * std::max(p.af, p.as), 1e-12);
  // Stiffens with stretch along the fibre.
  const Mat<3, double> F{{{1.2, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  EXPECT_GT(m.longitudinal_modulus(F), 1.5 * m.longitudinal_modulus(Mat<3, double>::identity()));
}
