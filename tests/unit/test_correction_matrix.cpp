// Kernel-gradient correction B0 (seed 000 eq. 21): with it the SPH gradient
// reproduces linear fields exactly at every particle (surface ones too) of a
// perturbed lattice, and dF/dt (eq. 22) is exact for linear velocity fields.
// Near-singular supports are regularized and counted.
#include <gtest/gtest.h>

#include "kernels/tlsph/correction_matrix.hpp"
#include "kernels/tlsph/deformation_rate.hpp"
#include "particle_fixture.hpp"

using namespace mfsd;

namespace {

template <int D, class Real>
struct Corrected {
  test::Fixture<D, Real> f;
  DeviceVector<Cpu, Mat<D, Real>> B;
  DeviceVector<Cpu, unsigned char> flag;
  long regularized = 0;

  Corrected(const std::vector<Vec<D, double>>& x, double dp, double floor = 0.1)
      : f(x, dp, 1.15 * dp, true), B(x.size()), flag(x.size()) {
    parallel_for<Cpu>(Index(x.size()),
                      CorrectionMatrixFunctor<D, Real>{f.pairs.view(), raw(B), raw(flag), Real(floor)});
    for (unsigned char c : to_host<Cpu>(flag)) regularized += c;
  }
};

template <int D, class Real>
void linear_velocity_gives_exact_rate(double tol) {
  const int n[3] = {12, 8, 6};
  const double dp = 0.01;
  const auto x = test::lattice<D>(n, dp, 0.15, 3);
  Corrected<D, Real> c(x, dp);
  EXPECT_EQ(c.regularized, 0);
  Mat<D, Real> L;
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) L.m[a][b] = Real(0.3 * (a + 1) - 0.2 * b + (a == b ? 0.5 : 0.0));
  const auto X = c.f.template host<Vec<D, Real>>(field::reference_position);
  std::vector<Vec<D, Real>> v(X.size());
  for (size_t i = 0; i < X.size(); ++i) {
    v[i] = L * X[i];
    v[i].v[0] += Real(2.0);  // plus a translation
  }
  DeviceVector<Cpu, Vec<D, Real>> vel;
  from_host<Cpu>(v, vel);
  DeviceVector<Cpu, Mat<D, Real>> rate(X.size());
  parallel_for<Cpu>(Index(X.size()), DeformationRateFunctor<D, Real>{c.f.pairs.view(), raw(vel), raw(c.B), raw(rate)});
  const auto r = to_host<Cpu>(rate);
  double worst = 0;
  for (size_t i = 0; i < r.size(); ++i)
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) worst = std::max(worst, std::abs(double(r[i].m[a][b] - L.m[a][b])));
  EXPECT_LT(worst, tol);
}

}  // namespace

TEST(CorrectionMatrix, LinearVelocityExactRate2DDouble) { linear_velocity_gives_exact_rate<2, double>(1e-11); }
TEST(CorrectionMatrix, LinearVelocityExactRate3DDouble) { linear_velocity_gives_exact_rate<3, double>(1e-11); }
TEST(CorrectionMatrix, LinearVelocityExactRate2DFloat) { linear_velocity_gives_exact_rate<2, float>(2e-4); }
TEST(CorrectionMatrix, LinearVelocityExactRate3DFloat) { linear_velocity_gives_exact_rate<3, float>(2e-4); }

TEST(CorrectionMatrix, IdentityInTheBulkOfARegularLattice) {
  const int n[3] = {11, 11, 11};
  const auto x = test::lattice<3>(n, 1.0, 0.0, 1);
  Corrected<3, double> c(x, 1.0);
  const auto ids = c.f.host<Index>(field::id);
  const auto B = to_host<Cpu>(c.B);
  for (size_t k = 0; k < ids.size(); ++k)
    if (ids[k] == 5 + 11 * 5 + 121 * 5) {
      // The discrete second moment of the kernel differs from 1 by a few %.
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) EXPECT_NEAR(B[k].m[a][b], a == b ? 1.0 : 0.0, 0.05);
    }
}

TEST(CorrectionMatrix, SingleRowIsRegularizedAndCounted) {
  // Particles on one line: the support has no extent across it.
  const int n[2] = {10, 1};
  const auto x = test::lattice<2>(n, 1.0, 0.0, 1);
  Corrected<2, double> c(x, 1.0);
  EXPECT_EQ(c.regularized, 10);
  for (const auto& B : to_host<Cpu>(c.B))
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) EXPECT_TRUE(std::isfinite(B.m[a][b]));
}
