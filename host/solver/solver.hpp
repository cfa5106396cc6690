// The interface between the run driver (g++) and a solver instantiated for a
// backend, precision and dimension (g++ for cpu, nvcc for cuda). Only plain
// host data crosses it.
#pragma once
#include <array>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "host/backend/cuda_devices.hpp"
#include "host/backend/stage_timers.hpp"
#include "host/halo/ghost_exchange.hpp"
#include "host/output/snapshot.hpp"
#include "host/particles/field_memory.hpp"
#include "host/particles/state_archive.hpp"
#include "host/scene/particle_generator.hpp"
#include "host/scene/scene.hpp"

namespace mfsd {

// Energies of one body (J; per metre of depth in 2-D). Work done on the body
// by its loads (external) and by its velocity conditions and clamps
// (boundary), and by contact forces (contact: of other bodies, rigid bodies
// and its own distant parts), accumulated over the run. Plastic: the plastic work of J2
// bodies (j2_plastic.hpp). Fracture: the elastic energy released by the
// phase-field degradation (a dissipation, kernels/fracture/fracture_stress.hpp);
// crack_surface: the crack surface energy of the phase field (not in the balance).
struct BodyEnergy {
  double kinetic = 0, strain = 0, plastic = 0, fracture = 0, external_work = 0, boundary_work = 0, contact_work = 0;
  double gravity_work = 0;   // work of solver.gravity since the start (sum m g . (u - u0))
  double damping = 0;        // work taken by the Kelvin-Voigt damping (solver.damping)
  double relaxation = 0;     // kinetic energy removed by solver.relaxation
  double crack_surface = 0;  // Gc int (1-s)^2/(4 eps0) + eps0 |grad s|^2 dV0 (fracturing bodies)
  double active_work = 0;    // work of the active stress on the body (Holzapfel-Ogden muscle)
  // ULSPH with solver.ulsph.energy_audit: sum V tau : (L - L~) dt, the work the
  // stress receives through the corrected velocity gradient L that the shear
  // force (with the uncorrected L~) does not take from the motion; not in the
  // balance, which it moves by this much (docs/theory.md, ULSPH "Energies").
  double shear_mismatch = 0;
  Point3 momentum{0, 0, 0};  // kg m/s (2-D: per metre of depth)
  // Constant in time for a conservative run:
  // E_k + E_s + dissipation - W_ext - W_bc - W_contact - W_gravity - W_active.
  double balance() const {
    return kinetic + strain + plastic + fracture + damping + relaxation - external_work - boundary_work - contact_work -
           gravity_work - active_work;
  }
};

struct EnergySample {
  double kinetic = 0, strain = 0;
  Point3 momentum{0, 0, 0};
  double hourglass_max = 0, hourglass_mean = 0;
  bool with_fracture = false;  // some body fractures: crack_surface columns are written
  bool with_active = false;    // some body has an active stress: active_work columns are written
  bool with_audit = false;     // solver.ulsph.energy_audit: shear_mismatch columns are written
  std::vector<BodyEnergy> bodies;
};

// The crack tip of a fracturing body (kernels/fracture/crack_tip.hpp):
// whether a particle has s < 0.5, the tip particle's current position, and the
// crack's length = the notch's length inside the body + its growth beyond the
// notch's tip along the crack's direction.
struct CrackTipSample {
  bool broken = false;
  Point3 tip{0, 0, 0};
  double length = 0;
  // What picks the tip among several (kernels/fracture/crack_tip.hpp): its
  // reach along the crack and its reference position (distributed runs).
  double reach = 0;
  Point3 reference{0, 0, 0};
};

// Force sum of one clamp or velocity condition (its reaction) or load (the
// applied force) over the last step, N (per metre of depth in 2-D).
struct BoundaryForceSample {
  std::string name;
  Point3 force{0, 0, 0};
};

struct ProbeSample {
  Point3 position{}, displacement{}, velocity{};
  double von_mises = 0, jacobian = 0, von_mises_strain = 0, plastic_strain = 0;
  double phase_field = 1;  // s (1 without fracture)
};

struct SetupReport {
  long particles = 0;
  std::vector<long> body_particles;
  long pairs = 0;
  double mean_neighbors = 0;
  long min_neighbors = 0, max_neighbors = 0;
  long regularized_corrections = 0;  // B0 that needed the eigenvalue floor
  double bytes_per_particle = 0;
  std::string pair_loop = "full";   // the strategy the pair stages ran (SolverOptions::pair_loop)
  std::string pair_layout = "csr";  // how the full gather's pairs are stored (SolverOptions::pair_layout)
  std::string pair_precision;       // of the reference pairs' data: "double" or "float" (TLSPH)
};

// A measure plane's particles: mean displacement [m] and total force
// sum m_i a_i [N; 2-D per metre of depth] (seed 001 Fig. 7).
struct MeasureSample {
  Point3 displacement{0, 0, 0};
  Point3 force{0, 0, 0};
};

class Solver {
 public:
  virtual ~Solver() = default;
  // Builds neighbour lists and reference data; computes the initial rates.
  virtual void initialize() = 0;
  // Advances one time step; throws NumericalFailure on NaN/Inf or escape.
  virtual void step() = 0;
  // Caps the next time step (end time, max step); never enlarges it.
  virtual void limit_next_dt(double dt_max) = 0;
  virtual double time() const = 0;
  virtual double next_dt() const = 0;
  virtual long steps() const = 0;
  virtual Snapshot snapshot() = 0;
  virtual EnergySample energies() = 0;
  virtual std::vector<ProbeSample> probes() = 0;
  // Clamps, velocity conditions and loads in scene order, walls, then the
  // rigid bodies in contact (the force each exerts on the bodies).
  virtual std::vector<BoundaryForceSample> boundary_forces() = 0;
  virtual std::vector<MeasureSample> measures() = 0;  // scene.measure_planes order
  // Per entry of crack_bodies(scene): its crack tip now.
  virtual std::vector<CrackTipSample> crack_tips() { return {}; }
  // The registered per-particle fields where they lie, in the solver's
  // particle order (field "id": each particle's index in the scene), the
  // output observables (von Mises, J, ...) brought up to date first. The
  // addresses hold while the solver lives (single-process runs keep their
  // buffers after the set-up); the values change with each step.
  virtual std::vector<FieldMemory> fields() { return {}; }
  // One field's values copied to the host (a GPU's fields).
  virtual std::string field_bytes(const std::string& /*name*/) { return {}; }
  virtual const StageTimers& timers() const = 0;
  virtual void reset_timers() = 0;  // after warm-up steps
  virtual SetupReport setup_report() const = 0;
  // Everything a continued run needs to reproduce the uninterrupted one bit
  // for bit (checkpoints): every particle field, time, step and dt, and the
  // accumulators and generators of its parts. restore_state() follows
  // initialize() and throws StateMismatch when the archive does not fit.
  virtual void save_state(StateArchive& archive) = 0;
  virtual void restore_state(const StateArchive& archive) = 0;
  // A distributed run (issue 25): before initialize(), the ghosts among the
  // particles and the transport that refreshes them. A method that cannot
  // run distributed yet says so.
  virtual void attach_ghosts(std::shared_ptr<GhostExchange> ghosts) = 0;
  // Distributed runs whose particles migrated before a checkpoint: this
  // rank holds the checkpoint's `n` particles (the exchange has taken the
  // checkpoint's membership), which the next restore_state() fills.
  virtual void expect_particles(long n) {
    (void)n;
    throw std::logic_error("this solver's particles do not migrate");
  }
};

struct SolverOptions {
  std::string backend = "cpu";
  int threads = 0;  // 0 = OpenMP default
  Precision precision = Precision::double_precision;
  // 3-D genog on the CPU: the packed neighbour record of the vectorized force
  // loop (kernels/tlsph/genog_neighbor_record.hpp); false takes the scalar
  // path the GPU always takes (tests compare the two).
  bool packed_genog_record = true;
  // The pair loops' strategy on the CPU (issue 24): each pair from both rows
  // (full gather, the GPU's) or once, from the row of its smaller index
  // (half; kernels/neighbors/half_pair_sink.hpp). automatic: half on CPU
  // threads, where it is faster (docs/performance.md), full on the GPU.
  enum class PairLoop { automatic, full, half };
  PairLoop pair_loop = PairLoop::automatic;
  // How the full gather's reference pairs are laid out (TLSPH): compressed
  // rows, or sliced (sliced ELLPACK, slices of kSliceHeight rows interleaved
  // so that a GPU warp's threads read adjacent pairs; issue 24 item 3). The
  // sliced layout needs the full gather: on the CPU it implies
  // pair_loop full. csr stays the default until a GPU has measured both
  // (scripts/gpu_check.sh runs the sliced layout's cross-backend test).
  enum class PairLayout { csr, sliced };
  PairLayout pair_layout = PairLayout::csr;
  // The reference pairs' data (g, stretch) in the run's precision, or in
  // float within a double run (issue 24 item 4: a third less memory per pair;
  // the CPU half-pair loop's list alone; docs/performance.md).
  enum class PairPrecision { same, single };
  PairPrecision pair_precision = PairPrecision::same;
};

// Factory: picks the instantiation for backend x precision x dimension.
std::unique_ptr<Solver> make_solver(const Scene& scene, const InitialParticles& particles,
                                    const SolverOptions& options);

}  // namespace mfsd
