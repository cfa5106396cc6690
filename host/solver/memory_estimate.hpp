// The memory a TLSPH run will hold, estimated from the scene and its particle
// count before anything is allocated, so that a scene too big for the machine
// is refused with the estimate (exit 2) instead of failing in an allocation.
#pragma once
#include <string>

#include "host/scene/scene.hpp"

namespace mfsd {

struct MemoryEstimate {
  double bytes = 0;               // particle fields + reference pairs + set-up copies, with a margin
  double bytes_per_particle = 0;  // of the run's state alone (compare run.json bytes_per_particle)
  double neighbors = 0;           // estimated pairs per particle
};

MemoryEstimate estimate_run_memory(const Scene& scene, long particles, Precision precision);

// Throws SceneError (naming the largest body's spacing) when the estimate
// exceeds what the backend has: host memory for cpu, free device memory for cuda.
void check_run_memory(const Scene& scene, const std::vector<long>& body_particles, Precision precision,
                      const std::string& backend);

}  // namespace mfsd
