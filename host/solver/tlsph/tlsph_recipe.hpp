// The total-Lagrangian SPH step as a recipe (seed 000 eq. 35-38; seed 003
// for the Laplacian form; formulations.md sections 1-2): its stages in order
// with their equations and halo refreshes (host/solver/common/step_recipe.hpp).
// tlsph_solver.hpp runs it.
#pragma once
#include "host/scene/scene.hpp"
#include "host/solver/common/step_recipe.hpp"

namespace mfsd {

StepRecipe tlsph_recipe(const Scene& scene);

}  // namespace mfsd
