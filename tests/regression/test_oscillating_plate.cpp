// Oscillating plate 2D at the CI resolution H/dp = 10 (seed 000 section 5.1,
// seed 003 section 4.1; configs/oscillating_plate_2d.json), nu = 0.3,
// v_f = 0.05. The tolerances come from the convergence study
// (scripts/validation/oscillating_plate.py convergence, docs/validation.md):
//
//   H/dp        10       20       40       seed (H/dp = 40)
//   genog       0.29469  0.28539  0.28185  0.28201 (seed 000 Table 1)
//   laplacian   0.29209  0.28610  0.28208  0.28166 (seed 003 Table 1)
//
// 1. Physics: at H/dp = 10 the period may differ from the seed value by the
//    discretization error the study measured between H/dp = 10 and 40
//    (4.56 % genog, 3.55 % laplacian) plus the 2 % target.
// 2. Regression: the period equals the study's H/dp = 10 value to 0.3 %
//    (the fit over 0.62 s instead of 1 s changes it by 0.02 % at H/dp = 40).
#include <gtest/gtest.h>

#include <cmath>

#include "scene_runner.hpp"

using namespace mfsd;

namespace {
struct Case {
  const char* hourglass;
  double study_T10, study_T40, seed;
};

double tip_period(const test::Trace& t) {
  std::vector<double> y;
  for (const auto& p : t.probes) y.push_back(p[0].position[1]);
  return test::oscillation_period(t.time, y);
}
}  // namespace

class OscillatingPlate : public ::testing::TestWithParam<Case> {};

TEST_P(OscillatingPlate, PeriodAtCiResolution) {
  const Case c = GetParam();
  auto t = test::run_config("oscillating_plate_2d.json",
                            {std::string("solver.hourglass=") + c.hourglass, "constants.H_over_dp=10",
                             "constants.vf=0.05", "bodies.plate.material.poisson_ratio=0.3", "solver.end_time=0.62"});
  const double T = tip_period(t);
  const double discretization = c.study_T10 / c.study_T40 - 1;
  EXPECT_LT(std::abs(T / c.seed - 1), discretization + 0.02) << c.hourglass << ": T = " << T;
  EXPECT_NEAR(T, c.study_T10, 0.003 * c.study_T10) << c.hourglass;
  RecordProperty("period", std::to_string(T));
}

INSTANTIATE_TEST_SUITE_P(Variants, OscillatingPlate,
                         ::testing::Values(Case{"genog", 0.29469, 0.28185, 0.28201},
                                           Case{"laplacian", 0.29209, 0.28208, 0.28166}),
                         [](const auto& info) { return std::string(info.param.hourglass); });
