// Semi-Lagrangian RKPM (seed 004; rkpm.md 7) on the shipped scenes at the CI
// resolution; the converged figures come from scripts/validation/rkpm.py.
//
// Oscillating plate (configs/oscillating_plate_rkpm_2d.json, H/dp = 10,
// v_f = 0.01, SNNI + VC + NSNI, a~ = 2): the first period against the
// thin-beam T = 0.264 s (rkpm.md 7.5; the plane-strain continuum is about 1 %
// longer), and the total energy without damping over the run.
//
// Spinning plate (configs/spinning_plate_rkpm_2d.json, omega = 105 rad/s):
// the Hughes-Winget update is objective, so a freely spinning plate keeps
// its angular momentum L = sum M x ^ v and only stretches (centrifugal);
// linear momentum stays zero.
//
// Copper Taylor bar (configs/taylor_bar_rkpm_3d.json at R0/dp = 4, J2
// linear hardening, 227 m/s, 80 us): the final length against the
// published FE band 21.4-21.7 mm (rkpm.md 7.6; a tracked metric at this
// resolution) and the energy balance of the impact. Measured: L_f = 21.19 mm,
// largest radius 5.09 mm (FE band 7.0-7.2 mm: not reached at this
// resolution), balance 254.9 J from 251.1 J (+1.5 %).
// Measured at the plate: T = 0.27558 s, energy drift 2.9e-4; spinning plate:
// L changes by 1.3e-3 in 0.1 s.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "scene_runner.hpp"

using namespace mfsd;

namespace {

double angular_momentum(const Snapshot& s, const std::vector<double>& mass) {
  double L = 0;
  for (size_t i = 0; i < s.n; ++i)
    L += mass[i] * (s.position[3 * i] * s.velocity[3 * i + 1] - s.position[3 * i + 1] * s.velocity[3 * i]);
  return L;
}

// The tip's first period and the largest relative change of the total
// energy of an RKPM plate scene run to 0.29 s (one thread: ctest runs two
// tests at once on two cores).
struct PlateRun {
  double period, drift;
};
PlateRun run_plate(const std::string& config) {
  auto t = test::run_config(config, {"solver.end_time=0.29"}, Precision::double_precision, 0, 500, 1);
  std::vector<double> y;
  for (const auto& p : t.probes) y.push_back(p[0].position[1]);
  const double e0 = t.energies.front().kinetic + t.energies.front().strain;
  double drift = 0;
  for (const auto& e : t.energies) drift = std::max(drift, std::abs(e.kinetic + e.strain - e0) / e0);
  return {test::oscillation_period(t.time, y), drift};
}

}  // namespace

TEST(RkpmOscillatingPlate, PeriodAndEnergyAtCiResolution) {
  const PlateRun r = run_plate("oscillating_plate_rkpm_2d.json");
  // Measured 0.2756 (4.4 % above the thin beam at this resolution).
  EXPECT_LT(std::abs(r.period / 0.264 - 1), 0.05) << "T = " << r.period;
  EXPECT_NEAR(r.period, 0.2756, 0.003 * 0.2756);
  EXPECT_LT(r.drift, 1e-3) << "largest relative change of the total energy";
  std::printf("RKPM plate H/dp = 10: T = %.5f s, energy drift %.3g\n", r.period, r.drift);
}

// The same plate clamped at its root by one column of singular-kernel nodes
// (configs/oscillating_plate_clamped_rkpm_2d.json; rkpm.md 7.5's clamp):
// measured T = 0.26676 s (+1.05 % on the thin beam; the slot holder's free
// insert gives +4.4 %), total energy within 3.4e-4.
TEST(RkpmOscillatingPlate, ClampedBySingularNodesMeetsThePeriodTarget) {
  const PlateRun r = run_plate("oscillating_plate_clamped_rkpm_2d.json");
  EXPECT_LT(std::abs(r.period / 0.264 - 1), 0.03) << "T = " << r.period;  // rkpm.md 7.5
  EXPECT_NEAR(r.period, 0.26676, 0.003 * 0.26676);
  EXPECT_LT(r.drift, 1e-3) << "largest relative change of the total energy";
  std::printf("RKPM plate clamped by singular nodes, H/dp = 10: T = %.5f s, energy drift %.3g\n", r.period, r.drift);
}

TEST(RkpmSpinningPlate, AngularMomentumIsKept) {
  auto t =
      test::run_config("spinning_plate_rkpm_2d.json", {"solver.end_time=0.1"}, Precision::double_precision, 0, 0, 1);
  // Nodal masses m = rho0 dp^2 (the lattice's full cells): the measure of L.
  const Snapshot s1 = t.solver->snapshot();
  const std::vector<double> m(s1.n, 1100.0 * 0.05 * 0.05);
  const double omega = 105, I0 = 1100.0 * (1.0 / 6.0);  // rho side^4 / 6 for the unit square
  const double L1 = angular_momentum(s1, m);
  const double L0 = omega * I0;
  const EnergySample e = t.solver->energies();
  EXPECT_LT(std::abs(e.momentum[0]) + std::abs(e.momentum[1]), 1e-8 * L0);
  // The lattice's discrete polar moment is (1 - dp^2/side^2 / ... ) below the
  // continuum's: compare with the start of the same run instead.
  auto t0 =
      test::run_config("spinning_plate_rkpm_2d.json", {"solver.end_time=1e-9"}, Precision::double_precision, 0, 0, 1);
  const double Ls = angular_momentum(t0.solver->snapshot(), m);
  EXPECT_LT(std::abs(L1 / Ls - 1), 2e-3) << "L(0) = " << Ls << ", L(0.1 s) = " << L1 << ", continuum " << L0;
  std::printf("RKPM spinning plate: L(0) = %.6g, L(0.1 s) = %.6g (relative change %.3g)\n", Ls, L1, L1 / Ls - 1);
}

TEST(RkpmTaylorBar, FinalLengthAtCiResolution) {
  auto t = test::run_config("taylor_bar_rkpm_3d.json", {"constants.R_over_dp=4"}, Precision::double_precision, 0, 0, 1);
  const Snapshot s = t.solver->snapshot();
  double top = 0, radius = 0;
  for (size_t i = 0; i < s.n; ++i) {
    top = std::max(top, s.position[3 * i + 2]);
    radius = std::max(radius, std::hypot(s.position[3 * i], s.position[3 * i + 1]));
  }
  // Node centres: the surface is dp/2 further out (dp = 0.8 mm here).
  const double length = (top + 0.0004) * 1e3, mushroom = (radius + 0.0004) * 1e3;
  const EnergySample e = t.solver->energies();
  const BodyEnergy& b = e.bodies[0];
  std::printf("RKPM Taylor bar R0/dp = 4: L_f = %.3f mm, R_f = %.3f mm, balance %.4g J (start 251.148)\n", length,
              mushroom, b.balance());
  EXPECT_NEAR(length, 21.3, 0.6);  // measured: see the file header; FE band 21.4-21.7
  EXPECT_LT(std::abs(b.balance() / 251.148 - 1), 0.03);
}

// Dienes' simple shear through the whole code (configs/simple_shear_rkpm_2d.json,
// rkpm.md 7.1/7.4): every node driven by v_x = rate y0 to gamma = 2 pi in 103
// steps; the middle node's von Mises stress follows the Jaumann-rate solution
// 2 sqrt(3) mu |sin(gamma/2)| (the stress of a drift-kick-drift step belongs
// to the mid-step configuration, gamma at t - dt/2). Measured: largest error
// 8.8e-4 mu, peak 3.46407 mu (2 sqrt 3 = 3.46410); scripts/validation/rkpm.py
// shear: 9.35e-4 mu with 100 steps, 5.6e-5 mu with 399 (second order).
TEST(RkpmSimpleShear, WholeCodeFollowsTheJaumannSolution) {
  auto t = test::run_config("simple_shear_rkpm_2d.json", {}, Precision::double_precision, 0, 0, 1);
  const double E = 1.0e6, nu = 0.3, mu = E / (2 * (1 + nu)), rate = 2 * M_PI / 0.14;
  double err = 0, peak = 0;
  for (size_t k = 1; k < t.time.size(); ++k) {
    const double gamma = rate * 0.5 * (t.time[k] + t.time[k - 1]);
    const double q = t.probes[k][0].von_mises / mu;
    err = std::max(err, std::abs(q - 2 * std::sqrt(3.0) * std::abs(std::sin(gamma / 2))));
    peak = std::max(peak, q);
  }
  std::printf("RKPM simple shear, %zu steps: largest error %.3g mu, peak %.5f mu\n", t.time.size() - 1, err, peak);
  EXPECT_LT(err, 2e-3);
  EXPECT_NEAR(peak, 2 * std::sqrt(3.0), 2e-3);
  EXPECT_GT(t.time.size(), 100u);
}
