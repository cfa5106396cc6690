// Fills each body's geometry with a lattice of particles (spacing dp,
// particle centres at min + (k + 1/2) dp of the body's bounding box), marks
// clamped particles, evaluates the initial velocity expressions and locates
// probes. Pure host code; errors are SceneErrors naming the JSON path.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "host/scene/scene.hpp"

namespace mfsd {

struct InitialParticles {
  int dimension = 2;
  std::vector<Point3> position;  // reference positions
  std::vector<Point3> velocity;
  std::vector<int> body;
  std::vector<unsigned char> constrained;
  std::vector<double> volume;
  struct Range {
    long begin, end;
  };
  std::vector<Range> body_range;                   // particles of body b are [begin, end)
  std::vector<std::vector<long>> probe_particles;  // ids of each probe's particles (averaged)
  std::vector<long> constrained_count;             // per body
  std::vector<std::vector<long>> clamp_particles;  // ids each clamp holds (a particle counts for its first clamp)
  // Per scene.conditions entry: the selected ids and, for tractions, the
  // surface area each carries (only surface particles of the selection).
  struct Selected {
    std::vector<long> ids;
    std::vector<double> area;
  };
  std::vector<Selected> condition_particles;
  std::vector<std::vector<long>> measure_particles;  // ids each measure plane holds
  std::vector<std::vector<Point3>> rigid_markers;    // per rigid body: surface markers (its shape as given)
  std::vector<unsigned char> surface;                // faces a particle exposes, 0 inside (surface.hpp)
  std::vector<Point3> displacement;                  // initial displacement; empty when no body sets one
  std::vector<double> phase_field_lower;             // restrict_phase_field bounds on s; empty when none
  // Holzapfel-Ogden bodies (empty when there are none): unit fibre f0 and
  // sheet s0 per particle (other bodies: zero), and k V_m of the active stress
  // (seed 000 eq. 43; zero for passive bodies).
  std::vector<Point3> fibre, sheet;
  std::vector<double> active_tension;

  size_t size() const { return position.size(); }
};

InitialParticles generate_particles(const Scene& scene);

// Constants available to a body's expressions: the scene's constants, then
// rho0 E nu K G c0 cs dp h of the body.
std::vector<std::pair<std::string, double>> body_expression_constants(const Scene& scene, size_t body);

}  // namespace mfsd
