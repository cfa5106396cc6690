// The transmembrane potential V_m of a Holzapfel-Ogden body's active stress
// (seed 000 eq. 43), compiled once when the scene is read, for the particle
// variables and the body's constants, with the decision where it is
// evaluated stored beside it (ActiveStressSpec::per_step): at set-up
// (particle_generator.cpp) when it reads only x0 y0 z0, else every step on
// the device (host/solver/common/conditions.hpp).
#pragma once
#include <cstddef>

#include "host/expr/program.hpp"
#include "host/scene/scene.hpp"

namespace mfsd {

// Compiles every active potential of the scene (read_scene does this);
// a compile error is a SceneError naming the potential's path.
void prepare_active_potentials(Scene& scene);

// The compiled potential of body b, and its path in the scene.
const expr::Program& active_potential_program(const Scene& scene, size_t b);
std::string active_potential_path(size_t b);

}  // namespace mfsd
