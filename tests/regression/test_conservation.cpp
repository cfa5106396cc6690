// Conservation and consistency of the TLSPH discretization on free bodies:
// a body at rest stays at rest, linear momentum is conserved to round-off
// (antisymmetric pair forces), and total energy is conserved by the
// position-based Verlet scheme without damping.
#include <gtest/gtest.h>

#include <cmath>

#include "scene_runner.hpp"

using namespace mfsd;
using test::run_config;

namespace {
std::string param_name(const ::testing::TestParamInfo<std::tuple<std::string, std::string>>& info) {
  std::string scene = std::get<0>(info.param);
  scene = scene.substr(scene.find('/') + 1);
  scene = scene.substr(0, scene.find('.'));
  return scene + "_" + std::get<1>(info.param);
}
}  // namespace

class AtRest : public ::testing::TestWithParam<std::tuple<std::string, std::string>> {};

// With the default force sums every variant leaves a body at rest untouched.
TEST_P(AtRest, BodyStaysAtRest) {
  const auto [scene, hourglass] = GetParam();
  auto t = run_config(scene, {"solver.hourglass=" + hourglass, "bodies.block.initial_velocity={}", "solver.end_time=1"},
                      Precision::double_precision, 200, 200);
  ASSERT_EQ(t.solver->steps(), 200);
  const EnergySample e = t.energies.back();
  // Round-off of the cancelling pair sums only (energy scale E V = 5000 J in 2-D, 200 J in 3-D;
  // measured 2e-15 J for laplacian, exactly 0 for none and genog).
  EXPECT_LT(e.kinetic + e.strain, 1e-12) << hourglass;
  EXPECT_LT(e.hourglass_max, 1e-12) << hourglass;
}
INSTANTIATE_TEST_SUITE_P(Variants, AtRest,
                         ::testing::Combine(::testing::Values("scenes/free_block_2d.json", "scenes/free_block_3d.json"),
                                            ::testing::Values("none", "laplacian", "genog")),
                         param_name);

// The papers' Laplacian form with B0 also in the remaining-stress sum (seed 003
// eq. 20 with eq. 28) is not in equilibrium at rest: B0 differs from I at the
// surface while the Laplacian shear sum (eq. 27) has no B0. This is why the
// default for `laplacian` leaves B0 out of the force sums (docs/theory.md).
TEST(AtRest, LaplacianWithCorrectionInForceSumsDeformsABodyAtRest) {
  auto t = run_config(
      "scenes/free_block_2d.json",
      {"solver.hourglass=laplacian", "solver.kernel_correction_in_force=true", "bodies.block.initial_velocity={}"},
      Precision::double_precision, 200, 200);
  EXPECT_GT(t.energies.back().strain, 1.0);  // J, from nothing
}

class FreeBody : public ::testing::TestWithParam<std::tuple<std::string, std::string>> {};

namespace {
// Largest |E(t) - E(0)| / E(0) of kinetic + strain energy; checks momentum on the way.
double energy_error(const std::string& scene, const std::string& hourglass, double cfl) {
  auto t = run_config(scene, {"solver.hourglass=" + hourglass, "constants.amp=2", "solver.cfl=" + std::to_string(cfl)},
                      Precision::double_precision, 0, 5);
  EXPECT_GT(t.energies.size(), 10u);
  const EnergySample& first = t.energies.front();
  double max_error = 0, max_strain = 0;
  for (const auto& e : t.energies) {
    for (int a = 0; a < 3; ++a)
      EXPECT_NEAR(e.momentum[a], first.momentum[a], 1e-11 * (1 + std::abs(first.momentum[a]))) << hourglass;
    max_error = std::max(max_error, std::abs(e.kinetic + e.strain - first.kinetic - first.strain));
    max_strain = std::max(max_strain, e.strain);
  }
  const double E0 = first.kinetic + first.strain;
  EXPECT_GT(max_strain, 0.2 * E0) << "the test must exchange energy";
  return max_error / E0;
}
}  // namespace

// Without damping: momentum to round-off; energy to the O(dt^2) error of the
// position-based Verlet scheme for the variational forms (none, genog: the
// correction stays inactive at these strains). Measured: 3.3e-4 -> 8.5e-5 (2-D),
// 1.3e-3 -> 3.3e-4 (3-D) from CFL 0.6 to 0.3.
TEST_P(FreeBody, ConservesMomentumAndEnergy) {
  const auto [scene, hourglass] = GetParam();
  const double e1 = energy_error(scene, hourglass, 0.6);
  if (hourglass == "laplacian") {
    // The Laplacian shear force (seed 003 eq. 27) is not the gradient of the
    // neo-Hookean energy used by the diagnostic: the two differ by about 1 %
    // (measured 0.8 % in 2-D, 1.5 % in 3-D), independent of dt.
    EXPECT_LT(e1, 0.025);
    return;
  }
  const double e2 = energy_error(scene, hourglass, 0.3);
  EXPECT_LT(e1, 2e-3);
  EXPECT_GT(e1 / e2, 3.0) << "energy error must fall as dt^2: " << e1 << " -> " << e2;
}
INSTANTIATE_TEST_SUITE_P(Variants, FreeBody,
                         ::testing::Combine(::testing::Values("scenes/free_block_2d.json", "scenes/free_block_3d.json"),
                                            ::testing::Values("none", "laplacian", "genog")),
                         param_name);
