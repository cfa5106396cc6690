// The step recipe of a scene's method (host/solver/<method>/<method>_recipe.cpp),
// and the text `mfsd check --recipe` prints: the stages in order with their
// equations and the ghost fields a distributed run refreshes around each
// (one recipe per method in a scene of two).
#pragma once
#include <string>

#include "host/scene/particle_generator.hpp"
#include "host/scene/scene.hpp"
#include "host/solver/common/step_recipe.hpp"

namespace mfsd {

StepRecipe step_recipe(const Scene& scene, Method method);

std::string step_recipe_text(const Scene& scene, const InitialParticles& particles);

}  // namespace mfsd
