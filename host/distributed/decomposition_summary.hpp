// `mfsd decompose SCENE --ranks N` (issue 25): the recursive coordinate
// bisection of a scene's particles (reference positions) into N parts and
// each part's halo at the scene's search radius, as a table: what a
// distributed run would own and exchange (docs/distributed.md).
#pragma once
#include <string>

#include "host/scene/particle_generator.hpp"
#include "host/scene/scene_reader.hpp"

namespace mfsd::distributed {

std::string decomposition_summary(const SceneDocument& doc, const InitialParticles& particles, int ranks);

}  // namespace mfsd::distributed
