// J2 return mapping on b_bar_e (kernels/materials/j2_return_mapping.hpp):
// the returned stress lies on the yield surface, the hardening variable and
// the multiplier are consistent (closed form for linear hardening, converged
// Newton for saturation hardening), plastic flow is isochoric (det b_bar_e = 1),
// the update is objective, and a uniaxial-stress tension path follows the
// hardening law.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "kernels/materials/j2_return_mapping.hpp"
#include "rotation.hpp"

using namespace mfsd;

namespace {

constexpr double kG = 26.0e9, kSigmaY = 0.29e9;  // aluminium of seed 000 Table 6 (shear modulus, yield stress)

Mat<3, double> isochoric(const Mat<3, double>& b) { return b * std::pow(det(b), -1.0 / 3.0); }

// A sheared, stretched trial state with det = 1.
Mat<3, double> trial(double gamma) {
  Mat<3, double> F = Mat<3, double>::identity();
  F.m[0][1] = gamma;
  F.m[0][0] = 1 + 0.3 * gamma;
  F.m[2][2] = 1 - 0.2 * gamma;
  return isochoric(mul_transposed(F, F));
}

// The end of a uniaxial-stress tension path: a point stretched to lambda = 1.3
// in 300 steps, the lateral stretch found by bisection so that
// tau_22 = tau_33 = 0 (neo-Hookean volumetric term K/2 (J^2 - 1)). The
// deviatoric stress is the return's s, or with `state_stress` G dev(b_bar_e)
// of the updated state.
struct UniaxialEnd {
  double tau11, alpha, lambda, eps_p;  // eps_p = ln(lambda_p) from b_e
};

template <class Law>
UniaxialEnd uniaxial_tension(const Law& h, double G, double K, bool state_stress) {
  Mat<3, double> be = Mat<3, double>::identity(), F_prev = Mat<3, double>::identity();
  double alpha = 0, tau11 = 0, lambda = 1;
  auto deviatoric = [&](const J2Update<double>& u) { return state_stress ? deviator(u.be_bar) * G : u.s; };
  for (int step = 1; step <= 300; ++step) {
    lambda = 1 + 0.3 * step / 300;
    auto state = [&](double lat, J2Update<double>& u, double& J) {
      Mat<3, double> F = Mat<3, double>::diagonal(lat);
      F.m[0][0] = lambda;
      J = det(F);
      const Mat<3, double> f = F * inverse(F_prev);
      const Mat<3, double> fb = f * std::pow(det(f), -1.0 / 3.0);
      u = j2_return_mapping(fb * be * transpose(fb), alpha, G, h);
      return deviatoric(u).m[1][1] + 0.5 * K * (J * J - 1);  // tau_22
    };
    double lo = 0.5, hi = 1.0, J = 1;
    J2Update<double> u{};
    for (int k = 0; k < 200; ++k) {
      const double mid = 0.5 * (lo + hi);
      (state(mid, u, J) > 0 ? hi : lo) = mid;
    }
    const double lat = 0.5 * (lo + hi);
    state(lat, u, J);
    Mat<3, double> F = Mat<3, double>::diagonal(lat);
    F.m[0][0] = lambda;
    F_prev = F;
    be = u.be_bar;
    alpha = u.alpha;
    tau11 = deviatoric(u).m[0][0] + 0.5 * K * (J * J - 1);
  }
  // ln(lambda_p) = ln(lambda) - ln(lambda_e), lambda_e from b_e = J^{2/3} b_bar_e.
  const double J = det(F_prev), lambda_e = std::sqrt(std::pow(J, 2.0 / 3.0) * be.m[0][0]);
  return UniaxialEnd{tau11, alpha, lambda, std::log(lambda) - std::log(lambda_e)};
}

}  // namespace

TEST(J2ReturnMapping, ElasticTrialIsKept) {
  const LinearHardening<double> h{kSigmaY, 1e9};
  const auto be = trial(0.001);  // |s| = G |dev b| about 0.05 GPa < sqrt(2/3) 0.29 GPa
  const auto u = j2_return_mapping(be, 0.0, kG, h);
  EXPECT_EQ(u.dgamma, 0.0);
  EXPECT_EQ(u.alpha, 0.0);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) EXPECT_EQ(u.be_bar.m[a][b], be.m[a][b]);
}

TEST(J2ReturnMapping, LinearHardeningLandsOnTheYieldSurfaceInClosedForm) {
  for (double H : {0.0, 1.0e9, 50.0e9}) {
    const LinearHardening<double> h{kSigmaY, H};
    const double alpha_n = 0.02;
    const auto be = trial(0.05);
    const auto u = j2_return_mapping(be, alpha_n, kG, h);
    const double c = std::sqrt(2.0 / 3.0), s_tr = frobenius_norm(deviator(be) * kG);
    const double f_tr = s_tr - c * h.yield(alpha_n), G_bar = kG * trace(be) / 3;
    EXPECT_NEAR(u.dgamma, f_tr / (2 * (G_bar + H / 3)), 1e-12 * u.dgamma) << H;  // Algorithm 1 step 9
    EXPECT_NEAR(u.alpha, alpha_n + c * u.dgamma, 1e-15) << H;
    EXPECT_NEAR(frobenius_norm(u.s), c * h.yield(u.alpha), 1e-12 * kSigmaY) << H;  // on the yield surface
    EXPECT_NEAR(det(u.be_bar), 1.0, 1e-14) << H;                                   // isochoric plastic flow
    const auto s_back = deviator(u.be_bar) * kG;  // tau_dev = G dev(b_bar_e) reproduces the returned s
    EXPECT_NEAR(frobenius_norm(s_back - u.s), 0.0, 1e-12 * kSigmaY) << H;
    // The return is radial: s parallel to s_tr.
    EXPECT_NEAR(ddot(u.s, deviator(be)) / (frobenius_norm(u.s) * frobenius_norm(deviator(be))), 1.0, 1e-14) << H;
  }
}

TEST(J2ReturnMapping, SaturationHardeningSolvesTheConsistencyCondition) {
  // seed 000 Table 7 style parameters: sigma_y 0.45 GPa, H 0.13 GPa, sigma_inf 0.715 GPa, delta 16.93.
  const SaturationHardening<double> h{0.45e9, 0.12924e9, 0.715e9, 16.93};
  const double c = std::sqrt(2.0 / 3.0);
  for (double alpha_n : {0.0, 0.1, 1.0}) {
    const auto be = trial(0.08);
    const auto u = j2_return_mapping(be, alpha_n, 80.19e9, h);
    ASSERT_GT(u.dgamma, 0.0);
    const double s_tr = frobenius_norm(deviator(be) * 80.19e9), G_bar = 80.19e9 * trace(be) / 3;
    const double r = s_tr - 2 * G_bar * u.dgamma - c * h.yield(alpha_n + c * u.dgamma);
    EXPECT_LT(std::abs(r), 1e-12 * s_tr) << alpha_n;
    EXPECT_NEAR(frobenius_norm(u.s), c * h.yield(u.alpha), 1e-11 * s_tr) << alpha_n;
    EXPECT_LE(u.iterations, 10) << alpha_n;
    EXPECT_NEAR(det(u.be_bar), 1.0, 1e-14) << alpha_n;
  }
  // delta = 0 or sigma_inf = sigma_y is linear hardening.
  const auto a = j2_return_mapping(trial(0.08), 0.0, kG, SaturationHardening<double>{kSigmaY, 1e9, kSigmaY, 16.93});
  const auto b = j2_return_mapping(trial(0.08), 0.0, kG, LinearHardening<double>{kSigmaY, 1e9});
  EXPECT_NEAR(a.alpha, b.alpha, 1e-12 * b.alpha);
}

TEST(J2ReturnMapping, IsObjective) {
  // Rotating the trial state rotates the result and leaves alpha unchanged.
  const LinearHardening<double> h{kSigmaY, 2e9};
  const auto be = trial(0.06);
  const auto Q = test::rotation({1, 2, 2}, 0.7);
  const auto u = j2_return_mapping(be, 0.01, kG, h);
  const auto v = j2_return_mapping(Q * be * transpose(Q), 0.01, kG, h);
  EXPECT_NEAR(v.alpha, u.alpha, 1e-14);
  const auto rotated = Q * u.be_bar * transpose(Q);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) EXPECT_NEAR(v.be_bar.m[a][b], rotated.m[a][b], 1e-13);
}

TEST(J2ReturnMapping, UniaxialTensionFollowsTheHardeningLaw) {
  // On the yield surface the axial Kirchhoff stress is tau_11 = sigma_y + H alpha.
  const double E = 70e9, nu = 0.3, G = E / (2 * (1 + nu)), K = E / (3 * (1 - 2 * nu)), H = 1e9;
  const UniaxialEnd r = uniaxial_tension(LinearHardening<double>{kSigmaY, H}, G, K, false);
  EXPECT_NEAR(r.tau11, kSigmaY + H * r.alpha, 1e-9 * kSigmaY);
  // The plastic log strain is the log strain less tau_11/E (small elastic strain).
  const double eps_e = r.tau11 / E;
  EXPECT_NEAR(r.eps_p, std::log(r.lambda) - eps_e, 0.01 * eps_e);  // measured 0.3 % of eps_e
  // alpha sums sqrt(2/3) dgamma; the update's first-order flow integration on
  // b_bar_e makes it exceed ln(lambda_p) by a fraction of order the elastic
  // strain (measured 0.56 % here, with eps_e = 0.78 %).
  EXPECT_GT(r.alpha, r.eps_p);
  EXPECT_LT(r.alpha - r.eps_p, eps_e * r.eps_p);
  EXPECT_GT(r.alpha, 0.25);
}

// Seed 001's return on C_p with the Mandel stress (j2_mandel_return).
TEST(J2MandelReturn, LandsOnTheYieldSurfaceWithTheSeedsMultiplier) {
  const double c = std::sqrt(2.0 / 3.0);
  for (double H : {0.0, 1.0e9, 50.0e9}) {
    const Seed001Hardening<double> h{kSigmaY, H};
    const double e_n = 0.02;
    const auto be = trial(0.05);
    const auto u = j2_return_mapping(be, e_n, kG, h);
    const double sigma_tr = frobenius_norm(deviator(be) * kG) / c;
    const double dgamma = (sigma_tr - h.yield(e_n)) / (3 * kG + H * c);            // eq. 48
    EXPECT_NEAR(u.alpha, e_n + c * dgamma, 1e-15) << H;                            // eq. 49
    EXPECT_NEAR(frobenius_norm(u.s) / c, h.yield(u.alpha), 1e-12 * kSigmaY) << H;  // sigma_eq = sigma_Y (eq. 41)
    EXPECT_NEAR(det(u.be_bar), 1.0, 1e-14) << H;                                   // det C_p = 1 (eq. 51)
    EXPECT_NEAR(ddot(u.s, deviator(be)) / (frobenius_norm(u.s) * frobenius_norm(deviator(be))), 1.0, 1e-14) << H;
  }
}

TEST(J2MandelReturn, StateStressFollowsTheReturn) {
  // The stress of the updated state, G dev(b_bar_e) from eq. 50-51, differs
  // from the returned Mandel stress of eq. 47 by O(dgamma x elastic strain):
  // measured 3.7e-3 x the overshoot, linear in it; the elastic strain
  // |s| / G is 9.1e-3.
  const Seed001Hardening<double> h{kSigmaY, 1e9};
  double previous = 0;
  for (double overshoot : {0.02, 0.01, 0.005}) {  // trial beyond the yield surface, relative
    // A pure-shear trial with |s_tr| = (1 + overshoot) sqrt(2/3) sigma_y.
    const double target = (1 + overshoot) * std::sqrt(2.0 / 3.0) * kSigmaY / kG;
    double lo = 0, hi = 0.1;
    for (int k = 0; k < 200; ++k) {
      const double g = 0.5 * (lo + hi);
      Mat<3, double> F = Mat<3, double>::identity();
      F.m[0][1] = g;
      (frobenius_norm(deviator(mul_transposed(F, F))) > target ? hi : lo) = g;
    }
    Mat<3, double> F = Mat<3, double>::identity();
    F.m[0][1] = 0.5 * (lo + hi);
    const auto u = j2_return_mapping(mul_transposed(F, F), 0.0, kG, h);
    const double gap = frobenius_norm(deviator(u.be_bar) * kG - u.s) / frobenius_norm(u.s);
    if (previous > 0) EXPECT_NEAR(previous / gap, 2.0, 0.1) << overshoot;  // first order in dgamma
    EXPECT_LT(gap, overshoot * std::sqrt(2.0 / 3.0) * kSigmaY / kG) << overshoot;
    previous = gap;
  }
}

TEST(J2MandelReturn, IsObjective) {
  const Seed001Hardening<double> h{kSigmaY, 1e9};
  const auto be = trial(0.05);
  const Mat<3, double> Q = test::rotation({0.3, 0.7, -0.4}, 1.1);
  const auto a = j2_return_mapping(be, 0.01, kG, h);
  const auto b = j2_return_mapping(Q * be * transpose(Q), 0.01, kG, h);
  EXPECT_NEAR(a.alpha, b.alpha, 1e-15);
  EXPECT_LT(frobenius_norm(Q * a.be_bar * transpose(Q) - b.be_bar), 1e-14);
  EXPECT_LT(frobenius_norm(Q * a.s * transpose(Q) - b.s), 1e-14 * kSigmaY);
}

TEST(J2MandelReturn, UniaxialTensionFollowsTheSeedsHardeningLaw) {
  // Seed 001's e_p grows by sqrt(2/3) dgamma while sigma_eq falls by 3 G
  // dgamma, so along the path e_p = sqrt(2/3) ln(lambda_p) and
  // tau_11 = sigma_y + H sqrt(2/3) ln(lambda_p); the stress is the state's.
  const double E = 70e9, nu = 0.3, G = E / (2 * (1 + nu)), K = E / (3 * (1 - 2 * nu)), H = 1e9;
  const UniaxialEnd r = uniaxial_tension(Seed001Hardening<double>{kSigmaY, H}, G, K, true);
  const double closed = kSigmaY + H * std::sqrt(2.0 / 3.0) * r.eps_p;
  std::printf("tau_11 %.6g, closed form %.6g, e_p %.5g, sqrt(2/3) ln(lambda_p) %.5g\n", r.tau11, closed, r.alpha,
              std::sqrt(2.0 / 3.0) * r.eps_p);
  EXPECT_NEAR(r.tau11, closed, 2e-3 * kSigmaY);  // measured 1.0e-3: the state stress lags the return (above)
  EXPECT_NEAR(r.alpha, std::sqrt(2.0 / 3.0) * r.eps_p, 0.01 * r.alpha);
  EXPECT_GT(r.eps_p, 0.25);
}
