// Compiling the user expressions that are evaluated per particle during a run
// (velocity conditions and loads): the variable table in the slot order of
// kernels/bc/conditions.hpp and the constants of the particle's body.
#pragma once
#include <string>

#include "host/expr/program.hpp"
#include "host/scene/scene.hpp"

namespace mfsd {

// x0 y0 z0 x y z ux uy uz vx vy vz t dt dx, in ParticleVariable order.
const expr::VariableTable& particle_variable_table();

// Compiles `text` for body `body` of the scene; errors become SceneErrors
// naming `path`.
expr::Program compile_particle_expression(const std::string& text, const Scene& scene, size_t body,
                                          const std::string& path);

// True when a program compiled by compile_particle_expression reads no
// variable but x0 y0 z0 (it can be evaluated once, at set-up).
bool reads_only_reference_position(const expr::Program& program);

}  // namespace mfsd
