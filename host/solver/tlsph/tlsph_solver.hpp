// Total-Lagrangian SPH solver for one backend, precision and dimension.
// A step is the position-based Verlet pipeline of seed 000 eq. 35-38 in three
// passes over the particles plus the clamps, each stage fused so that a
// particle's fields are read once per pass:
//   stress           per body: F, u to t + dt/2 (eq. 35), then the material x
//                    hourglass variant matrices            (eq. 3, 7, 25-28)
//   force            per body: gathered pair sums (eq. 20, 27, 32), then
//                    v to t + dt                           (eq. 36)
//   contact          pair forces at the half-step positions (tlsph_contact.hpp),
//                    v += dt f/m like a load
//   loads            per load: v += dt f/m at t + dt/2 (conditions.hpp)
//   boundary         velocity conditions at t + dt, then clamps, with reactions
//   relaxation       dynamic relaxation of v (tlsph_relaxation.hpp), when
//                    the scene asks for it; holds the boundary's particles
//   deformation_rate dF/dt at the new velocity (eq. 22), F, u to t + dt
//                    (eq. 37), reduced to max |v|, max |a| and health
//   time_step        next dt on the host                   (eq. 38)
// Positions are stored as displacements u = x - X, so that in single precision
// the small increments dt v keep their full relative accuracy.
// Each stage is timed on its own. Include after the backend header.
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "host/backend/device_results.hpp"
#include "host/backend/round_trips.hpp"
#include "host/particles/field_names.hpp"
#include "host/particles/particle_set.hpp"
#include "host/scene/body_properties.hpp"
#include "host/solver/common/particle_solver.hpp"
#include "host/solver/numerical_failure.hpp"
#include "host/solver/solver.hpp"
#include "host/solver/stage_run.hpp"
#include "host/solver/tlsph/reference_neighbor_list.hpp"
#include "host/solver/tlsph/tlsph_body_kernels.hpp"
#include "host/solver/tlsph/tlsph_fracture_kernels.hpp"
#include "host/solver/tlsph/tlsph_relaxation.hpp"
#include "kernels/core/step_statistics.hpp"
#include "kernels/fracture/crack_tip.hpp"
#include "kernels/tlsph/correction_matrix.hpp"
#include "kernels/tlsph/deformation_rate.hpp"
#include "kernels/tlsph/deformation_rate_half.hpp"
#include "kernels/tlsph/hourglass_indicator.hpp"

namespace mfsd {

// Initial plastic state: C_p^{-1} = I, alpha = 0, no plastic work.
template <class Real>
struct InitialPlasticStateFunctor {
  J2State<Real>* state;
  MFSD_HD void operator()(Index i) const { state[i] = J2State<Real>::initial(); }
};

// Sets F = I.
template <int D, class Real>
struct IdentityFunctor {
  Mat<D, Real>* m;
  MFSD_HD void operator()(Index i) const { m[i] = Mat<D, Real>::identity(); }
};

// F = I + grad u (initial displacement field).
template <int D, class Real>
struct AddIdentityFunctor {
  const Mat<D, Real>* grad_u;
  Mat<D, Real>* F;
  MFSD_HD void operator()(Index i) const { F[i] = Mat<D, Real>::identity() + grad_u[i]; }
};

template <class Real>
struct MaxPlus {
  MFSD_HD Real operator()(Real a, Real b) const { return math::max(a, b); }
};
// A particle's value, 0 for a ghost (distributed runs; ghost null otherwise).
template <class Real>
struct ReadScalar {
  const Real* p;
  const unsigned char* ghost = nullptr;
  MFSD_HD double operator()(Index i) const { return ghost && ghost[i] ? 0.0 : double(p[i]); }
};
template <class Real>
struct ReadScalarReal {
  const Real* p;
  const unsigned char* ghost = nullptr;
  MFSD_HD Real operator()(Index i) const { return ghost && ghost[i] ? Real(0) : p[i]; }
};

template <class B, int D, class Real>
class TlsphSolver final : public ParticleSolver<B, D, Real> {
  using Base = ParticleSolver<B, D, Real>;
  using Base::clock_, Base::conditions_, Base::contact_, Base::dt_next_, Base::init_, Base::options_, Base::particles_,
      Base::probes_need_stress_, Base::ranges_, Base::report_, Base::results_, Base::scene_, Base::snapshot_fields_,
      Base::stage_names_, Base::steps_, Base::time_, Base::timers_;
  using Base::declare_stage, Base::props, Base::run;

 public:
  TlsphSolver(const Scene& scene, const InitialParticles& init, const SolverOptions& options)
      : Base(scene, init, options) {
    bool loads = false;
    for (const auto& c : scene.conditions) loads = loads || c.type != ConditionSpec::Type::velocity;
    has_fracture_ = has_fracture_body(scene);
    cracks_ = crack_specs(scene);
    for (const char* name : {"stress", "force", "phase_field", "contact", "loads", "boundary", "relaxation",
                             "deformation_rate", "time_step"})
      if ((loads || std::string(name) != "loads") && (scene.contact.enabled || std::string(name) != "contact") &&
          (scene.solver.relaxation.enabled || std::string(name) != "relaxation") &&
          (has_fracture_ || std::string(name) != "phase_field"))
        declare_stage(name);
    has_loads_ = loads;
    conditions_.compile(scene_);
  }

  void initialize() override {
    const Index n = particles_.size();
    this->upload_kinematics();
    upload_model_fields();

    // Reference neighbour search with reordering, then B0 (seed 000 eq. 21).
    std::vector<BodySearch> search;
    for (size_t b = 0; b < scene_.bodies.size(); ++b) {
      search.push_back(BodySearch{ranges_[b], props(b).h});
      if (this->ghosts_) {  // the whole body's cells (distributed runs)
        for (size_t k = 0; k < 6; ++k) search.back().box[k] = this->ghosts_->body_boxes()[6 * b + k];
        search.back().fixed_box = true;
      }
    }
    const bool paper_limiter =
        scene_.solver.hourglass == HourglassControl::genog && scene_.solver.genog_limiter == GenogLimiterChoice::paper;
    std::vector<Notch<D>> notches;  // pairs they cut are left out (seed 001 section 3.3.1)
    for (size_t b = 0; b < scene_.bodies.size(); ++b)
      for (const auto& points : scene_.bodies[b].material.fracture.notches) {
        Notch<D> cut{};
        for (size_t k = 0; k < points.size(); ++k)
          for (int a = 0; a < D; ++a) cut.p[k].v[a] = points[k][size_t(a)];
        cut.body = int(b);
        notches.push_back(cut);
      }
    // The half-pair loop (issue 24) on the CPU: where every per-step pass runs
    // it (no relaxation and no phase field, whose passes read full rows), its
    // list is filled straight from the search and the full rows never exist;
    // otherwise it is derived from the full list.
    const bool sliced = options_.pair_layout == SolverOptions::PairLayout::sliced;  // a full-gather layout
    const bool half_loop =
        std::is_same<B, Cpu>::value && options_.pair_loop != SolverOptions::PairLoop::full && !sliced;
    const bool half_only = half_loop && scene_.solver.reorder && !scene_.solver.relaxation.enabled && !has_fracture_;
    // Float pair data in a double run (issue 24 item 4): the half list alone.
    const bool half_float =
        options_.pair_precision == SolverOptions::PairPrecision::single && !std::is_same<Real, float>::value;
    if (half_float && !half_only)
      throw UsageError(
          "--pair-precision float stores the CPU half-pair loop's own list in float; this run does not keep that "
          "list alone (it runs on the GPU, with --pair-loop full or --pair-layout sliced, with relaxation or a phase "
          "field, or without reordering)");
    report_.pair_precision = half_float || std::is_same<Real, float>::value ? "float" : "double";
    particles_.template add<Mat<D, Real>>(field::correction_matrix);  // the moment matrices, then B0
    pairs_ = build_reference_neighbor_list<B, D, Real>(particles_, search, scene_.solver.reorder, paper_limiter,
                                                       notches, field::correction_matrix, half_only, half_float);
    particles_.remove(field::reference_position_double);
    this->bind_ghosts();  // distributed runs: the exchange in the reordered indices
    if constexpr (std::is_same<B, Cpu>::value)
      if (half_loop && !half_only) build_half_pair_list(pairs_, n);

    DeviceVector<B, unsigned char> regularized(size_t(n), 0);
    parallel_for<B>(
        n, CorrectionFromMomentFunctor<D, Real>{particles_.template get<Mat<D, Real>>(field::correction_matrix),
                                                raw(regularized), Real(scene_.solver.correction_floor)});
    report_.regularized_corrections =
        long(thrust::count(BackendTraits<B>::policy(), regularized.begin(), regularized.end(), (unsigned char)1));
    // A ghost's neighbourhood is cut by the halo: its B0 comes from its owner.
    this->refresh_ghosts({field::correction_matrix});

    // State and stage fields, registered by need.
    particles_.template add<Mat<D, Real>>(field::deformation_gradient);
    particles_.template add<Mat<D, Real>>(field::deformation_rate);
    particles_.template add<Vec<D, Real>>(field::acceleration);
    // The packed neighbour record of the vectorized CPU force loop (3-D genog)
    // holds Q and F^{-1} in place of the separate fields, which are then left
    // out (the phase field's stress stage still writes Q); the indicator at
    // output times takes a scratch F^{-1} of its own.
    const bool record = scene_.solver.hourglass == HourglassControl::genog && D == 3 && std::is_same<B, Cpu>::value &&
                        options_.packed_genog_record;
    if (record) particles_.template add<GenogNeighborRecord<Real>>(field::genog_neighbor_record);
    if (!record || has_fracture_) particles_.template add<Mat<D, Real>>(field::force_stress);
    if (!record) particles_.template add<Mat<D, Real>>(field::inverse_deformation_gradient);  // genog + indicator
    if (scene_.solver.hourglass == HourglassControl::laplacian) particles_.template add<Real>(field::shear_coefficient);
    if (scene_.solver.hourglass == HourglassControl::genog) particles_.template add<Mat<D, Real>>(field::shear_stress);
    particles_.template add<Real>(field::hourglass_indicator);
    particles_.template add<Real>(field::von_mises);
    particles_.template add<Real>(field::jacobian);
    particles_.template add<Real>(field::von_mises_strain);
    // Plastic state over the whole set when some body is plastic (bodies are ranges of one set).
    if (has_plastic_body(scene_)) {
      particles_.template add<J2State<Real>>(field::plastic_state);
      particles_.template add<Real>(field::plastic_strain);
    }
    if (scene_.solver.damping_factor > 0) particles_.template add<Real>(field::damping_work);  // zero
    bind_views();
    v_.ghost = this->ghost_flags();
    // Snapshot fields: (output name, particle field), written by every writer under the name.
    snapshot_fields_ = {{"von_mises", field::von_mises},
                        {"J", field::jacobian},
                        {"hourglass", field::hourglass_indicator},
                        {"von_mises_strain", field::von_mises_strain}};
    if (v_.plastic_strain) snapshot_fields_.emplace_back("plastic_strain", field::plastic_strain);
    if (has_fracture_) snapshot_fields_.emplace_back("phase_field", field::phase_field);
    parallel_for<B>(n, IdentityFunctor<D, Real>{v_.deformation_gradient});
    if (v_.plastic_state) parallel_for<B>(n, InitialPlasticStateFunctor<Real>{v_.plastic_state});

    for (size_t b = 0; b < scene_.bodies.size(); ++b) bodies_.push_back(make_body_kernels(b));

    // Clamps, conditions, loads and probe particles, located after reordering.
    const auto ids = to_host<B>(particles_.template buffer<Index>(field::id));
    const std::vector<Index> where = this->locate();
    conditions_.setup(init_, where, particles_.template get<Index>(field::id), ranges_);
    if (scene_.contact.enabled) {
      std::vector<BodyProperties> body_props;
      for (size_t b = 0; b < scene_.bodies.size(); ++b) body_props.push_back(props(b));
      // Contact candidates: the surface particles and their reference
      // neighbours (a layer one kernel support deep), in the solver's order.
      // From the full rows, or from the half rows in both directions.
      std::vector<unsigned char> near_surface(size_t(n), 0);
      const bool full = pairs_.full_rows;
      const auto offsets = to_host<B>(full ? pairs_.offsets : pairs_.half_offsets);
      const auto neighbor = to_host<B>(full ? pairs_.neighbor : pairs_.half_neighbor);
      const auto surface = [&](Index i) { return init_.surface[size_t(ids[size_t(i)])] != 0; };
      for (Index i = 0; i < n; ++i) {
        if (surface(i)) near_surface[size_t(i)] = 1;
        for (PairIndex k = offsets[size_t(i)]; k < offsets[size_t(i) + 1]; ++k) {
          if (surface(i)) near_surface[size_t(neighbor[k])] = 1;
          if (!full && surface(neighbor[k])) near_surface[size_t(i)] = 1;
        }
      }
      this->setup_contact(std::move(near_surface));
    }
    {
      std::vector<double> density, viscosity;
      double support = 0;
      const RelaxationSpec& r = scene_.solver.relaxation;
      for (size_t b = 0; b < scene_.bodies.size(); ++b) {
        const double rho = scene_.bodies[b].material.density;
        density.push_back(rho);
        // eta = factor p rho0 c0 h / CFL: factor 1 makes (eta/p) dt / (rho0 h^2) = 1 (docs/theory.md).
        viscosity.push_back(r.factor > 0
                                ? r.factor * r.random_ratio * rho * props(b).c0 * props(b).h / scene_.solver.cfl
                                : r.viscosity);
        support = std::max(support, 2.0 * props(b).h);
      }
      // Held by the relaxation: the particles of clamps and velocity conditions.
      std::vector<unsigned char> held(size_t(n), 0);
      for (size_t i = 0; i < init_.constrained.size(); ++i)
        if (init_.constrained[i]) held[size_t(where[i])] = 1;
      for (size_t c = 0; c < scene_.conditions.size(); ++c)
        if (scene_.conditions[c].type == ConditionSpec::Type::velocity)
          for (long id : init_.condition_particles[c].ids) held[size_t(where[size_t(id)])] = 1;
      relaxation_.setup(scene_.solver.relaxation, ranges_, density, viscosity,
                        r.enabled ? to_host<B>(particles_.template buffer<Vec<D, Real>>(field::reference_position))
                                  : std::vector<Vec<D, Real>>{},
                        support, held);
    }
    this->locate_probes(where);
    const bool initial_displacement = !init_.displacement.empty();
    this->release_initial_particles();

    // An initial displacement field deforms the body: F = I + grad u (seed 000
    // eq. 22 with u in place of v).
    if (initial_displacement) {
      gradient_into_rate(v_.displacement);
      parallel_for<B>(n, AddIdentityFunctor<D, Real>{v_.deformation_rate, v_.deformation_gradient});
      this->refresh_ghosts({field::deformation_gradient});
    }
    results_.clear();
    conditions_.apply_initial(v_, results_);  // velocity conditions at t = 0, clamps
    conditions_.apply_fields(v_, v_.active_tension, 0.0, 0.0, 0,
                             results_);  // time-dependent active potentials at t = 0
    results_.fetch();
    conditions_.collect(results_, v_);
    // Distributed runs: conditions act on owned particles; ghosts follow
    // their owners after every pass whose pair sums their cut rows get wrong.
    this->refresh_ghosts({field::velocity, field::displacement});

    // Initial rates and forces, so that the first time step sees them.
    gradient_into_rate(v_.velocity);
    this->refresh_ghosts({field::deformation_rate});
    for (auto& k : bodies_) k->prepare_step(0.0);
    for (auto& k : bodies_) k->stress(v_, Real(0));
    for (auto& k : bodies_) k->acceleration(v_, Real(0));
    this->refresh_ghosts({field::acceleration, field::velocity});
    update_time_step(statistics());
    for (auto& k : bodies_) gravity_at_start_.push_back(k->energy(v_).gravity);  // with an initial displacement

    // Where every per-step pass runs the half-pair loop (no relaxation, no
    // phase field, whose passes read full rows), the full rows go.
    const bool release = v_.half_bandwidth >= 0 && !relaxation_.enabled() && !has_fracture_;
    if (release) {
      pairs_.release_full_rows();
      bind_views();
    }
    // The per-step passes' full rows in the sliced layout (issue 24 item 3):
    // the same sums in the same order, read coalesced on the GPU.
    if (sliced) {
      make_sliced_layout(pairs_, n, kSliceHeight);
      report_.pair_layout = "sliced";
      bind_views();
    }

    // Set-up report.
    this->report_particles_and_pairs(to_host<B>(pairs_.offsets), pairs_.full_bytes() + pairs_.half_bytes());
  }

  void begin_step() override {
    this->round_trips_before_ = round_trips();
    const double dt = this->step_dt_ = dt_next_;
    const Real half_dt = Real(0.5 * dt);
    results_.clear();
    run("stress", [&] {
      conditions_.apply_fields(v_, v_.active_tension, time_ + 0.5 * dt, dt, steps_ + 1, results_);
      for (auto& k : bodies_) k->prepare_step(time_ + 0.5 * dt);
      for (auto& k : bodies_) k->stress(v_, half_dt);
    });
    run("force", [&] {
      for (auto& k : bodies_) k->acceleration(v_, Real(dt));
    });
    if (has_fracture_) {
      run("phase_field", [&] {
        for (auto& k : bodies_) k->phase_field_rate(v_, Real(dt));
        for (auto& k : bodies_) k->phase_field_half_step(v_, half_dt);
      });
      // Distributed runs: the ghosts' s and ds/dt (their Laplacians' rows
      // are cut). The owned rows' Laplacians and crack surfaces read s; the
      // ghosts' own stress stage reads both (s_n+1/2 = s + dt/2 ds/dt), and
      // with them the degradation and the history. Their next values are
      // read by their own half step alone, whose s the refresh replaces.
      if (this->ghosts_) run("halo", [&] { this->refresh_ghosts({field::phase_field, field::phase_field_rate}); });
    }
    if (contact_.enabled()) run("contact", [&] { contact_.apply(v_, time_, dt, results_); });
  }

  void end_step() override {
    const Index n = particles_.size();
    const double dt = this->step_dt_;
    const Real half_dt = Real(0.5 * dt);
    if (has_loads_) run("loads", [&] { conditions_.apply_loads(v_, time_, dt, steps_ + 1, results_); });
    run("boundary", [&] { conditions_.apply_boundary(v_, time_, dt, steps_ + 1, results_); });
    if (relaxation_.enabled()) run("relaxation", [&] { relaxation_.apply(v_, time_, dt, results_); });
    // Distributed runs: the new velocities of the ghosts (their rows' sums
    // were cut), read by the owned rows' rate sums.
    if (this->ghosts_) run("halo", [&] { this->refresh_ghosts({field::velocity, field::acceleration}); });
    ResultSlot<StepStatistics<Real>> stats_slot;
    run("deformation_rate", [&] {
      RateHalfStepFunctor<D, Real> f{
          v_.pairs,        v_.velocity, v_.correction,       v_.deformation_rate, v_.deformation_gradient,
          v_.displacement, half_dt,     statistics_functor()};
      const StepStatistics<Real> init{Real(0), Real(0), Real(0), Real(0), n};
      if constexpr (std::is_same<B, Cpu>::value) {
        if (v_.half_bandwidth >= 0) {  // the half-pair loop, dF/dt summed in place of the rate
          auto loop = [&](const auto& h) {
            stats_slot = results_.template reduce_into<StepStatistics<Real>>([&](StepStatistics<Real>* out) {
              half_pair_reduce(
                  Cpu{}, Index(0), n, v_.half_bandwidth, Mat<D, Real>::zero(), v_.deformation_rate, rate_workspace_, h,
                  [&](Index i, const Mat<D, Real>& total) { return h.finish(i, total); }, init,
                  StepStatisticsCombine<Real>{}, out);
            });
          };
          v_.with_half_pairs([&](const auto& pairs) {
            using P = HalfPairReal<decltype(pairs)>;
            loop(RateHalfStepHalfFunctor<D, Real, P>{f, {pairs, v_.velocity, v_.volume}});
          });
          return;
        }
      }
      stats_slot = results_.reduce(Index(0), n, f, init, StepStatisticsCombine<Real>{});
    });
    // Distributed runs: the state the next step's stress stage reads.
    if (this->ghosts_)
      run("halo", [&] {
        this->refresh_ghosts({field::displacement, field::deformation_gradient, field::deformation_rate});
      });
    // The step's one synchronisation: every sum of the step comes to the host.
    run("time_step", [&] {
      results_.fetch();
      conditions_.collect(results_, v_);
      contact_.collect(results_);
      relaxation_.collect(results_);
      const StepStatistics<Real> stats = results_.get(stats_slot);
      time_ += dt;
      ++steps_;
      if (stats.first_bad < n) fail(stats.first_bad);
      update_time_step(stats);
    });
    clock_.collect(timers_);
    timers_.add_round_trips(round_trips() - this->round_trips_before_);
  }

  void save_state(StateArchive& a) override {
    this->save_shared_state(a);
    a.put("solver/gravity_at_start", gravity_at_start_);
    relaxation_.save(a);
  }

  void restore_state(const StateArchive& a) override {
    this->restore_shared_state(a);
    gravity_at_start_ = a.get<double>("solver/gravity_at_start", long(bodies_.size()));
    relaxation_.restore(a);
  }

  EnergySample energies() override {
    EnergySample e;
    e.with_fracture = has_fracture_;
    e.with_active = has_active_stress(scene_);
    for (size_t b = 0; b < bodies_.size(); ++b) {
      const EnergySums s = bodies_[b]->energy(v_);
      e.kinetic += s.kinetic;
      e.strain += s.strain;
      for (int a = 0; a < 3; ++a) e.momentum[a] += s.momentum[a];
      BodyEnergy be;
      be.kinetic = s.kinetic;
      be.strain = s.strain;
      be.plastic = s.plastic;
      this->add_shared_work(b, be);
      be.relaxation = relaxation_.dissipation(b);
      be.gravity_work = s.gravity - gravity_at_start_[b];
      be.damping = s.damping;
      be.fracture = s.fracture;
      be.crack_surface = s.surface;
      be.active_work = s.active;
      for (int a = 0; a < 3; ++a) be.momentum[a] = s.momentum[a];
      e.bodies.push_back(be);
    }
    compute_hourglass_indicator();
    // Over the owned particles (distributed runs: not the ghosts).
    const Index n = particles_.size();
    const Index owned =
        v_.ghost ? n - Index(thrust::count(
                           BackendTraits<B>::policy(), particles_.template buffer<unsigned char>(field::ghost).begin(),
                           particles_.template buffer<unsigned char>(field::ghost).end(), (unsigned char)1))
                 : n;
    e.hourglass_max = double(
        transform_reduce<B>(0, n, ReadScalarReal<Real>{v_.hourglass_indicator, v_.ghost}, Real(0), MaxPlus<Real>{}));
    e.hourglass_mean = owned ? transform_reduce<B>(0, n, ReadScalar<Real>{v_.hourglass_indicator, v_.ghost}, 0.0,
                                                   thrust::plus<double>{}) /
                                   owned
                             : 0.0;
    return e;
  }

  std::vector<CrackTipSample> crack_tips() override {
    std::vector<CrackTipSample> out;
    for (const CrackSpec& c : cracks_) {
      CrackTipFunctor<D, Real> f{v_.reference_position, v_.phase.s, {}, {}, Real(0.5)};
      for (int a = 0; a < D; ++a) {
        f.origin.v[a] = Real(c.origin[size_t(a)]);
        f.direction.v[a] = Real(c.direction[size_t(a)]);
      }
      const BodyRange r = ranges_[c.body];
      const CrackTip<Real> tip = transform_reduce<B>(
          r.begin, r.end, f, CrackTip<Real>{Real(-1e30), r.begin, {Real(0), Real(0), Real(0)}}, CrackTipMax<Real>{});
      CrackTipSample sample;
      sample.broken = tip.reach > Real(-1e29);
      if (sample.broken) {
        sample.reach = double(tip.reach);
        for (int a = 0; a < 3; ++a) sample.reference[size_t(a)] = double(tip.X[a]);
        const Vec<D, Real> X = particles_.template buffer<Vec<D, Real>>(field::reference_position)[size_t(tip.index)];
        const Vec<D, Real> u = particles_.template buffer<Vec<D, Real>>(field::displacement)[size_t(tip.index)];
        for (int a = 0; a < D; ++a) sample.tip[size_t(a)] = double(X.v[a]) + double(u.v[a]);
        sample.length = c.notch_length + std::max(0.0, double(tip.reach));
      }
      out.push_back(sample);
    }
    return out;
  }

 private:
  bool ghosts_supported() const override { return true; }
  void update_observables() override { compute_observables(); }
  void update_stress_observables() override {
    for (auto& k : bodies_) k->stress_observables(v_);
  }

  // The fields of Holzapfel-Ogden and fracturing bodies from the scene.
  void upload_model_fields() {
    const size_t n = init_.size();
    if (!init_.fibre.empty()) {  // Holzapfel-Ogden bodies: f0, s0, k V_m; stiffening written by the stress stage
      std::vector<Vec<D, Real>> f(n), s(n);
      for (size_t i = 0; i < n; ++i)
        for (int a = 0; a < D; ++a) f[i].v[a] = Real(init_.fibre[i][a]), s[i].v[a] = Real(init_.sheet[i][a]);
      particles_.template add<Vec<D, Real>>(field::fibre);
      from_host<B>(f, particles_.template buffer<Vec<D, Real>>(field::fibre));
      particles_.template add<Vec<D, Real>>(field::sheet);
      from_host<B>(s, particles_.template buffer<Vec<D, Real>>(field::sheet));
      particles_.template add<Real>(field::active_tension);
      from_host<B>(std::vector<Real>(init_.active_tension.begin(), init_.active_tension.end()),
                   particles_.template buffer<Real>(field::active_tension));
      particles_.template add<Real>(field::stiffening);
      if (has_active_stress(scene_)) particles_.template add<Real>(field::active_work);  // zero
    }
    if (has_fracture_) {  // s = 1 (intact), the rest zero; every particle (bodies are ranges of one set)
      particles_.template add<Real>(field::phase_field);
      from_host<B>(std::vector<Real>(n, Real(1)), particles_.template buffer<Real>(field::phase_field));
      for (const char* name : {field::phase_field_rate, field::fracture_history, field::tensile_energy,
                               field::fracture_released, field::phase_field_next})
        particles_.template add<Real>(name);
      if (!init_.phase_field_lower.empty()) {
        particles_.template add<Real>(field::phase_field_lower);
        from_host<B>(std::vector<Real>(init_.phase_field_lower.begin(), init_.phase_field_lower.end()),
                     particles_.template buffer<Real>(field::phase_field_lower));
      }
    }
  }

  void bind_views() {
    auto opt_real = [&](const char* name) -> Real* {
      return particles_.has(name) ? particles_.template get<Real>(name) : nullptr;
    };
    auto opt_mat = [&](const char* name) -> Mat<D, Real>* {
      return particles_.has(name) ? particles_.template get<Mat<D, Real>>(name) : nullptr;
    };
    v_.pairs = pairs_.view();
    const bool half = pairs_.bandwidth >= 0;
    v_.half_pairs = half ? pairs_.half_view() : ReferencePairs<D, Real>{};
    v_.half_bandwidth = pairs_.bandwidth;
    v_.half_float = half && pairs_.half_float;
    v_.half_pairs_f = v_.half_float ? pairs_.half_view_f() : ReferencePairs<D, float>{};
    report_.pair_loop = half ? "half" : "full";
    v_.reference_position = particles_.template get<Vec<D, Real>>(field::reference_position);
    v_.displacement = particles_.template get<Vec<D, Real>>(field::displacement);
    v_.velocity = particles_.template get<Vec<D, Real>>(field::velocity);
    v_.acceleration = particles_.template get<Vec<D, Real>>(field::acceleration);
    v_.volume = particles_.template get<Real>(field::volume);
    v_.deformation_gradient = particles_.template get<Mat<D, Real>>(field::deformation_gradient);
    v_.deformation_rate = particles_.template get<Mat<D, Real>>(field::deformation_rate);
    v_.correction = particles_.template get<Mat<D, Real>>(field::correction_matrix);
    v_.force_stress = opt_mat(field::force_stress);
    v_.shear_coefficient = opt_real(field::shear_coefficient);
    v_.shear_stress = opt_mat(field::shear_stress);
    v_.inverse_F = opt_mat(field::inverse_deformation_gradient);
    v_.neighbor_record = particles_.has(field::genog_neighbor_record)
                             ? particles_.template get<GenogNeighborRecord<Real>>(field::genog_neighbor_record)
                             : nullptr;
    v_.hourglass_indicator = particles_.template get<Real>(field::hourglass_indicator);
    v_.von_mises = particles_.template get<Real>(field::von_mises);
    v_.jacobian = particles_.template get<Real>(field::jacobian);
    v_.von_mises_strain = particles_.template get<Real>(field::von_mises_strain);
    v_.plastic_state =
        particles_.has(field::plastic_state) ? particles_.template get<J2State<Real>>(field::plastic_state) : nullptr;
    v_.plastic_strain = opt_real(field::plastic_strain);
    v_.damping_work = opt_real(field::damping_work);
    v_.fibre = particles_.has(field::fibre) ? particles_.template get<Vec<D, Real>>(field::fibre) : nullptr;
    v_.sheet = particles_.has(field::sheet) ? particles_.template get<Vec<D, Real>>(field::sheet) : nullptr;
    v_.active_tension = opt_real(field::active_tension);
    v_.stiffening = opt_real(field::stiffening);
    v_.active_work = opt_real(field::active_work);
    v_.phase = PhaseFieldViews<Real>{opt_real(field::phase_field),       opt_real(field::phase_field_rate),
                                     opt_real(field::fracture_history),  opt_real(field::tensile_energy),
                                     opt_real(field::fracture_released), opt_real(field::phase_field_lower),
                                     opt_real(field::phase_field_next)};
  }

  std::unique_ptr<BodyKernels<B, D, Real>> make_body_kernels(size_t b) {
    const BodySpec& spec = scene_.bodies[b];
    const BodyProperties& p = props(b);
    const SolverSpec& s = scene_.solver;
    BodyKernelSettings k;
    k.range = ranges_[b];
    k.density = spec.material.density;
    k.gravity = s.gravity;
    k.zeta = s.zeta;
    k.correction_in_force = s.correction_in_force;
    k.genog_limiter = s.genog_limiter == GenogLimiterChoice::paper ? GenogLimiter::paper : GenogLimiter::capped;
    k.genog_form = s.genog_form == GenogFormChoice::vector ? GenogForm::vector : GenogForm::dyadic;
    k.genog_alpha = s.genog_alpha;
    // tau_d = (chi/2) db/dt, chi = rho0 c h / 2 (seed 003 eq. 23): coefficient of E_dot is rho0 c h / 2.
    const double base = s.damping_factor * spec.material.density * p.h * 0.5;
    k.damping_normal = base * p.c0;
    k.damping_shear = base * (s.damping_form == DampingForm::split ? p.c_shear : p.c0);
    const MaterialSpec& m = spec.material;
    if (m.model == MaterialModel::j2_mandel)
      return make_variant(
          J2Plastic<D, Real, Seed001Hardening<Real>>{
              Real(p.K), Real(p.G), {Real(m.yield_stress), Real(m.hardening_modulus)}},
          k);
    if (m.model == MaterialModel::j2) {
      if (m.hardening == HardeningLaw::herschel_bulkley)
        return make_variant(
            J2Plastic<D, Real, HerschelBulkley<Real>>{
                Real(p.K), Real(p.G), {Real(m.yield_stress), Real(m.viscosity), Real(m.flow_exponent)}},
            k);
      if (m.hardening == HardeningLaw::saturation)
        return make_variant(
            J2Plastic<D, Real, SaturationHardening<Real>>{Real(p.K),
                                                          Real(p.G),
                                                          {Real(m.yield_stress), Real(m.hardening_modulus),
                                                           Real(m.saturation_stress), Real(m.saturation_exponent)}},
            k);
      return make_variant(
          J2Plastic<D, Real, LinearHardening<Real>>{
              Real(p.K), Real(p.G), {Real(m.yield_stress), Real(m.hardening_modulus)}},
          k);
    }
    if (m.model == MaterialModel::holzapfel_ogden) {
      const HolzapfelOgdenSpec& h = m.holzapfel_ogden;
      const HolzapfelOgdenParameters<Real> hp{Real(h.lambda), Real(h.a),  Real(h.b),   Real(h.af), Real(h.bf),
                                              Real(h.as),     Real(h.bs), Real(h.afs), Real(h.bfs)};
      const double reference = h.lambda + 2.0 * h.a * h.b + 2.0 * h.a + 4.0 * std::max(h.af, h.as);
      k.active_ramp_time = h.active.enabled ? h.active.ramp_time : -1.0;
      return make_variant(HolzapfelOgden<D, Real>{hp, Real(reference), v_.fibre, v_.sheet,
                                                  h.active.enabled ? v_.active_tension : nullptr, Real(1)},
                          k);
    }
    if (m.fracture.enabled) {  // hourglass "none" (scene_reader refuses the others)
      const double speed = m.fracture.speed > 0 ? m.fracture.speed : std::sqrt((p.K + 4.0 * p.G / 3.0) / m.density);
      const FractureParameters<Real> f{Real(m.fracture.energy_release_rate), Real(m.fracture.length_scale), Real(speed),
                                       Real(m.fracture.phase_field_limit)};
      if (m.model == MaterialModel::neo_hookean)
        return std::make_unique<FractureBodyKernels<B, D, Real, NeoHookean<D, Real>>>(
            NeoHookean<D, Real>{Real(p.K), Real(p.G)}, k, f);
      return std::make_unique<FractureBodyKernels<B, D, Real, SaintVenantKirchhoff<D, Real>>>(
          SaintVenantKirchhoff<D, Real>{Real(p.K), Real(p.G), Real(p.lambda)}, k, f);
    }
    if (m.model == MaterialModel::neo_hookean) return make_variant(NeoHookean<D, Real>{Real(p.K), Real(p.G)}, k);
    return make_variant(SaintVenantKirchhoff<D, Real>{Real(p.K), Real(p.G), Real(p.lambda)}, k);
  }

  template <class Material>
  std::unique_ptr<BodyKernels<B, D, Real>> make_variant(const Material& m, const BodyKernelSettings& k) {
    switch (scene_.solver.hourglass) {
      case HourglassControl::none:
        return std::make_unique<BodyKernelsImpl<B, D, Real, Material, HourglassNone>>(m, k);
      case HourglassControl::laplacian:
        if constexpr (IsPlastic<Material>::value || IsHolzapfelOgden<Material>::value)
          throw std::logic_error("the Laplacian hourglass form is defined for isotropic elastic bodies only");
        else
          return std::make_unique<BodyKernelsImpl<B, D, Real, Material, HourglassLaplacian>>(m, k);
      case HourglassControl::genog:
        return std::make_unique<BodyKernelsImpl<B, D, Real, Material, HourglassGenog>>(m, k);
      case HourglassControl::gnog:
      case HourglassControl::gnog_amc:
        break;  // ULSPH variants (the scene reader keeps them from tlsph)
    }
    throw std::logic_error("unknown hourglass variant");
  }

  StepStatisticsFunctor<D, Real> statistics_functor() const {
    const Index n = particles_.size();
    StepStatisticsFunctor<D, Real> f{v_.reference_position,
                                     v_.displacement,
                                     v_.velocity,
                                     v_.acceleration,
                                     scene_.solver.deformed_time_step ? v_.deformation_gradient : nullptr,
                                     v_.stiffening,
                                     {},
                                     {},
                                     n,
                                     v_.ghost};
    for (int a = 0; a < D; ++a) {
      f.lower.v[a] = Real(scene_.bounds.min[a]);
      f.upper.v[a] = Real(scene_.bounds.max[a]);
    }
    return f;
  }

  StepStatistics<Real> statistics() {
    const Index n = particles_.size();
    return transform_reduce<B>(0, n, statistics_functor(), StepStatistics<Real>{Real(0), Real(0), Real(0), Real(0), n},
                               StepStatisticsCombine<Real>{});
  }

  // dt = CFL min(h/(c0 + |v|max), sqrt(h/|a|max)) (seed 000 eq. 38); with
  // solver.deformed_time_step, c0 is scaled by s = max(1, max_i |F_i^{-1}|_2),
  // the Lagrangian wave speed where the body is compressed most (theory.md).
  void update_time_step(StepStatistics<Real> s) {
    this->maxima_over_ranks(s);  // distributed runs: the whole scene's maxima
    const double vmax = std::sqrt(double(s.max_speed2));
    const double amax = std::sqrt(double(s.max_acceleration2));
    const double stretch = std::max(1.0, double(s.max_inverse_stretch));
    // Holzapfel-Ogden: c0 from the stiffest particle's current modulus
    // (HolzapfelOgdenPoint::longitudinal_modulus), never below the reference.
    const double stiffening = std::sqrt(std::max(1.0, double(s.max_stiffening)));
    double dt = std::numeric_limits<double>::infinity();
    for (size_t b = 0; b < scene_.bodies.size(); ++b) {
      dt = std::min(dt, props(b).h / (wave_speed(b) * stretch * stiffening + vmax));
      if (amax > 0) dt = std::min(dt, std::sqrt(props(b).h / amax));
    }
    // Contact springs and dashpots (kernels/contact/contact_force.hpp).
    if (contact_.inverse_stable_step() > 0) dt = std::min(dt, 1.0 / contact_.inverse_stable_step());
    dt_next_ = std::min(scene_.solver.cfl * dt, damping_step_limit());
  }

  // The Kelvin-Voigt damping stress is explicit, a diffusion of velocity with
  // nu = factor h c0 / 2: its diffusion number nu dt / h^2 must stay below
  // kDampingDiffusionNumber whatever the CFL number (docs/theory.md, "Time
  // step"). 0.3 is the papers' own setting (factor 1, CFL 0.6), which it
  // leaves unchanged.
  static constexpr double kDampingDiffusionNumber = 0.3;
  double damping_step_limit() {
    double dt = std::numeric_limits<double>::infinity();
    const double factor = scene_.solver.damping_factor;
    if (factor > 0)
      for (size_t b = 0; b < scene_.bodies.size(); ++b)
        dt = std::min(dt, kDampingDiffusionNumber * 2.0 * props(b).h / (factor * props(b).c0));
    return dt;
  }

  // The fastest wave of a body: c0, or the phase field's speed limit where it is larger.
  double wave_speed(size_t b) {
    const FractureSpec& f = scene_.bodies[b].material.fracture;
    if (!f.enabled) return props(b).c0;
    const double c =
        f.speed > 0 ? f.speed : std::sqrt((props(b).K + 4.0 * props(b).G / 3.0) / scene_.bodies[b].material.density);
    return std::max(props(b).c0, c);
  }

  // Finite and inside the bounds: then |F^{-1}| of the deformed time step was not finite.
  [[noreturn]] void fail(Index i) {
    Base::fail(i, {"deformation_gradient", "has no finite inverse (|F^{-1}| is not finite)"});
  }

  // deformation_rate = sum_j (f_j - f_i) (x) g_ij B0_i (seed 000 eq. 22) of
  // the field f (the velocity, or the initial displacement), in the pair loop
  // the run takes.
  void gradient_into_rate(const Vec<D, Real>* f) {
    const Index n = particles_.size();
    if constexpr (std::is_same<B, Cpu>::value) {
      if (v_.half_bandwidth >= 0) {
        auto loop = [&](const auto& h) {
          half_pair_for(Cpu{}, Index(0), n, v_.half_bandwidth, Mat<D, Real>::zero(), v_.deformation_rate,
                        rate_workspace_, h, [&](Index i, const Mat<D, Real>& total) { h.finish(i, total); });
        };
        v_.with_half_pairs([&](const auto& pairs) {
          using P = HalfPairReal<decltype(pairs)>;
          loop(DeformationRateHalfFunctor<D, Real, P>{{pairs, f, v_.volume}, v_.correction, v_.deformation_rate});
        });
        return;
      }
    }
    parallel_for<B>(n, DeformationRateFunctor<D, Real>{v_.pairs, f, v_.correction, v_.deformation_rate});
  }

  void compute_hourglass_indicator() {
    const Index n = particles_.size();
    // Without an F^{-1} field (the genog record) the functors invert F per pair.
    if (v_.inverse_F) parallel_for<B>(n, InverseDeformationFunctor<D, Real>{v_.deformation_gradient, v_.inverse_F});
    const InverseOfF<D, Real> inverse_F{v_.inverse_F, v_.deformation_gradient};
    if constexpr (std::is_same<B, Cpu>::value) {
      if (v_.half_bandwidth >= 0) {
        indicator_sums_.resize(size_t(n));
        auto loop = [&](const auto& h) {
          half_pair_for(Cpu{}, Index(0), n, v_.half_bandwidth, SumCount<Real>{Real(0), Real(0)}, indicator_sums_.data(),
                        indicator_workspace_, h, [&](Index i, const SumCount<Real>& t) { h.finish(i, t); });
        };
        v_.with_half_pairs([&](const auto& pairs) {
          using P = HalfPairReal<decltype(pairs)>;
          loop(HourglassIndicatorHalfFunctor<D, Real, P>{pairs, inverse_F, v_.displacement, v_.hourglass_indicator});
        });
        return;
      }
    }
    parallel_for<B>(n,
                    HourglassIndicatorFunctor<D, Real>{v_.pairs, inverse_F, v_.displacement, v_.hourglass_indicator});
  }

  void compute_observables() {
    for (auto& k : bodies_) k->stress_observables(v_);
    compute_hourglass_indicator();
  }

  ReferenceNeighborList<B, D, Real> pairs_;
  std::vector<Mat<D, Real>> rate_workspace_;                          // the half-pair loop's buffers (CPU)
  std::vector<SumCount<Real>> indicator_sums_, indicator_workspace_;  // the indicator's, at output times
  std::vector<std::unique_ptr<BodyKernels<B, D, Real>>> bodies_;
  TlsphRelaxation<B, D, Real> relaxation_;
  std::vector<double> gravity_at_start_;  // per body: sum m g . u0
  bool has_loads_ = false;
  bool has_fracture_ = false;
  std::vector<CrackSpec> cracks_;  // crack-tip outputs
  TlsphViews<D, Real> v_{};
};

}  // namespace mfsd
