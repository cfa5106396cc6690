// The seed 001 scenes of configs/ written with velocity conditions, loads and
// measure planes: every scene in configs/ is valid, and the cantilever beam at
// a reduced resolution keeps the numbers measured when it was written
// (docs/validation.md, scripts/validation/cantilever_beam.py --quick).
#include <gtest/gtest.h>

#include <filesystem>

#include "scene_runner.hpp"

using namespace mfsd;
using test::run_config;

TEST(Configs, EveryShippedSceneIsValid) {
  int n = 0;
  for (auto& f : std::filesystem::directory_iterator(std::string(MFSD_SOURCE_DIR) + "/configs")) {
    if (f.path().extension() != ".json") continue;
    SCOPED_TRACE(f.path().string());
    // Coarse spacings keep the particle generation quick for the big scenes.
    const std::string name = f.path().filename().string();
    std::vector<std::string> sets;
    if (name == "cantilever_plate_3d.json") sets = {"constants.dp=0.004"};
    EXPECT_NO_THROW(generate_particles(load_scene_file(f.path().string(), sets).scene));
    ++n;
  }
  EXPECT_GE(n, 7);
  // The tutorial's finished scene (docs/tutorial.md).
  EXPECT_NO_THROW(
      generate_particles(load_scene_file(std::string(MFSD_SOURCE_DIR) + "/docs/tutorial/beam.json", {}).scene));
}

TEST(CantileverBeam2d, FirstSwingAtDx1mm) {
  // dx = 1 mm (4,060 particles): the tip's first maximum and the time it
  // crosses zero again (half a period). Measured 23.335 mm and a period of
  // 0.2610 s over 0.3 s; Euler-Bernoulli with the plane-strain modulus gives
  // 23.057 mm and 0.2542 s.
  auto t = run_config("cantilever_beam_2d.json",
                      {"constants.dp=0.001", "solver.end_time=0.14", "output.probe_interval=0.0005"});
  double umax = 0, tmax = 0, t_half = 0;
  for (size_t k = 1; k < t.time.size(); ++k) {
    const double u = t.probes[k][0].displacement[1], u_prev = t.probes[k - 1][0].displacement[1];
    if (u > umax) umax = u, tmax = t.time[k];
    if (t_half == 0 && tmax > 0 && u_prev > 0 && u <= 0)
      t_half = t.time[k - 1] + (t.time[k] - t.time[k - 1]) * u_prev / (u_prev - u);
  }
  EXPECT_NEAR(umax, 0.023335, 0.0001);
  EXPECT_NEAR(2 * t_half, 0.2610, 0.003);
  EXPECT_NEAR(tmax, 0.2610 / 4, 0.004);
}
