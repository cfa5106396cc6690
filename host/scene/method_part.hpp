// The bodies of one method in a scene of two (bodies[].method; the solver
// host/solver/coupled/ runs one solver per method): a scene of those bodies
// alone, with what refers to them (clamps, conditions, loads, walls, contact,
// the probes' and measure planes' particles), their particles, and the maps
// back to the whole scene.
#pragma once
#include <vector>

#include "host/scene/particle_generator.hpp"
#include "host/scene/scene.hpp"

namespace mfsd {

struct MethodPart {
  Method method = Method::tlsph;
  Scene scene;                     // settings: solver_for(scene.solver, method)
  InitialParticles particles;      // the part's particles, ids 0 .. n-1 in scene order
  std::vector<size_t> scene_body;  // part body -> scene body
  std::vector<long> id;            // part particle id -> scene particle id
  // Per scene probe and measure plane: how many of its particles are in the
  // part (all probes and planes are kept; one with none here reads nothing).
  std::vector<long> probe_count, measure_count;
};

MethodPart method_part(const Scene& scene, const InitialParticles& particles, Method method);

}  // namespace mfsd
