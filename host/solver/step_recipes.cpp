#include "host/solver/step_recipes.hpp"

#include "host/scene/method_part.hpp"
#include "host/solver/rkpm/rkpm_recipe.hpp"
#include "host/solver/tlsph/tlsph_recipe.hpp"
#include "host/solver/ulsph/ulsph_recipe.hpp"

namespace mfsd {

StepRecipe step_recipe(const Scene& scene, Method method) {
  switch (method) {
    case Method::tlsph:
      return tlsph_recipe(scene);
    case Method::ulsph:
      return ulsph_recipe(scene);
    case Method::rkpm:
      return rkpm_recipe(scene);
  }
  return StepRecipe();
}

std::string step_recipe_text(const Scene& scene, const InitialParticles& particles) {
  const std::string note =
      " step (stages in order, their equations, and the fields a distributed run's ghosts "
      "refresh around them):\n";
  if (!mixed_methods(scene)) {
    const Method m = scene_method(scene);
    return to_string(m) + note + step_recipe(scene, m).describe();
  }
  std::string out;
  for (Method m : {Method::tlsph, Method::ulsph, Method::rkpm}) {
    bool used = false;
    for (const auto& b : scene.bodies) used = used || b.method == m;
    if (!used) continue;
    const MethodPart part = method_part(scene, particles, m);
    out += to_string(m) + note + step_recipe(part.scene, m).describe();
  }
  return out;
}

}  // namespace mfsd
