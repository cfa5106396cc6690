// Boundary conditions and loads (scene keys velocity_conditions[] and
// loads[]): each load type on a free block against its analytic impulse
// (internal forces conserve momentum to round-off, so the momentum is the
// impulse of the loads), time windows, velocity conditions and their
// reactions, clamp reactions in equilibrium, the energy balance, initial
// displacement fields, selections and the errors users see.
#include <gtest/gtest.h>

#include <cmath>

#include "host/scene/scene_error.hpp"
#include "host/solver/numerical_failure.hpp"
#include "scene_runner.hpp"

using namespace mfsd;
using test::run_config;

namespace {

// free_block_2d: 0.1 x 0.05 m, rho0 1000 (mass 5 kg per metre of depth),
// 40 x 20 particles at dp = 2.5 mm, undamped, initial velocity (0.3, 0).
constexpr double kMass = 1000 * 0.1 * 0.05;
constexpr double kVx0 = 0.3;

const BoundaryForceSample& force_of(const std::vector<BoundaryForceSample>& f, const std::string& name) {
  for (auto& s : f)
    if (s.name == name) return s;
  throw std::runtime_error("no boundary force named " + name);
}

}  // namespace

TEST(Loads, PointForceImpulseIsExact) {
  // F = (2, -3) N shared by the particles of a corner region: the momentum
  // grows by F dt every step, so P(T) = P(0) + F T to round-off.
  auto t = run_config("scenes/free_block_2d.json",
                      {R"J(loads=[{"name": "pull", "body": "block", "type": "point",
                          "region": {"box": {"min": [0.09, 0.04], "max": [0.1, 0.05]}}, "x": 2, "y": "-3"}])J",
                       "solver.hourglass=genog"},
                      Precision::double_precision, 0, 1);
  const double T = t.time.back();
  const EnergySample e = t.solver->energies();
  EXPECT_NEAR(e.momentum[0], kMass * kVx0 + 2 * T, 1e-11);
  EXPECT_NEAR(e.momentum[1], -3 * T, 1e-11);
  const auto f = force_of(t.solver->boundary_forces(), "pull");
  EXPECT_NEAR(f.force[0], 2, 1e-12);
  EXPECT_NEAR(f.force[1], -3, 1e-12);
  // Work-energy balance: E_k + E_s - W_ext stays at its initial value to the
  // time-integration error (second order in dt; small against the work).
  const double e0 = t.energies.front().bodies[0].balance(), e1 = e.bodies[0].balance();
  EXPECT_GT(e.bodies[0].external_work, 1e-3);
  EXPECT_LT(std::abs(e1 - e0), 1e-4 * e.bodies[0].external_work);  // measured 2e-6
}

TEST(Loads, TractionActsOnTheSurfaceLayerOnly) {
  // 1000 Pa in x on the right face: the selection holds two layers, of which
  // the 20 particles exposing +x carry dp x 1 m each: 1000 * 0.05 = 50 N.
  // Without "face", every surface particle of the selection carries it: also
  // the two of the inner layer on the top and bottom faces (55 N).
  const std::string load =
      R"J(loads=[{"name": "face", "body": "block", "type": "traction", "where": "x0 > 0.095", "x": 1000)J";
  for (const auto& [face, total] :
       {std::pair<std::string, double>{R"J(, "face": "+x"}])J", 50.0}, std::pair<std::string, double>{"}]", 55.0}}) {
    auto t = run_config("scenes/free_block_2d.json", {load + face}, Precision::double_precision, 0, 0);
    EXPECT_NEAR(force_of(t.solver->boundary_forces(), "face").force[0], total, 1e-9) << face;
    EXPECT_NEAR(t.solver->energies().momentum[0], kMass * kVx0 + total * t.time.back(), 1e-9) << face;
  }
}

TEST(Loads, AccelerationActsLikeGravity) {
  auto a =
      run_config("scenes/free_block_2d.json", {R"J(loads=[{"body": "block", "type": "acceleration", "y": -9.81}])J"});
  auto g = run_config("scenes/free_block_2d.json", {"solver.gravity=[0,-9.81]"});
  ASSERT_EQ(a.time.size(), g.time.size());
  const ProbeSample &pa = a.probes.back()[0], &pg = g.probes.back()[0];
  EXPECT_NEAR(pa.displacement[1], pg.displacement[1], 1e-14);
  EXPECT_NEAR(pa.displacement[1], -0.5 * 9.81 * a.time.back() * a.time.back(), 1e-12);
  EXPECT_NEAR(a.solver->energies().momentum[1], -kMass * 9.81 * a.time.back(), 1e-10);
}

TEST(Loads, TimeWindowBoundsTheImpulse) {
  // Active for t + dt/2 in [0.005, 0.012]: the impulse is F times the
  // duration to within one step at each end.
  auto t = run_config("scenes/free_block_2d.json",
                      {R"J(loads=[{"body": "block", "type": "point", "y": 4, "t_start": 0.005, "t_end": 0.012}])J"},
                      Precision::double_precision, 0, 0);
  double dt_max = 0;
  for (size_t k = 1; k < t.time.size(); ++k) dt_max = std::max(dt_max, t.time[k] - t.time[k - 1]);
  EXPECT_NEAR(t.solver->energies().momentum[1], 4 * 0.007, 4 * dt_max);
  EXPECT_EQ(force_of(t.solver->boundary_forces(), "load0").force[1], 0.0);  // inactive at the end
}

TEST(VelocityConditions, PrescribeVelocityAndReportTheReaction) {
  // The left layer moves at vx = 0.5 sin(200 t), vy = 0; the rest is free.
  // Those particles follow the prescribed motion exactly, and the work of
  // the reaction is what the block receives: E_k + E_s - W_bc is constant.
  auto t = run_config("scenes/free_block_2d.json",
                      {R"J(velocity_conditions=[{"name": "drive", "body": "block", "where": "x0 < 0.0025",
                          "x": "0.5 * sin(200 * t)", "y": 0}])J",
                       "bodies.block.initial_velocity={\"x\": 0}", "solver.hourglass=genog",
                       "probes=[{\"name\": \"left\", \"point\": [0, 0.025], \"fields\": [\"displacement\", "
                       "\"velocity\"]}]"},
                      Precision::double_precision, 0, 1);
  const double T = t.time.back();
  const ProbeSample& p = t.probes.back()[0];
  EXPECT_NEAR(p.velocity[0], 0.5 * std::sin(200 * T), 1e-12);
  EXPECT_EQ(p.velocity[1], 0.0);
  // u = sum of dt v at the step ends (trapezoidal in the Verlet scheme): the
  // exact integral 0.5 (1 - cos 200 T) / 200 to O(dt^2).
  EXPECT_NEAR(p.displacement[0], 0.5 * (1 - std::cos(200 * T)) / 200, 1e-6);
  const EnergySample e = t.solver->energies();
  const double w = e.bodies[0].boundary_work;
  EXPECT_GT(std::abs(w), 1e-4);
  EXPECT_LT(std::abs(e.bodies[0].balance() - t.energies.front().bodies[0].balance()),
            5e-4 * std::abs(w));  // measured 5e-5
  EXPECT_NE(force_of(t.solver->boundary_forces(), "drive").force[0], 0.0);
}

TEST(VelocityConditions, SkipLeavesTheSeedsInitialVelocityFree) {
  // seed 001 Fig. 8 style: the condition sets the velocity at t = 0 only
  // ("if(t <= 0, ..., skip)"), so it acts as an initial condition.
  auto t = run_config("scenes/free_block_2d.json",
                      {R"J(velocity_conditions=[{"body": "block", "y": "if(t <= 0, 0.2, skip)"}])J",
                       "bodies.block.initial_velocity={\"x\": 0}"},
                      Precision::double_precision, 0, 0);
  EXPECT_NEAR(t.solver->energies().momentum[1], kMass * 0.2, 1e-12);
  EXPECT_NEAR(t.probes.back()[0].displacement[1], 0.2 * t.time.back(), 1e-12);
}

TEST(Clamps, ReactionIsTheMomentumTheClampRemoves) {
  // A block clamped on its left, under gravity and a point load: every step
  // the clamp removes m v from its particles, so P(T) = P(0) + (M g + F) T
  // + sum_n R_n dt_n to round-off. In the damped motion the time-averaged
  // reaction tends to -(M g + F).
  const SceneDocument doc = test::load_config(
      "scenes/free_block_2d.json",
      {"solver.gravity=[0,-9.81]", "bodies.block.initial_velocity={\"x\": 0}", "solver.damping={\"factor\": 1}",
       "solver.end_time=0.05", "solver.hourglass=genog",
       R"J(clamps=[{"name": "wall", "body": "block", "region": {"box": {"min": [0, 0], "max": [0.005, 0.05]}}}])J",
       R"J(loads=[{"name": "tip", "body": "block", "type": "point", "where": "x0 > 0.0975", "y": -2}])J"});
  const InitialParticles particles = generate_particles(doc.scene);
  auto solver = make_solver(doc.scene, particles, SolverOptions{});
  solver->initialize();
  double impulse[2] = {0, 0}, t_prev = 0;
  while (solver->time() < 0.05 * (1 - 1e-12)) {
    solver->limit_next_dt(0.05 - solver->time());
    solver->step();
    const double dt = solver->time() - t_prev;
    t_prev = solver->time();
    const auto f = force_of(solver->boundary_forces(), "wall");
    for (int a = 0; a < 2; ++a) impulse[a] += f.force[a] * dt;
  }
  const double T = solver->time();
  const EnergySample e = solver->energies();
  EXPECT_NEAR(e.momentum[0], impulse[0], 1e-11);
  EXPECT_NEAR(e.momentum[1], -(kMass * 9.81 + 2) * T + impulse[1], 1e-10);
  // Average reaction over the run: within 15 % of the static value 51.05 N.
  EXPECT_NEAR(impulse[1] / T, kMass * 9.81 + 2, 0.15 * (kMass * 9.81 + 2));
}

TEST(InitialDisplacement, GivesTheDeformationGradient) {
  // u0 = (0.01 x0, -0.003 y0): F = diag(1.01, 0.997) exactly (a linear field
  // and the corrected gradient), so J = 1.01 * 0.997 at every particle.
  auto t = run_config("scenes/free_block_2d.json",
                      {"bodies.block.initial_displacement={\"x\": \"0.01 * x0\", \"y\": \"-0.003 * y0\"}",
                       "bodies.block.initial_velocity={\"x\": 0}",
                       "probes=[{\"name\": \"c\", \"point\": [0.05, 0.025], \"fields\": [\"position\", "
                       "\"displacement\", \"J\"]}, {\"name\": \"corner\", \"point\": [0, 0], \"fields\": [\"J\"]}]"},
                      Precision::double_precision, 1, 0);
  const ProbeSample& c = t.probes.front()[0];
  const double X = c.position[0] - c.displacement[0], Y = c.position[1] - c.displacement[1];
  EXPECT_NEAR(c.displacement[0], 0.01 * X, 1e-15);
  EXPECT_NEAR(c.displacement[1], -0.003 * Y, 1e-15);
  EXPECT_NEAR(c.jacobian, 1.01 * 0.997, 1e-12);
  EXPECT_NEAR(t.probes.front()[1].jacobian, 1.01 * 0.997, 1e-12);
  EXPECT_GT(t.solver->energies().strain, 0.0);
}

TEST(Selections, ErrorsNameTheCondition) {
  auto expect_error = [](const std::string& set, const std::string& text) {
    try {
      run_config("scenes/free_block_2d.json", {set}, Precision::double_precision, 1);
      ADD_FAILURE() << "no error for " << set;
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
  };
  expect_error(R"J(loads=[{"body": "block", "type": "point", "where": "x0 > 1", "x": 1}])J", "/loads/0");
  expect_error(R"J(loads=[{"body": "block", "type": "point", "where": "q > 1", "x": 1}])J", "/loads/0/where");
  expect_error(R"J(loads=[{"body": "block", "type": "point", "x": "1 +"}])J", "/loads/0/x");
  expect_error(R"J(loads=[{"body": "block", "type": "point"}])J", "/loads/0");
  expect_error(R"J(loads=[{"body": "nobody", "type": "point", "x": 1}])J", "/loads/0/body");
  expect_error(R"J(loads=[{"body": "block", "type": "point", "face": "+x", "x": 1}])J", "/loads/0/face");
  expect_error(R"J(loads=[{"body": "block", "type": "traction", "face": "+z", "x": 1}])J", "/loads/0/face");
  expect_error(R"J(loads=[{"body": "block", "type": "pressure", "x": 1}])J", "/loads/0/type");
  expect_error(R"J(velocity_conditions=[{"body": "block", "x": 1, "t_start": 2, "t_end": 1}])J",
               "/velocity_conditions/0/t_end");
  expect_error(R"J(velocity_conditions=[{"body": "block", "x": 1, "region": {"box": {"min": [0, 0], "max": [1, 1]}},
                  "where": "1"}])J",
               "/velocity_conditions/0");
}

TEST(Loads, RunTimeExpressionErrorsStopTheRunNamingTheParticle) {
  const std::string m = test::numerical_failure_message(
      "scenes/free_block_2d.json",
      {R"J(loads=[{"name": "bad", "body": "block", "type": "acceleration", "y": "sqrt(0.001 - t)"}])J"});
  EXPECT_NE(m.find("load 'bad' component y"), std::string::npos) << m;
  EXPECT_NE(m.find("sqrt"), std::string::npos) << m;
  EXPECT_NE(m.find("x0 = ("), std::string::npos) << m;
}
