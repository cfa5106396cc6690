// `mfsd check`: the resolved scene in a few lines (bodies, particle counts,
// clamps, probes, estimated time step and cost), after full validation.
#pragma once
#include <string>

#include "host/scene/particle_generator.hpp"
#include "host/scene/scene_reader.hpp"

namespace mfsd {

std::string check_summary(const SceneDocument& doc, const InitialParticles& particles);

}  // namespace mfsd
