// Measure planes (seed 001 Fig. 7): which particles a plane holds, their mean
// displacement and total force in a rigid motion with an analytic answer,
// and the errors for bad planes.
#include <gtest/gtest.h>

#include "host/scene/scene_error.hpp"
#include "scene_runner.hpp"

using namespace mfsd;
using test::run_config;

TEST(MeasurePlanes, RigidAccelerationGivesMassTimesAcceleration) {
  // A free block under a uniform acceleration load moves rigidly (no
  // stress): the right-face layer (20 particles of 1000 * dp^2 = 6.25 g)
  // carries f = m a, and its mean displacement is v0 t + a t^2 / 2.
  const SceneDocument doc =
      test::load_config("scenes/free_block_2d.json",
                        {R"J(loads=[{"body": "block", "type": "acceleration", "x": 2, "y": -5}])J",
                         R"J(measure_planes=[{"name": "right", "points": [[0.09875, 0], [0.09875, 0.05]]}])J"});
  const InitialParticles particles = generate_particles(doc.scene);
  ASSERT_EQ(particles.measure_particles.size(), 1u);
  EXPECT_EQ(particles.measure_particles[0].size(), 20u);
  auto solver = make_solver(doc.scene, particles, SolverOptions{});
  solver->initialize();
  for (int k = 0; k < 40; ++k) solver->step();
  const double t = solver->time(), m = 20 * 1000 * 0.0025 * 0.0025;
  const MeasureSample s = solver->measures().at(0);
  EXPECT_NEAR(s.force[0], m * 2, 1e-12);
  EXPECT_NEAR(s.force[1], -m * 5, 1e-12);
  EXPECT_NEAR(s.displacement[0], 0.3 * t + 0.5 * 2 * t * t, 1e-13);
  EXPECT_NEAR(s.displacement[1], -0.5 * 5 * t * t, 1e-13);
}

TEST(MeasurePlanes, RigidAccelerationInRkpm) {
  // The same in semi-Lagrangian RKPM (the measure planes are the platform's):
  // a uniform body force gives f_ext_I = M_I b (rkpm.md 3.3), so the block
  // moves rigidly, and with `mass: nodal` (M_I = m_I) the layer carries
  // f = m a as above. With the row-sum mass (default) the motion is the same
  // and the force is sum M_I a over the layer: a surface node's row-sum
  // mass differs from rho dp^2 (measured 1.160 m a: the surface layer's
  // kernels reach into the interior's mass; checked as a range).
  for (const char* mass : {"nodal", "row_sum"}) {
    const SceneDocument doc =
        test::load_config("scenes/free_block_2d.json",
                          {"solver.method=rkpm", "solver.hourglass=null", "solver.damping=null",
                           "bodies.block.material.model=linear_elastic", std::string("solver.rkpm.mass=") + mass,
                           R"J(loads=[{"body": "block", "type": "acceleration", "x": 2, "y": -5}])J",
                           R"J(measure_planes=[{"name": "right", "points": [[0.09875, 0], [0.09875, 0.05]]}])J"});
    const InitialParticles particles = generate_particles(doc.scene);
    ASSERT_EQ(particles.measure_particles.at(0).size(), 20u);
    auto solver = make_solver(doc.scene, particles, SolverOptions{});
    solver->initialize();
    for (int k = 0; k < 40; ++k) solver->step();
    const double t = solver->time(), m = 20 * 1000 * 0.0025 * 0.0025;
    const MeasureSample s = solver->measures().at(0);
    std::printf("RKPM, mass %s: layer force (%.6g, %.6g) N/m = (%.6f, %.6f) m a\n", mass, s.force[0], s.force[1],
                s.force[0] / (2 * m), s.force[1] / (-5 * m));
    EXPECT_NEAR(s.displacement[0], 0.3 * t + 0.5 * 2 * t * t, 1e-12);
    EXPECT_NEAR(s.displacement[1], -0.5 * 5 * t * t, 1e-12);
    if (std::string(mass) == "nodal") {
      EXPECT_NEAR(s.force[0], m * 2, 1e-12);
      EXPECT_NEAR(s.force[1], -m * 5, 1e-12);
    } else {
      EXPECT_NEAR(s.force[1] / s.force[0], -2.5, 1e-9);  // f = (sum M_I) a: parallel to a
      EXPECT_GT(s.force[0], 1.1 * m * 2);
      EXPECT_LT(s.force[0], 1.2 * m * 2);
    }
  }
}

TEST(MeasurePlanes, QuadrilateralSelectsTheFaceLayer3d) {
  // The top face z = 0.04 of the 3-D block (20 x 10 particles at dp = 5 mm);
  // a quadrilateral over half of it holds half of them.
  auto count = [](const std::string& points) {
    const SceneDocument doc = test::load_config("scenes/free_block_3d.json",
                                                {R"J(measure_planes=[{"name": "top", "points": )J" + points + "}]"});
    return generate_particles(doc.scene).measure_particles.at(0).size();
  };
  EXPECT_EQ(count("[[0, 0, 0.0375], [0.1, 0, 0.0375], [0.1, 0.05, 0.0375], [0, 0.05, 0.0375]]"), 200u);
  EXPECT_EQ(count("[[0, 0, 0.0375], [0.05, 0, 0.0375], [0.05, 0.05, 0.0375], [0, 0.05, 0.0375]]"), 100u);
  // Corners given clockwise (normal -z) hold the same particles.
  EXPECT_EQ(count("[[0, 0.05, 0.0375], [0.05, 0.05, 0.0375], [0.05, 0, 0.0375], [0, 0, 0.0375]]"), 100u);
}

TEST(MeasurePlanes, BadPlanesAreErrors) {
  auto expect_error = [](const std::string& scene, const std::string& planes, const std::string& text) {
    try {
      generate_particles(test::load_config(scene, {"measure_planes=" + planes}).scene);
      ADD_FAILURE() << "no error for " << planes;
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
  };
  expect_error("scenes/free_block_2d.json", R"J([{"name": "far", "points": [[1, 0], [1, 1]]}])J", "/measure_planes/0");
  expect_error("scenes/free_block_2d.json", R"J([{"name": "p", "points": [[0, 0]]}])J", "/measure_planes/0/points");
  expect_error("scenes/free_block_3d.json",
               R"J([{"name": "bent", "points": [[0, 0, 0], [0.1, 0, 0], [0.1, 0.05, 0.01], [0, 0.05, 0]]}])J",
               "coplanar");
  expect_error("scenes/free_block_3d.json",
               R"J([{"name": "bow", "points": [[0, 0, 0.02], [0.1, 0.05, 0.02], [0.1, 0, 0.02], [0, 0.05, 0.02]]}])J",
               "convex");
  expect_error("scenes/free_block_2d.json", R"J([{"name": "a b", "points": [[0, 0], [0, 1]]}])J",
               "/measure_planes/0/name");
}
