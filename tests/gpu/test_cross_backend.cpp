// The same scene on the cpu and cuda backends agrees to round-off (design.md:
// "the most important GPU test"). Skips without a CUDA device unless
// MFSD_REQUIRE_GPU=1 (scripts/test.sh --gpu), which turns the skip into a failure.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "host/scene/particle_generator.hpp"
#include "host/scene/scene_reader.hpp"
#include "host/solver/solver.hpp"

using namespace mfsd;

namespace {

// The checkout the configs are read from: MFSD_SOURCE_DIR in the environment
// (a build run on another machine, scripts/gpu_check.sh), else the build's.
std::string source_dir() {
  const char* v = std::getenv("MFSD_SOURCE_DIR");
  return v && *v ? std::string(v) : std::string(MFSD_SOURCE_DIR);
}

bool gpu_required() {
  const char* v = std::getenv("MFSD_REQUIRE_GPU");
  return v && std::string(v) == "1";
}

#define MFSD_REQUIRE_CUDA_DEVICE()                                                                          \
  do {                                                                                                      \
    if (!cuda_compiled() || cuda_device_count() == 0) {                                                     \
      if (gpu_required()) FAIL() << "MFSD_REQUIRE_GPU=1 but no usable CUDA device: " << cuda_device_name(); \
      GTEST_SKIP() << "no CUDA device (" << cuda_device_name() << ")";                                      \
    }                                                                                                       \
  } while (0)

std::vector<ProbeSample> run(const std::string& config, const std::vector<std::string>& sets,
                             const std::string& backend, Precision precision, long steps) {
  const SceneDocument doc = load_scene_file(source_dir() + "/configs/" + config, sets);
  const InitialParticles particles = generate_particles(doc.scene);
  SolverOptions o;
  o.backend = backend;
  o.precision = precision;
  auto solver = make_solver(doc.scene, particles, o);
  solver->initialize();
  for (long s = 0; s < steps; ++s) solver->step();
  return solver->probes();
}

void compare(const std::string& config, const std::vector<std::string>& sets, Precision precision, double tol) {
  const auto cpu = run(config, sets, "cpu", precision, 300);
  const auto gpu = run(config, sets, "cuda", precision, 300);
  ASSERT_EQ(cpu.size(), gpu.size());
  for (size_t k = 0; k < cpu.size(); ++k)
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(cpu[k].displacement[a], gpu[k].displacement[a], tol * (1e-3 + std::abs(cpu[k].displacement[a])));
      EXPECT_NEAR(cpu[k].velocity[a], gpu[k].velocity[a], tol * (1e-3 + std::abs(cpu[k].velocity[a])));
    }
  for (size_t k = 0; k < cpu.size(); ++k) EXPECT_NEAR(cpu[k].phase_field, gpu[k].phase_field, tol);
}

}  // namespace

TEST(CrossBackend, OscillatingPlateDouble) {
  MFSD_REQUIRE_CUDA_DEVICE();
  for (const char* hg : {"none", "laplacian", "genog"})
    compare("oscillating_plate_2d.json", {std::string("solver.hourglass=") + hg}, Precision::double_precision, 1e-9);
}

TEST(CrossBackend, TwistingColumnDouble) {
  MFSD_REQUIRE_CUDA_DEVICE();
  compare("twisting_column_3d.json", {"constants.H_over_dp=4"}, Precision::double_precision, 1e-9);
}

TEST(CrossBackend, BendingColumnFloat) {
  MFSD_REQUIRE_CUDA_DEVICE();
  compare("bending_column_3d.json", {"constants.H_over_dp=4"}, Precision::single_precision, 1e-3);
}

TEST(CrossBackend, ConditionsAndLoadsDouble) {
  // Velocity conditions and loads evaluate their expressions with the device
  // interpreter: the seed 001 cantilever (whole-body conditions) and the
  // large-deformation beam (a ramped traction), coarse.
  MFSD_REQUIRE_CUDA_DEVICE();
  compare("cantilever_beam_2d.json", {"constants.dp=0.002"}, Precision::double_precision, 1e-9);
  compare("cantilever_large_deformation_3d.json", {"constants.dp=0.002", "constants.Tmax=0.0005"},
          Precision::double_precision, 1e-9);
}

TEST(CrossBackend, TaylorBarsDouble) {
  // J2 return mapping, plastic state, wall contact and the deformed time step
  // (its inverse-stretch reduction) on the device: 2-D and round 3-D bars, coarse.
  MFSD_REQUIRE_CUDA_DEVICE();
  compare("taylor_bar_2d.json", {"constants.H_over_dp=10"}, Precision::double_precision, 1e-7);
  compare("taylor_bar_3d_round.json", {"constants.R_over_dp=4"}, Precision::double_precision, 1e-7);
}

TEST(CrossBackend, ContactAndMandelReturnDouble) {
  // Contact on the device (the hash search, pair forces, rigid-body markers
  // placed by their motion, self-contact) and seed 001's return: the flyer
  // plates, the octopus (floor, punch, self-contact) and seed 001's bar, coarse.
  MFSD_REQUIRE_CUDA_DEVICE();
  compare("flyer_plate_2d.json", {"constants.L_over_dp=20"}, Precision::double_precision, 1e-7);
  compare("oobleck_octopus_2d.json", {"constants.dp=0.01"}, Precision::double_precision, 1e-7);
  compare("taylor_bar_seed001_3d.json", {"constants.R_over_dp=4"}, Precision::double_precision, 1e-7);
}

TEST(CrossBackend, RelaxationDouble) {
  // The coloured Gauss-Seidel sweeps of the dynamic relaxation (one thread
  // per cell, the same random choice of steps), with held particles (the
  // necking bar's pulled ends) in 2-D and a clamp in 3-D.
  MFSD_REQUIRE_CUDA_DEVICE();
  compare("necking_bar_2d.json", {"constants.H_over_dp=10", "solver.relaxation={\"viscosity\": 1e4}"},
          Precision::double_precision, 1e-7);
  compare("twisting_column_3d.json", {"constants.H_over_dp=4", "solver.relaxation={\"viscosity\": 100}"},
          Precision::double_precision, 1e-9);
}

TEST(CrossBackend, FractureDouble) {
  // Phase-field fracture on the device: the split stress, the exact phase-field
  // update, the notch mask and the crack-tip reduction; the crack-branching
  // plate at dp = 0.5 mm (eps0 = dp/4, the coarsest allowed), 300 steps (27 us:
  // the crack starts at 22 us).
  MFSD_REQUIRE_CUDA_DEVICE();
  compare("crack_branching_2d.json", {"constants.dp=0.5e-3"}, Precision::double_precision, 1e-7);
}
