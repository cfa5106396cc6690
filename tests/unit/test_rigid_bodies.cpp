// Kinematic rigid bodies: the prescribed motion and its inverse, surface
// markers, and "near" selections of loaded particles (seed 001 Fig. 3).
#include <gtest/gtest.h>

#include <cmath>

#include "host/scene/particle_generator.hpp"
#include "host/scene/rigid_body.hpp"
#include "host/scene/scene_error.hpp"
#include "host/scene/scene_reader.hpp"

using namespace mfsd;

namespace {

SceneDocument scene_with(const std::string& extra) {
  const std::string text = R"({"name": "s", "dimension": 2, "constants": {"dp": 0.0025},
    "solver": {"end_time": 1},
    "bodies": [{"name": "block", "spacing": "dp", "geometry": {"box": {"min": [0, 0], "max": [0.1, 0.05]}},
                "material": {"model": "neo_hookean", "density": 1000, "youngs_modulus": 1e6, "poisson_ratio": 0.3}}])" +
                           extra + "}";
  return load_scene_text(text, "test", {});
}

}  // namespace

TEST(RigidBodies, MotionAndItsInverse) {
  RigidBodySpec r;
  r.name = "axle";
  r.shape = Shape::box({0, 0, 0}, {1, 1, 1});
  r.translation = {"0.1 * t", "0", "-2 * t^2"};
  r.angle_degrees = "90 * t";
  r.axis = {0, 0, 1};
  r.center = {0.5, 0.5, 0.5};
  const RigidBodyMotion m(r, {}, "/rigid_bodies/0");
  // At t = 1: rotate (1, 0.5, 0.5) by 90 degrees about z through the centre -> (0.5, 1, 0.5), then translate.
  const Point3 x = m.position({1, 0.5, 0.5}, 1.0);
  EXPECT_NEAR(x[0], 0.5 + 0.1, 1e-14);
  EXPECT_NEAR(x[1], 1.0, 1e-14);
  EXPECT_NEAR(x[2], 0.5 - 2, 1e-14);
  const Point3 X = m.reference(x, 1.0);
  EXPECT_NEAR(X[0], 1, 1e-14);
  EXPECT_NEAR(X[1], 0.5, 1e-14);
  EXPECT_NEAR(X[2], 0.5, 1e-14);
  EXPECT_THROW(
      RigidBodyMotion(RigidBodySpec{"bad", r.shape, {"x0", "0", "0"}, "0", {0, 0, 1}, {}, 0}, {}, "/rigid_bodies/0"),
      SceneError);  // only t is a variable
}

TEST(RigidBodies, NearSelectsTheParticlesWithinTheDistance) {
  // A circle of radius 0.01 touching the block's right face at mid-height:
  // the particles within dp of it are those with |X - c| <= 0.01 + dp.
  const auto doc = scene_with(R"(, "rigid_bodies": [{"name": "pin", "shape": {"circle": {"center": [0.11, 0.025],
      "radius": 0.01}}}], "loads": [{"name": "push", "body": "block", "type": "point",
      "near": {"rigid_body": "pin", "distance": "dp"}, "x": -1}])");
  const InitialParticles P = generate_particles(doc.scene);
  long expected = 0;
  for (const Point3& x : P.position) expected += std::hypot(x[0] - 0.11, x[1] - 0.025) <= 0.01 + 0.0025 + 1e-12;
  EXPECT_GT(expected, 0);
  EXPECT_EQ(long(P.condition_particles.at(0).ids.size()), expected);
  ASSERT_EQ(P.rigid_markers.size(), 1u);
  EXPECT_GT(P.rigid_markers[0].size(), 10u);
  for (const Point3& m : P.rigid_markers[0])  // on the surface layer of the circle
    EXPECT_GT(std::hypot(m[0] - 0.11, m[1] - 0.025), 0.01 - 2 * 0.0025);
}

TEST(RigidBodies, Errors) {
  auto error = [](const std::string& extra) {
    try {
      generate_particles(scene_with(extra).scene);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(
      error(R"(, "loads": [{"body": "block", "type": "point", "near": {"rigid_body": "x", "distance": 0}, "x": 1}])")
          .find("/loads/0/near/rigid_body"),
      std::string::npos);
  EXPECT_NE(error(R"(, "rigid_bodies": [{"name": "block", "shape": {"circle": {"center": [0, 0], "radius": 1}}}])")
                .find("/rigid_bodies/0/name"),
            std::string::npos);
  EXPECT_NE(error(R"(, "rigid_bodies": [{"name": "p", "shape": {"circle": {"center": [0, 0], "radius": 1}},
                      "translation": {"x": "1/"}}])")
                .find("/rigid_bodies/0/translation/x"),
            std::string::npos);
  EXPECT_NE(error(R"(, "rigid_bodies": [{"name": "p", "shape": {"circle": {"center": [1, 1], "radius": 0.1}}}],
                      "loads": [{"body": "block", "type": "point", "near": {"rigid_body": "p", "distance": 0}, "x": 1}])")
                .find("/loads/0"),
            std::string::npos);
}
