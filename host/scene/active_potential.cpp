#include "host/scene/active_potential.hpp"

#include <memory>
#include <stdexcept>
#include <string>

#include "host/scene/particle_expressions.hpp"

namespace mfsd {

std::string active_potential_path(size_t b) {
  return "/bodies/" + std::to_string(b) + "/material/active_stress/potential";
}

void prepare_active_potentials(Scene& scene) {
  for (size_t b = 0; b < scene.bodies.size(); ++b) {
    MaterialSpec& m = scene.bodies[b].material;
    ActiveStressSpec& a = m.holzapfel_ogden.active;
    if (m.model != MaterialModel::holzapfel_ogden || !a.enabled) continue;
    auto program = std::make_shared<const expr::Program>(
        compile_particle_expression(a.potential, scene, b, active_potential_path(b)));
    a.per_step = !reads_only_reference_position(*program);
    a.program = std::move(program);
  }
}

const expr::Program& active_potential_program(const Scene& scene, size_t b) {
  const ActiveStressSpec& a = scene.bodies.at(b).material.holzapfel_ogden.active;
  if (!a.program)
    throw std::logic_error("the active potential of body " + std::to_string(b) +
                           " was not compiled (prepare_active_potentials)");
  return *a.program;
}

}  // namespace mfsd
