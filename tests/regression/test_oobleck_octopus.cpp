// The viscoplastic showcase (configs/oobleck_octopus_2d.json) at dp = 1 cm
// to 0.6 s: the rigid punch touches the octopus, no particle tunnels into the
// rigid floor, and once the oobleck has slumped to rest the floor carries its
// weight (rigid-body contact forces add up to the body force).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "scene_runner.hpp"

using namespace mfsd;

TEST(OobleckOctopus, FloorCarriesTheWeightAndKeepsTheParticlesOut) {
  const SceneDocument doc = test::load_config("oobleck_octopus_2d.json", {"constants.dp=0.01", "solver.end_time=0.6"});
  const InitialParticles particles = generate_particles(doc.scene);
  auto solver = make_solver(doc.scene, particles, SolverOptions{});
  solver->initialize();
  const double weight = 1000 * 9.81 * double(particles.size()) * 1e-4;
  double punch_peak = 0, lowest = 1e300, floor_sum = 0, late_time = 0, t_prev = 0;
  while (solver->time() < 0.6 * (1 - 1e-12)) {
    solver->limit_next_dt(0.6 - solver->time());
    solver->step();
    const auto f = solver->boundary_forces();  // floor, punch
    punch_peak = std::max(punch_peak, -f[1].force[1]);
    const double dt = solver->time() - t_prev;
    t_prev = solver->time();
    if (solver->time() > 0.5) floor_sum += f[0].force[1] * dt, late_time += dt;
    if (solver->steps() % 25) continue;
    const Snapshot s = solver->snapshot();
    for (size_t i = 0; i < s.n; ++i) lowest = std::min(lowest, s.position[3 * i + 1]);
  }
  const double floor_mean = floor_sum / late_time;
  std::printf("punch peak %.1f N/m, floor force over the last 0.1 s %.1f N/m (weight %.1f), lowest centre %.3f dp\n",
              punch_peak, floor_mean, weight, lowest / 0.01);
  EXPECT_GT(punch_peak, 100.0);
  EXPECT_NEAR(floor_mean, weight, 0.05 * weight);  // measured +1.7 %
  EXPECT_GT(lowest, 0.0);                          // centres stay above the floor face
}
