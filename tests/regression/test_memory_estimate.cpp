// The memory estimate that refuses scenes too big for the machine
// (host/solver/memory_estimate.hpp) against the state the solver then holds
// (timing.json bytes_per_particle), for each method, precision and pair-loop
// storage: it must not be below it (a run it lets through would not fit) nor
// far above it (it would refuse a run that fits: issue 24, item 6, the 2 M
// particle plate in 4 GB).
#include <gtest/gtest.h>

#include "host/solver/memory_estimate.hpp"
#include "scene_runner.hpp"

using namespace mfsd;

namespace {

struct Case {
  std::string config;
  std::vector<std::string> sets;
  SolverOptions::PairLoop loop = SolverOptions::PairLoop::automatic;
  Precision precision = Precision::double_precision;
  SolverOptions::PairPrecision pairs = SolverOptions::PairPrecision::same;
};

TEST(MemoryEstimate, FollowsTheStateTheSolverHolds) {
  const std::vector<Case> cases = {
      {"oscillating_plate_2d.json", {"constants.H_over_dp=10"}},
      {"oscillating_plate_2d.json", {"constants.H_over_dp=10"}, SolverOptions::PairLoop::full},
      {"oscillating_plate_2d.json",
       {"constants.H_over_dp=10"},
       SolverOptions::PairLoop::automatic,
       Precision::single_precision},
      {"bending_column_3d.json", {"constants.H_over_dp=6"}},
      {"bending_column_3d.json", {"constants.H_over_dp=6"}, SolverOptions::PairLoop::full},
      {"bending_column_3d.json",
       {"constants.H_over_dp=6"},
       SolverOptions::PairLoop::automatic,
       Precision::single_precision},
      {"cantilever_plate_3d.json", {"constants.dp=4e-3"}},
      {"cantilever_plate_3d.json",
       {"constants.dp=4e-3"},
       SolverOptions::PairLoop::automatic,
       Precision::double_precision,
       SolverOptions::PairPrecision::single},
      {"taylor_bar_3d_round.json", {"constants.R_over_dp=4"}},
      {"crack_branching_2d.json", {"constants.dp=1e-3", "constants.eps0=1e-3"}},
      {"oscillating_plate_ulsph_2d.json", {"constants.H_over_dp=10"}},
      {"bending_column_ulsph_3d.json", {"constants.H_over_dp=6"}},
  };
  for (const Case& c : cases) {
    const SceneDocument doc = test::load_config(c.config, c.sets);
    const InitialParticles particles = generate_particles(doc.scene);
    SolverOptions o;
    o.precision = c.precision;
    o.pair_loop = c.loop;
    o.pair_precision = c.pairs;
    auto solver = make_solver(doc.scene, particles, o);
    solver->initialize();
    const SetupReport r = solver->setup_report();
    std::vector<long> counts;
    for (const auto& b : particles.body_range) counts.push_back(b.end - b.begin);
    const MemoryEstimate e = estimate_run_memory(doc.scene, counts, o);
    const double ratio = e.bytes_per_particle / r.bytes_per_particle;
    std::printf("%-34s %-5s %-6s %7.0f B/particle, estimate %7.0f (%.2f), neighbours %.1f / %.1f\n", c.config.c_str(),
                r.pair_loop.c_str(), to_string(c.precision), r.bytes_per_particle, e.bytes_per_particle, ratio,
                r.mean_neighbors, e.neighbors);
    EXPECT_GE(ratio, 1.0) << c.config << " " << r.pair_loop;
    // Above it by the surface particles' missing neighbours (these coarse
    // scenes are mostly surface; 1.04 on the 2 M particle plate).
    EXPECT_LE(ratio, 1.4) << c.config << " " << r.pair_loop;
  }
}

}  // namespace

// The seed 001 cantilever plate at its resolution (1,934,400 particles): the
// estimate lets it run in 4 GiB (its measured peak: 3.88e9 bytes,
// docs/performance.md "Memory per particle").
TEST(MemoryEstimate, TheTwoMillionParticlePlateIsLetThroughIn4GiB) {
  const SceneDocument doc = test::load_config("cantilever_plate_3d.json", {});
  const InitialParticles particles = generate_particles(doc.scene);
  ASSERT_EQ(particles.size(), 1934400u);
  const MemoryEstimate e = estimate_run_memory(doc.scene, {long(particles.size())}, SolverOptions{});
  std::printf("estimate: %.3g bytes, %.0f B/particle of state at %.0f neighbours\n", e.bytes, e.bytes_per_particle,
              e.neighbors);
  EXPECT_LT(e.bytes, 4.0 * 1024 * 1024 * 1024);
  EXPECT_GT(e.bytes, 3.88e9);  // not below the measured peak
}
