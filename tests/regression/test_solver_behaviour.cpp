// Solver-level behaviour: free fall under gravity (analytic), invariance of
// the results under particle reordering (round-off) and thread count
// (bitwise), single against double precision, and the numerical-failure
// report.
#include <gtest/gtest.h>

#include <cmath>

#include "host/solver/numerical_failure.hpp"
#include "scene_runner.hpp"

using namespace mfsd;
using test::run_config;

TEST(Gravity, FreeFallIsExactAndStressFree) {
  // A body with uniform initial velocity in uniform gravity moves rigidly:
  // u = v0 t + g t^2 / 2 at every particle, F stays I.
  auto t = run_config("scenes/free_block_2d.json",
                      {"solver.gravity=[0,-9.81]", "bodies.block.initial_velocity={\"x\": 0.3}"},
                      Precision::double_precision, 0, 50);
  const double T = t.time.back();
  const ProbeSample& p = t.probes.back().front();
  EXPECT_NEAR(p.displacement[0], 0.3 * T, 1e-12);
  EXPECT_NEAR(p.displacement[1], -0.5 * 9.81 * T * T, 1e-12);
  EXPECT_NEAR(p.velocity[1], -9.81 * T, 1e-12);
  const EnergySample e = t.solver->energies();
  EXPECT_LT(e.strain, 1e-12);
  EXPECT_NEAR(e.kinetic, 0.5 * 1000 * 0.1 * 0.05 * (0.09 + std::pow(9.81 * T, 2)), 1e-9);
}

TEST(Reordering, ChangesResultsOnlyByRoundOff) {
  const std::vector<std::string> base = {"solver.end_time=0.05"};
  for (const char* hg : {"none", "laplacian", "genog"}) {
    auto sets = base;
    sets.push_back(std::string("solver.hourglass=") + hg);
    auto a = run_config("oscillating_plate_2d.json", sets);
    sets.push_back("solver.reorder=false");
    auto b = run_config("oscillating_plate_2d.json", sets);
    ASSERT_EQ(a.time.size(), b.time.size()) << hg;
    const ProbeSample &pa = a.probes.back()[0], &pb = b.probes.back()[0];
    for (int k = 0; k < 2; ++k) {
      EXPECT_NEAR(pa.displacement[k], pb.displacement[k], 1e-13) << hg;
      EXPECT_NEAR(pa.velocity[k], pb.velocity[k], 1e-11) << hg;
    }
    EXPECT_GT(std::abs(pa.displacement[1]), 0.05) << "the tip must have moved";
  }
}

// The full gather sums every particle's pairs in one order whatever the
// thread count; the half-pair loop (the CPU default) sums a particle's pairs
// in an order that depends on the thread blocks, so its runs are identical
// for one thread count and agree to round-off across counts.
TEST(Threads, ResultsAreIdenticalForOneAndTwoThreads) {
  const std::vector<std::string> sets = {"constants.H_over_dp=4", "solver.end_time=0.02"};
  const auto full = SolverOptions::PairLoop::full, half = SolverOptions::PairLoop::half;
  auto a = run_config("twisting_column_3d.json", sets, Precision::double_precision, 0, 0, 1, full);
  auto b = run_config("twisting_column_3d.json", sets, Precision::double_precision, 0, 0, 2, full);
  ASSERT_EQ(a.time.size(), b.time.size());
  for (int k = 0; k < 3; ++k) EXPECT_EQ(a.probes.back()[0].displacement[k], b.probes.back()[0].displacement[k]);
  auto c = run_config("twisting_column_3d.json", sets, Precision::double_precision, 0, 0, 2, half);
  auto d = run_config("twisting_column_3d.json", sets, Precision::double_precision, 0, 0, 2, half);
  auto e = run_config("twisting_column_3d.json", sets, Precision::double_precision, 0, 0, 1, half);
  EXPECT_EQ(c.setup.pair_loop, "half");
  ASSERT_EQ(c.time.size(), a.time.size());
  for (int k = 0; k < 3; ++k) {
    const double u = a.probes.back()[0].displacement[k];
    EXPECT_EQ(c.probes.back()[0].displacement[k], d.probes.back()[0].displacement[k]);
    EXPECT_NEAR(c.probes.back()[0].displacement[k], u, 1e-12 * (1 + std::abs(u)));
    EXPECT_NEAR(e.probes.back()[0].displacement[k], u, 1e-12 * (1 + std::abs(u)));
  }
}

TEST(Precision, FloatFollowsDouble) {
  // Tip history of the plate in float and double over a quarter period.
  auto d = run_config("oscillating_plate_2d.json", {"solver.end_time=0.07"}, Precision::double_precision);
  auto f = run_config("oscillating_plate_2d.json", {"solver.end_time=0.07"}, Precision::single_precision);
  const double amplitude = std::abs(d.probes.back()[0].displacement[1]);
  EXPECT_GT(amplitude, 0.05);
  EXPECT_NEAR(f.probes.back()[0].displacement[1], d.probes.back()[0].displacement[1], 1e-4 * amplitude);
}

TEST(NumericalFailure, InvertedParticlesStopTheRunNamingParticleAndField) {
  // A violent compression inverts the block within a few steps: J < 0 makes
  // the 3-D stress NaN, which the step's health check reports.
  try {
    run_config("scenes/free_block_3d.json", {"bodies.block.initial_velocity={\"x\": \"-2e4 * x0\"}", "solver.cfl=1"});
    FAIL() << "the run should have stopped";
  } catch (const NumericalFailure& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("of body 'block'"), std::string::npos) << m;
    EXPECT_TRUE(m.find("is not finite") != std::string::npos || m.find("left the scene bounds") != std::string::npos)
        << m;
    EXPECT_GE(e.particle_id(), 0);
  }
}
