// Reference maps (bodies[].reference_map, particle_generator.cpp): the
// lattice points move to X = map(x0) and each volume scales by the map's
// Jacobian, so the particles fill the mapped shape; a map that folds is an
// input error naming the particle.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "host/scene/particle_generator.hpp"
#include "host/scene/scene_error.hpp"
#include "host/scene/scene_reader.hpp"

using namespace mfsd;

namespace {

InitialParticles particles(const std::string& map) {
  const std::string text = R"({
  "name": "mapped", "dimension": 2,
  "solver": {"end_time": 1},
  "bodies": [{"name": "bar", "spacing": 0.01, "geometry": {"box": {"min": [-0.5, -0.05], "max": [0.5, 0.05]}},
              "reference_map": )" +
                           map + R"(,
              "material": {"model": "neo_hookean", "density": 1000, "youngs_modulus": 1e6, "poisson_ratio": 0.3}}]
})";
  return generate_particles(load_scene_text(text, "test", {}).scene);
}

double total_volume(const InitialParticles& P) {
  double v = 0;
  for (double x : P.volume) v += x;
  return v;
}

}  // namespace

TEST(ReferenceMap, TaperKeepsTheMappedArea) {
  // The necking bar's taper: height 0.1 (1 - 0.018 (1 - |x|/0.5)); area
  // 0.1 (1 - 0.009) = 0.0991, exact for the volume sum since the map is
  // linear in y and piecewise linear in x.
  const InitialParticles P = particles(R"J({"y": "y0 * (1 - 0.018 * max(0, 1 - abs(x0) / 0.5))"})J");
  EXPECT_NEAR(total_volume(P), 0.1 * (1 - 0.009), 1e-4 * 0.1);
  double top_centre = 0, top_end = 0;
  for (size_t i = 0; i < P.size(); ++i) {
    const auto& x = P.position[i];
    if (std::abs(x[0] - 0.005) < 1e-9) top_centre = std::max(top_centre, x[1]);
    if (std::abs(x[0] - 0.495) < 1e-9) top_end = std::max(top_end, x[1]);
  }
  EXPECT_NEAR(top_centre, 0.045 * (1 - 0.018 * (1 - 0.01)), 1e-12);
  EXPECT_NEAR(top_end, 0.045 * (1 - 0.018 * 0.01), 1e-12);
  // The identity map changes nothing.
  EXPECT_NEAR(total_volume(particles(R"J({"x": "x0"})J")), 0.1, 1e-12);
}

TEST(ReferenceMap, ShearAndStretchScaleTheVolumes) {
  const InitialParticles P = particles(R"J({"x": "2 * x0 + 0.3 * y0", "y": "y0"})J");
  EXPECT_NEAR(total_volume(P), 0.2, 1e-12);  // det = 2
}

TEST(ReferenceMap, FoldingMapIsRefused) {
  try {
    particles(R"J({"x": "x0 * x0"})J");  // det = 2 x0 <= 0 for x0 <= 0
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("/bodies/0/reference_map"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("keeps every particle's volume positive"), std::string::npos) << e.what();
  }
}
