#include "host/solver/memory_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "host/backend/host_memory.hpp"
#include "host/scene/scene_error.hpp"
#include "host/solver/solver.hpp"

namespace mfsd {

namespace {
constexpr double kPi = 3.14159265358979323846;
// What the set-up holds beside the run's state (the generated particles and
// their copy in the solver, the search's keys and permutations), per particle.
constexpr double kSetupBytesPerParticle = 600;
// Lattice neighbourhoods hold more particles than the support's volume / dp^D.
constexpr double kNeighborMargin = 1.3;
}  // namespace

MemoryEstimate estimate_run_memory(const Scene& scene, long particles, Precision precision) {
  const int D = scene.dimension;
  const double R = precision == Precision::single_precision ? 4.0 : 8.0;
  const double support = 2.0 * scene.solver.h_over_dp;  // in spacings
  MemoryEstimate e;
  e.neighbors = kNeighborMargin * (D == 2 ? kPi * support * support : 4.0 / 3.0 * kPi * std::pow(support, 3));
  // Per pair: neighbour index, corrected gradient, kernel value, the limiter's distance.
  const double pair = 4.0 + D * R + 2.0 * R;
  // Per particle: 7 D x D tensors (F, dF/dt, B0, force stress, F^-1, shear
  // stress, plastic state), 5 vectors (X, u, v, a, gradient sum), 12 scalars
  // (volume, observables, phase field ...), id, body, flag, CSR offset.
  double fields = 7.0 * D * D * R + 5.0 * D * R + 12.0 * R + 4 + 4 + 1 + 8;
  if (scene.solver.hourglass == HourglassControl::genog && D == 3) fields += 16.0 * R;  // packed record (CPU)
  e.bytes_per_particle = fields + e.neighbors * pair;
  e.bytes = double(particles) * (e.bytes_per_particle + kSetupBytesPerParticle);
  return e;
}

void check_run_memory(const Scene& scene, const std::vector<long>& body_particles, Precision precision,
                      const std::string& backend) {
  long n = 0;
  size_t largest = 0;
  for (size_t b = 0; b < body_particles.size(); ++b) {
    n += body_particles[b];
    if (body_particles[b] > body_particles[largest]) largest = b;
  }
  const MemoryEstimate e = estimate_run_memory(scene, n, precision);
  const bool gpu = backend == "cuda";
  const double have = gpu ? cuda_device_free_bytes() : host_memory_limit_bytes();
  if (e.bytes <= have || have <= 0) return;
  std::ostringstream got, expected;
  got.precision(3);
  expected.precision(3);
  got << scene.bodies[largest].spacing << ", which gives " << n << " particles in all: about " << e.bytes / 1e9
      << " GB (" << e.bytes / double(n) << " B per particle at " << e.neighbors << " neighbours)";
  expected << "a scene that fits in " << (gpu ? "the GPU's free memory" : "the memory mfsd may use") << " ("
           << have / 1e9 << " GB)";
  throw SceneError("/bodies/" + std::to_string(largest) + "/spacing", got.str(), expected.str());
}

}  // namespace mfsd
