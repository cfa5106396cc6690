// The semi-Lagrangian RKPM step as a recipe (seed 004, the MEGA method;
// ../shared/reference/rkpm.md): its stages in order with their equations
// and halo refreshes (host/solver/common/step_recipe.hpp). rkpm_solver.hpp
// runs it.
#pragma once
#include "host/scene/scene.hpp"
#include "host/solver/common/step_recipe.hpp"

namespace mfsd {

StepRecipe rkpm_recipe(const Scene& scene);

}  // namespace mfsd
