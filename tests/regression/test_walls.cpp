// Rigid frictionless walls (scene key walls[]): a free elastic block thrown
// at a wall never crosses it (particle centres stay dp/2 away), the wall's
// reactions add up to the momentum it removes, and the energy balance closes
// to second order in dt.
#include <gtest/gtest.h>

#include <cmath>

#include "host/scene/scene_error.hpp"
#include "scene_runner.hpp"

using namespace mfsd;

namespace {

struct WallRun {
  double min_gap = 1e300, impulse_x = 0, momentum_x0 = 0, momentum_x = 0, balance_drift = 0;
};

// free_block_2d moves at +0.3 m/s towards a wall at x = 0.101 (normal -x).
WallRun throw_at_wall(double cfl) {
  const SceneDocument doc = test::load_config("scenes/free_block_2d.json",
                                              {R"J(walls=[{"name": "stop", "point": [0.101, 0], "normal": [-1, 0]}])J",
                                               "solver.hourglass=genog", "solver.cfl=" + std::to_string(cfl)});
  const InitialParticles particles = generate_particles(doc.scene);
  auto solver = make_solver(doc.scene, particles, SolverOptions{});
  solver->initialize();
  WallRun r;
  r.momentum_x0 = solver->energies().momentum[0];
  const double b0 = solver->energies().bodies[0].balance();
  double t_prev = 0;
  while (solver->time() < 0.02 * (1 - 1e-12)) {
    solver->limit_next_dt(0.02 - solver->time());
    solver->step();
    r.impulse_x += solver->boundary_forces().at(0).force[0] * (solver->time() - t_prev);
    t_prev = solver->time();
    const Snapshot s = solver->snapshot();
    for (size_t i = 0; i < s.n; ++i) r.min_gap = std::min(r.min_gap, 0.101 - s.position[3 * i]);
    r.balance_drift = std::max(r.balance_drift, std::abs(solver->energies().bodies[0].balance() - b0));
  }
  r.momentum_x = solver->energies().momentum[0];
  return r;
}

}  // namespace

TEST(Walls, StopABlockWithoutPenetrationAndConserveMomentumAndEnergy) {
  const WallRun a = throw_at_wall(0.6), b = throw_at_wall(0.3);
  EXPECT_GE(a.min_gap, 0.5 * 0.0025 - 1e-12);  // centres stay dp/2 from the wall
  EXPECT_NEAR(a.momentum_x, a.momentum_x0 + a.impulse_x, 1e-12);
  EXPECT_LT(a.momentum_x, 0.0);  // the elastic block bounces back
  // Balance error: 8.8e-4 J at CFL 0.6, 1.7e-4 at 0.3 (measured): second order.
  EXPECT_GT(a.balance_drift / b.balance_drift, 3.0);
  EXPECT_LT(a.balance_drift, 2e-3);
}

TEST(Walls, BadWallsAreErrors) {
  auto error = [](const std::string& walls) {
    try {
      generate_particles(test::load_config("scenes/free_block_2d.json", {"walls=" + walls}).scene);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error(R"J([{"point": [0, 0], "normal": [0, 0]}])J").find("/walls/0/normal"), std::string::npos);
  EXPECT_NE(error(R"J([{"point": [0, 0], "normal": [0, 1], "bodies": ["x"]}])J").find("/walls/0/bodies/0"),
            std::string::npos);
}
