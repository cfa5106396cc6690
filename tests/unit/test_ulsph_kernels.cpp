// ULSPH kernels (formulations.md section 3, seed 002): equation of state and
// failure, continuity, pressure + Riemann dissipation, corrected velocity
// gradient, Jaumann / J2 shear stress update, shear acceleration and the GNOG
// penalty, on jittered lattices with a brute-force O(N^2) pair list (the
// oracle of design.md) built with the Wendland C2 kernel, h = 1.3 dp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "kernels/sph/wendland_c2.hpp"
#include "kernels/ulsph/continuity.hpp"
#include "kernels/ulsph/equation_of_state.hpp"
#include "kernels/ulsph/failure.hpp"
#include "kernels/ulsph/gnog.hpp"
#include "kernels/ulsph/pressure_force.hpp"
#include "kernels/ulsph/shear_force.hpp"
#include "kernels/ulsph/shear_stress.hpp"
#include "kernels/ulsph/velocity_gradient.hpp"

using namespace mfsd;

namespace {

template <int D>
std::vector<Vec<D, double>> lattice(const int* n, double dp, double jitter, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter * dp, jitter * dp);
  std::vector<Vec<D, double>> x;
  const int nz = D == 3 ? n[2] : 1;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        Vec<D, double> p;
        p.v[0] = (i + 0.5) * dp + u(rng);
        p.v[1] = (j + 0.5) * dp + u(rng);
        if constexpr (D == 3) p.v[2] = (k + 0.5) * dp + u(rng);
        x.push_back(p);
      }
  return x;
}

// Brute-force CSR pair list in the current configuration (pair_list.hpp):
// grad_ij = V_j dW e_ij, stretch_ij = V_j dW / r_ij, computed in double.
template <int D, class Real>
struct Pairs {
  std::vector<PairIndex> offsets;
  std::vector<Index> neighbor;
  std::vector<Vec<D, Real>> grad;
  std::vector<Real> stretch;
  std::vector<Vec<D, Real>> gradient_sum;

  Pairs(const std::vector<Vec<D, double>>& x, const std::vector<double>& volume, double h) {
    const WendlandC2<D, double> kernel = WendlandC2<D, double>::make(h);
    const size_t n = x.size();
    offsets.push_back(0);
    for (size_t i = 0; i < n; ++i) {
      Vec<D, double> sum = Vec<D, double>::zero();
      for (size_t j = 0; j < n; ++j) {
        if (j == i) continue;
        const Vec<D, double> d = x[i] - x[j];
        const double r = norm(d);
        if (r >= kernel.cutoff()) continue;
        const double dWV = kernel.dW(r) * volume[j];
        const Vec<D, double> g = d * (dWV / r);
        neighbor.push_back(Index(j));
        grad.push_back(cast<Real>(g));
        stretch.push_back(Real(dWV / r));
        sum += g;
      }
      offsets.push_back(PairIndex(neighbor.size()));
      gradient_sum.push_back(cast<Real>(sum));
    }
    neighbor.resize(neighbor.size() + kPairPrefetchDistance, 0);  // the prefetch padding
  }
  PairList<D, Real> view() const {
    return PairList<D, Real>{offsets.data(), neighbor.data(),     grad.data(),
                             stretch.data(), gradient_sum.data(), nullptr};
  }
};

// Whether x is farther than `margin` from every face of the lattice box.
template <int D>
bool inside(const Vec<D, double>& x, const int* n, double dp, double margin) {
  for (int a = 0; a < D; ++a)
    if (x.v[a] < margin || x.v[a] > n[a] * dp - margin) return false;
  return true;
}

const double* const kElastic = nullptr;  // kappa of an elastic body: null (kappa = 1)

template <class F>
void for_each_particle(size_t n, const F& f) {
  for (size_t i = 0; i < n; ++i) f(Index(i));
}

template <int D, class Real>
Mat<D, Real> random_matrix(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  Mat<D, Real> A;
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) A.m[a][b] = Real(u(rng));
  return A;
}

template <int D, class Real>
double max_abs(const Mat<D, Real>& A) {
  double m = 0;
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) m = std::max(m, std::abs(double(A.m[a][b])));
  return m;
}

// A non-symmetric velocity gradient: dv_x/dy = 0.7, dv_y/dx = -0.2, ...
template <int D>
Mat<D, double> nonsymmetric_gradient() {
  Mat<D, double> A;
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) A.m[a][b] = 0.3 * (a + 1) - 0.2 * b + (a == b ? 0.5 : 0.0);
  A.m[0][1] = 0.7;
  A.m[1][0] = -0.2;
  return A;
}

// B and L of a velocity field on a particle set.
template <int D, class Real>
struct Gradients {
  std::vector<Mat<D, Real>> B, L;
  std::vector<unsigned char> fallback;
  long fallbacks = 0;

  Gradients(const Pairs<D, Real>& p, const std::vector<Vec<D, Real>>& v)
      : B(v.size()), L(v.size()), fallback(v.size()) {
    for_each_particle(v.size(), ulsph::CorrectionMatrixFunctor<D, Real>{p.view(), B.data(), fallback.data()});
    for_each_particle(v.size(), ulsph::VelocityGradientFunctor<D, Real>{p.view(), v.data(), B.data(), L.data()});
    for (unsigned char f : fallback) fallbacks += f;
  }
};

// ---------------------------------------------------------------- velocity gradient

template <int D, class Real>
void linear_field_gives_exact_gradient(double tol) {
  const int n[3] = {11, 9, 7};
  const double dp = 0.01;
  const auto x = lattice<D>(n, dp, 0.2, 7);
  const Pairs<D, Real> p(x, std::vector<double>(x.size(), std::pow(dp, D)), 1.3 * dp);
  const Mat<D, double> A = nonsymmetric_gradient<D>();
  std::vector<Vec<D, Real>> v(x.size());
  for (size_t i = 0; i < x.size(); ++i) {
    v[i] = cast<Real>(A * x[i]);
    v[i].v[0] += Real(1.5);  // plus a translation
  }
  const Gradients<D, Real> g(p, v);
  EXPECT_EQ(g.fallbacks, 0);
  double worst_interior = 0, worst_surface = 0;
  int surface = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    double e = 0;
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) e = std::max(e, std::abs(double(g.L[i].m[a][b]) - A.m[a][b]));
    const bool on_surface = !inside(x[i], n, dp, 2.6 * dp);  // truncated support
    surface += on_surface;
    (on_surface ? worst_surface : worst_interior) = std::max(on_surface ? worst_surface : worst_interior, e);
  }
  EXPECT_GT(surface, 20);
  EXPECT_LT(worst_interior, tol);
  EXPECT_LT(worst_surface, tol);
  // L_ab = dv_a/dx_b, element by element at a corner particle.
  EXPECT_NEAR(double(g.L[0].m[0][1]), 0.7, tol);
  EXPECT_NEAR(double(g.L[0].m[1][0]), -0.2, tol);
}

TEST(UlsphVelocityGradient, LinearFieldExactEverywhere2DDouble) { linear_field_gives_exact_gradient<2, double>(1e-10); }
TEST(UlsphVelocityGradient, LinearFieldExactEverywhere3DDouble) { linear_field_gives_exact_gradient<3, double>(1e-10); }
TEST(UlsphVelocityGradient, LinearFieldExactEverywhere2DFloat) { linear_field_gives_exact_gradient<2, float>(2e-4); }
TEST(UlsphVelocityGradient, LinearFieldExactEverywhere3DFloat) { linear_field_gives_exact_gradient<3, float>(2e-4); }

TEST(UlsphVelocityGradient, SingularSupportFallsBackToIdentity) {
  // One row of particles: no neighbour across it, det(A) = 0.
  const int n[2] = {8, 1};
  const auto x = lattice<2>(n, 1.0, 0.0, 1);
  const Pairs<2, double> p(x, std::vector<double>(x.size(), 1.0), 1.3);
  std::vector<Vec<2, double>> v(x.size(), Vec<2, double>::zero());
  const Gradients<2, double> g(p, v);
  EXPECT_EQ(g.fallbacks, 8);
  for (const auto& B : g.B) EXPECT_EQ(max_abs(B - Mat<2, double>::identity()), 0.0);
}

// ---------------------------------------------------------------- GNOG

template <int D>
Mat<D, double> spin_matrix(const Vec<3, double>& w) {  // Omega v = w x v (2-D: w_z only)
  Mat<D, double> W = Mat<D, double>::zero();
  W.m[1][0] = w.v[2];
  W.m[0][1] = -w.v[2];
  if constexpr (D == 3) {
    W.m[2][1] = w.v[0];
    W.m[1][2] = -w.v[0];
    W.m[0][2] = w.v[1];
    W.m[2][0] = -w.v[1];
  }
  return W;
}

template <int D>
void rigid_rotation_has_no_non_affine_velocity() {
  const int n[3] = {10, 9, 8};
  const double dp = 0.02;
  const auto x = lattice<D>(n, dp, 0.2, 11);
  const Pairs<D, double> p(x, std::vector<double>(x.size(), std::pow(dp, D)), 1.3 * dp);
  const Mat<D, double> W = spin_matrix<D>(Vec<3, double>{{0.4, -0.9, 2.0}});
  std::vector<Vec<D, double>> v(x.size());
  for (size_t i = 0; i < x.size(); ++i) v[i] = W * x[i] + Vec<D, double>::constant(0.3);
  const Gradients<D, double> g(p, v);
  EXPECT_EQ(g.fallbacks, 0);
  std::vector<Mat<D, double>> LT(x.size());
  for (size_t i = 0; i < x.size(); ++i) LT[i] = transpose(g.L[i]);
  const double wn = frobenius_norm(W);
  double worst = 0, worst_transposed = 0;
  for (size_t i = 0; i < x.size(); ++i)
    for (PairIndex k = p.offsets[i]; k < p.offsets[i + 1]; ++k) {
      const Index j = p.neighbor[k];
      const double r = norm(x[i] - x[j]);
      const Vec<D, double> vt = ulsph::non_affine_velocity(v[i], v[j], g.L[i], g.L[j], p.grad[k], p.stretch[k]);
      const Vec<D, double> vt_T = ulsph::non_affine_velocity(v[i], v[j], LT[i], LT[j], p.grad[k], p.stretch[k]);
      worst = std::max(worst, norm(vt) / (wn * r));
      worst_transposed = std::max(worst_transposed, norm(vt_T) / (wn * r));
    }
  EXPECT_LT(worst, 1e-10);
  EXPECT_GT(worst_transposed, 0.5);  // = 2 |W x_ij| / (|W| r): the test can tell L from L^T
  // The GNOG increment vanishes for both variants (kappa = 1), and not with L^T.
  const double G = 1.0, xi = 4.0, rho = 1.0;
  double rate = 0, rate_amc = 0, rate_T = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    const auto pv = p.view();
    rate = std::max(rate, norm(ulsph::gnog_penalty_rate(pv, v.data(), g.L.data(), kElastic, xi, G, rho, Index(i))));
    rate_amc = std::max(rate_amc, norm(ulsph::gnog_penalty_rate<D, double, ulsph::GnogAngularMomentumConserving>(
                                      pv, v.data(), g.L.data(), kElastic, xi, G, rho, Index(i))));
    rate_T = std::max(rate_T, norm(ulsph::gnog_penalty_rate(pv, v.data(), LT.data(), kElastic, xi, G, rho, Index(i))));
  }
  // Scale: the penalty of a non-affine velocity |W| dp, xi G |W| dp sum |stretch| ~ xi G |W| / dp.
  const double scale = xi * G * wn / (rho * dp);
  EXPECT_LT(rate / scale, 1e-10);
  EXPECT_LT(rate_amc / scale, 1e-10);
  EXPECT_GT(rate_T / scale, 0.1);
}

TEST(UlsphGnog, RigidRotationHasNoNonAffineVelocity2D) { rigid_rotation_has_no_non_affine_velocity<2>(); }
TEST(UlsphGnog, RigidRotationHasNoNonAffineVelocity3D) { rigid_rotation_has_no_non_affine_velocity<3>(); }

TEST(UlsphGnog, PenaltyOpposesACheckerboardMode) {
  // The hourglass mode of a regular lattice: v alternates sign particle by
  // particle. L barely sees it; the penalty rate points against v inside.
  const int n[2] = {12, 12};
  const double dp = 0.01;
  const auto x = lattice<2>(n, dp, 0.0, 1);
  const Pairs<2, double> p(x, std::vector<double>(x.size(), dp * dp), 1.3 * dp);
  std::vector<Vec<2, double>> v(x.size());
  for (int j = 0; j < n[1]; ++j)
    for (int i = 0; i < n[0]; ++i) v[size_t(i + n[0] * j)] = Vec<2, double>{{(i + j) % 2 ? 1.0 : -1.0, 0.0}};
  const Gradients<2, double> g(p, v);
  int interior = 0;
  for (int j = 3; j < n[1] - 3; ++j)
    for (int i = 3; i < n[0] - 3; ++i) {
      const Index k = Index(i + n[0] * j);
      const Vec<2, double> r = ulsph::gnog_penalty_rate(p.view(), v.data(), g.L.data(), kElastic, 4.0, 1.0, 1.0, k);
      EXPECT_LT(dot(r, v[size_t(k)]), -1.0 / (dp * dp));  // against v, of size xi G |v| / (rho dp^2)
      ++interior;
    }
  EXPECT_EQ(interior, 36);
}

TEST(UlsphGnog, RotateWithSpin) {
  // 2-D: a plane rotation by omega_z dt.
  const Mat<2, double> L2 = spin_matrix<2>(Vec<3, double>{{0, 0, 3.0}}) + Mat<2, double>::diagonal(0.7);
  const Vec<2, double> r2 = ulsph::rotate_with_spin(Vec<2, double>{{1.0, 0.0}}, L2, 0.1);
  EXPECT_NEAR(r2.v[0], std::cos(0.3), 1e-15);
  EXPECT_NEAR(r2.v[1], std::sin(0.3), 1e-15);
  // 3-D: Rodrigues about omega; the component along omega is kept, the norm too.
  const Vec<3, double> w{{1.0, 2.0, -2.0}};  // |w| = 3
  const Mat<3, double> L3 = spin_matrix<3>(w) + Mat<3, double>::diagonal(0.2);
  const Vec<3, double> a{{0.3, -1.0, 0.8}};
  const Vec<3, double> r3 = ulsph::rotate_with_spin(a, L3, 0.25);
  EXPECT_NEAR(norm(r3), norm(a), 1e-14);
  EXPECT_NEAR(dot(r3, w), dot(a, w), 1e-14);
  // Small angle: R a ~ a + dt w x a.
  const Vec<3, double> small = ulsph::rotate_with_spin(a, L3, 1e-6);
  const Vec<3, double> expect = a + cross(w, a) * 1e-6;
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(small.v[k], expect.v[k], 1e-11);
  // The AMC functor rotates the stored a_h (zero increment: a single particle).
  const PairIndex offsets[2] = {0, 0};
  Index neighbor[1 + kPairPrefetchDistance] = {};
  const Vec<3, double> G0 = Vec<3, double>::zero();
  const PairList<3, double> pl{offsets, neighbor, nullptr, nullptr, &G0, nullptr};
  const Vec<3, double> vel = Vec<3, double>::zero();
  const double rho = 1.0;
  Vec<3, double> a_h = a, acc = Vec<3, double>::zero();
  ulsph::GnogPenaltyFunctor<3, double, ulsph::GnogAngularMomentumConserving>{pl,  &vel, &L3,  &rho, nullptr,
                                                                             2.0, 1.0,  0.25, &a_h, &acc}(0);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(a_h.v[k], r3.v[k], 1e-15);
    EXPECT_NEAR(acc.v[k], r3.v[k], 1e-15);
  }
}

// ---------------------------------------------------------------- shear stress

template <int D>
Mat<D, double> rotation_of(const Mat<D, double>& W, double t) {  // exp(W t), W skew
  if constexpr (D == 2) {
    const double th = W.m[1][0] * t;
    Mat<2, double> R;
    R.m[0][0] = std::cos(th), R.m[0][1] = -std::sin(th), R.m[1][0] = std::sin(th), R.m[1][1] = std::cos(th);
    return R;
  } else {
    const double w = std::sqrt(0.5 * ddot(W, W));
    const Mat<3, double> K = W * (1.0 / w);
    return Mat<3, double>::identity() + K * std::sin(w * t) + (K * K) * (1.0 - std::cos(w * t));
  }
}

template <int D>
Mat<D, double> deviatoric_stress() {
  Mat<D, double> t;
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) t.m[a][b] = a == b ? (a == 0 ? 2.0 : -1.0) : 0.6 + 0.3 * (a + b);
  return deviator(t);
}

// Error of n explicit steps of pure spin against R tau0 R^T over the time T.
template <int D>
double spin_error(const Mat<D, double>& W, int n, double T, bool transposed = false) {
  const auto model = ulsph::HypoelasticJ2<double>::elastic(1.0);
  const Mat<D, double> tau0 = deviatoric_stress<D>();
  const Mat<D, double> L = transposed ? transpose(W) : W;
  Mat<D, double> tau = tau0;
  for (int s = 0; s < n; ++s) tau = ulsph::update_shear_stress(tau, L, 0.0, model, T / n).shear_stress;
  const Mat<D, double> R = rotation_of(W, T);
  return frobenius_norm(tau - R * tau0 * transpose(R)) / frobenius_norm(tau0);
}

template <int D>
void jaumann_rate_is_objective() {
  const Mat<D, double> W = spin_matrix<D>(Vec<3, double>{{0.6, -0.3, 1.0}});
  const double w2 = 0.5 * ddot(W, W);  // |omega|^2
  const Mat<D, double> tau0 = deviatoric_stress<D>();
  const auto model = ulsph::HypoelasticJ2<double>::elastic(1.0);
  // One step: the Hughes-Winget rotation keeps |tau| to round-off, and its
  // angle 2 atan(|omega| dt/2) differs from |omega| dt by O(dt^3).
  double local[2];
  for (int k = 0; k < 2; ++k) {
    const double dt = 1e-2 / (1 << k);
    const Mat<D, double> tau1 = ulsph::update_shear_stress(tau0, W, 0.0, model, dt).shear_stress;
    EXPECT_NEAR(ddot(tau1, tau1) / ddot(tau0, tau0), 1.0, 1e-14);
    const Mat<D, double> R = rotation_of(W, dt);
    local[k] = frobenius_norm(tau1 - R * tau0 * transpose(R)) / frobenius_norm(tau0);
    EXPECT_LT(local[k], dt * dt * dt * w2 * std::sqrt(w2));
  }
  EXPECT_NEAR(local[1] / local[0], 0.125, 0.005);  // third order locally
  // Many steps over a rotation of 1 rad: second-order convergence to R tau0 R^T.
  const double T = 1.0 / std::sqrt(w2);
  const double e1 = spin_error(W, 100, T), e2 = spin_error(W, 200, T);
  EXPECT_LT(e1, 1e-4);
  EXPECT_NEAR(e2 / e1, 0.25, 0.01);
  // With L^T in place of L the stress turns the other way.
  EXPECT_GT(spin_error(W, 1000, T, true), 0.1);
}

TEST(UlsphShearStress, JaumannRateIsObjective2D) { jaumann_rate_is_objective<2>(); }
TEST(UlsphShearStress, JaumannRateIsObjective3D) { jaumann_rate_is_objective<3>(); }

template <int D, class Real>
Mat<D, Real> shear_with_spin(double rate) {  // L_01 = rate (D and Omega both nonzero), plus a compression
  Mat<D, Real> L = Mat<D, Real>::zero();
  L.m[0][1] = Real(rate);
  L.m[D - 1][D - 1] = Real(-0.4 * rate);
  return L;
}

// The trial stress of one elastic step, written out: the spin as the rotation
// Q = (I - dt W/2)^{-1} (I + dt W/2), then 2G dev(D) dt.
template <int D>
Mat<D, double> rotated_trial(const Mat<D, double>& tau, const Mat<D, double>& L, double G, double dt) {
  const Mat<D, double> W = (L - transpose(L)) * 0.5, Dm = (L + transpose(L)) * 0.5;
  const Mat<D, double> Q =
      inverse(Mat<D, double>::identity() - W * (0.5 * dt)) * (Mat<D, double>::identity() + W * (0.5 * dt));
  return Q * tau * transpose(Q) + deviator(Dm) * (2 * G * dt);
}

template <int D, class Real>
void radial_return(double tol) {
  const double G = 80e9, sigma_y = 300e6, H = 2e9;
  const auto model = ulsph::HypoelasticJ2<Real>::plastic(Real(G), Real(sigma_y), Real(H));
  const Mat<D, Real> L = shear_with_spin<D, Real>(1e3);
  // Elastic step from zero: kappa = 1, a unchanged, tau = 2G dev(D) dt.
  const Real dt_small = Real(1e-9);
  const auto e = ulsph::update_shear_stress(Mat<D, Real>::zero(), L, Real(0.1), model, dt_small);
  EXPECT_EQ(e.kappa, Real(1));
  EXPECT_EQ(e.hardening, Real(0.1));
  const Mat<D, Real> strain_rate = (L + transpose(L)) * Real(0.5);
  EXPECT_LT(max_abs(e.shear_stress - deviator(strain_rate) * Real(2 * G * 1e-9)), tol * 2 * G * 1e3 * 1e-9);
  // Plastic step from a stress inside the surface (a = 0.1): the trial is returned.
  const double a0 = 0.1, R0 = std::sqrt(2.0 / 3.0) * (sigma_y + H * a0), dt = 1e-5;
  Mat<D, Real> tau0 = cast<Real>(deviatoric_stress<D>());
  tau0 *= Real(0.5 * R0 / frobenius_norm(deviatoric_stress<D>()));
  const auto r = ulsph::update_shear_stress(tau0, L, Real(a0), model, Real(dt));
  const Mat<D, double> trial = rotated_trial(cast<double>(tau0), cast<double>(L), G, dt);
  const double f = frobenius_norm(trial) - R0;
  ASSERT_GT(f, 0.0);
  const double a1 = a0 + std::sqrt(2.0 / 3.0) * f / (2 * (G + H / 3));
  const double R1 = std::sqrt(2.0 / 3.0) * (sigma_y + H * a1);
  EXPECT_LT(r.kappa, Real(1));
  EXPECT_NEAR(double(r.kappa), R1 / frobenius_norm(trial), tol);
  EXPECT_NEAR(double(r.hardening), a1, tol * a1);
  EXPECT_NEAR(double(frobenius_norm(r.shear_stress)), R1, tol * R1);  // on the surface
  EXPECT_NEAR(double(frobenius_norm(r.shear_stress)), std::sqrt(2.0 / 3.0) * (sigma_y + H * double(r.hardening)),
              tol * R1);
  EXPECT_LT(max_abs(cast<double>(r.shear_stress) - trial * (R1 / frobenius_norm(trial))), tol * R1);  // radial
  // An elastic body (sigma_y = infinity) takes any strain elastically.
  const auto el = ulsph::update_shear_stress(tau0, L, Real(0), ulsph::HypoelasticJ2<Real>::elastic(Real(G)), Real(dt));
  EXPECT_EQ(el.kappa, Real(1));
  EXPECT_EQ(el.hardening, Real(0));
  EXPECT_GT(double(frobenius_norm(el.shear_stress)), 3 * R0);
}

TEST(UlsphShearStress, RadialReturn2DDouble) { radial_return<2, double>(1e-13); }
TEST(UlsphShearStress, RadialReturn3DDouble) { radial_return<3, double>(1e-13); }
TEST(UlsphShearStress, RadialReturn2DFloat) { radial_return<2, float>(2e-6); }
TEST(UlsphShearStress, RadialReturn3DFloat) { radial_return<3, float>(2e-6); }

TEST(UlsphShearStress, ProportionalLoadingFollowsLinearHardening) {
  // Pure shear without spin, classical radial return (remove_plastic_rate = false):
  // exact for proportional loading, |tau| = sqrt(2/3) sigma_y + (2/3) H gamma with
  // gamma = (2G |e| - sqrt(2/3) sigma_y) / (2G + 2H/3), e = int dev D dt.
  const double G = 80e9, sigma_y = 300e6, H = 2e9, rate = 10.0, dt = 1e-6;
  const auto model = ulsph::HypoelasticJ2<double>::plastic(G, sigma_y, H, false);
  Mat<3, double> L = Mat<3, double>::zero();
  L.m[0][1] = L.m[1][0] = rate;
  Mat<3, double> tau = Mat<3, double>::zero();
  double a = 0;
  const int steps = 1000;
  for (int s = 0; s < steps; ++s) {
    const auto r = ulsph::update_shear_stress(tau, L, a, model, dt);
    tau = r.shear_stress;
    a = r.hardening;
  }
  const double e = std::sqrt(2.0) * rate * dt * steps, ry = std::sqrt(2.0 / 3.0) * sigma_y;
  ASSERT_GT(2 * G * e, 2 * ry);  // well into the plastic range
  const double gamma = (2 * G * e - ry) / (2 * G + 2 * H / 3);
  EXPECT_NEAR(frobenius_norm(tau), ry + 2.0 / 3.0 * H * gamma, 1e-9 * ry);
  EXPECT_NEAR(a, std::sqrt(2.0 / 3.0) * gamma, 1e-9 * gamma);
}

TEST(UlsphShearStress, PerfectPlasticityStaysOnTheSurfaceAndUnloadsElastically) {
  // Default model (the rate loses its plastic part on the surface), H = 0.
  const double G = 26e9, sigma_y = 100e6, dt = 1e-6;
  const auto model = ulsph::HypoelasticJ2<double>::plastic(G, sigma_y, 0.0);
  const double ry = std::sqrt(2.0 / 3.0) * sigma_y;
  const Mat<3, double> L = shear_with_spin<3, double>(20.0);
  Mat<3, double> tau = Mat<3, double>::zero();
  double a = 0, kappa = 1;
  int plastic = 0;
  for (int s = 0; s < 400; ++s) {
    const auto r = ulsph::update_shear_stress(tau, L, a, model, dt);
    tau = r.shear_stress;
    a = r.hardening;
    kappa = r.kappa;
    if (frobenius_norm(tau) > (1 - 1e-12) * ry) {
      ++plastic;
      EXPECT_NEAR(frobenius_norm(tau), ry, 1e-12 * ry);
    }
  }
  EXPECT_GT(plastic, 100);
  EXPECT_LE(kappa, 1.0);
  // Reverse the loading: the first step is elastic (kappa = 1) and lowers |tau|.
  const Mat<3, double> back = L * -1.0;
  const auto u = ulsph::update_shear_stress(tau, back, a, model, dt);
  EXPECT_EQ(u.kappa, 1.0);
  EXPECT_EQ(u.hardening, a);
  const Mat<3, double> expect = rotated_trial(tau, back, G, dt);
  EXPECT_LT(max_abs(u.shear_stress - expect), 1e-12 * ry);
  EXPECT_LT(frobenius_norm(u.shear_stress), ry * (1 - 1e-4));
}

TEST(UlsphShearStress, FunctorStoresKappaAndHardening) {
  const auto model = ulsph::HypoelasticJ2<double>::plastic(1e3, 1.0, 10.0);
  const Mat<2, double> L[2] = {shear_with_spin<2, double>(1e-6), shear_with_spin<2, double>(1.0)};
  Mat<2, double> tau[2] = {Mat<2, double>::zero(), Mat<2, double>::zero()};
  double a[2] = {0, 0}, kappa[2] = {-1, -1};
  const ulsph::ShearStressFunctor<2, double> f{L, tau, a, kappa, model, 0.1};
  f(0);
  f(1);
  EXPECT_EQ(kappa[0], 1.0);
  EXPECT_EQ(a[0], 0.0);
  EXPECT_LT(kappa[1], 1.0);
  EXPECT_GT(a[1], 0.0);
  EXPECT_NEAR(frobenius_norm(tau[1]), std::sqrt(2.0 / 3.0) * (1.0 + 10.0 * a[1]), 1e-12);
  // An elastic body passes null hardening and kappa.
  Mat<2, double> t = Mat<2, double>::zero();
  ulsph::ShearStressFunctor<2, double>{&L[1], &t, nullptr, nullptr, ulsph::HypoelasticJ2<double>::elastic(1e3), 0.1}(0);
  EXPECT_NEAR(frobenius_norm(t), 1e3 * 2 * 0.1 * frobenius_norm(deviator((L[1] + transpose(L[1])) * 0.5)), 1e-9);
}

// ---------------------------------------------------------------- continuity

TEST(UlsphContinuity, UniformTranslationLeavesDensity) {
  const int n[3] = {8, 7, 6};
  const double dp = 0.01;
  const auto x = lattice<3>(n, dp, 0.2, 5);
  const Pairs<3, double> p(x, std::vector<double>(x.size(), dp * dp * dp), 1.3 * dp);
  const std::vector<Vec<3, double>> v(x.size(), Vec<3, double>{{3.0, -1.0, 2.0}});
  std::vector<double> rho(x.size(), 1000.0), rate(x.size());
  for_each_particle(x.size(), ulsph::DensityRateFunctor<3, double>{p.view(), v.data(), rho.data(), rate.data()});
  for (double r : rate) EXPECT_LT(std::abs(r), 1e-9 * 1000 * 3 / dp);
}

// drho/dt of v = c x on a lattice with the given jitter, and the moments A_i.
template <int D>
void expansion_rate(const int* n, double dp, double jitter, double c, std::vector<Vec<D, double>>& x,
                    std::vector<double>& rho, std::vector<double>& rate, std::vector<double>& trA) {
  x = lattice<D>(n, dp, jitter, 9);
  const Pairs<D, double> p(x, std::vector<double>(x.size(), std::pow(dp, D)), 1.3 * dp);
  std::vector<Vec<D, double>> v(x.size());
  rho.resize(x.size()), rate.resize(x.size()), trA.resize(x.size());
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(990, 1010);
  for (size_t i = 0; i < x.size(); ++i) v[i] = x[i] * c, rho[i] = u(rng);
  for_each_particle(x.size(), ulsph::DensityRateFunctor<D, double>{p.view(), v.data(), rho.data(), rate.data()});
  for (size_t i = 0; i < x.size(); ++i) trA[i] = trace(ulsph::correction_moment(p.view(), Index(i)));
  // The functor that advances rho: rho += dt drho/dt.
  std::vector<double> advanced = rho;
  for_each_particle(x.size(), ulsph::ContinuityFunctor<D, double>{p.view(), v.data(), advanced.data(), 1e-4});
  for (size_t i = 0; i < x.size(); ++i) EXPECT_DOUBLE_EQ(advanced[i], rho[i] + 1e-4 * rate[i]);
}

template <int D>
void uniform_expansion() {
  // v = c x: drho_i/dt = -rho_i c tr(A_i) at every particle of a jittered lattice
  // (A_i = -sum_j (x_i - x_j) (x) grad_ij), and ~ -rho c D inside a regular one,
  // where tr(A_i)/D is the discrete second moment of the kernel (0.974 in 2-D,
  // 0.979 in 3-D at h = 1.3 dp).
  const int n[3] = {12, 11, 10};
  const double dp = 0.01, c = 0.5;
  std::vector<Vec<D, double>> x;
  std::vector<double> rho, rate, trA;
  expansion_rate<D>(n, dp, 0.2, c, x, rho, rate, trA);
  double worst = 0;
  for (size_t i = 0; i < x.size(); ++i) worst = std::max(worst, std::abs(rate[i] + rho[i] * c * trA[i]) / (rho[i] * c));
  EXPECT_LT(worst, 1e-12);
  expansion_rate<D>(n, dp, 0.0, c, x, rho, rate, trA);
  int interior = 0;
  for (size_t i = 0; i < x.size(); ++i)
    if (inside(x[i], n, dp, 2.7 * dp)) {  // full support
      EXPECT_NEAR(rate[i] / (-rho[i] * c * D), D == 2 ? 0.974 : 0.979, 1e-3);
      ++interior;
    }
  EXPECT_GT(interior, 10);
}

TEST(UlsphContinuity, UniformExpansion2D) { uniform_expansion<2>(); }
TEST(UlsphContinuity, UniformExpansion3D) { uniform_expansion<3>(); }

TEST(UlsphContinuity, VolumeRateIsThePairDivergenceSum) {
  // sum_i (m_i/rho_i^2) drho_i/dt = sum_i V_i sum_j (v_i - v_j) . grad_ij, with
  // V = m/rho: each unordered pair contributes twice V_i V_j dW_ij (v_i - v_j) . e_ij,
  // evaluated here directly from positions and the kernel.
  const int n[2] = {12, 10};
  const double dp = 0.01, h = 1.3 * dp;
  const auto x = lattice<2>(n, dp, 0.2, 21);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double> m(x.size()), rho(x.size()), V(x.size()), rate(x.size());
  std::vector<Vec<2, double>> v(x.size());
  for (size_t i = 0; i < x.size(); ++i) {
    m[i] = 1000 * dp * dp * (1 + 0.1 * u(rng));
    rho[i] = 1000 * (1 + 0.05 * u(rng));
    V[i] = m[i] / rho[i];
    v[i] = Vec<2, double>{{u(rng), u(rng)}};
  }
  const Pairs<2, double> p(x, V, h);
  for_each_particle(x.size(), ulsph::DensityRateFunctor<2, double>{p.view(), v.data(), rho.data(), rate.data()});
  double per_particle = 0, scale = 0;
  for (size_t i = 0; i < x.size(); ++i) per_particle += m[i] / (rho[i] * rho[i]) * rate[i];
  const WendlandC2<2, double> W = WendlandC2<2, double>::make(h);
  double pair_sum = 0;
  for (size_t i = 0; i < x.size(); ++i)
    for (size_t j = i + 1; j < x.size(); ++j) {
      const Vec<2, double> d = x[i] - x[j];
      const double r = norm(d);
      if (r >= W.cutoff()) continue;
      const double term = 2 * V[i] * V[j] * W.dW(r) * dot(v[i] - v[j], d) / r;
      pair_sum += term;
      scale += std::abs(term);
    }
  EXPECT_NEAR(per_particle, pair_sum, 1e-12 * scale);
}

// ---------------------------------------------------------------- forces

TEST(UlsphPressureForce, PairIsPushedApart) {
  // Two particles on the x axis, V = 1, i = 0 at x = 0.5 h right of j = 1.
  const std::vector<Vec<2, double>> x = {Vec<2, double>{{0.5, 0.0}}, Vec<2, double>{{0.0, 0.0}}};
  const Pairs<2, double> p(x, {1.0, 1.0}, 1.0);
  const double rho[2] = {1.0, 1.0};
  const Vec<2, double> at_rest[2] = {Vec<2, double>::zero(), Vec<2, double>::zero()};
  const Vec<2, double> approach[2] = {Vec<2, double>{{-1.0, 0.3}}, Vec<2, double>{{1.0, 0.3}}};
  const Vec<2, double> recede[2] = {Vec<2, double>{{1.0, 0.0}}, Vec<2, double>{{-1.0, 0.0}}};
  const double compressed[2] = {2.0, 2.0}, none[2] = {0.0, 0.0}, tension[2] = {-2.0, -2.0};
  Vec<2, double> a[2];
  auto run = [&](const Vec<2, double>* v, const double* pr, double Z, double limiter = 0.0) {
    for_each_particle(2, ulsph::PressureAccelerationFunctor<2, double>{p.view(), v, rho, pr, Z, limiter, a});
    EXPECT_NEAR(a[0].v[0], -a[1].v[0], 1e-15);  // m_i a_i = -m_j a_j
    EXPECT_NEAR(a[0].v[1], 0.0, 1e-15);         // central
    EXPECT_NEAR(a[1].v[1], 0.0, 1e-15);
  };
  run(at_rest, compressed, 10.0);
  EXPECT_GT(a[0].v[0], 0.0);  // pressure repels
  run(at_rest, tension, 10.0);
  EXPECT_LT(a[0].v[0], 0.0);  // tension attracts
  run(approach, none, 10.0);
  EXPECT_GT(a[0].v[0], 0.0);  // dissipation repels approaching particles
  const double approach_a = a[0].v[0];
  run(recede, none, 10.0);
  EXPECT_LT(a[0].v[0], 0.0);  // and holds back receding ones
  // Size: Z |v_i - v_j| |dW| V / rho with dW = dW/dr(0.5).
  const double dW = WendlandC2<2, double>::make(1.0).dW(0.5);
  EXPECT_NEAR(approach_a, 10.0 * 2.0 * std::abs(dW), 1e-12);
  // The low-dissipation limiter (seed 002 ref. [38]), limiter = eta / c0:
  // Z u scaled by min(eta u / c0, 1) with the approach speed u = 2 here.
  run(approach, none, 10.0, 0.25);
  EXPECT_NEAR(a[0].v[0], 0.5 * approach_a, 1e-12);  // eta u / c0 = 0.5
  run(approach, none, 10.0, 1.0);
  EXPECT_NEAR(a[0].v[0], approach_a, 1e-12);  // capped at 1: the full dissipation
  run(recede, none, 10.0, 1.0);
  EXPECT_EQ(a[0].v[0], 0.0);  // receding pairs are not held back
  run(approach, compressed, 10.0, 0.25);
  EXPECT_NEAR(a[0].v[0], 0.5 * approach_a + 2.0 * 2.0 * std::abs(dW), 1e-12);  // the pressure is not limited
}

TEST(UlsphShearForce, UniformStressBalancesInsideAndPullsABarBack) {
  const int n[2] = {20, 8};
  const double dp = 0.01;
  const auto x = lattice<2>(n, dp, 0.0, 1);
  const Pairs<2, double> p(x, std::vector<double>(x.size(), dp * dp), 1.3 * dp);
  Mat<2, double> s = Mat<2, double>::zero();
  s.m[0][0] = 1e6, s.m[1][1] = -1e6;  // tension along the bar
  const std::vector<Mat<2, double>> tau(x.size(), s);
  const std::vector<double> rho(x.size(), 1000.0);
  std::vector<Vec<2, double>> a(x.size(), Vec<2, double>::zero());
  for_each_particle(x.size(), ulsph::ShearAccelerationFunctor<2, double>{p.view(), rho.data(), tau.data(), a.data()});
  const double scale = 1e6 / (1000.0 * dp);
  for (int j = 0; j < n[1]; ++j)
    for (int i = 0; i < n[0]; ++i) {
      const Vec<2, double> ai = a[size_t(i + n[0] * j)];
      if (i >= 3 && i < n[0] - 3 && j >= 3 && j < n[1] - 3) {
        EXPECT_LT(norm(ai), 1e-12 * scale);
      }
      if (i == 0) {
        EXPECT_GT(ai.v[0], 0.1 * scale);  // left end pulled right
      }
      if (i == n[0] - 1) {
        EXPECT_LT(ai.v[0], -0.1 * scale);  // right end pulled left
      }
    }
}

// Random state on a jittered lattice with V = m / rho in the pair data: the
// pair terms of every force are antisymmetric, so sum_i m_i a_i = 0; the central
// ones (pressure + Riemann, GNOG-AMC) also keep sum_i x_i x m_i a_i = 0.
template <int D>
void pair_forces_conserve_momentum() {
  const int n[3] = {9, 8, 7};
  const double dp = 0.01;
  const auto x = lattice<D>(n, dp, 0.25, 13);
  const size_t N = x.size();
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double> m(N), rho(N), V(N), pr(N), kappa(N);
  std::vector<Vec<D, double>> v(N);
  std::vector<Mat<D, double>> tau(N), L(N);
  for (size_t i = 0; i < N; ++i) {
    m[i] = 7800 * std::pow(dp, D) * (1 + 0.2 * u(rng));
    rho[i] = 7800 * (1 + 0.05 * u(rng));
    V[i] = m[i] / rho[i];
    pr[i] = 1e8 * u(rng);
    kappa[i] = 0.6 + 0.4 * std::abs(u(rng));
    for (int a = 0; a < D; ++a) v[i].v[a] = 10 * u(rng);
    tau[i] = random_matrix<D, double>(rng, 1e8);
    tau[i] = deviator(tau[i] + transpose(tau[i]));
    L[i] = random_matrix<D, double>(rng, 1e4);
  }
  const Pairs<D, double> p(x, V, 1.3 * dp);
  const double Z = 7800 * 5000.0, G = 80e9, dt = 1e-7;
  std::vector<Vec<D, double>> a_p(N), a_s(N, Vec<D, double>::zero()), a_h(N, Vec<D, double>::zero()),
      a_amc(N, Vec<D, double>::zero());
  for_each_particle(
      N, ulsph::PressureAccelerationFunctor<D, double>{p.view(), v.data(), rho.data(), pr.data(), Z, 0.0, a_p.data()});
  for_each_particle(N, ulsph::ShearAccelerationFunctor<D, double>{p.view(), rho.data(), tau.data(), a_s.data()});
  for_each_particle(N, ulsph::GnogPenaltyFunctor<D, double>{p.view(), v.data(), L.data(), rho.data(), kappa.data(), 0.2,
                                                            G, dt, a_h.data(), nullptr});
  for_each_particle(N, ulsph::GnogPenaltyFunctor<D, double, ulsph::GnogAngularMomentumConserving>{
                           p.view(), v.data(), L.data(), rho.data(), kappa.data(), 2.0, G, dt, a_amc.data(), nullptr});
  struct Balance {
    double momentum, momentum_scale, angular, angular_scale;
  };
  auto balance = [&](const std::vector<Vec<D, double>>& a) {
    Vec<D, double> P = Vec<D, double>::zero();
    double Ps = 0, Lz = 0, Ls = 0;
    Vec<3, double> Lv = Vec<3, double>::zero();
    for (size_t i = 0; i < N; ++i) {
      const Vec<D, double> f = a[i] * m[i];
      P += f;
      Ps += norm(f);
      Vec<3, double> x3 = Vec<3, double>::zero(), f3 = Vec<3, double>::zero();
      for (int k = 0; k < D; ++k) x3.v[k] = x[i].v[k], f3.v[k] = f.v[k];
      Lv += cross(x3, f3);
      Ls += norm(x3) * norm(f3);
    }
    Lz = norm(Lv);
    return Balance{norm(P), Ps, Lz, Ls};
  };
  for (const auto* a : {&a_p, &a_s, &a_h, &a_amc}) {
    const Balance b = balance(*a);
    EXPECT_GT(b.momentum_scale, 0.0);
    EXPECT_LT(b.momentum, 1e-13 * b.momentum_scale);
  }
  EXPECT_LT(balance(a_p).angular, 1e-13 * balance(a_p).angular_scale);
  EXPECT_LT(balance(a_amc).angular, 1e-13 * balance(a_amc).angular_scale);
  EXPECT_GT(balance(a_h).angular, 1e-3 * balance(a_h).angular_scale);  // the plain GNOG pair force is not central
}

TEST(UlsphMomentum, PairForcesConserveMomentum2D) { pair_forces_conserve_momentum<2>(); }
TEST(UlsphMomentum, PairForcesConserveMomentum3D) { pair_forces_conserve_momentum<3>(); }

// ---------------------------------------------------------------- equation of state, failure

TEST(UlsphFailure, TensionBeyondThresholdFailsAndThenCarriesNoTension) {
  const ulsph::LinearEquationOfState<double> eos{2e9, 1000.0};
  EXPECT_NEAR(eos.pressure(1001.0), 2e6, 1e-6);
  EXPECT_DOUBLE_EQ(eos.density(eos.pressure(987.0)), 987.0);
  // Thresholds of 5 MPa: particle 0 compressed, 1 in mild tension, 2 beyond.
  std::vector<double> rho = {1001.0, 999.0, 996.0};
  std::vector<double> p(3);
  std::vector<unsigned char> failed(3, 0);
  const ulsph::PressureFunctor<double, ulsph::TensileFailure<double>> f{
      rho.data(), p.data(), eos, {5e6, failed.data()}};
  for_each_particle(3, f);
  EXPECT_EQ(failed, (std::vector<unsigned char>{0, 0, 1}));
  EXPECT_NEAR(p[0], 2e6, 1e-6);
  EXPECT_NEAR(p[1], -2e6, 1e-6);  // below the threshold: tension carried
  EXPECT_EQ(p[2], 0.0);           // failed: p >= 0
  // Later: the failed particle still takes compression but never tension again.
  rho[0] = 999.0, rho[1] = 1002.0, rho[2] = 1003.0;  // in place: the functor holds the pointer
  for_each_particle(3, f);
  EXPECT_NEAR(p[2], 6e6, 1e-6);
  rho[2] = 999.5;
  for_each_particle(3, f);
  EXPECT_EQ(failed, (std::vector<unsigned char>{0, 0, 1}));
  EXPECT_EQ(p[2], 0.0);
  EXPECT_NEAR(p[0], -2e6, 1e-6);
  // Without a failure model the law is plain.
  std::vector<double> q(3);
  for_each_particle(3, ulsph::PressureFunctor<double>{rho.data(), q.data(), eos, {}});
  EXPECT_NEAR(q[2], -1e6, 1e-6);
  EXPECT_TRUE(ulsph::exceeds_tensile_threshold(-6e6, 5e6));
  EXPECT_FALSE(ulsph::exceeds_tensile_threshold(-4e6, 5e6));
}

}  // namespace
