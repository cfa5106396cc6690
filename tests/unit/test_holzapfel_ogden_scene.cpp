// Holzapfel-Ogden scenes (issue 21): what the reader and the particle
// generator make of the material block (fibres normalised per particle, the
// active tension k V_m, the moduli), and the input errors, each naming its
// JSON path: non-positive a or b, negative anisotropic constants, a missing
// fibre or sheet, directions that are zero, non-finite or not orthogonal,
// both or neither of bulk_modulus and poisson_ratio, the Laplacian form.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "host/scene/body_properties.hpp"
#include "host/scene/particle_generator.hpp"
#include "host/scene/scene_error.hpp"
#include "host/scene/scene_reader.hpp"

using namespace mfsd;

namespace {

// A 3-D cube of 4 x 4 x 4 particles with the given material keys (after "model").
std::string cube(const std::string& material, const std::string& hourglass = "genog") {
  return R"({"name": "ho", "dimension": 3, "solver": {"end_time": 0.01, "hourglass": ")" + hourglass + R"("},
  "bodies": [{"name": "muscle", "spacing": 0.25, "geometry": {"box": {"min": [0, 0, 0], "max": [1, 1, 1]}},
              "material": {"model": "holzapfel_ogden", "density": 1.0, )" +
         material + "}}]}";
}

InitialParticles particles(const std::string& text) {
  return generate_particles(load_scene_text(text, "test", {}).scene);
}

// The SceneError's message (path and expectation), or "" when none is thrown.
std::string error_of(const std::string& text) {
  try {
    particles(text);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(HolzapfelOgdenScene, FibresPerParticleAndActiveTension) {
  const InitialParticles P = particles(cube(R"("a": 0.059, "b": 8.023, "a_f": 18.472, "bulk_modulus": 450,
      "fibre": {"x": "1 + x0", "y": "y0", "z": 0}, "sheet": {"x": 0, "y": 0, "z": 1},
      "active_stress": {"potential": "30 * x0", "tension_per_potential": -0.5, "ramp_time": 1})"));
  ASSERT_EQ(P.size(), 64u);
  ASSERT_EQ(P.fibre.size(), 64u);
  for (size_t i = 0; i < P.size(); ++i) {
    const auto& x = P.position[i];
    const double n = std::hypot(1 + x[0], x[1]);
    EXPECT_NEAR(P.fibre[i][0], (1 + x[0]) / n, 1e-14);
    EXPECT_NEAR(P.fibre[i][1], x[1] / n, 1e-14);
    EXPECT_NEAR(P.sheet[i][2], 1.0, 1e-14);
    EXPECT_NEAR(P.active_tension[i], -15.0 * x[0], 1e-12);
  }
}

TEST(HolzapfelOgdenScene, ModuliFromBulkModulusOrPoissonRatio) {
  const Scene s = load_scene_text(cube(R"("a": 2.0, "b": 1.0, "a_f": 3.0, "fibre": {"x": 1, "y": 0, "z": 0},
      "poisson_ratio": 0.45)"),
                                  "test", {})
                      .scene;
  const HolzapfelOgdenSpec& h = s.bodies[0].material.holzapfel_ogden;
  EXPECT_NEAR(h.lambda, 2 * 2.0 * 0.45 / (1 - 0.9), 1e-12);  // lambda = 2 a nu / (1 - 2 nu)
  const BodyProperties p = body_properties(s.bodies[0], s.solver, 3);
  EXPECT_NEAR(p.G, 2.0, 1e-12);
  EXPECT_NEAR(p.K, h.lambda + 2 * 2.0 * 1.0 + 2 * 2.0 / 3, 1e-12);  // tangent bulk lambda + 2ab + 2a/3
  EXPECT_NEAR(p.c0, std::sqrt(p.K + 4 * 3.0), 1e-12);               // bulk c0, + 4 a_f along the fibre
  const Scene k = load_scene_text(cube(R"("a": 0.059, "b": 8.023, "bulk_modulus": 450)"), "test", {}).scene;
  EXPECT_NEAR(k.bodies[0].material.holzapfel_ogden.lambda, 450 - 2 * 0.059 / 3, 1e-12);
}

TEST(HolzapfelOgdenScene, InputErrorsNameTheirPath) {
  const std::string K = R"("bulk_modulus": 450)";
  struct Case {
    std::string material, path, hourglass = "genog";
  };
  const Case cases[] = {
      {R"("a": 0, "b": 1, )" + K, "/bodies/0/material/a"},
      {R"("a": -1, "b": 1, )" + K, "/bodies/0/material/a"},
      {R"("a": 1, "b": 0, )" + K, "/bodies/0/material/b"},
      {R"("a": 1, "b": 1, "a_f": -2, "fibre": {"x": 1}, )" + K, "/bodies/0/material/a_f"},
      {R"("a": 1, "b": 1, "a_f": 2, "b_f": -1, "fibre": {"x": 1}, )" + K, "/bodies/0/material/b_f"},
      {R"("a": 1, "b": 1, "a_f": 2, )" + K, "/bodies/0/material/fibre"},
      {R"("a": 1, "b": 1, "a_s": 2, "fibre": {"x": 1}, )" + K, "/bodies/0/material/sheet"},
      {R"("a": 1, "b": 1, "active_stress": {"potential": "x0", "tension_per_potential": 1}, )" + K,
       "/bodies/0/material/fibre"},
      {R"("a": 1, "b": 1, "a_f": 2, "fibre": {"x": 0, "y": 0, "z": 0}, )" + K, "/bodies/0/material/fibre"},
      {R"J("a": 1, "b": 1, "a_f": 2, "fibre": {"x": "x0 - x0", "y": 0, "z": "if(x0 < 0.5, 1, 0)"}, )J" + K,
       "/bodies/0/material/fibre"},
      {R"J("a": 1, "b": 1, "a_f": 2, "fibre": {"x": "1 / (x0 - x0)"}, )J" + K, "/bodies/0/material/fibre"},
      {R"("a": 1, "b": 1, "a_s": 2, "fibre": {"x": 1}, "sheet": {"x": 1, "y": 1}, )" + K, "/bodies/0/material/sheet"},
      {R"("a": 1, "b": 1, "bulk_modulus": 450, "poisson_ratio": 0.4)", "/bodies/0/material"},
      {R"("a": 1, "b": 1)", "/bodies/0/material"},
      {R"("a": 1, "b": 1, "bulk_modulus": 0.5)", "/bodies/0/material/bulk_modulus"},
      {R"("a": 1, "b": 1, "youngs_modulus": 1e6, )" + K, "/bodies/0/material"},
      {R"("a": 1, "b": 1, "active_stress": {"potential": "30 * w0", "tension_per_potential": 1}, "fibre": {"x": 1}, )" + K,
       "/bodies/0/material/active_stress/potential"},
      {R"("a": 1, "b": 1, )" + K, "/solver/hourglass", "laplacian"},
  };
  for (const Case& c : cases) {
    const std::string msg = error_of(cube(c.material, c.hourglass));
    EXPECT_NE(msg.find(c.path), std::string::npos) << c.material << "\n  -> " << (msg.empty() ? "(no error)" : msg);
  }
}
