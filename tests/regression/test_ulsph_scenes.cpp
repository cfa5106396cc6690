// ULSPH with GNOG (seed 002) on the shipped scenes at the CI resolution.
//
// Oscillating plate (configs/oscillating_plate_ulsph_2d.json, H/dp = 10,
// nu = 0.3975, h = 1.3 dp, v_f = 0.05): the first period against seed 002
// Table 1 (0.272; analytical 0.254) within the 2 %, the measured
// 0.2725 to 0.3 % (regression), and the total energy, which only the
// Riemann dissipation lowers, within -2 % / +0.5 % over two periods.
//
// Spinning plate (configs/spinning_plate_ulsph_2d.json, omega = 105 rad/s,
// single-criterion stepping, gnog_amc): angular momentum L = sum m x ^ v and
// the polar moment I = sum m |x|^2 from the particles. The plate stretches
// until I = 68.6 (3 % above the start; the TLSPH run of the same plate gives
// 68.5) and then spins at omega = L / I = 101.9 rad/s, as the TLSPH run does.
// With the pair data of the step's start instead of its half step (a
// development build before fa775d0; no present option), the plate
// crept outwards (I = 81.5 at t = 0.2 s) and gained 9 % of L; with dual
// stepping and the pair data frozen over the advection step, I = 83.1 and
// +9.8 % (theory.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "host/scene/scene_error.hpp"
#include "scene_runner.hpp"

using namespace mfsd;

namespace {

struct Spin {
  double L, I;  // per unit mass: all particles have the same mass
};

Spin spin_of(const Snapshot& s) {
  Spin r{0, 0};
  for (size_t i = 0; i < s.n; ++i) {
    const double x = s.position[3 * i], y = s.position[3 * i + 1];
    r.L += x * s.velocity[3 * i + 1] - y * s.velocity[3 * i];
    r.I += x * x + y * y;
  }
  return r;
}

}  // namespace

TEST(UlsphOscillatingPlate, PeriodAndEnergyAtCiResolution) {
  auto t = test::run_config("oscillating_plate_ulsph_2d.json", {"solver.end_time=0.62"}, Precision::double_precision, 0,
                            200);
  std::vector<double> y;
  for (const auto& p : t.probes) y.push_back(p[0].position[1]);
  const double T = test::oscillation_period(t.time, y);
  EXPECT_LT(std::abs(T / 0.272 - 1), 0.02) << "T = " << T;
  EXPECT_NEAR(T, 0.2725, 0.003 * 0.2725);
  const double e0 = t.energies.front().kinetic + t.energies.front().strain;
  double lo = e0, hi = e0;
  for (const auto& e : t.energies) lo = std::min(lo, e.kinetic + e.strain), hi = std::max(hi, e.kinetic + e.strain);
  // Measured: 4.0029 to 4.0790 against 4.0648 (-1.5 % to +0.35 %): the
  // stored-energy measure of the hypo-elastic solid (energy.hpp) is exact at
  // small strain only.
  EXPECT_GT(lo, 0.98 * e0);
  EXPECT_LT(hi, 1.005 * e0);
  RecordProperty("energy_low", std::to_string(lo / e0));
  RecordProperty("period", std::to_string(T));
}

class UlsphSpinningPlate : public ::testing::TestWithParam<const char*> {};

// single: a search every step; dual: searches every advection step with the
// pair data formed again at every step's half-step positions.
TEST_P(UlsphSpinningPlate, KeepsAngularMomentumAndSettles) {
  const SceneDocument doc =
      test::load_config("spinning_plate_ulsph_2d.json", {std::string("solver.ulsph.time_stepping=") + GetParam()});
  const InitialParticles particles = generate_particles(doc.scene);
  auto solver = make_solver(doc.scene, particles, SolverOptions{});
  solver->initialize();
  const Spin s0 = spin_of(solver->snapshot());
  EXPECT_NEAR(s0.L / s0.I, 105.0, 1e-9);
  Spin early{0, 0};
  while (solver->time() < 0.2 * (1 - 1e-12)) {
    solver->limit_next_dt(0.2 - solver->time());
    solver->step();
    if (early.I == 0 && solver->time() >= 0.04) early = spin_of(solver->snapshot());
  }
  const Spin s1 = spin_of(solver->snapshot());
  EXPECT_NEAR(s1.L, s0.L, 0.005 * s0.L);
  EXPECT_NEAR(s1.I, early.I, 0.002 * early.I);  // no creep after the stretch
  EXPECT_NEAR(s1.I, 68.6, 0.01 * 68.6);
  EXPECT_NEAR(s1.L / s1.I, 101.9, 0.5);
}

INSTANTIATE_TEST_SUITE_P(Stepping, UlsphSpinningPlate, ::testing::Values("single", "dual"),
                         [](const auto& info) { return std::string(info.param); });

TEST(UlsphSpinningPlateTlsph, MethodsAgreeOnTheStretchedPlate) {
  // The same plate in TLSPH (neo-Hookean, GENOG): the same polar moment.
  const SceneDocument doc = test::load_config("spinning_plate_ulsph_2d.json",
                                              {"solver.method=tlsph", "solver.hourglass=genog", "solver.ulsph=null",
                                               "bodies.plate.material.model=neo_hookean", "solver.end_time=0.1"});
  const InitialParticles particles = generate_particles(doc.scene);
  auto solver = make_solver(doc.scene, particles, SolverOptions{});
  solver->initialize();
  while (solver->time() < 0.1 * (1 - 1e-12)) {
    solver->limit_next_dt(0.1 - solver->time());
    solver->step();
  }
  const Spin s = spin_of(solver->snapshot());
  EXPECT_NEAR(s.I, 68.6, 0.01 * 68.6);
  EXPECT_NEAR(s.L / s.I, 101.9, 0.5);
}

// The 2-D copper Taylor bar (configs/taylor_bar_ulsph_2d.json: J2, linear
// hardening, 227 m/s onto the wall of configs/taylor_bar_2d.json) against the
// TLSPH run of the same bar (measured: length 0.021157 m, bulge 0.010355 m,
// plastic strain 0.500 at the corner). ULSPH, radial return: 0.021809,
// 0.010485, 0.506. With the seed's rate removal (j2_return "seed") the
// corner's plastic strain is 0.067: the removed rate no longer drives it
// (theory.md, "J2").
TEST(UlsphTaylorBar, AgreesWithTlsph) {
  for (const char* j2 : {"radial", "seed"}) {
    SCOPED_TRACE(j2);
    auto t = test::run_config("taylor_bar_ulsph_2d.json", {std::string("solver.ulsph.j2_return=") + j2},
                              Precision::double_precision, 0, 100);
    const ProbeSample top = t.probes.back()[0], corner = t.probes.back()[1];
    if (std::string(j2) == "radial") {
      // Where the impact's 41.4 kJ/m went by 60 us (energies.csv `plastic`,
      // `damping`): measured 0.804 of it into plastic work, 0.273 taken by the
      // Riemann dissipation and the GNOG penalty; the balance ends 13.5 %
      // above the start (docs/theory.md, "ULSPH", Energies).
      const BodyEnergy &e0 = t.energies.front().bodies[0], &e1 = t.energies.back().bodies[0];
      EXPECT_NEAR(e1.plastic / e0.kinetic, 0.804, 0.02);
      EXPECT_NEAR(e1.damping / e0.kinetic, 0.273, 0.02);
      EXPECT_NEAR(e1.balance() / e0.balance(), 1.135, 0.02);
      EXPECT_NEAR(top.position[1], 0.021809, 0.003 * 0.021809);
      EXPECT_NEAR(top.position[1], 0.021157, 0.04 * 0.021157);
      EXPECT_NEAR(corner.position[0], 0.010355, 0.02 * 0.010355);
      EXPECT_NEAR(corner.plastic_strain, 0.500, 0.05 * 0.500);
    } else {
      EXPECT_LT(corner.plastic_strain, 0.2);
    }
  }
}

// Where the balance's excess comes from (issue 48; docs/theory.md, ULSPH
// "Energies"): solver.ulsph.energy_audit sums V tau : (L - L~) dt, the stress
// power through the corrected velocity gradient L (eq. 20) that the shear force
// of eq. 18, built on the uncorrected gradient L~, does not take from the
// motion. The balance moves by exactly that sum (measured on this bar: excess
// 0.1357 and audit 0.1362 of the impact energy), so the identity holds to 1 % of
// the impact energy whatever the size of the excess. The audit changes no
// result: the bar's top bit for bit.
TEST(UlsphTaylorBar, BalanceMovesByTheShearForcesMissingWork) {
  auto plain = test::run_config("taylor_bar_ulsph_2d.json", {}, Precision::double_precision, 0, 100);
  auto audit = test::run_config("taylor_bar_ulsph_2d.json", {"solver.ulsph.energy_audit=true"},
                                Precision::double_precision, 0, 100);
  ASSERT_EQ(plain.probes.size(), audit.probes.size());
  EXPECT_EQ(plain.probes.back()[0].position[1], audit.probes.back()[0].position[1]);
  const BodyEnergy &e0 = audit.energies.front().bodies[0], &e1 = audit.energies.back().bodies[0];
  EXPECT_EQ(e0.shear_mismatch, 0.0);
  EXPECT_NE(e1.shear_mismatch, 0.0);
  EXPECT_NEAR(e1.balance() - e0.balance(), e1.shear_mismatch, 0.01 * e0.balance());
  EXPECT_FALSE(plain.energies.back().with_audit);
  EXPECT_TRUE(audit.energies.back().with_audit);
}

// Tension failure (seed 002 section 5.9; tests/regression/scenes/pulled_bar_ulsph_2d.json):
// a strip pulled at 20 m/s from both ends. Measured at 2e-5 s: 204 of 240
// particles failed, none of them with p < 0; the least pressure of the intact
// ones is -4.5e7 Pa. Without failure_pressure the same strip carries tensions
// beyond the 2e8 Pa threshold.
TEST(UlsphFailure, FailedParticlesCarryNoTension) {
  auto t = test::run_config("scenes/pulled_bar_ulsph_2d.json", {});
  const Snapshot s = t.solver->snapshot();
  const auto* failed = s.field("failed");
  const auto* pressure = s.field("pressure");
  ASSERT_TRUE(failed && pressure);
  size_t count = 0;
  for (size_t i = 0; i < s.n; ++i)
    if ((*failed)[i] > 0) {
      ++count;
      EXPECT_GE((*pressure)[i], 0.0) << "particle " << s.id[i];
    }
  EXPECT_GT(count, s.n / 2);
  auto intact = test::run_config("scenes/pulled_bar_ulsph_2d.json", {"bodies.bar.material.failure_pressure=null"});
  const Snapshot si = intact.solver->snapshot();
  EXPECT_EQ(si.field("failed"), nullptr);
  double least = 0;
  for (double p : *si.field("pressure")) least = std::min(least, p);
  EXPECT_LT(least, -2e8);  // the tension that failed the particles above
}

// Colliding rubber rings (configs/colliding_rings_ulsph_2d.json, seed 002
// section 5.3) at dp = 2 mm, made asymmetric (the right ring lower by 10 mm
// and at half the speed) so that mirror symmetry cannot hide a momentum
// error: the rings meet by contact and part. Measured: momentum 9.03266 kept
// to 1e-14 in x and y; the left ring leaves at -0.294 of its initial
// momentum, the right one at +0.794 of it (from -0.5); the total (kinetic + stored)
// ends at 0.822 of the start (the Riemann dissipation; seed 002 ends its 2-D
// run at 0.861, docs/validation.md).
TEST(UlsphCollidingRings, PartKeepingMomentumToRoundOff) {
  auto t = test::run_config("colliding_rings_ulsph_2d.json",
                            {"constants.dp=0.002", "bodies.right.initial_velocity.x=-0.5*u_f*c0",
                             "bodies.right.geometry.circle.center=[\"gap/2\", 0.01]"},
                            Precision::double_precision, 0, 100);
  const EnergySample& e0 = t.energies.front();
  const EnergySample& e1 = t.energies.back();
  const double p0 = e0.bodies[0].momentum[0];
  EXPECT_NEAR(e0.momentum[0], 0.5 * p0, 1e-12 * p0);
  for (const EnergySample& e : t.energies) {
    EXPECT_NEAR(e.momentum[0], e0.momentum[0], 1e-12 * p0) << "t step " << &e - &t.energies[0];
    EXPECT_NEAR(e.momentum[1], 0.0, 1e-12 * p0);
  }
  EXPECT_NEAR(e1.bodies[0].momentum[0] / p0, -0.294, 0.03);
  EXPECT_NEAR(e1.bodies[1].momentum[0] / p0, 0.794, 0.03);
  // The contact moved 40 J/m from the left ring to the right one and, with
  // restitution 1, kept the rest (measured: -0.048 of 77.5 J/m).
  EXPECT_GT(e1.bodies[1].contact_work, 0.4 * (e0.kinetic + e0.strain));
  EXPECT_LT(std::abs(e1.bodies[0].contact_work + e1.bodies[1].contact_work), 2e-3 * (e0.kinetic + e0.strain));
  const double ratio = (e1.kinetic + e1.strain) / (e0.kinetic + e0.strain);
  EXPECT_NEAR(ratio, 0.822, 0.01);
  // The energy the Riemann dissipation and the GNOG penalty took accounts
  // for the loss: the balance moves by less than 1 % (measured +0.44 %).
  double balance0 = 0, balance1 = 0, taken = 0;
  for (size_t b = 0; b < 2; ++b) {
    balance0 += e0.bodies[b].balance();
    balance1 += e1.bodies[b].balance();
    taken += e1.bodies[b].damping;
  }
  EXPECT_NEAR(balance1 / balance0, 1.0, 0.01);
  EXPECT_GT(taken, 0.15 * balance0);
  RecordProperty("energy_ratio", std::to_string(ratio));
}

// The rings as shipped (dp = 2 mm, head-on) with the full Riemann dissipation
// and with the low-dissipation limiter of seed 002's ref. [38]
// (solver.ulsph.riemann_limiter = 3): the dissipation takes most of the
// loss. Measured: 0.798 of the total is left at 16 ms with the full
// dissipation, 0.915 with the limiter (seed 002: 0.861 at dp = 1 mm, relaxed
// particles; docs/validation.md). A negative eta is refused.
TEST(UlsphCollidingRings, RiemannLimiterTakesLessEnergy) {
  auto total_left = [](const std::vector<std::string>& sets) {
    auto t = test::run_config("colliding_rings_ulsph_2d.json", sets, Precision::double_precision, 0, 100);
    const EnergySample& e0 = t.energies.front();
    const EnergySample& e1 = t.energies.back();
    EXPECT_NEAR(e1.momentum[0], 0.0, 1e-12 * e0.bodies[0].momentum[0]);
    EXPECT_LT(e1.bodies[0].momentum[0], -0.7 * e0.bodies[0].momentum[0]);  // rebounded
    return (e1.kinetic + e1.strain) / (e0.kinetic + e0.strain);
  };
  EXPECT_NEAR(total_left({"constants.dp=0.002"}), 0.798, 0.01);
  EXPECT_NEAR(total_left({"constants.dp=0.002", "solver.ulsph.riemann_limiter=3"}), 0.915, 0.01);
  try {
    test::load_config("colliding_rings_ulsph_2d.json", {"solver.ulsph.riemann_limiter=-1"});
    ADD_FAILURE() << "a negative riemann_limiter was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("/solver/ulsph/riemann_limiter"), std::string::npos) << e.what();
  }
}

// Hollow balls (configs/colliding_balls_ulsph_3d.json, seed 002 section 5.4)
// at dp = 4 mm, asymmetric as the rings above: in 3-D the lattice of a sphere
// is not mirror-symmetric, and the forces divided by the half-step density
// while the pair data held the volumes of the step's start lost 2e-5 of the
// momentum in a collision. Measured since: round-off.
TEST(UlsphCollidingBalls, KeepMomentumToRoundOffIn3d) {
  for (const char* hourglass : {"gnog", "none"}) {
    SCOPED_TRACE(hourglass);
    auto t = test::run_config(
        "colliding_balls_ulsph_3d.json",
        {"constants.dp=0.004", "solver.end_time=0.003", std::string("solver.hourglass=") + hourglass,
         "bodies.right.initial_velocity.x=-0.5*u_f*c0", "bodies.right.geometry.sphere.center=[\"gap/2\", 0.01, 0.005]"},
        Precision::double_precision, 0, 20);
    const EnergySample& e0 = t.energies.front();
    const double p0 = e0.bodies[0].momentum[0];
    for (const EnergySample& e : t.energies)
      for (int a = 0; a < 3; ++a) EXPECT_NEAR(e.momentum[a], e0.momentum[a], 1e-12 * p0) << "axis " << a;
    // The balls have met: the left one has slowed down.
    EXPECT_LT(t.energies.back().bodies[0].momentum[0], 0.8 * p0);
  }
}

// Bending column 3-D (configs/bending_column_ulsph_3d.json, seed 002
// section 5.2) at H/dp = 6: the deepest point of the first swing of the top
// centre S. Measured: z = 4.042 m at 0.565 s; the TLSPH column (genog) at
// H/dp = 12 reaches 4.045 m at 0.555 s, at H/dp = 6 only 3.817 m at 0.590 s
// (scripts/validation/ulsph.py column; docs/validation.md).
TEST(UlsphBendingColumn, FirstSwingMatchesTheResolvedTlsphColumn) {
  auto t = test::run_config("bending_column_ulsph_3d.json", {"solver.end_time=0.7"});
  double z_min = 1e300, t_min = 0;
  for (size_t k = 0; k < t.time.size(); ++k)
    if (t.time[k] > 0.45 && t.probes[k][0].position[2] < z_min) z_min = t.probes[k][0].position[2], t_min = t.time[k];
  EXPECT_NEAR(z_min, 4.042, 0.01);
  EXPECT_NEAR(z_min, 4.045, 0.05) << "TLSPH, H/dp = 12";
  EXPECT_NEAR(t_min, 0.565, 0.005);
  EXPECT_NEAR(t_min, 0.555, 0.015) << "TLSPH, H/dp = 12";
}

// High-velocity impact (configs/projectile_impact_ulsph_2d.json, seed 002
// section 5.8) at dp = 0.4 mm: an aluminium disc at 3100 m/s perforates a
// 2 mm plate. Measured at 8 us: the projectile's particles move on at a mean
// 2475 m/s (2501 and 2499 at dp = 0.2 and 0.1 mm), the debris cloud's front
// is at x = 21.41 mm, the hole in the plate reaches |y| = 9.52 mm; momentum
// kept to round-off; the balance (kinetic, stored, plastic and the
// numerical forces' work) ends 0.9 % above the start
// (scripts/validation/ulsph.py projectile; docs/validation.md).
TEST(UlsphProjectile, PerforatesThePlate) {
  auto t =
      test::run_config("projectile_impact_ulsph_2d.json", {"constants.dp=0.0004"}, Precision::double_precision, 0, 50);
  const Snapshot s = t.solver->snapshot();
  double v_sum = 0, front = -1e300, hole = 1e300;
  size_t n_projectile = 0;
  for (size_t i = 0; i < s.n; ++i) {
    const double x = s.position[3 * i], y = s.position[3 * i + 1];
    front = std::max(front, x);
    if (s.body[i] == 0) {
      v_sum += s.velocity[3 * i];
      ++n_projectile;
    } else if (x > -0.0004 && x < 0.0024) {
      hole = std::min(hole, std::abs(y));
    }
  }
  EXPECT_NEAR(v_sum / double(n_projectile), 2475.0, 0.02 * 2475.0);
  EXPECT_NEAR(front, 0.02141, 0.0003);
  EXPECT_NEAR(hole, 0.00952, 0.0004);
  const EnergySample &e0 = t.energies.front(), &e1 = t.energies.back();
  const double p0 = e0.bodies[0].momentum[0];
  EXPECT_NEAR(e1.momentum[0], e0.momentum[0], 1e-12 * p0);
  EXPECT_NEAR(e1.momentum[1], 0.0, 1e-12 * p0);
  double b0 = 0, b1 = 0;
  for (size_t b = 0; b < 2; ++b) b0 += e0.bodies[b].balance(), b1 += e1.bodies[b].balance();
  EXPECT_NEAR(b1 / b0, 1.009, 0.005);
}

namespace {
// Whether the plate particles with |X| < 1 mm are joined to those with
// |X| > 8 mm (the clamped ends) by a chain of particles closer than `reach`
// now (X: reference x). Brute-force breadth-first search.
bool centre_joined_to_ends(const Snapshot& s, int body, double reach) {
  std::vector<size_t> plate;
  for (size_t i = 0; i < s.n; ++i)
    if (s.body[i] == body) plate.push_back(i);
  std::vector<char> seen(plate.size(), 0);
  std::vector<size_t> queue;
  auto X = [&](size_t k) { return s.position[3 * plate[k]] - s.displacement[3 * plate[k]]; };
  for (size_t k = 0; k < plate.size(); ++k)
    if (std::abs(X(k)) < 0.001) seen[k] = 1, queue.push_back(k);
  for (size_t q = 0; q < queue.size(); ++q) {
    const double* a = &s.position[3 * plate[queue[q]]];
    for (size_t k = 0; k < plate.size(); ++k) {
      if (seen[k]) continue;
      const double* b = &s.position[3 * plate[k]];
      const double d2 = (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]);
      if (d2 < reach * reach) {
        if (std::abs(X(k)) > 0.008) return true;
        seen[k] = 1;
        queue.push_back(k);
      }
    }
  }
  return false;
}
}  // namespace

// Striker pin fuse (configs/striker_pin_ulsph_3d.json, seed 002 section 5.9)
// at dp = 0.4 mm: at 400 m/s the pin cuts the plate's centre out along the
// grooves; at 200 m/s the plate bends and stays whole over the same 30 us
// (scripts/validation/ulsph.py pin; docs/validation.md).
TEST(UlsphStrikerPin, CutsThePlateAlongTheGrooves) {
  const double dp = 0.0004, reach = 2 * 1.3 * dp;
  for (const char* v0 : {"400", "200"}) {
    SCOPED_TRACE(v0);
    auto t = test::run_config("striker_pin_ulsph_3d.json", {"constants.dp=0.0004", std::string("constants.v0=") + v0});
    const Snapshot s = t.solver->snapshot();
    EXPECT_EQ(centre_joined_to_ends(s, 0, reach), std::string(v0) == "200");
    const auto* failed = s.field("failed");
    ASSERT_TRUE(failed);
    size_t n_failed = 0;
    for (size_t i = 0; i < s.n; ++i) n_failed += (*failed)[i] > 0 && s.body[i] == 0;
    EXPECT_GT(n_failed, 300u);
  }
}
