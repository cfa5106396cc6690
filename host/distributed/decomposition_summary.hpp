// `mfsd decompose SCENE --ranks N` (issue 25): the recursive coordinate
// bisection of a scene's particles (reference positions) into N parts and
// each part's halo at the scene's search radius, as a table: what a
// distributed run would own and exchange (docs/distributed.md).
#pragma once
#include <string>

#include "host/scene/particle_generator.hpp"
#include "host/scene/scene_reader.hpp"

namespace mfsd::distributed {

// The radius within which a particle's partners lie: per body 2h (SPH
// kernels) or, for RKPM, (a~ reach + cell half-diagonal + skin) dp; the
// largest over the bodies.
double halo_radius(const Scene& scene);

std::string decomposition_summary(const SceneDocument& doc, const InitialParticles& particles, int ranks);

}  // namespace mfsd::distributed
