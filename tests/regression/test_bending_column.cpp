// Bending column 3D at the CI resolution H/dp = 6 (configs/bending_column_3d.json).
// Observable: z of S, the centre of the top face (mean of the particles within
// dp of it). From scripts/validation/columns.py bending (docs/validation.md):
//
//   first minimum of z(S)     H/dp = 4   H/dp = 6   H/dp = 12 (genog)
//   z [m]                     3.383      3.817      4.045
//   t [s]                     0.655      0.590      0.555
//
// The H/dp = 6 value may differ from the H/dp = 12 one by the measured
// 0.23 m; the test allows 1.5 times that (and the same for the time), and
// checks that hourglass control does not change the v0 = 10 m/s answer
// (genog, laplacian and none agree to 0.002 m at H/dp = 12).
// Hard case v0 = 20 m/s: peak of the mean hourglass indicator over 1 s,
// genog 0.019 (H/dp 6) and 0.013 (12), none 0.206 (6) and 0.216 (12).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "scene_runner.hpp"

using namespace mfsd;

namespace {
struct Minimum {
  double z, t;
};
Minimum first_minimum(const test::Trace& tr) {
  Minimum m{1e9, 0};
  for (size_t k = 0; k < tr.time.size(); ++k)
    if (tr.time[k] < 0.8 && tr.probes[k][0].position[2] < m.z) m = {tr.probes[k][0].position[2], tr.time[k]};
  return m;
}
}  // namespace

TEST(BendingColumn, FirstMinimumOfTopCentreHeight) {
  for (const char* hg : {"genog", "laplacian", "none"}) {
    auto t = test::run_config("bending_column_3d.json",
                              {"constants.H_over_dp=6", "solver.end_time=0.8", std::string("solver.hourglass=") + hg});
    const Minimum m = first_minimum(t);
    EXPECT_NEAR(m.z, 4.045, 1.5 * 0.23) << hg;
    EXPECT_NEAR(m.t, 0.555, 1.5 * 0.035) << hg;
    if (std::string(hg) == "genog") {
      EXPECT_NEAR(m.z, 3.817, 0.01);  // the study's H/dp = 6 value
    }
  }
}

TEST(BendingColumn, HardCaseStaysOrderlyOnlyWithHourglassControl) {
  auto peak = [](const char* hg) {
    auto t = test::run_config(
        "bending_column_3d.json",
        {"constants.H_over_dp=6", "constants.v0=20", "solver.end_time=1.0", std::string("solver.hourglass=") + hg},
        Precision::double_precision, 0, 20);
    double p = 0;
    for (const auto& e : t.energies) p = std::max(p, e.hourglass_mean);
    return p;
  };
  EXPECT_LT(peak("genog"), 0.05);
  EXPECT_GT(peak("none"), 0.1);
}
