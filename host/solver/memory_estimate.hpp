// The memory a run will hold, estimated from the scene, its particle counts
// and the run options before anything is allocated, so that a scene too big
// for the machine is refused with the estimate (exit 2) instead of failing in
// an allocation. It follows what the solvers register (tlsph_solver.hpp,
// ulsph_solver.hpp): the particle fields by need, and the reference pairs as
// the pair loop stores them (issue 24, item 6: the CPU's half-pair list alone
// holds each pair once, and its set-up never holds the full rows).
#pragma once
#include <string>
#include <vector>

#include "host/scene/scene.hpp"
#include "host/solver/solver.hpp"

namespace mfsd {

struct MemoryEstimate {
  double bytes = 0;               // state + set-up copies, with the neighbour margin: the peak
  double bytes_per_particle = 0;  // of the run's state alone (compare timing.json bytes_per_particle)
  double neighbors = 0;           // estimated pairs per particle (with the margin)
};

// body_particles: the particles of each body of the scene.
MemoryEstimate estimate_run_memory(const Scene& scene, const std::vector<long>& body_particles,
                                   const SolverOptions& options);

// Throws SceneError (naming the largest body's spacing) when the estimate
// exceeds what the backend has: host memory for cpu, free device memory for cuda.
void check_run_memory(const Scene& scene, const std::vector<long>& body_particles, const SolverOptions& options);

}  // namespace mfsd
