// Phase-field fracture on real scenes: the crack-branching plate of seed 001
// (section 4.2.1) at dp = 0.5 mm (16,000 particles) initiates at the notch,
// runs and branches, with its momentum conserved to round-off and its energy
// balance closed by the released energy. The asserted windows come from the
// resolution study
// (scripts/validation/crack_branching.py, docs/validation.md).
#include <gtest/gtest.h>

#include <cmath>

#include "scene_runner.hpp"

using namespace mfsd;

namespace {
// The scene's solver on 2 threads, initialized.
std::unique_ptr<Solver> start(const SceneDocument& doc) {
  SolverOptions o;
  o.threads = 2;
  auto solver = make_solver(doc.scene, generate_particles(doc.scene), o);
  solver->initialize();
  return solver;
}
}  // namespace

TEST(Fracture, CrackBranchingInitiatesRunsAndBranches) {
  const SceneDocument doc = test::load_config("crack_branching_2d.json", {"constants.dp=0.5e-3"});
  auto solver = start(doc);
  const double end = doc.scene.solver.end_time, notch = 0.05 + 0.5e-3;  // the notch starts dp outside
  double initiation = -1, impulse = 0;
  const EnergySample e0 = solver->energies();
  while (solver->time() < end * (1 - 1e-12)) {
    solver->limit_next_dt(end - solver->time());
    const double dt = solver->next_dt();
    solver->step();
    impulse += dt * 2 * 1e6 * 0.1;  // |traction| x length, both faces
    if (initiation < 0) {
      const auto tips = solver->crack_tips();
      ASSERT_EQ(tips.size(), 1u);
      if (tips[0].broken && tips[0].length - notch >= 0.5e-3) initiation = solver->time();
    }
  }
  // Initiation (0.5 mm of growth beyond the notch): 22.3 us at dp = 0.5 mm,
  // converging towards the seed's ~14 us with finer spacing (docs/validation.md).
  EXPECT_GT(initiation, 18e-6);
  EXPECT_LT(initiation, 26e-6);

  const EnergySample e = solver->energies();
  ASSERT_EQ(e.bodies.size(), 1u);
  const BodyEnergy& b = e.bodies[0];
  // Momentum: the two tractions cancel; the pair forces conserve it exactly.
  EXPECT_LT(std::abs(e.momentum[0]), 1e-12 * impulse);
  EXPECT_LT(std::abs(e.momentum[1]), 1e-12 * impulse);
  // Energy: kinetic + strain + released + damping - work of the loads stays put
  // (measured drift 7.6e-4 of the work).
  EXPECT_LT(std::abs(b.balance() - e0.bodies[0].balance()), 2e-3 * b.external_work);
  // Crack surface energy at 80 us: 0.355 J/m at dp = 0.5 mm; 0.350-0.363 J/m
  // over the resolution study down to the seed's dx.
  EXPECT_GT(b.crack_surface, 0.31);
  EXPECT_LT(b.crack_surface, 0.40);
  EXPECT_GT(b.fracture, b.crack_surface);  // what is released also feeds the phase field's damping

  // Branches: broken particles (s < 0.5) beyond x = 70 mm on both sides of the line.
  const Snapshot s = solver->snapshot();
  const auto* phase = s.field("phase_field");
  ASSERT_NE(phase, nullptr);
  int above = 0, below = 0, on_line_far = 0;
  for (size_t i = 0; i < s.n; ++i) {
    if ((*phase)[i] >= 0.5) continue;
    const double X = s.position[3 * i] - s.displacement[3 * i], Y = s.position[3 * i + 1] - s.displacement[3 * i + 1];
    if (X < 0.07) continue;
    if (Y > 0.02 + 3e-3) ++above;
    if (Y < 0.02 - 3e-3) ++below;
    if (std::abs(Y - 0.02) < 1e-3 && X > 0.075) ++on_line_far;
  }
  EXPECT_GT(above, 10);
  EXPECT_GT(below, 10);
  EXPECT_EQ(on_line_far, 0) << "the crack should have branched, not run straight on";
}

// A bar with an edge notch pulled by tractions on its ends: the crack starts at
// the notch's tip and runs across the bar there. The phase field is restricted
// (s >= 0.9999) next to the loaded ends, and that is checked too. Measured:
// the crack starts at 8 us and reaches the far edge at 12 us with every broken
// particle within 3 mm of the notch's line until the last millimetre of the
// ligament goes; as it breaks, two spots on the far edge 4.4 mm either side of
// the line break too (the kink of the separating halves), so the check of
// the path stops there.
TEST(Fracture, NotchedBarOpensAtItsNotch) {
  const SceneDocument doc = test::load_config("scenes/notched_bar_2d.json", {});
  auto solver = start(doc);
  const double end = 25e-6, mid = 0.02;
  bool started = false, crossed = false;
  while (solver->time() < end && !crossed) {
    solver->step();
    if (solver->steps() % 10 != 0) continue;
    const Snapshot s = solver->snapshot();
    const auto* phase = s.field("phase_field");
    ASSERT_NE(phase, nullptr);
    int broken = 0, elsewhere = 0;
    double reach = 0;
    for (size_t i = 0; i < s.n; ++i) {
      if ((*phase)[i] >= 0.5) continue;
      ++broken;
      const double X = s.position[3 * i] - s.displacement[3 * i], Y = s.position[3 * i + 1] - s.displacement[3 * i + 1];
      if (!started) {  // the first broken particles sit at the notch's tip
        EXPECT_NEAR(X, mid, 1e-3);
        EXPECT_NEAR(Y, 3e-3, 1e-3);
      }
      if (std::abs(X - mid) > 3e-3) ++elsewhere;
      if (X < 2e-3 || X > 0.038) ADD_FAILURE() << "s below the restriction at X = " << X;
      reach = std::max(reach, Y);
    }
    started = started || broken > 0;
    crossed = reach > 9.5e-3;
    if (reach < 9e-3) {
      EXPECT_EQ(elsewhere, 0) << "at t = " << solver->time();
    }
  }
  EXPECT_TRUE(started);
  EXPECT_TRUE(crossed) << "the crack should have crossed the bar by 25 us";
}

// Kalthoff-Winkler at dp = 0.5 mm (40,250 particles): the crack leaves the
// notch's tip at about 70 degrees to the notch. Study
// (scripts/validation/kalthoff_winkler.py): initiation 25.8 us and 67.8
// degrees at this spacing, 25.0 us / 68.3 at 0.25 mm, 22.8 us / 68.4 at the
// seed's 0.125 mm (seed: about 23 us and 70 degrees).
TEST(Fracture, KalthoffWinklerCrackRunsAtSeventyDegrees) {
  const SceneDocument doc = test::load_config("kalthoff_winkler_2d.json", {"constants.dp=0.5e-3"});
  auto solver = start(doc);
  const double end = doc.scene.solver.end_time, notch = 0.05 + 0.5e-3;
  double initiation = -1;
  while (solver->time() < end * (1 - 1e-12)) {
    solver->limit_next_dt(end - solver->time());
    solver->step();
    if (initiation < 0) {
      const auto tips = solver->crack_tips();
      if (tips[0].broken && tips[0].length - notch >= 0.5e-3) initiation = solver->time();
    }
  }
  EXPECT_GT(initiation, 22e-6);
  EXPECT_LT(initiation, 30e-6);
  // The angle of the broken particles more than 2 mm from the tip (orthogonal fit).
  const Snapshot s = solver->snapshot();
  const auto* phase = s.field("phase_field");
  ASSERT_NE(phase, nullptr);
  double n = 0, mx = 0, my = 0, sxx = 0, syy = 0, sxy = 0;
  for (size_t i = 0; i < s.n; ++i) {
    const double X = s.position[3 * i] - s.displacement[3 * i], Y = s.position[3 * i + 1] - s.displacement[3 * i + 1];
    if ((*phase)[i] >= 0.5 || Y <= 0.0256 || std::hypot(X - 0.05, Y - 0.0256) <= 2e-3) continue;
    n += 1, mx += X, my += Y, sxx += X * X, syy += Y * Y, sxy += X * Y;
  }
  ASSERT_GT(n, 50);
  mx /= n, my /= n;
  sxx = sxx / n - mx * mx, syy = syy / n - my * my, sxy = sxy / n - mx * my;
  double angle = 0.5 * std::atan2(2 * sxy, sxx - syy) * 180 / M_PI;
  if (angle < 0) angle += 180;
  EXPECT_GT(angle, 62);
  EXPECT_LT(angle, 74);
}
