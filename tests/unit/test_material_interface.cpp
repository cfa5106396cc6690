// The TLSPH material interface (kernels/materials/material_interface.hpp):
// the GENOG split of each material adds up to its Kirchhoff stress where the
// split is exact, the optional members are detected on the materials that
// have them, the active stress's work is tau_a : L dt, and the activation
// ramp of a time-dependent material.
#include <gtest/gtest.h>

#include <cmath>

#include "kernels/materials/holzapfel_ogden.hpp"
#include "kernels/materials/j2_plastic.hpp"
#include "kernels/materials/material_interface.hpp"
#include "kernels/materials/neo_hookean.hpp"
#include "kernels/materials/saint_venant_kirchhoff.hpp"

using namespace mfsd;

namespace {
HolzapfelOgdenParameters<double> muscle() {  // seed 000 Table 4, lambda from K = 100 a
  const double a = 0.059;
  return {100 * a - 2 * a / 3, a, 8.023, 18.472, 16.026, 2.841, 11.12, 0.216, 11.436};
}
template <int D>
Mat<D, double> deformation() {  // a stretch with shear, det > 0
  Mat<D, double> F = Mat<D, double>::identity();
  F.m[0][0] = 1.12, F.m[0][1] = 0.07, F.m[1][0] = -0.04, F.m[1][1] = 0.93;
  if constexpr (D == 3) F.m[2][2] = 1.05, F.m[0][2] = 0.03, F.m[2][1] = -0.02;
  return F;
}
template <int D, class Point>
void expect_split_adds_up(const Point& m, double tolerance) {
  const Mat<D, double> F = deformation<D>();
  const KirchhoffSplit<D, double> s = m.genog_split(F);
  const Mat<D, double> tau = s.remainder + mul_transposed(F, F) * s.coefficient;
  const Mat<D, double> expected = m.kirchhoff(F);
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) EXPECT_NEAR(tau.m[a][b], expected.m[a][b], tolerance) << a << b;
}
}  // namespace

TEST(MaterialInterface, GenogSplitAddsUpToTheStress) {
  expect_split_adds_up<3>(NeoHookean<3, double>{2.0, 0.7}.at(5), 1e-13);
  expect_split_adds_up<2>(NeoHookean<2, double>{2.0, 0.7}.at(5), 1e-13);
  const HolzapfelOgdenPoint<3, double> ho3{muscle(), Vec<3, double>{{0.6, 0.8, 0}}, Vec<3, double>{{-0.8, 0.6, 0}}, 0.3,
                                           1.0};
  expect_split_adds_up<3>(ho3, 1e-12);
  const HolzapfelOgdenPoint<2, double> ho2{muscle(), Vec<2, double>{{0.6, 0.8}}, Vec<2, double>{{-0.8, 0.6}}, 0.3, 1.0};
  expect_split_adds_up<2>(ho2, 1e-12);
}

// Saint Venant-Kirchhoff's split is the authors' (K J (J - 1), c = G J^{-2/d};
// formulations.md section 1), not its own tau: the two agree at F = I only,
// and to first order in the strain.
TEST(MaterialInterface, SaintVenantKirchhoffSplitIsTheAuthorsForm) {
  const SaintVenantKirchhoff<3, double> m{2.0, 0.7, 2.0 - 2.0 * 0.7 / 3.0};
  Mat<3, double> F = Mat<3, double>::identity();
  const KirchhoffSplit<3, double> at_rest = m.at(0).genog_split(F);
  const Mat<3, double> tau0 = at_rest.remainder + mul_transposed(F, F) * at_rest.coefficient;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) EXPECT_NEAR(tau0.m[a][b], 0.0, 1e-15);
  const double e = 1e-6;
  F.m[0][0] += e, F.m[0][1] += 0.5 * e;
  const KirchhoffSplit<3, double> s = m.at(0).genog_split(F);
  const Mat<3, double> tau = s.remainder + mul_transposed(F, F) * s.coefficient, exact = m.kirchhoff(F);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) EXPECT_NEAR(tau.m[a][b], exact.m[a][b], 100 * e * e);
}

TEST(MaterialInterface, OptionalMembersAreDetected) {
  EXPECT_TRUE((Stiffens<HolzapfelOgdenPoint<3, double>>::value));
  EXPECT_TRUE((HasActiveWork<HolzapfelOgdenPoint<2, double>>::value));
  EXPECT_TRUE((IsTimeDependent<HolzapfelOgden<3, double>>::value));
  EXPECT_FALSE((IsIsotropic<HolzapfelOgden<3, double>>::value));
  EXPECT_FALSE((Stiffens<NeoHookean<3, double>>::value));
  EXPECT_FALSE((HasActiveWork<SaintVenantKirchhoff<3, double>>::value));
  EXPECT_FALSE((IsTimeDependent<NeoHookean<2, double>>::value));
  EXPECT_TRUE((IsIsotropic<NeoHookean<3, double>>::value));
  EXPECT_TRUE((IsIsotropic<SaintVenantKirchhoff<2, double>>::value));
}

// tau_a = T_a f (x) f with f = F f0 (seed 000 eq. 19): its work over dt at the
// rate L is tau_a : L dt.
TEST(MaterialInterface, ActiveWorkIsTheActiveStressTimesTheRate) {
  const double Ta = 1.7, dt = 1e-3;
  const HolzapfelOgdenPoint<3, double> m{muscle(), Vec<3, double>{{0.6, 0.8, 0}}, Vec<3, double>{{-0.8, 0.6, 0}}, Ta,
                                         1.0};
  const Mat<3, double> F = deformation<3>();
  Mat<3, double> L = Mat<3, double>::zero();
  L.m[0][0] = 0.3, L.m[0][1] = -0.2, L.m[1][0] = 0.5, L.m[2][2] = -0.1, L.m[1][2] = 0.25;
  const Vec<3, double> f = F * m.f0;
  double expected = 0;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) expected += Ta * f.v[a] * f.v[b] * L.m[a][b] * dt;
  EXPECT_NEAR(m.active_work(F, L, dt), expected, 1e-15);
  const HolzapfelOgdenPoint<3, double> passive{muscle(), m.f0, m.s0, 0.0, 1.0};
  EXPECT_EQ(passive.active_work(F, L, dt), 0.0);
}

TEST(MaterialInterface, StiffeningIsOneAtRestWithoutActiveTension) {
  const HolzapfelOgdenParameters<double> p = muscle();
  const double reference = p.lambda + 2 * p.a * p.b + 2 * p.a + 4 * std::max(p.af, p.as);
  const HolzapfelOgdenPoint<3, double> m{p, Vec<3, double>{{1, 0, 0}}, Vec<3, double>{{0, 1, 0}}, 0.0, reference};
  EXPECT_NEAR(m.stiffening(Mat<3, double>::identity()), 1.0, 1e-14);
  EXPECT_GT(m.stiffening(deformation<3>()), 1.0);  // the exponential terms stiffen under stretch
}

// T_a = k V_m min(t / ramp_time, 1); ramp_time 0: at once; < 0: no active stress.
TEST(MaterialInterface, ActivationRamp) {
  HolzapfelOgden<3, double> m{muscle(), 1.0, nullptr, nullptr, nullptr, 0.0, 2.0};
  m.set_time(0.5);
  EXPECT_DOUBLE_EQ(m.activation, 0.25);
  m.set_time(3.0);
  EXPECT_DOUBLE_EQ(m.activation, 1.0);
  m.ramp_time = 0;
  m.activation = 0;
  m.set_time(0.0);
  EXPECT_DOUBLE_EQ(m.activation, 1.0);
  m.ramp_time = -1;
  m.activation = 0.125;
  m.set_time(5.0);
  EXPECT_DOUBLE_EQ(m.activation, 0.125);
}
