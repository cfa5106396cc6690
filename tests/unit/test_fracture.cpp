// Phase-field fracture kernels (kernels/fracture/): the tension/compression
// split against closed forms, the 1-D steady phase-field profile, the
// irreversibility of the history and of s, and the notch pair mask against a
// brute-force oracle.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "kernels/fracture/fracture_stress.hpp"
#include "kernels/fracture/notch.hpp"
#include "kernels/fracture/phase_field.hpp"
#include "kernels/fracture/tension_split.hpp"
#include "kernels/materials/elastic_moduli.hpp"
#include "tests/unit/particle_fixture.hpp"

using namespace mfsd;

namespace {

const ElasticModuli kModuli{32e9, 0.2};
template <int D>
SaintVenantKirchhoff<D, double> svk() {
  return {kModuli.bulk(), kModuli.shear(), kModuli.lame_lambda()};
}
template <int D>
NeoHookean<D, double> neo() {
  return {kModuli.bulk(), kModuli.shear()};
}
Mat<2, double> rotation2(double a) { return Mat<2, double>{{{std::cos(a), -std::sin(a)}, {std::sin(a), std::cos(a)}}}; }

template <int D>
void expect_near(const Mat<D, double>& A, const Mat<D, double>& B, double tol) {
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) EXPECT_NEAR(A.m[a][b], B.m[a][b], tol) << "component " << a << b;
}

// Principal stretches (1.1, 0.95) and a rigid rotation: F = R U, E = diag(0.105, -0.048875).
TEST(TensionSplit, SaintVenantKirchhoffSpectralClosedForm) {
  const auto m = svk<2>();
  const Mat<2, double> R = rotation2(0.4);
  const Mat<2, double> F = R * Mat<2, double>{{{1.1, 0}, {0, 0.95}}};
  const TensionSplit<2, double> sp = tension_split(m, F);
  const double e1 = 0.5 * (1.1 * 1.1 - 1), e2 = 0.5 * (0.95 * 0.95 - 1), tr = e1 + e2;
  EXPECT_GT(tr, 0);
  EXPECT_NEAR(sp.psi_plus, 0.5 * m.lambda * tr * tr + m.G * e1 * e1, 1e-9 * sp.psi_plus);   // eq. 11
  EXPECT_NEAR(sp.psi_minus, m.G * e2 * e2, 1e-9 * sp.psi_plus);                             // eq. 12
  EXPECT_NEAR(sp.psi_plus + sp.psi_minus, m.strain_energy_density(F), 1e-9 * sp.psi_plus);  // exact split
  expect_near(sp.tau_plus + sp.tau_minus, m.kirchhoff(F), 1e-9 * m.G);
  // s = 1 is the undegraded material; s = 0 keeps the compressive part only.
  expect_near(sp.kirchhoff(1.0), m.kirchhoff(F), 1e-9 * m.G);
  // tau_minus = F S_minus F^T with S_minus = 2 G e2 n2 (x) n2 (tr E > 0), n2 = e_y.
  const Vec<2, double> n2{{0.0, 1.0}};
  const Mat<2, double> S_minus = outer(n2, n2) * (2 * m.G * e2);
  expect_near(sp.kirchhoff(0.0), mul_transposed(F * S_minus, F), 1e-9 * m.G);
}

TEST(TensionSplit, NoDegradationUnderPureCompression) {
  const Mat<3, double> F{{{0.97, 0.01, 0}, {0.0, 0.98, 0.005}, {0, 0, 0.99}}};
  const auto m3 = svk<3>();
  const TensionSplit<3, double> a = tension_split(m3, F);
  EXPECT_EQ(a.psi_plus, 0.0);
  expect_near(a.kirchhoff(0.0), m3.kirchhoff(F), 1e-6);
  const auto n3 = neo<3>();
  const TensionSplit<3, double> b = tension_split(n3, F);  // J < 1: the volumetric part is kept
  Mat<3, double> vol = Mat<3, double>::diagonal(n3.volumetric_kirchhoff(det(F)));
  expect_near(b.kirchhoff(0.0), vol, 1e-6);
  EXPECT_NEAR(b.psi_plus + b.psi_minus, n3.strain_energy_density(F), 1e-9 * n3.strain_energy_density(F));
}

TEST(TensionSplit, NeoHookeanInTensionDegradesEverything) {
  const Mat<2, double> F = rotation2(1.0) * Mat<2, double>{{{1.05, 0.02}, {0, 1.01}}};
  const auto m = neo<2>();
  const TensionSplit<2, double> sp = tension_split(m, F);
  EXPECT_GE(det(F), 1.0);
  EXPECT_EQ(sp.psi_minus, 0.0);
  EXPECT_NEAR(sp.psi_plus, m.strain_energy_density(F), 1e-12 * m.G);
  expect_near(sp.kirchhoff(0.0), Mat<2, double>::zero(), 0.0);
  expect_near(sp.kirchhoff(0.5), m.kirchhoff(F) * 0.25, 1e-9 * m.G);
}

// Phase-field state on host vectors for the functors.
struct PhaseState {
  std::vector<double> s, rate, H, tensile, released, next;
  explicit PhaseState(size_t n) : s(n, 1.0), rate(n, 0.0), H(n, 0.0), tensile(n, 0.0), released(n, 0.0), next(n, 1.0) {}
  PhaseFieldViews<double> view() {
    return {s.data(), rate.data(), H.data(), tensile.data(), released.data(), nullptr, next.data()};
  }
};

// The steady state of eq. 6 with H = 0 away from a line where s = 0 is
// s = 1 - exp(-|x| / (2 eps0)) (eq. 6 with s'' = s' = 0: 4 eps0^2 s'' = s - 1).
// The line is held at s ~ 0 by a very large H; a strip tall enough that its
// middle row has the full kernel support.
TEST(PhaseField, SteadyProfileMatchesTheExponential) {
  const double dp = 1e-3, h = 1.15 * dp, eps0 = 1.5 * dp;
  const int n[2] = {121, 41};
  const auto x = test::lattice<2>(n, dp, 0.0, 1);
  test::Fixture<2, double> fx(x, dp, h, false);
  PhaseState st(x.size());
  const double x_mid = 60.5 * dp, Gc = 3.0;
  for (size_t i = 0; i < x.size(); ++i)
    if (std::fabs(x[i].v[0] - x_mid) < 0.25 * dp) st.H[i] = 1e5 * Gc / eps0;
  const FractureParameters<double> f{Gc, eps0, 4000.0, 0.1};
  const double dt = 0.3 * h / f.speed;
  for (int step = 0; step < 4000; ++step) {
    auto v = st.view();
    for (Index i = 0; i < Index(x.size()); ++i) v.s[i] += 0.5 * dt * v.rate[i];
    for (Index i = 0; i < Index(x.size()); ++i) PhaseFieldRateFunctor<2, double>{fx.pairs.view(), v, f, dt}(i);
    for (Index i = 0; i < Index(x.size()); ++i) PhaseFieldHalfStepFunctor<double>{v}(i);
  }
  double worst = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    if (std::fabs(x[i].v[1] - 20.5 * dp) > 0.25 * dp) continue;  // the middle row
    const double d = std::fabs(x[i].v[0] - x_mid);
    if (d < 0.5 * dp || d > 40 * dp) continue;
    const double exact = 1.0 - std::exp(-d / (2 * eps0));
    worst = std::max(worst, std::fabs(st.s[i] - exact));
  }
  std::printf("largest |s - exact| on the middle row: %.4f\n", worst);
  // Measured: 0.0065 (SPH Laplacian with h = 1.15 dp, eps0 = 1.5 dp).
  EXPECT_LT(worst, 0.01);
  EXPECT_LT(*std::min_element(st.s.begin(), st.s.end()), 0.01);
}

// A particle with no neighbours, stretched, then unloaded: H keeps its
// maximum and s only decreases (the damping of eq. 9 makes it monotone).
TEST(PhaseField, IrreversibleUnderUnloading) {
  const double dp = 1e-3;
  const std::vector<Vec<2, double>> x{Vec<2, double>{{0.0, 0.0}}};
  test::Fixture<2, double> fx(x, dp, 1.15 * dp, false);
  PhaseState st(1);
  const FractureParameters<double> f{3.0, 1e-4, 3800.0, 0.0};
  const auto m = svk<2>();
  const double dt = 1e-8;
  Mat<2, double> F = Mat<2, double>::identity(), rate = Mat<2, double>::zero(), B0 = Mat<2, double>::identity(), M;
  Vec<2, double> u = Vec<2, double>::zero(), vel = Vec<2, double>::zero();
  double H_prev = 0, s_prev = 1;
  for (int step = 0; step < 2000; ++step) {
    const double strain = step < 500 ? 4e-3 * step / 500.0 : std::max(0.0, 4e-3 * (1000 - step) / 500.0);
    F = Mat<2, double>{{{1 + strain, 0}, {0, 1}}};
    rate = Mat<2, double>::zero();
    auto v = st.view();
    FractureStressFunctor<2, double, SaintVenantKirchhoff<2, double>>{m,    {0.0, 0.0}, f,   true, 0.5 * dt, &F, &u,
                                                                      &vel, &rate,      &B0, &M,   nullptr,  v}(0);
    PhaseFieldRateFunctor<2, double>{fx.pairs.view(), v, f, dt}(0);
    PhaseFieldHalfStepFunctor<double>{v}(0);
    EXPECT_GE(st.H[0], H_prev);
    EXPECT_LE(st.s[0], s_prev + 1e-12) << "step " << step;
    H_prev = st.H[0];
    s_prev = st.s[0];
  }
  EXPECT_LT(st.s[0], 0.9);  // it did break partly
  EXPECT_GT(st.H[0], 0.0);
}

// Every pair within the support is in the list unless its segment crosses
// the notch; checked against a brute-force search with its own crossing test.
TEST(Notch, RemovesExactlyThePairsThatCrossIt) {
  const double dp = 1e-3, h = 1.15 * dp;
  const int n[2] = {20, 10};
  const auto x = test::lattice<2>(n, dp, 0.1, 3);
  Notch<2> cut{};
  cut.p[0] = Vec<2, double>{{-dp, 5 * dp}};
  cut.p[1] = Vec<2, double>{{10.3 * dp, 5 * dp}};
  cut.body = 0;
  test::Fixture<2, double> fx(x, dp, h, false, {}, false, {cut});
  const auto offsets = to_host<Cpu>(fx.pairs.offsets);
  const auto neighbor = to_host<Cpu>(fx.pairs.neighbor);
  long removed = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    std::vector<Index> expected;
    for (size_t j = 0; j < x.size(); ++j) {
      if (j == i || squared_norm(x[i] - x[j]) >= 4 * h * h) continue;
      const double yi = x[i].v[1] - 5 * dp, yj = x[j].v[1] - 5 * dp;
      bool crosses = false;
      if ((yi >= 0) != (yj >= 0)) {
        const double xc = x[i].v[0] + (x[j].v[0] - x[i].v[0]) * yi / (yi - yj);
        crosses = xc >= -dp && xc <= 10.3 * dp;
      }
      if (crosses)
        ++removed;
      else
        expected.push_back(Index(j));
    }
    std::vector<Index> got(neighbor.begin() + long(offsets[i]), neighbor.begin() + long(offsets[i + 1]));
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, expected) << "particle " << i;
  }
  EXPECT_GT(removed, 100);  // the notch did cut pairs
}

// A notch ending exactly on a lattice point midway between particles: the
// pairs through that end are cut from both sides or from neither (else the
// forces would not conserve momentum).
TEST(Notch, CutsEveryPairFromBothSides) {
  const double dp = 0.5e-3, h = 1.15 * dp;
  const int n[2] = {200, 80};
  const auto x = test::lattice<2>(n, dp, 0.0, 1);
  Notch<2> cut{};
  cut.p[0] = Vec<2, double>{{-dp, 0.02}};
  cut.p[1] = Vec<2, double>{{0.05, 0.02}};
  test::Fixture<2, double> fx(x, dp, h, false, {}, false, {cut});
  const auto offsets = to_host<Cpu>(fx.pairs.offsets);
  const auto neighbor = to_host<Cpu>(fx.pairs.neighbor);
  std::vector<std::vector<Index>> list(x.size());
  for (size_t i = 0; i < x.size(); ++i)
    list[i].assign(neighbor.begin() + long(offsets[i]), neighbor.begin() + long(offsets[i + 1]));
  long asymmetric = 0;
  for (size_t i = 0; i < x.size(); ++i)
    for (Index j : list[i])
      if (std::find(list[size_t(j)].begin(), list[size_t(j)].end(), Index(i)) == list[size_t(j)].end()) ++asymmetric;
  EXPECT_EQ(asymmetric, 0);
}

TEST(Notch, QuadCutsOnlyInsideItsCorners) {
  Notch<3> q{};
  q.p[0] = Vec<3, double>{{0, 0, 0}};
  q.p[1] = Vec<3, double>{{1, 0, 0}};
  q.p[2] = Vec<3, double>{{1, 1, 0}};
  q.p[3] = Vec<3, double>{{0, 1, 0}};
  EXPECT_TRUE(notch_cuts(q, Vec<3, double>{{0.5, 0.5, -0.1}}, Vec<3, double>{{0.5, 0.5, 0.1}}));
  EXPECT_FALSE(notch_cuts(q, Vec<3, double>{{1.5, 0.5, -0.1}}, Vec<3, double>{{1.5, 0.5, 0.1}}));
  EXPECT_FALSE(notch_cuts(q, Vec<3, double>{{0.5, 0.5, 0.1}}, Vec<3, double>{{0.6, 0.5, 0.2}}));
  // On the plane counts as the positive side: one of the two pairs through it is cut.
  EXPECT_FALSE(notch_cuts(q, Vec<3, double>{{0.5, 0.5, 0.0}}, Vec<3, double>{{0.5, 0.5, 0.1}}));
  EXPECT_TRUE(notch_cuts(q, Vec<3, double>{{0.5, 0.5, 0.0}}, Vec<3, double>{{0.5, 0.5, -0.1}}));
}

}  // namespace
