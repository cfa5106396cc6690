// Updated-Lagrangian SPH solver with generalized non-hourglass control
// (seed 002; formulations.md section 3) for one backend, precision and
// dimension. One call of step() is one acoustic step of the recipe in
// ulsph_recipe.cpp (the stages, their equations and halo refreshes) on the
// current-configuration skeleton (current_configuration_solver.hpp):
// half_step, [migrate, neighbors], half_step, stress, force, contact,
// loads, boundary, advance, time_step.
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
#include "host/solver/common/current_configuration_solver.hpp"
#include "host/solver/ulsph/ulsph_recipe.hpp"
#include "kernels/core/owned_only.hpp"
#include "kernels/core/step_statistics.hpp"
#include "kernels/neighbors/bounding_box.hpp"
#include "kernels/ulsph/current_pair_fill.hpp"
#include "kernels/ulsph/energy.hpp"
#include "kernels/ulsph/step.hpp"

namespace mfsd {

template <class B, int D, class Real>
class UlsphSolver final : public CurrentConfigurationSolver<B, D, Real> {
  using Base = CurrentConfigurationSolver<B, D, Real>;
  using Base::acceleration, Base::displacement, Base::mat, Base::real, Base::reference, Base::velocity;
  using Base::body_total_, Base::cells_, Base::count_, Base::gravity_at_start_, Base::migration_travelled_,
      Base::neighbor_, Base::offsets_, Base::pairs_, Base::rebuild_due_, Base::search_;
  using Base::conditions_, Base::contact_, Base::dt_next_, Base::init_, Base::particles_, Base::ranges_, Base::report_,
      Base::results_, Base::scene_, Base::snapshot_fields_, Base::steps_, Base::time_;
  using Base::props, Base::run;

 public:
  UlsphSolver(const Scene& scene, const InitialParticles& init, const SolverOptions& options)
      : Base(scene, init, options) {
    this->set_recipe(ulsph_recipe(scene));
    conditions_.compile(scene_);
  }

  void initialize() override;

  // ---- the step (ulsph_recipe.cpp) -----------------------------------------
  // The pair data of a rebuild are those of the half-step positions, at
  // which the forces act and between the velocities of the two density
  // half steps: the lag of pair directions behind a spinning body then
  // cancels (docs/theory.md, "ULSPH").
  void forces(double dt) override {
    const Real half_dt = Real(0.5 * dt);
    const bool refresh = !rebuild_due_ && scene_.solver.ulsph.refresh_pairs;
    run("half_step", [&] {  // u to the half step (eq. 14)
      if (refresh)          // with x and V of the step's start for the refresh below
        parallel_for<B>(particles_.size(), ulsph::DisplacementHalfStepPositionVolumeFunctor<D, Real>{
                                               velocity(), displacement(), half_dt, position_volume()});
      else
        parallel_for<B>(particles_.size(),
                        ulsph::DisplacementHalfStepFunctor<D, Real>{velocity(), displacement(), half_dt});
    });
    this->migrate_if_due();
    if (rebuild_due_) run("neighbors", [&] { rebuild(false); });
    const PairList<D, Real> pairs = pair_list();
    run("half_step", [&] {  // rho to the half step (eq. 30)
      if (refresh)          // pair data, B and the density half step in one pass over the rows
        refresh_half_step(half_dt);
      else
        parallel_for<B>(particles_.size(),
                        ulsph::HalfStepFunctor<D, Real>{pairs, velocity(), real(field::density), nullptr, half_dt});
    });
    run("stress", [&] {
      for (size_t b = 0; b < scene_.bodies.size(); ++b) stress(b, pairs, Real(dt));
    });
    run("force", [&] {
      for (size_t b = 0; b < scene_.bodies.size(); ++b) force(b, pairs, Real(dt));
      parallel_for<B>(particles_.size(), ulsph::VelocityFunctor<D, Real>{acceleration(), velocity(), Real(dt)});
    });
  }

  void advance(double dt) override {
    const Index n = particles_.size();
    box_slots_.clear();
    run("advance", [&] {  // rho and u through the second half (eq. 32), the maxima
      ulsph::SecondHalfStepFunctor<D, Real> f{
          {pair_list(), velocity(), real(field::density), displacement(), Real(0.5 * dt)},
          statistics_functor(),
          numerical_work(Real(dt))};
      stats_slot_ = results_.reduce(Index(0), n, f, StepStatistics<Real>{Real(0), Real(0), Real(0), Real(0), n},
                                    StepStatisticsCombine<Real>{});
      // The boxes of the next search, should the next step rebuild.
      for (const BodyRange& r : ranges_)
        box_slots_.push_back(results_.reduce(r.begin, r.end, BoundingBoxFunctor<D, Real>{reference(), displacement()},
                                             BoundingBox<D, Real>::empty(), BoundingBoxCombine<D, Real>{}));
    });
  }

  // Dual criteria (seed 002 eq. 28-29): acoustic steps until the advection
  // step is covered, then a new advection step with a neighbour rebuild.
  void finish_step(double dt) override {
    StepStatistics<Real> stats = results_.get(stats_slot_);
    this->maxima_over_ranks(stats);  // distributed runs: the whole scene's
    for (size_t b = 0; b < box_slots_.size(); ++b) boxes_[b] = results_.get(box_slots_[b]);
    globalize_boxes();
    if (stats.first_bad < particles_.size()) fail(stats.first_bad);
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
  }

  EnergySample energies() override {
    EnergySample e;
    e.with_audit = scene_.solver.ulsph.energy_audit;
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
      be.shear_mismatch = s.shear_mismatch;
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

  Real* optional(const char* name) { return this->optional_real(name); }

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
  bool migration_due() override { return migration_travelled_ > migration_reach(); }
  double migration_radius() override { return distributed::halo_radius(scene_); }
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

  // Per particle, outside the fields (a restored run refreshes its kept
  // pairs without a search first).
  void migrated() override {
    gradient_sum_.resize(size_t(particles_.size()));
    fallback_.resize(size_t(particles_.size()));
  }

  // MFSD_VERIFY_HALO=1: after every search, the brute-force check that each
  // owned particle's partners are all held here (host/halo/halo_check.hpp).
  void verify_halo() {
    std::vector<double> support;
    for (size_t b = 0; b < scene_.bodies.size(); ++b) support.push_back(2.0 * props(b).h);
    Base::verify_halo(to_host<B>(particles_.template buffer<Vec<D, Real>>(field::current_position)), support, false);
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
                                                         dt,
                                                         optional(field::shear_mismatch)};
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
        OwnedOnly<Energy>{
            Energy{velocity(), displacement(), real(field::mass), real(field::density), real(field::pressure),
                   mat(field::shear_stress), real(field::dissipated_work), optional(field::plastic_work), props(b).K,
                   props(b).G, g, optional(field::shear_mismatch)},
            this->ghost_flags()},
        ulsph::EnergySums{0, 0, {0, 0, 0}, 0, 0, 0, 0}, ulsph::EnergySumsPlus{});
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

  std::vector<BoundingBox<D, Real>> boxes_;  // per body, the current positions' box
  DeviceVector<B, Vec<D, Real>> grad_;
  DeviceVector<B, Real> stretch_;
  DeviceVector<B, Vec<D, Real>> gradient_sum_;
  DeviceVector<B, unsigned char> fallback_;
  long fallback_count_ = 0;
  double advection_step_ = 0, advection_elapsed_ = 0;
  double advection_travelled_ = 0;  // sum dt |v|max since the last search
  // The step's results between advance() and finish_step().
  ResultSlot<StepStatistics<Real>> stats_slot_;
  std::vector<ResultSlot<BoundingBox<D, Real>>> box_slots_;
};

}  // namespace mfsd

#include "host/solver/ulsph/ulsph_setup.hpp"
