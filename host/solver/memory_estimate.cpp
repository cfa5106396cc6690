#include "host/solver/memory_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "host/backend/host_memory.hpp"
#include "host/scene/scene_error.hpp"

namespace mfsd {

namespace {
// What the set-up's peak holds beside the run's state (the generated
// particles until they are uploaded, host copies of ids, the allocator's
// slack), per particle: measured 103 on the 2 M particle plate (peak RSS
// against timing.json bytes_per_particle, docs/performance.md), with a margin.
constexpr double kSetupBytesPerParticle = 150;
// The neighbours of an interior particle of the generated lattice: the
// lattice points other than its own within the support radius (in spacings),
// as the search counts them (r < radius). Surface particles have fewer.
double lattice_neighbors(int D, double support) {
  const int k = int(std::ceil(support));
  long count = 0;
  for (int x = -k; x <= k; ++x)
    for (int y = -k; y <= k; ++y)
      for (int z = (D == 3 ? -k : 0); z <= (D == 3 ? k : 0); ++z) {
        const double r2 = double(x * x + y * y + z * z);
        if (r2 > 0 && r2 < support * support) ++count;
      }
  return double(count);
}

struct BodyBytes {
  double state = 0, setup = 0, neighbors = 0;
};

BodyBytes body_bytes(const Scene& scene, size_t b, const SolverOptions& o) {
  const int D = scene.dimension;
  const double R = o.precision == Precision::single_precision ? 4.0 : 8.0;
  const double vec = D * R, mat = D * D * R;
  const BodySpec& body = scene.bodies[b];
  const SolverSpec& s = scene.solver;
  const double support = 2.0 * s.h_over_dp;  // in spacings (one spacing per scene here)
  BodyBytes e;
  e.neighbors = lattice_neighbors(D, support);
  const bool cpu = o.backend != "cuda";
  double fields = 4 + 4 + 1 + 4 * vec + R;  // id, body, constrained; X, v, u, a; V0
  double pair = 4 + vec + R;                // neighbour, gradient, stretch
  double stored = e.neighbors;              // pairs stored per particle (also the set-up's)
  if (body.method == Method::ulsph) {
    // rho, m, pair density, p, observables, dissipated work; x, a_num (a_h);
    // tau, B, L; the per-step list with the current volume.
    fields += 7 * R + 3 * vec + 3 * mat;
    if (body.material.plastic()) fields += 3 * R;
  } else {
    const bool genog = s.hourglass == HourglassControl::genog;
    const bool fracture = has_fracture_body(scene);  // fields and lists are the whole set's
    const bool record = genog && D == 3 && cpu && o.packed_genog_record;
    fields += 3 * mat + 4 * R;  // B0, F, dF/dt; observables
    if (record) fields += 28 * R;
    if (!record || fracture) fields += mat;  // force stress
    if (!record) fields += mat;              // F^{-1}
    if (genog) fields += mat;                // shear stress
    if (s.hourglass == HourglassControl::laplacian) fields += R;
    if (has_plastic_body(scene)) fields += 9 * R;  // J2 state, plastic strain
    if (s.damping_factor > 0) fields += R;
    if (fracture) fields += 8 * R;
    if (genog && s.genog_limiter == GenogLimiterChoice::paper) pair += R;    // beta
    fields += 8 + vec;                                                       // offsets, gradient sum
    if (cpu && o.pair_loop != SolverOptions::PairLoop::full && s.reorder) {  // the half-pair loop
      fields += 8;                                                           // the half list's offsets
      if (!s.relaxation.enabled && !fracture) {
        stored = e.neighbors / 2;  // the half list alone, filled from the search
        if (o.pair_precision == SolverOptions::PairPrecision::single)
          pair = 4 + D * 4.0 + 4 + (genog && s.genog_limiter == GenogLimiterChoice::paper ? 4 : 0);  // in float
      } else
        stored = 1.5 * e.neighbors;  // both lists
    }
  }
  e.state = fields + stored * pair;
  e.setup = kSetupBytesPerParticle;
  return e;
}
}  // namespace

MemoryEstimate estimate_run_memory(const Scene& scene, const std::vector<long>& body_particles,
                                   const SolverOptions& options) {
  MemoryEstimate e;
  double n = 0, state = 0, setup = 0, neighbors = 0;
  for (size_t b = 0; b < body_particles.size() && b < scene.bodies.size(); ++b) {
    const BodyBytes k = body_bytes(scene, b, options);
    const double m = double(body_particles[b]);
    n += m;
    state += m * k.state;
    setup += m * k.setup;
    neighbors += m * k.neighbors;
  }
  if (n > 0) {
    e.bytes_per_particle = state / n;
    e.neighbors = neighbors / n;
  }
  e.bytes = state + setup;
  return e;
}

void check_run_memory(const Scene& scene, const std::vector<long>& body_particles, const SolverOptions& options) {
  long n = 0;
  size_t largest = 0;
  for (size_t b = 0; b < body_particles.size(); ++b) {
    n += body_particles[b];
    if (body_particles[b] > body_particles[largest]) largest = b;
  }
  const MemoryEstimate e = estimate_run_memory(scene, body_particles, options);
  const bool gpu = options.backend == "cuda";
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
