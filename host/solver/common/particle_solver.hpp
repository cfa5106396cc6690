// What every method's solver shares, written once (design.md, "Inside
// host/"): the particle set and its upload from the scene, the bodies'
// ranges, the location of particles by their original id after reordering,
// the conditions, walls, clamps and loads, contact, probes and measure
// planes, the stage runner with its clocks, the numerical-failure report,
// snapshots as named fields, and the Solver interface's bookkeeping (time,
// steps, next dt, timers, set-up report, checkpoints of the shared parts).
// A method (host/solver/<method>/) derives from it, adds its own fields,
// gives its step recipe (<method>_recipe.cpp: the stages with their
// equations and halo refreshes, which run() reads), fills the step's
// method stages (forces, advance, finish_step) and registers its output
// fields in snapshot_fields_.
// Include after the backend header.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <memory>
#include <numeric>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "host/backend/device_results.hpp"
#include "host/backend/round_trips.hpp"
#include "host/halo/halo_check.hpp"
#include "host/particles/field_names.hpp"
#include "host/particles/particle_set.hpp"
#include "host/scene/body_properties.hpp"
#include "host/scene/scene_error.hpp"
#include "host/solver/common/conditions.hpp"
#include "host/solver/common/contact.hpp"
#include "host/solver/common/kinematics.hpp"
#include "host/solver/common/step_recipe.hpp"
#include "host/solver/numerical_failure.hpp"
#include "host/solver/solver.hpp"
#include "host/solver/stage_run.hpp"
#include "kernels/core/step_statistics.hpp"
#include "kernels/probes/probe_gather.hpp"

namespace mfsd {

template <class B, int D, class Real>
class ParticleSolver : public Solver {
 public:
  ParticleSolver(const Scene& scene, const InitialParticles& init, const SolverOptions& options)
      : scene_(scene), init_(init), options_(options), particles_(Index(init.size())) {}

  void limit_next_dt(double dt_max) override { dt_next_ = std::min(dt_next_, dt_max); }

  // A step in two halves around the contact, so that the solvers of a scene
  // of two methods (host/solver/coupled/) meet there with the same dt: the
  // first ends after this solver's own contact, the second takes the loads,
  // the boundary conditions and the advance to the end of the step.
  void step() override {
    begin_step();
    end_step();
  }
  // The skeleton every method's step shares (docs/architecture.md, "Step
  // recipes"): the method's stages up to its forces, then the contact.
  virtual void begin_step() {
    round_trips_before_ = round_trips();
    const double dt = step_dt_ = dt_next_;
    results_.clear();
    forces(dt);
    if (contact_.enabled()) {
      before_contact();
      run("contact", [&] {
        prepare_contact();
        contact_.apply(step_kinematics(), time_, dt, results_);
      });
    }
  }
  // The loads, the boundary conditions, the method's advance and the step's
  // one synchronisation, whose results the method reads in finish_step().
  virtual void end_step() {
    const double dt = step_dt_;
    const Kinematics<D, Real> k = step_kinematics();
    if (has_loads_) run("loads", [&] { conditions_.apply_loads(k, time_, dt, steps_ + 1, results_); });
    run("boundary", [&] { conditions_.apply_boundary(k, time_, dt, steps_ + 1, results_); });
    advance(dt);
    run("time_step", [&] {
      results_.fetch();
      conditions_.collect(results_, k);
      contact_.collect(results_);
      time_ += dt;
      ++steps_;
      finish_step(dt);
    });
    clock_.collect(timers_);
    timers_.add_round_trips(round_trips() - round_trips_before_);
  }
  // The fields the contact between two solvers reads and changes, and the
  // candidates this solver offers it (scene.contact's bodies).
  Kinematics<D, Real> contact_view() { return kinematics(); }
  const ContactPartSetup<Real>& contact_part() const { return contact_part_; }
  // The sums of the step in progress: what is reduced into them between
  // begin_step() and end_step() comes to the host with the step's own, in its
  // one synchronisation, and can be read after end_step().
  DeviceResults<B>& step_results() { return results_; }
  // The acoustic CFL number of this solver's time step.
  double cfl() const { return scene_.solver.cfl; }
  // A distributed run (issue 25): methods that refresh their ghosts say so
  // in ghosts_supported(); the others refuse.
  void attach_ghosts(std::shared_ptr<GhostExchange> ghosts) override {
    if (!ghosts_supported())
      throw UsageError(std::string("the ") + to_string(scene_.solver.method) +
                       " method does not run on several processes yet (docs/distributed.md)");
    ghosts_ = std::move(ghosts);
  }
  double time() const override { return time_; }
  double next_dt() const override { return dt_next_; }
  long steps() const override { return steps_; }
  const StageTimers& timers() const override { return timers_; }
  void reset_timers() override { timers_.reset(); }
  SetupReport setup_report() const override { return report_; }

  // Kinematics and every registered field, in the current particle order.
  Snapshot snapshot() override {
    update_observables();
    Snapshot s;
    const Index n = particles_.size();
    s.n = size_t(n);
    const auto ids = to_host<B>(particles_.template buffer<Index>(field::id));
    s.id.assign(ids.begin(), ids.end());
    s.body = to_host<B>(particles_.template buffer<int>(field::body));
    s.constrained = to_host<B>(particles_.template buffer<unsigned char>(field::constrained));
    const auto X = to_host<B>(particles_.template buffer<Vec<D, Real>>(field::reference_position));
    const auto u = to_host<B>(particles_.template buffer<Vec<D, Real>>(field::displacement));
    const auto v = to_host<B>(particles_.template buffer<Vec<D, Real>>(field::velocity));
    s.position.assign(3 * s.n, 0.0);
    s.displacement.assign(3 * s.n, 0.0);
    s.velocity.assign(3 * s.n, 0.0);
    for (size_t i = 0; i < s.n; ++i)
      for (int a = 0; a < D; ++a) {
        s.position[3 * i + a] = double(X[i].v[a]) + double(u[i].v[a]);
        s.displacement[3 * i + a] = double(u[i].v[a]);
        s.velocity[3 * i + a] = double(v[i].v[a]);
      }
    for (const auto& [name, source] : snapshot_fields_) {
      const auto values = to_host<B>(particles_.template buffer<Real>(source));
      s.fields.push_back({name, std::vector<double>(values.begin(), values.end())});
    }
    return s;
  }

  std::vector<FieldMemory> fields() override {
    update_observables();
    std::vector<FieldMemory> out;
    for (const std::string& name : particles_.field_names()) {
      FieldMemory m = particles_.memory(name);
      if (m.plain) out.push_back(m);
    }
    return out;
  }
  std::string field_bytes(const std::string& name) override { return particles_.bytes(name); }

  std::vector<BoundaryForceSample> boundary_forces() override {
    std::vector<BoundaryForceSample> out = conditions_.forces();
    for (const auto& f : contact_.forces()) out.push_back(f);
    return out;
  }

  std::vector<MeasureSample> measures() override {
    std::vector<MeasureSample> out(measure_offsets_.size() - 1);
    if (out.empty()) return out;
    const Kinematics<D, Real> k = kinematics();
    parallel_for<B>(Index(measure_index_.size()),
                    MeasureGatherFunctor<D, Real>{raw(measure_index_), k.displacement, k.acceleration, k.volume,
                                                  raw(measure_density_), raw(measure_buffer_)});
    const auto h = to_host<B>(measure_buffer_);
    for (size_t k = 0; k < out.size(); ++k) {
      const double w = 1.0 / double(measure_offsets_[k + 1] - measure_offsets_[k]);
      for (size_t m = measure_offsets_[k]; m < measure_offsets_[k + 1]; ++m)
        for (int a = 0; a < D; ++a) {
          out[k].displacement[a] += w * double(h[m * 2 * D + a]);
          out[k].force[a] += double(h[m * 2 * D + D + a]);
        }
    }
    return out;
  }

  // Each probe is the mean over its particles (one, or those within its
  // radius); the stress measures come from the registered fields of their
  // names (zero, or s = 1, where a method or body has none).
  std::vector<ProbeSample> probes() override {
    std::vector<ProbeSample> out(probe_offsets_.size() - 1);
    if (out.empty()) return out;
    if (probes_need_stress_) update_stress_observables();
    const Kinematics<D, Real> k = kinematics();
    parallel_for<B>(
        Index(probe_index_.size()),
        ProbeGatherFunctor<D, Real>{raw(probe_index_), k.reference_position, k.displacement, k.velocity,
                                    optional_real(field::von_mises), optional_real(field::jacobian),
                                    optional_real(field::von_mises_strain), optional_real(field::plastic_strain),
                                    optional_real(field::phase_field), raw(probe_buffer_)});
    const auto h = to_host<B>(probe_buffer_);
    for (size_t k = 0; k < out.size(); ++k) {
      const double w = 1.0 / double(probe_offsets_[k + 1] - probe_offsets_[k]);
      out[k].phase_field = 0;
      for (size_t m = probe_offsets_[k]; m < probe_offsets_[k + 1]; ++m) {
        const Real* o = h.data() + m * kProbeValues<D>;
        for (int a = 0; a < D; ++a) {
          out[k].position[a] += w * double(o[a]);
          out[k].displacement[a] += w * double(o[D + a]);
          out[k].velocity[a] += w * double(o[2 * D + a]);
        }
        out[k].von_mises += w * double(o[3 * D]);
        out[k].jacobian += w * double(o[3 * D + 1]);
        out[k].von_mises_strain += w * double(o[3 * D + 2]);
        out[k].plastic_strain += w * double(o[3 * D + 3]);
        out[k].phase_field += w * double(o[3 * D + 4]);
      }
    }
    return out;
  }

 protected:
  // Output fields of snapshots: refresh what is computed only for output.
  virtual void update_observables() {}
  // The stress measures that probes read (von_mises, J, ...), when asked for.
  virtual void update_stress_observables() {}

  const BodyProperties& props(size_t b) {
    while (props_.size() < scene_.bodies.size())
      props_.push_back(body_properties(scene_.bodies[props_.size()], scene_.solver, D));
    return props_[b];
  }

  Real* optional_real(const char* name) { return particles_.has(name) ? particles_.template get<Real>(name) : nullptr; }

  Kinematics<D, Real> kinematics() {
    return Kinematics<D, Real>{particles_.template get<Vec<D, Real>>(field::reference_position),
                               particles_.template get<Vec<D, Real>>(field::displacement),
                               particles_.template get<Vec<D, Real>>(field::velocity),
                               particles_.template get<Vec<D, Real>>(field::acceleration),
                               particles_.template get<Real>(kinematic_volume_),
                               ghost_flags()};
  }

  // One timed stage of the recipe; a device error names it
  // (backend_error.hpp), and in the checked mode (MFSD_CUDA_SYNC_CHECK=1) the
  // stage ends with a synchronisation so that its kernels' faults are found
  // in it. Distributed runs refresh the ghosts' fields the recipe names
  // before and after the stage (step_recipe.hpp).
  template <class F>
  void run(const char* name, F&& f) {
    const StageRecipe* stage = ghosts_ ? recipe_.find(name) : nullptr;
    if (stage && !stage->refresh_before.empty()) refresh_halo(stage->refresh_before);
    const int id = timers_.id(name);
    clock_.start(id);
    run_stage<B>(name, stage_names_, std::forward<F>(f));
    clock_.stop(id, timers_);
    if (stage && !stage->refresh_after.empty()) refresh_halo(stage->refresh_after);
  }

  // The method's recipe: its stages registered for the timers and the
  // device-error messages, in the recipe's order.
  void set_recipe(StepRecipe recipe) {
    recipe_ = std::move(recipe);
    for (const StageRecipe& s : recipe_.stages())
      if (s.present) {
        timers_.id(s.name.c_str());
        stage_names_ += (stage_names_.empty() ? "" : ", ") + s.name;
      }
    has_loads_ = has_load_condition(scene_);
  }
  const StepRecipe& recipe() const { return recipe_; }

  // The method's stages of a step (begin_step, end_step): up to the forces
  // (before the contact), the advance after the boundary conditions, and
  // the host's part of the step's synchronisation (its time step).
  virtual void forces(double dt) = 0;
  virtual void advance(double dt) = 0;
  virtual void finish_step(double dt) = 0;
  // Before the contact stage (outside its clock; distributed checks), and
  // inside it before the contact's forces.
  virtual void before_contact() {}
  virtual void prepare_contact() {}
  // The fields the conditions and the contact act on.
  virtual Kinematics<D, Real> step_kinematics() { return kinematics(); }

  // A distributed run's refresh of the ghosts' copies of these fields, timed
  // as the stage "halo".
  void refresh_halo(const std::vector<std::string>& names) {
    run("halo", [&] { refresh_stage_ghosts(names); });
  }
  // A method whose fields hold particle indices translates them around the
  // exchange (RKPM's Kronecker nodes).
  virtual void refresh_stage_ghosts(const std::vector<std::string>& names) { refresh_ghosts(names); }

  virtual bool ghosts_supported() const { return false; }

  // Distributed runs: the send and receive indices of the ghost exchange in
  // the solver's order, once the set-up has reordered the particles.
  void bind_ghosts();

  // Distributed runs: the ghosts' copies of these fields (those registered)
  // from their owners, in one message per pair of ranks (each rank's block
  // holds the fields one after the other). Nothing in a single-process run.
  void refresh_ghosts(std::initializer_list<const char*> names) {
    refresh_ghosts(std::vector<std::string>(names.begin(), names.end()));
  }
  // Every field but the local ids and the ghost flags (a method whose passes
  // read partners' fields in many places: ULSPH).
  void refresh_all_ghosts();
  void refresh_ghosts(const std::vector<std::string>& names);

  // Distributed runs of methods whose particles move through the cut (ULSPH;
  // docs/distributed.md, "Migration"): every field of each owned particle
  // goes to its new owner and to the ranks whose halo (`radius`) now holds
  // it; the held particles are put in the single-process run's relative
  // order (body, set-up cell key in field::order_key, global index), so
  // that every row still sums its neighbours in that run's order. Then the
  // exchange plan, the lists of the conditions, probes and planes follow,
  // and after_migration() re-binds what the method keeps by index.
  void migrate_particles(double radius);

  // After this rank's particles changed (a migration, or a checkpoint of
  // migrated particles restored): local ids are the positions, the ghost
  // flags the exchange's; the body ranges, the lists of the conditions,
  // probes and planes, the exchange's indices and the method's own follow.
  void follow_membership();

 public:
  void expect_particles(long n) override {
    if (!ghosts_ || !ghosts_supported()) Solver::expect_particles(n);
    particles_.resize(Index(n));
    sequence<B, Index>(particles_.template buffer<Index>(field::id));
    membership_restored_ = true;
  }

 protected:
  // What a method keeps by particle index besides the shared lists (search
  // ranges, contact candidates), after migrate_particles().
  virtual void after_migration() {}

  // Contact set up again over the current particles (after a migration),
  // its accumulated work and forces kept.
  void setup_contact_again(std::vector<unsigned char> near_surface) {
    StateArchive kept;
    contact_.save(kept);
    setup_contact(std::move(near_surface));
    contact_.restore(kept);
  }

  // Distributed runs: the time step's statistics over the whole scene.
  void maxima_over_ranks(StepStatistics<Real>& s);

  // MFSD_VERIFY_HALO=1 (test only; host/halo/halo_check.hpp): every
  // particle within `support` (per body of the owned particle) of an owned
  // particle at the positions x, of its own body or (across_bodies) of any,
  // is held by this rank; else the run stops with the missing pair.
  void verify_halo(const std::vector<Vec<D, Real>>& x, const std::vector<double>& support, bool across_bodies);

  // The owned particles among [begin, end) (all of them in a single-process run).
  Index owned_in(Index begin, Index end) {
    if (!ghosts_) return end - begin;
    const auto& mask = ghosts_->ghost_mask();  // by local id: the ranges hold the same particles
    Index owned = 0;
    for (Index i = begin; i < end; ++i) owned += mask[size_t(i)] ? 0 : 1;
    return owned;
  }

  // Null in a single-process run; else 1 per ghost particle, in the solver's order.
  const unsigned char* ghost_flags() {
    return ghosts_ ? particles_.template get<unsigned char>(field::ghost) : nullptr;
  }

  // The fields every method has, from the scene's initial particles: id,
  // body, constrained, X (also in double for the set-up's searches), u, v
  // and V0. Index ranges of the bodies follow.
  void upload_kinematics() {
    const size_t n = init_.size();
    std::vector<Index> id(n);
    std::vector<Vec<D, double>> xd(n);
    std::vector<Vec<D, Real>> x(n), v(n);
    std::vector<Real> volume(n);
    for (size_t i = 0; i < n; ++i) {
      id[i] = Index(i);
      for (int a = 0; a < D; ++a) {
        xd[i].v[a] = init_.position[i][a];
        x[i].v[a] = Real(init_.position[i][a]);
        v[i].v[a] = Real(init_.velocity[i][a]);
      }
      volume[i] = Real(init_.volume[i]);
    }
    particles_.template add<Index>(field::id);
    from_host<B>(id, particles_.template buffer<Index>(field::id));
    particles_.template add<int>(field::body);
    from_host<B>(init_.body, particles_.template buffer<int>(field::body));
    particles_.template add<unsigned char>(field::constrained);
    from_host<B>(init_.constrained, particles_.template buffer<unsigned char>(field::constrained));
    if (ghosts_) {
      particles_.template add<unsigned char>(field::ghost);
      from_host<B>(ghosts_->ghost_mask(), particles_.template buffer<unsigned char>(field::ghost));
    }
    particles_.template add<Vec<D, double>>(field::reference_position_double);
    from_host<B>(xd, particles_.template buffer<Vec<D, double>>(field::reference_position_double));
    particles_.template add<Vec<D, Real>>(field::reference_position);
    from_host<B>(x, particles_.template buffer<Vec<D, Real>>(field::reference_position));
    particles_.template add<Vec<D, Real>>(field::velocity);
    from_host<B>(v, particles_.template buffer<Vec<D, Real>>(field::velocity));
    particles_.template add<Vec<D, Real>>(field::displacement);
    if (!init_.displacement.empty()) {
      std::vector<Vec<D, Real>> u(n);
      for (size_t i = 0; i < n; ++i)
        for (int a = 0; a < D; ++a) u[i].v[a] = Real(init_.displacement[i][a]);
      from_host<B>(u, particles_.template buffer<Vec<D, Real>>(field::displacement));
    }
    particles_.template add<Real>(field::volume);
    from_host<B>(volume, particles_.template buffer<Real>(field::volume));
    for (size_t b = 0; b < scene_.bodies.size(); ++b)
      ranges_.push_back(BodyRange{Index(init_.body_range[b].begin), Index(init_.body_range[b].end)});
  }

  // At the end of set-up: the per-particle arrays of the initial particles,
  // now in the particle fields, go, so that a run holds its state and not a
  // second copy of it (issue 24, item 6); the id lists stay.
  void release_initial_particles() {
    InitialParticles kept;
    kept.dimension = init_.dimension;
    kept.body_range = std::move(init_.body_range);
    kept.probe_particles = std::move(init_.probe_particles);
    kept.constrained_count = std::move(init_.constrained_count);
    kept.clamp_particles = std::move(init_.clamp_particles);
    kept.condition_particles = std::move(init_.condition_particles);
    kept.measure_particles = std::move(init_.measure_particles);
    kept.rigid_markers = std::move(init_.rigid_markers);
    init_ = std::move(kept);
  }

  // where[id] = the current index of the particle with original id `id`.
  std::vector<Index> locate() {
    const auto ids = to_host<B>(particles_.template buffer<Index>(field::id));
    std::vector<Index> where(ids.size());
    for (size_t k = 0; k < ids.size(); ++k) where[size_t(ids[k])] = Index(k);
    return where;
  }

  // The particles of the probes and measure planes, by their current index.
  void locate_probes(const std::vector<Index>& where) {
    for (const auto& p : scene_.probes)
      for (const auto& f : p.fields)
        probes_need_stress_ =
            probes_need_stress_ || f == "von_mises" || f == "J" || f == "von_mises_strain" || f == "plastic_strain";
    std::vector<Index> probe_index;
    probe_offsets_.assign(1, 0);
    for (const auto& members : init_.probe_particles) {
      for (long id : members) probe_index.push_back(where[size_t(id)]);
      probe_offsets_.push_back(probe_index.size());
    }
    from_host<B>(probe_index, probe_index_);
    std::vector<Index> measure_index;
    std::vector<Real> measure_density;
    measure_offsets_.assign(1, 0);
    const auto body = to_host<B>(particles_.template buffer<int>(field::body));
    for (const auto& members : init_.measure_particles) {
      for (long id : members) {
        measure_index.push_back(where[size_t(id)]);
        measure_density.push_back(Real(scene_.bodies[size_t(body[size_t(where[size_t(id)])])].material.density));
      }
      measure_offsets_.push_back(measure_index.size());
    }
    from_host<B>(measure_index, measure_index_);
    from_host<B>(measure_density, measure_density_);
    measure_buffer_.resize(measure_index.size() * 2 * D);
    probe_buffer_.resize(probe_index.size() * kProbeValues<D>);
  }

  // The set-up report's particle and pair figures from the method's CSR
  // offsets (host copy) and the bytes its pair data take.
  void report_particles_and_pairs(const std::vector<PairIndex>& offsets, double pair_bytes) {
    const Index n = particles_.size();
    report_.particles = n;
    report_.body_particles.clear();
    for (auto& r : ranges_) report_.body_particles.push_back(r.size());
    report_.pairs = n ? long(offsets[size_t(n)]) : 0;
    report_.mean_neighbors = n ? double(report_.pairs) / n : 0;
    report_.min_neighbors = n ? std::numeric_limits<long>::max() : 0;
    report_.max_neighbors = 0;
    for (Index i = 0; i < n; ++i) {
      const long c = long(offsets[size_t(i) + 1] - offsets[size_t(i)]);
      report_.min_neighbors = std::min(report_.min_neighbors, c);
      report_.max_neighbors = std::max(report_.max_neighbors, c);
    }
    report_.bytes_per_particle = n ? (double(particles_.bytes()) + pair_bytes) / n : 0;
  }

  // Contact: `near_surface` marks the particles that can touch (the method's
  // choice). The solver's own contact runs when it has partners (two bodies,
  // a rigid body or self-contact); the part is kept for the contact with
  // another method's solver.
  void setup_contact(std::vector<unsigned char> near_surface) {
    const ContactSpec& spec = scene_.contact;
    if (!spec.enabled) return;
    size_t in_contact = 0;
    for (size_t b = 0; b < scene_.bodies.size(); ++b)
      in_contact += std::count(spec.bodies.begin(), spec.bodies.end(), scene_.bodies[b].name);
    const bool between_particles = in_contact >= 2 || !spec.self_contact.empty();
    // Distributed runs. Where the ghosts are the current configuration's
    // neighbours (ULSPH) they are candidates too, as the partners of the
    // owned particles near the cut; the contact's sums leave them out.
    // Elsewhere (TLSPH: the reference configuration's) the candidates are the
    // owned particles, and contact between particles takes the other ranks'
    // candidates near this rank's as remote partners at every step.
    std::vector<unsigned char> ghost;
    const bool remote = ghosts_ && !ghosts_are_current_neighbours();
    if (ghosts_) ghost = to_host<B>(particles_.template buffer<unsigned char>(field::ghost));
    if (remote) {
      for (size_t i = 0; i < near_surface.size(); ++i)
        if (ghost[i]) near_surface[i] = 0;
      ghost.clear();
    }
    contact_part_ = ContactPartSetup<Real>{{},
                                           ranges_,
                                           {},
                                           to_host<B>(particles_.template buffer<Real>(kinematic_volume_)),
                                           std::move(near_surface),
                                           std::move(ghost)};
    for (size_t b = 0; b < scene_.bodies.size(); ++b) {
      contact_part_.scene_body.push_back(b);
      contact_part_.props.push_back(props(b));
    }
    if (between_particles || !spec.rigid_bodies.empty())
      contact_.setup(scene_, init_.rigid_markers, {contact_part_}, false);
    if (remote && between_particles) contact_.attach_remote(ghosts_.get());
  }

  // Whether a distributed run's ghosts hold every particle near an owned one
  // in the current configuration (a method whose particles migrate).
  virtual bool ghosts_are_current_neighbours() const { return false; }

  // The work of conditions, walls, clamps and contact on body b.
  void add_shared_work(size_t b, BodyEnergy& e) const {
    e.external_work = conditions_.external_work(b);
    e.boundary_work = conditions_.boundary_work(b);
    e.contact_work = contact_.work(b);
  }

  void save_shared_state(StateArchive& a) {
    particles_.save(a);
    a.put_value("solver/time", time_);
    a.put_value("solver/dt_next", dt_next_);
    a.put_value("solver/steps", steps_);
    conditions_.save(a);
    contact_.save(a);
  }

  void restore_shared_state(const StateArchive& a) {
    // The particle order comes from the search; a checkpoint of another
    // order (another backend's sort) cannot be restored field by field.
    if (a.get<Index>("field/" + std::string(field::id), long(particles_.size())) !=
        to_host<B>(particles_.template buffer<Index>(field::id)))
      throw StateMismatch("the checkpoint's particle order differs from this run's (another backend?)");
    particles_.restore(a);
    time_ = a.get_value<double>("solver/time");
    dt_next_ = a.get_value<double>("solver/dt_next");
    steps_ = a.get_value<long>("solver/steps");
    conditions_.restore(a);
    contact_.restore(a);
    if (membership_restored_) {  // the particles of a checkpoint written after a migration
      membership_restored_ = false;
      follow_membership();
    }
  }

  bool inside_bounds(const Vec<D, Real>& x) const {
    for (int a = 0; a < D; ++a)
      if (!(double(x.v[a]) >= scene_.bounds.min[a] && double(x.v[a]) <= scene_.bounds.max[a])) return false;
    return true;
  }

  // Stops the run at particle i, naming the first of its fields that is not
  // finite, or its escape from the scene bounds; `inside` (field, detail)
  // names the method's own cause when the particle is finite and inside.
  [[noreturn]] void fail(Index i, const std::pair<std::string, std::string>& inside) {
    auto one = [&](const char* name, auto tag) {
      using T = decltype(tag);
      return to_host<B>(particles_.template buffer<T>(name))[size_t(i)];
    };
    const Index id = one(field::id, Index{});
    const int body = one(field::body, int{});
    const auto X = one(field::reference_position, Vec<D, Real>{});
    const auto u = one(field::displacement, Vec<D, Real>{});
    const auto v = one(field::velocity, Vec<D, Real>{});
    const auto a = one(field::acceleration, Vec<D, Real>{});
    auto finite = [](const Vec<D, Real>& w) {
      for (int k = 0; k < D; ++k)
        if (!std::isfinite(double(w.v[k]))) return false;
      return true;
    };
    std::string fieldname, detail;
    if (!finite(a)) {
      fieldname = "acceleration";
      detail = "is not finite: " + vector_text(a);
    } else if (!finite(v)) {
      fieldname = "velocity";
      detail = "is not finite: " + vector_text(v);
    } else if (!finite(u)) {
      fieldname = "displacement";
      detail = "is not finite: " + vector_text(u);
    } else if (inside_bounds(X + u)) {
      fieldname = inside.first;
      detail = inside.second + " at " + vector_text(X + u);
    } else {
      fieldname = "position";
      detail = vector_text(X + u) + " left the scene bounds";
    }
    throw NumericalFailure(steps_, time_, long(id), scene_.bodies[size_t(body)].name, fieldname, detail);
  }

  static std::string vector_text(const Vec<D, Real>& w) {
    std::string s = "(";
    for (int k = 0; k < D; ++k) s += (k ? ", " : "") + std::to_string(double(w.v[k]));
    return s + ")";
  }

  // The volume field whose rho0 V is the mass conditions, walls, clamps,
  // measure planes and contact act on: V0, or RKPM's lumped mass / rho0.
  const char* kinematic_volume_ = field::volume;
  Scene scene_;
  InitialParticles init_;
  SolverOptions options_;
  std::vector<BodyProperties> props_;
  ParticleSet<B> particles_;
  std::vector<BodyRange> ranges_;
  Conditions<B, D, Real> conditions_;
  Contact<B, D, Real> contact_;
  ContactPartSetup<Real> contact_part_;
  std::vector<std::pair<std::string, const char*>> snapshot_fields_;  // output name, particle field
  DeviceVector<B, Index> probe_index_;  // all probes' particles, probe k at [offsets[k], offsets[k+1])
  std::vector<size_t> probe_offsets_{0};
  bool probes_need_stress_ = false;  // von_mises, J, ... requested by a probe
  DeviceVector<B, Real> probe_buffer_;
  DeviceVector<B, Index> measure_index_;  // all measure planes' particles, plane k at [offsets[k], offsets[k+1])
  DeviceVector<B, Real> measure_density_;
  std::vector<size_t> measure_offsets_{0};
  DeviceVector<B, Real> measure_buffer_;
  StageClock<B> clock_;
  StageTimers timers_;
  DeviceResults<B> results_;  // the step's sums until its one synchronisation
  std::string stage_names_;   // the stages of a step, for deferred device errors
  StepRecipe recipe_;
  bool has_loads_ = false;  // some condition is a load (the loads stage runs)
  SetupReport report_;
  double time_ = 0, dt_next_ = 0;
  long steps_ = 0;
  // The step between begin_step() and end_step(): its dt and the host round trips before it.
  double step_dt_ = 0;
  long round_trips_before_ = 0;
  std::shared_ptr<GhostExchange> ghosts_;  // distributed runs only
  bool membership_restored_ = false;       // expect_particles() before restore_state()
  DeviceVector<B, Index> ghost_send_index_, ghost_receive_index_;
};

}  // namespace mfsd

#include "host/solver/common/particle_solver_distributed.hpp"
