// The ULSPH step as a recipe (formulations.md section 3, seed 002): its
// stages in order with their equations and halo refreshes
// (host/solver/common/step_recipe.hpp). ulsph_solver.hpp runs it.
#pragma once
#include "host/scene/scene.hpp"
#include "host/solver/common/step_recipe.hpp"

namespace mfsd {

StepRecipe ulsph_recipe(const Scene& scene);

}  // namespace mfsd
