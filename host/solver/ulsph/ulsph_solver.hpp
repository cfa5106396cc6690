// Updated-Lagrangian SPH solver with generalized non-hourglass control
// (seed 002; formulations.md section 3) for one backend, precision and
// dimension. One call of step() is one acoustic step:
//   neighbors    at the start of an advection step: x = X + u, cell sort,
//                CSR with the current pair data (V = m/rho), B   (eq. 20-21)
//   half_step    rho and u to the half step                     (eq. 30, 14)
//   stress       p (linear EOS, tension failure), L, Jaumann tau with the
//                J2 return and kappa                             (eq. 6-12)
//   force        a = pressure + Riemann + shear + GNOG + g, v += dt a
//                                                            (eq. 15-18, 27-29, 31)
//   contact, loads, boundary   the shared services (host/solver/common/)
//   advance      rho and u through the second half at the new v (eq. 32),
//                reduced to the step's maxima and health check
//   time_step    the step's one synchronisation; dual-criteria time step:
//                dt_adv = C_adv h / max(U_ref, |v|max), dt_ac = CFL h / (c0 + |v|max)
//                (eq. 28-29), acoustic steps until dt_adv is covered
// Bodies are ranges of one particle set; pairs join particles of one body
// only, bodies meet by contact. Positions are displacements from the initial
// positions (kinematics.hpp). Include after the backend header.
#pragma once
#include <thrust/copy.h>
#include <thrust/count.h>
#include <thrust/fill.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "host/halo/halo_check.hpp"
#include "host/halo/halo_radius.hpp"
#include "host/neighbors/cell_list_search.hpp"
#include "host/solver/common/particle_solver.hpp"
#include "kernels/core/owned_only.hpp"
#include "kernels/core/step_statistics.hpp"
#include "kernels/neighbors/bounding_box.hpp"
#include "kernels/ulsph/current_pair_fill.hpp"
#include "kernels/ulsph/energy.hpp"
#include "kernels/ulsph/step.hpp"

namespace mfsd {

template <class B, int D, class Real>
class UlsphSolver final : public ParticleSolver<B, D, Real> {
  using Base = ParticleSolver<B, D, Real>;
  using Base::conditions_, Base::contact_, Base::dt_next_, Base::init_, Base::particles_, Base::ranges_, Base::report_,
      Base::results_, Base::scene_, Base::snapshot_fields_, Base::steps_, Base::time_;
  using Base::declare_stage, Base::props, Base::run;

 public:
  UlsphSolver(const Scene& scene, const InitialParticles& init, const SolverOptions& options)
      : Base(scene, init, options) {
    for (const auto& c : scene.conditions) has_loads_ = has_loads_ || c.type != ConditionSpec::Type::velocity;
    for (const char* name :
         {"neighbors", "half_step", "stress", "force", "contact", "loads", "boundary", "advance", "time_step"})
      if ((has_loads_ || std::string(name) != "loads") && (scene.contact.enabled || std::string(name) != "contact"))
        declare_stage(name);
    conditions_.compile(scene_);
  }

  void initialize() override {
    const Index n = particles_.size();
    this->upload_kinematics();
    // State: rho = rho0, m = rho0 V0, tau = 0, a_h = 0; the stage fields.
    std::vector<Real> density(static_cast<size_t>(n)), mass(static_cast<size_t>(n));
    for (size_t b = 0; b < scene_.bodies.size(); ++b)
      for (Index i = ranges_[b].begin; i < ranges_[b].end; ++i) {
        density[size_t(i)] = Real(scene_.bodies[b].material.density);
        mass[size_t(i)] = Real(scene_.bodies[b].material.density * init_.volume[size_t(i)]);
      }
    particles_.template add<Real>(field::density);
    from_host<B>(density, particles_.template buffer<Real>(field::density));
    particles_.template add<Real>(field::mass);
    from_host<B>(mass, particles_.template buffer<Real>(field::mass));
    if (scene_.solver.ulsph.refresh_pairs) particles_.template add<Real>(field::current_volume);
    particles_.template add<Real>(field::pair_density);
    particles_.template add<Vec<D, Real>>(field::acceleration);
    particles_.template add<Real>(field::pressure);
    particles_.template add<Mat<D, Real>>(field::shear_stress);
    particles_.template add<Mat<D, Real>>(field::correction_matrix);
    particles_.template add<Mat<D, Real>>(field::velocity_gradient);
    particles_.template add<Vec<D, Real>>(field::current_position);
    particles_.template add<Real>(field::von_mises);
    particles_.template add<Real>(field::jacobian);
    if (scene_.solver.hourglass != HourglassControl::none)
      particles_.template add<Vec<D, Real>>(field::hourglass_acceleration);
    particles_.template add<Real>(field::dissipated_work);                 // zero
    particles_.template add<Vec<D, Real>>(field::numerical_acceleration);  // a_num of the step
    if (has_plastic_body(scene_)) {
      particles_.template add<Real>(field::plastic_work);    // zero
      particles_.template add<Real>(field::plastic_strain);  // a, the accumulated plastic strain
      particles_.template add<Real>(field::plastic_scale);
      Real* kappa = particles_.template get<Real>(field::plastic_scale);
      thrust::fill(BackendTraits<B>::policy(), kappa, kappa + n, Real(1));
    }
    bool failure = false;
    for (const auto& b : scene_.bodies) failure = failure || b.material.failure_pressure > 0;
    if (failure) particles_.template add<unsigned char>(field::failed);
    for (size_t b = 0; b < scene_.bodies.size(); ++b) search_.push_back(BodySearch{ranges_[b], props(b).h});

    // The first search sorts the particles by cell and, with solver.reorder,
    // permutes every field into that order (memory locality for the run);
    // later rebuilds keep the order and search through the cell order.
    for (size_t b = 0; b < scene_.bodies.size(); ++b)
      body_total_.push_back(double(this->owned_in(ranges_[b].begin, ranges_[b].end)));
    if (this->ghosts_) this->ghosts_->sum_over_ranks(body_total_);  // the cell grid of the whole body
    boxes_ = host_boxes();
    globalize_boxes();
    rebuild(scene_.solver.reorder);
    particles_.remove(field::reference_position_double);
    if (this->ghosts_) {  // each particle's place in the single-process order (migrate_particles)
      particles_.template add<std::int64_t>(field::order_key);
      if (scene_.solver.reorder)
        thrust::copy(BackendTraits<B>::policy(), cells_.keys.begin(), cells_.keys.end(),
                     particles_.template buffer<std::int64_t>(field::order_key).begin());
    }
    // Distributed runs: the exchange in the sorted order, and the ghosts'
    // B and pair densities (their rows are cut) from their owners.
    this->bind_ghosts();
    this->refresh_all_ghosts();

    snapshot_fields_ = {{"von_mises", field::von_mises},
                        {"J", field::jacobian},
                        {"pressure", field::pressure},
                        {"density", field::density}};
    if (particles_.has(field::plastic_strain)) snapshot_fields_.emplace_back("plastic_strain", field::plastic_strain);
    if (particles_.has(field::failed)) {
      particles_.template add<Real>(field::failed_output);
      snapshot_fields_.emplace_back("failed", field::failed_output);
    }

    const std::vector<Index> where = this->locate();
    conditions_.setup(init_, where, particles_.template get<Index>(field::id), ranges_);
    if (scene_.contact.enabled) {
      // Every particle of a body in contact is a candidate: its surface moves.
      this->setup_contact(std::vector<unsigned char>(size_t(n), 1));
    }
    this->locate_probes(where);
    results_.clear();
    conditions_.apply_initial(this->kinematics(), results_);
    results_.fetch();
    conditions_.collect(results_, this->kinematics());
    this->refresh_all_ghosts();

    // Initial stress (rho = rho0: p = 0, tau = 0) and the first time step.
    for (size_t b = 0; b < scene_.bodies.size(); ++b) gravity_at_start_.push_back(energy(b).gravity);
    StepStatistics<Real> stats =
        transform_reduce<B>(0, n, statistics_functor(), StepStatistics<Real>{Real(0), Real(0), Real(0), Real(0), n},
                            StepStatisticsCombine<Real>{});
    this->maxima_over_ranks(stats);  // distributed runs: the whole scene's
    advection_step_ = advection_step(stats);
    dt_next_ = std::min(acoustic_step(stats), advection_step_);

    report_.regularized_corrections = fallback_count_;
    this->release_initial_particles();
    this->report_particles_and_pairs(to_host<B>(offsets_),
                                     double(pairs_) * (sizeof(Index) + sizeof(Vec<D, Real>) + sizeof(Real)) +
                                         double(n) * (sizeof(PairIndex) + sizeof(Vec<D, Real>)));
  }

  void begin_step() override {
    this->round_trips_before_ = round_trips();
    Index n = particles_.size();
    const double dt = this->step_dt_ = dt_next_;
    const Real half_dt = Real(0.5 * dt);
    results_.clear();
    // The pair data of a rebuild are those of the half-step positions, at
    // which the forces act and between the velocities of the two density
    // half steps: the lag of pair directions behind a spinning body then
    // cancels (docs/theory.md, "ULSPH").
    const bool refresh = !rebuild_due_ && scene_.solver.ulsph.refresh_pairs;
    run("half_step", [&] {
      if (refresh)  // with x and V of the step's start for the refresh below
        parallel_for<B>(n, ulsph::DisplacementHalfStepPositionVolumeFunctor<D, Real>{velocity(), displacement(),
                                                                                     half_dt, position_volume()});
      else
        parallel_for<B>(n, ulsph::DisplacementHalfStepFunctor<D, Real>{velocity(), displacement(), half_dt});
    });
    if (rebuild_due_ && this->ghosts_ && migration_travelled_ > migration_reach() &&
        !distributed::migration_switched_off()) {
      run("migrate", [&] { this->migrate_particles(distributed::halo_radius(scene_)); });
      migration_travelled_ = 0;
    }
    if (rebuild_due_) run("neighbors", [&] { rebuild(false); });
    n = particles_.size();  // a migration changes this rank's particles
    const PairList<D, Real> pairs = pair_list();
    if (refresh)  // pair data, B and the density half step in one pass over the rows
      run("half_step", [&] { refresh_half_step(half_dt); });
    else
      run("half_step", [&] {
        parallel_for<B>(n, ulsph::HalfStepFunctor<D, Real>{pairs, velocity(), real(field::density), nullptr, half_dt});
      });
    run("stress", [&] {
      for (size_t b = 0; b < scene_.bodies.size(); ++b) stress(b, pairs, Real(dt));
    });
    halo({field::pressure, field::shear_stress, field::velocity_gradient, field::plastic_scale, field::failed});
    run("force", [&] {
      for (size_t b = 0; b < scene_.bodies.size(); ++b) force(b, pairs, Real(dt));
      parallel_for<B>(n, ulsph::VelocityFunctor<D, Real>{acceleration(), velocity(), Real(dt)});
    });
    if (contact_.enabled()) {
      if (this->ghosts_ && distributed::halo_check_requested()) verify_contact_halo();
      halo({field::velocity});  // the contact's partners across the cut
      run("contact", [&] { contact_.apply(this->kinematics(), time_, dt, results_); });
    }
  }

  void end_step() override {
    const Index n = particles_.size();
    const double dt = this->step_dt_;
    const Real half_dt = Real(0.5 * dt);
    const PairList<D, Real> pairs = pair_list();
    const Kinematics<D, Real> k = this->kinematics();
    if (has_loads_) run("loads", [&] { conditions_.apply_loads(k, time_, dt, steps_ + 1, results_); });
    run("boundary", [&] { conditions_.apply_boundary(k, time_, dt, steps_ + 1, results_); });
    halo({field::velocity});
    ResultSlot<StepStatistics<Real>> stats_slot;
    std::vector<ResultSlot<BoundingBox<D, Real>>> box_slots;
    run("advance", [&] {
      ulsph::SecondHalfStepFunctor<D, Real> f{{pairs, velocity(), real(field::density), displacement(), half_dt},
                                              statistics_functor(),
                                              numerical_work(Real(dt))};
      stats_slot = results_.reduce(Index(0), n, f, StepStatistics<Real>{Real(0), Real(0), Real(0), Real(0), n},
                                   StepStatisticsCombine<Real>{});
      // The boxes of the next search, should the next step rebuild.
      for (const BodyRange& r : ranges_)
        box_slots.push_back(results_.reduce(r.begin, r.end, BoundingBoxFunctor<D, Real>{reference(), displacement()},
                                            BoundingBox<D, Real>::empty(), BoundingBoxCombine<D, Real>{}));
    });
    halo({field::density});
    run("time_step", [&] {
      results_.fetch();
      conditions_.collect(results_, k);
      contact_.collect(results_);
      StepStatistics<Real> stats = results_.get(stats_slot);
      this->maxima_over_ranks(stats);  // distributed runs: the whole scene's
      for (size_t b = 0; b < box_slots.size(); ++b) boxes_[b] = results_.get(box_slots[b]);
      globalize_boxes();
      time_ += dt;
      ++steps_;
      if (stats.first_bad < n) fail(stats.first_bad);
      // Dual criteria (seed 002 eq. 28-29): acoustic steps until the advection
      // step is covered, then a new advection step with a neighbour rebuild.
      advection_elapsed_ += dt;
      // The bound of eq. 28 itself, for speeds that grow within the advection
      // step (a plate at rest when a projectile strikes it has dt_adv = inf
      // with U_ref = 0): no particle moves more than C_adv h between searches.
      advection_travelled_ += dt * std::sqrt(double(stats.max_speed2));
      migration_travelled_ += dt * std::sqrt(double(stats.max_speed2));
      const bool single = !scene_.solver.ulsph.dual_time_stepping;
      rebuild_due_ = single || advection_elapsed_ >= advection_step_ * (1.0 - 1e-12) ||
                     advection_travelled_ > advection_reach() * (1.0 + 1e-9);
      if (rebuild_due_) {
        advection_elapsed_ = 0;
        advection_travelled_ = 0;
        advection_step_ = advection_step(stats);
      }
      dt_next_ = acoustic_step(stats);
      if (!single) dt_next_ = std::min(dt_next_, advection_step_ - advection_elapsed_);
    });
    this->clock_.collect(this->timers_);
    this->timers_.add_round_trips(round_trips() - this->round_trips_before_);
  }

  EnergySample energies() override {
    EnergySample e;
    for (size_t b = 0; b < scene_.bodies.size(); ++b) {
      const ulsph::EnergySums s = energy(b);
      e.kinetic += s.kinetic;
      e.strain += s.strain;
      for (int a = 0; a < 3; ++a) e.momentum[a] += s.momentum[a];
      BodyEnergy be;
      be.kinetic = s.kinetic;
      be.strain = s.strain;
      be.gravity_work = s.gravity - gravity_at_start_[b];
      be.plastic = s.plastic;
      be.damping = s.dissipated;
      this->add_shared_work(b, be);
      for (int a = 0; a < 3; ++a) be.momentum[a] = s.momentum[a];
      e.bodies.push_back(be);
    }
    return e;
  }

  void save_state(StateArchive& a) override {
    this->save_shared_state(a);
    a.put("solver/gravity_at_start", gravity_at_start_);
    a.put_value("ulsph/advection_step", advection_step_);
    a.put_value("ulsph/advection_elapsed", advection_elapsed_);
    a.put_value("ulsph/advection_travelled", advection_travelled_);
    a.put_value("ulsph/migration_travelled", migration_travelled_);
    a.put_value("ulsph/rebuild_due", rebuild_due_ ? 1L : 0L);
    a.put("ulsph/offsets", to_host<B>(offsets_));
    a.put("ulsph/neighbor", to_host<B>(neighbor_));
  }

  // The list of pairs comes back as it was; its pair data and B are formed
  // again by the next step (a search, or the refresh of the kept pairs), as
  // in the uninterrupted run. With refresh_pairs false the frozen pair data
  // are formed at the restored positions instead of the advection step's.
  void restore_state(const StateArchive& a) override {
    this->restore_shared_state(a);
    gravity_at_start_ = a.get<double>("solver/gravity_at_start", long(scene_.bodies.size()));
    advection_step_ = a.get_value<double>("ulsph/advection_step");
    advection_elapsed_ = a.get_value<double>("ulsph/advection_elapsed");
    // (Checkpoints written before this bound was kept: none travelled.)
    advection_travelled_ = a.has("ulsph/advection_travelled") ? a.get_value<double>("ulsph/advection_travelled") : 0;
    rebuild_due_ = a.get_value<long>("ulsph/rebuild_due") != 0;
    if (a.has("ulsph/migration_travelled")) migration_travelled_ = a.get_value<double>("ulsph/migration_travelled");
    boxes_ = host_boxes();
    globalize_boxes();
    const auto offsets = a.get<PairIndex>("ulsph/offsets", long(particles_.size()) + 1);
    pairs_ = offsets.back();
    from_host<B>(offsets, offsets_);
    from_host<B>(a.get<Index>("ulsph/neighbor", long(pairs_) + kPairPrefetchDistance), neighbor_);
    grad_.resize(size_t(pairs_));
    stretch_.resize(size_t(pairs_));
    if (!scene_.solver.ulsph.refresh_pairs) refresh_pair_data();
  }

 private:
  void update_observables() override {
    if (particles_.has(field::failed)) {
      const unsigned char* f = particles_.template get<unsigned char>(field::failed);
      thrust::copy(BackendTraits<B>::policy(), f, f + particles_.size(), real(field::failed_output));
    }
    for (size_t b = 0; b < scene_.bodies.size(); ++b)
      parallel_for<B>(ranges_[b].begin, ranges_[b].end,
                      ulsph::ObservablesFunctor<D, Real>{mat(field::shear_stress), real(field::density),
                                                         Real(scene_.bodies[b].material.density),
                                                         real(field::von_mises), real(field::jacobian)});
  }
  void update_stress_observables() override { update_observables(); }

  Real* real(const char* name) { return particles_.template get<Real>(name); }
  Real* optional(const char* name) { return this->optional_real(name); }
  Mat<D, Real>* mat(const char* name) { return particles_.template get<Mat<D, Real>>(name); }
  Vec<D, Real>* velocity() { return particles_.template get<Vec<D, Real>>(field::velocity); }
  Vec<D, Real>* acceleration() { return particles_.template get<Vec<D, Real>>(field::acceleration); }
  Vec<D, Real>* displacement() { return particles_.template get<Vec<D, Real>>(field::displacement); }
  const Vec<D, Real>* reference() { return particles_.template get<Vec<D, Real>>(field::reference_position); }

  PairList<D, Real> pair_list() const {
    return PairList<D, Real>{raw(offsets_), raw(neighbor_), raw(grad_), raw(stretch_), raw(gradient_sum_), nullptr};
  }

  // The bodies' boxes of the current positions (set-up and restarts; in a
  // run they come with the step's results).
  std::vector<BoundingBox<D, Real>> host_boxes() {
    std::vector<BoundingBox<D, Real>> boxes;
    for (const BodyRange& r : ranges_)
      boxes.push_back(transform_reduce<B>(r.begin, r.end, BoundingBoxFunctor<D, Real>{reference(), displacement()},
                                          BoundingBox<D, Real>::empty(), BoundingBoxCombine<D, Real>{}));
    return boxes;
  }

  // Current-configuration search (host/neighbors/cell_list_search.hpp) and
  // the pair data with V = m/rho, then B (seed 002 eq. 21). A body that has
  // spread far (fragments) gets coarser cells, so that the grid never holds
  // more than kCellsPerParticle cells per particle.
  static constexpr double kCellsPerParticle = 4.0;
  void rebuild(bool reorder) {
    const Index n = particles_.size();
    parallel_for<B>(
        n, ulsph::CurrentPositionFunctor<D, Real>{reference(), displacement(),
                                                  particles_.template get<Vec<D, Real>>(field::current_position)});
    std::vector<CellGrid<D, Real>> grids;
    std::int64_t first = 0;
    for (size_t b = 0; b < search_.size(); ++b) {
      double lo[D], hi[D], cell = 2.0 * search_[b].smoothing_length, cells = 1;
      for (int a = 0; a < D; ++a) {
        lo[a] = double(boxes_[b].lo.v[a]);
        hi[a] = std::max(lo[a], double(boxes_[b].hi.v[a]));
        cells *= std::floor((hi[a] - lo[a]) / cell) + 1;
      }
      const double limit = std::max(64.0, kCellsPerParticle * body_total_[b]);
      if (cells > limit) cell *= std::pow(cells / limit, 1.0 / D);
      grids.push_back(make_cell_grid<D, Real>(lo, hi, cell, first));
      first += grids.back().cells;
    }
    sort_into_cells<B, D, Real>(particles_, field::current_position, grids, reorder, cells_);
    CellNeighborhood<D, Real> hood = cell_neighborhood<B, D, Real>(particles_, field::current_position, cells_);
    pairs_ = count_pairs<B, D, Real>(hood, search_, n, count_, offsets_);
    neighbor_.resize(size_t(pairs_) + kPairPrefetchDistance, 0);  // padded for the prefetch
    grad_.resize(size_t(pairs_));
    stretch_.resize(size_t(pairs_));
    gradient_sum_.resize(size_t(n));
    for (const auto& s : search_) {
      hood.radius2 = support_radius2<Real>(s.smoothing_length);
      parallel_for<B>(
          s.range.begin, s.range.end,
          ulsph::CurrentPairFillFunctor<D, Real>{hood, WendlandC2<D, Real>::make(Real(s.smoothing_length)),
                                                 real(field::mass), real(field::density), raw(offsets_), raw(neighbor_),
                                                 raw(grad_), raw(stretch_), raw(gradient_sum_)});
    }
    keep_pair_density();
    fallback_.resize(size_t(n));
    parallel_for<B>(n, ulsph::CorrectionMatrixFunctor<D, Real>{pair_list(), mat(field::correction_matrix),
                                                               raw(fallback_), Real(1e-3)});
    if (reorder)  // at set-up: how many particles have too few neighbours for B
      fallback_count_ =
          long(thrust::count(BackendTraits<B>::policy(), fallback_.begin(), fallback_.end(), (unsigned char)1));
    if (this->ghosts_ && distributed::halo_check_requested()) verify_halo();
  }

  bool ghosts_supported() const override { return true; }
  bool ghosts_are_current_neighbours() const override { return true; }

  // Distributed runs: the ghosts' copies of every field after a pass whose
  // pair sums their cut rows got wrong (docs/distributed.md).
  // Each refresh holds what the passes until the next one read of a partner
  // and a ghost's own row got wrong (its row is cut by the halo):
  //   after the stress: p, tau, L, kappa (the force and GNOG read them of the
  //     partners; the failure flag with them);
  //   after the force, with contact: v (the contact's partners);
  //   after the boundary conditions: v (the density step and L read it);
  //   after the advance: rho (the search's V_j = m_j / rho_j, and p).
  // Every other field a ghost holds is its own function of these (x = X + u,
  // the pair data, B) or is read of no partner (a, the work sums). The
  // single-process comparisons (tests/mpi) check that this is complete.
  void halo(std::initializer_list<const char*> names) {
    if (this->ghosts_) run("halo", [&] { this->refresh_ghosts(names); });
  }

  // Distributed runs: the boxes of the whole bodies (every rank's cells are
  // the single-process run's).
  void globalize_boxes() {
    if (!this->ghosts_) return;
    std::vector<double> v;
    for (const auto& box : boxes_)
      for (int a = 0; a < D; ++a) v.push_back(-double(box.lo.v[a])), v.push_back(double(box.hi.v[a]));
    this->ghosts_->max_over_ranks(v);
    size_t k = 0;
    for (auto& box : boxes_)
      for (int a = 0; a < D; ++a) box.lo.v[a] = Real(-v[k++]), box.hi.v[a] = Real(v[k++]);
  }

  // Distributed ULSPH (docs/distributed.md, "Migration"). A rank's ghosts
  // are the particles within the halo radius r (3h) of its region at the
  // last migration, whose owned particles were inside it. Between
  // migrations no particle moves more than d, so an owned particle and a
  // partner within the support 2h of it now were within 2h + 2d of that
  // region then: the ghosts hold every partner while 2d <= r - 2h. The
  // bound of each particle's travel is the sum over the steps of dt max|v|
  // (the ranks' common maxima), with a fifth of the margin kept back for the
  // change of v within a step. A search past it migrates first.
  //   Contact searches its pairs at every step, not only at the searches:
  // its reach (kContactRateReach spacings) plus twice the travel until the
  // next search (at most the advection reach more) must stay within r too.
  double migration_reach() {
    double reach = std::numeric_limits<double>::infinity(), spacing = 0;
    const double r = distributed::halo_radius(scene_);
    for (size_t b = 0; b < scene_.bodies.size(); ++b) {
      reach = std::min(reach, 0.4 * (r - 2.0 * props(b).h));
      spacing = std::max(spacing, scene_.bodies[b].spacing);
    }
    if (scene_.contact.enabled) reach = std::min(reach, 0.4 * (r - kContactRateReach * spacing) - advection_reach());
    return reach;
  }

  void after_migration() override {
    for (size_t b = 0; b < search_.size(); ++b) search_[b].range = ranges_[b];
    // Per particle, outside the fields (a restored run refreshes its kept
    // pairs without a search first).
    gradient_sum_.resize(size_t(particles_.size()));
    fallback_.resize(size_t(particles_.size()));
    if (scene_.contact.enabled) this->setup_contact_again(std::vector<unsigned char>(size_t(particles_.size()), 1));
  }

  // MFSD_VERIFY_HALO=1: after every search, the brute-force check that each
  // owned particle's partners are all held here (host/halo/halo_check.hpp).
  // MFSD_VERIFY_HALO=1 with contact: at every step, every particle of any
  // body within the contact's reach of an owned particle is held here (the
  // contact searches its pairs at every step, with positions moved since the
  // last search).
  void verify_contact_halo() {
    double spacing = 0;
    for (const auto& b : scene_.bodies) spacing = std::max(spacing, b.spacing);
    verify_halo(std::vector<double>(scene_.bodies.size(), kContactRateReach * spacing), true);
  }

  void verify_halo() {
    std::vector<double> support;
    for (size_t b = 0; b < scene_.bodies.size(); ++b) support.push_back(2.0 * props(b).h);
    verify_halo(support, false);
  }

  void verify_halo(const std::vector<double>& support, bool across_bodies) {
    // The search's positions, or (contact) those of this step: X + u.
    std::vector<Vec<D, Real>> x = to_host<B>(particles_.template buffer<Vec<D, Real>>(field::current_position));
    if (across_bodies) {
      const auto X = to_host<B>(particles_.template buffer<Vec<D, Real>>(field::reference_position));
      const auto u = to_host<B>(particles_.template buffer<Vec<D, Real>>(field::displacement));
      for (size_t i = 0; i < x.size(); ++i) x[i] = X[i] + u[i];
    }
    Base::verify_halo(x, support, across_bodies);
  }

  // x = X + u into current_position and V = m / rho into current_volume.
  ulsph::PositionVolumeFunctor<D, Real> position_volume() {
    return {reference(),
            displacement(),
            real(field::mass),
            real(field::density),
            particles_.template get<Vec<D, Real>>(field::current_position),
            real(field::current_volume)};
  }

  ulsph::PairRefreshFunctor<D, Real> pair_refresh(const BodySearch& s) {
    return {particles_.template get<Vec<D, Real>>(field::current_position),
            real(field::current_volume),
            WendlandC2<D, Real>::make(Real(s.smoothing_length)),
            raw(offsets_),
            raw(neighbor_),
            raw(grad_),
            raw(stretch_),
            raw(gradient_sum_)};
  }

  // The pair data of the kept pairs at the current positions and B (restarts).
  void refresh_pair_data() {
    if (!particles_.has(field::current_volume)) particles_.template add<Real>(field::current_volume);
    parallel_for<B>(particles_.size(), position_volume());
    for (const auto& s : search_) parallel_for<B>(s.range.begin, s.range.end, pair_refresh(s));
    keep_pair_density();
    parallel_for<B>(particles_.size(), ulsph::CorrectionMatrixFunctor<D, Real>{
                                           pair_list(), mat(field::correction_matrix), raw(fallback_), Real(1e-3)});
  }

  // The pair data of the kept pairs at the half-step positions, B and the
  // first density half step (ulsph::RefreshHalfStepFunctor).
  void refresh_half_step(Real half_dt) {
    for (const auto& s : search_)
      parallel_for<B>(s.range.begin, s.range.end,
                      ulsph::RefreshHalfStepFunctor<D, Real>{pair_refresh(s), velocity(), real(field::density),
                                                             real(field::pair_density), mat(field::correction_matrix),
                                                             Real(1e-3), half_dt});
  }

  // The densities the pair data were formed with (V_i = m_i / rho_i in
  // grad_ji): the forces divide by them, so that m_i a_i = sum_j V_i V_j (..)
  // dW_ij e_ij is antisymmetric pair by pair and momentum is kept to round-off
  // (with rho_i of the half step instead, V_i V_j differs from V_j V_i by the
  // half step's density change: 5e-8 of the momentum of a deforming ball in
  // 0.4 ms, 2e-5 in a collision).
  void keep_pair_density() {
    const Real* rho = real(field::density);
    thrust::copy(BackendTraits<B>::policy(), rho, rho + particles_.size(), real(field::pair_density));
  }

  // The shear law of body b: J2 with linear hardening, or elastic.
  ulsph::HypoelasticJ2<Real> shear_law(size_t b) {
    const MaterialSpec& m = scene_.bodies[b].material;
    if (m.model == MaterialModel::j2)
      return ulsph::HypoelasticJ2<Real>::plastic(Real(props(b).G), Real(m.yield_stress), Real(m.hardening_modulus),
                                                 scene_.solver.ulsph.remove_plastic_rate);
    return ulsph::HypoelasticJ2<Real>::elastic(Real(props(b).G));
  }

  void stress(size_t b, const PairList<D, Real>& pairs, Real dt) {
    const MaterialSpec& m = scene_.bodies[b].material;
    const ulsph::LinearEquationOfState<Real> eos{Real(props(b).K), Real(m.density)};
    const bool plastic = m.model == MaterialModel::j2;
    auto launch = [&](auto failure) {
      ulsph::StressFunctor<D, Real, decltype(failure)> f{pairs,
                                                         velocity(),
                                                         mat(field::correction_matrix),
                                                         real(field::density),
                                                         real(field::pressure),
                                                         mat(field::velocity_gradient),
                                                         mat(field::shear_stress),
                                                         plastic ? real(field::plastic_strain) : nullptr,
                                                         plastic ? real(field::plastic_scale) : nullptr,
                                                         plastic ? real(field::plastic_work) : nullptr,
                                                         real(field::mass),
                                                         eos,
                                                         failure,
                                                         shear_law(b),
                                                         dt};
      parallel_for<B>(ranges_[b].begin, ranges_[b].end, f);
    };
    if (m.failure_pressure > 0)
      launch(
          ulsph::TensileFailure<Real>{Real(m.failure_pressure), particles_.template get<unsigned char>(field::failed)});
    else
      launch(ulsph::NoFailure{});
  }

  void force(size_t b, const PairList<D, Real>& pairs, Real dt) {
    const MaterialSpec& m = scene_.bodies[b].material;
    const bool plastic = m.model == MaterialModel::j2;
    const HourglassControl hg = scene_.solver.hourglass;
    // xi: 4 elastic, 0.2 plastic (gnog), 2 (gnog_amc) unless solver.ulsph.xi (formulations.md 3).
    const double xi = scene_.solver.ulsph.xi > 0         ? scene_.solver.ulsph.xi
                      : hg == HourglassControl::gnog_amc ? 2.0
                      : plastic                          ? 0.2
                                                         : 4.0;
    Vec<D, Real> g;
    for (int a = 0; a < D; ++a) g.v[a] = Real(scene_.solver.gravity[a]);
    auto launch = [&](auto variant) {
      ulsph::ForceFunctor<D, Real, decltype(variant)> f{
          pairs,
          velocity(),
          real(field::pair_density),  // 1/rho_i of eq. 15, 18, 29 at the pair data's volumes
          real(field::pressure),
          mat(field::shear_stress),
          mat(field::velocity_gradient),
          plastic ? real(field::plastic_scale) : nullptr,
          hg == HourglassControl::none ? nullptr : particles_.template get<Vec<D, Real>>(field::hourglass_acceleration),
          acceleration(),
          numerical_work(dt),
          Real(m.density * props(b).c0),                            // Z = rho0 c0 (formulations.md 3)
          Real(scene_.solver.ulsph.riemann_limiter / props(b).c0),  // eta / c0 (seed 002 ref. [38]); 0: none
          Real(xi),
          Real(props(b).G),
          dt,
          g};
      parallel_for<B>(ranges_[b].begin, ranges_[b].end, f);
    };
    if (hg == HourglassControl::gnog)
      launch(ulsph::GnogStandard{});
    else if (hg == HourglassControl::gnog_amc)
      launch(ulsph::GnogAngularMomentumConserving{});
    else
      launch(ulsph::GnogNone{});
  }

  ulsph::EnergySums energy(size_t b) {
    Vec<D, Real> g;
    for (int a = 0; a < D; ++a) g.v[a] = Real(scene_.solver.gravity[a]);
    using Energy = ulsph::EnergyFunctor<D, Real>;
    return transform_reduce<B>(
        ranges_[b].begin, ranges_[b].end,
        OwnedOnly<Energy>{Energy{velocity(), displacement(), real(field::mass), real(field::density),
                                 real(field::pressure), mat(field::shear_stress), real(field::dissipated_work),
                                 optional(field::plastic_work), props(b).K, props(b).G, g},
                          this->ghost_flags()},
        ulsph::EnergySums{0, 0, {0, 0, 0}, 0, 0, 0}, ulsph::EnergySumsPlus{});
  }

  ulsph::NumericalWork<D, Real> numerical_work(Real dt) {
    return {particles_.template get<Vec<D, Real>>(field::numerical_acceleration), real(field::mass),
            real(field::dissipated_work), Real(0.5) * dt};
  }

  StepStatisticsFunctor<D, Real> statistics_functor() {
    StepStatisticsFunctor<D, Real> f{reference(), displacement(),   velocity(), acceleration(), nullptr, nullptr, {},
                                     {},          particles_.size()};
    f.ghost = this->ghost_flags();
    for (int a = 0; a < D; ++a) {
      f.lower.v[a] = Real(scene_.bounds.min[a]);
      f.upper.v[a] = Real(scene_.bounds.max[a]);
    }
    return f;
  }

  // dt_ac = CFL h / (c0 + |v|max) (seed 002 eq. 29), and the contact's bound.
  double acoustic_step(const StepStatistics<Real>& s) {
    const double vmax = std::sqrt(double(s.max_speed2));
    double dt = std::numeric_limits<double>::infinity();
    for (size_t b = 0; b < scene_.bodies.size(); ++b) dt = std::min(dt, props(b).h / (props(b).c0 + vmax));
    dt *= scene_.solver.cfl;
    if (contact_.inverse_stable_step() > 0) dt = std::min(dt, 1.0 / contact_.inverse_stable_step());
    return dt;
  }

  // dt_adv = C_adv h / max(U_ref, |v|max) (seed 002 eq. 28): no particle moves
  // more than C_adv h between two neighbour searches.
  double advection_step(const StepStatistics<Real>& s) {
    const double speed = std::max(scene_.solver.ulsph.reference_speed, std::sqrt(double(s.max_speed2)));
    if (!(speed > 0)) return std::numeric_limits<double>::infinity();
    return advection_reach() / speed;
  }
  // C_adv h, the smallest h of the bodies.
  double advection_reach() {
    double h = std::numeric_limits<double>::infinity();
    for (size_t b = 0; b < scene_.bodies.size(); ++b) h = std::min(h, props(b).h);
    return scene_.solver.ulsph.advection_cfl * h;
  }

  // Finite and inside the bounds: the density was not (the pressure then is not either).
  [[noreturn]] void fail(Index i) { Base::fail(i, {"density", "is not finite or not positive"}); }

  std::vector<BodySearch> search_;
  std::vector<BoundingBox<D, Real>> boxes_;  // per body, the current positions' box
  CellIndex<B, D, Real> cells_;
  DeviceVector<B, Index> count_;
  DeviceVector<B, PairIndex> offsets_;
  DeviceVector<B, Index> neighbor_;
  DeviceVector<B, Vec<D, Real>> grad_;
  DeviceVector<B, Real> stretch_;
  DeviceVector<B, Vec<D, Real>> gradient_sum_;
  DeviceVector<B, unsigned char> fallback_;
  PairIndex pairs_ = 0;
  long fallback_count_ = 0;
  bool has_loads_ = false;
  bool rebuild_due_ = false;
  std::vector<double> body_total_;  // particles of each body in the whole scene (distributed runs: all ranks')
  double advection_step_ = 0, advection_elapsed_ = 0;
  double advection_travelled_ = 0;  // sum dt |v|max since the last search
  double migration_travelled_ = 0;  // distributed runs: sum dt |v|max since the last migration
  std::vector<double> gravity_at_start_;
};

}  // namespace mfsd
