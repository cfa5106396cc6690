// Semi-Lagrangian RKPM solver with stabilized nodal integration (seed 004,
// the MEGA method; ../shared/reference/rkpm.md) for one backend, precision
// and dimension, on the current-configuration skeleton
// (current_configuration_solver.hpp). One call of step() is a
// drift-kick-drift step of the recipe in rkpm_recipe.cpp (the stages,
// their equations and halo refreshes; the scheme of the SPH methods, so
// that the shared conditions, loads, walls and contact act as they do
// there): half_step, stress, [migrate, neighbors], operators, force,
// contact, loads, boundary, advance, time_step.
// The strain of a step is that of the displacement between two operator
// configurations (the mid-steps): du = dt v^n, centred. The conditions act
// on the lumped mass: the kinematics' volume is M_I / rho0.
// Include after the backend header.
#pragma once
#include <thrust/copy.h>
#include <thrust/count.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

#include "host/halo/halo_radius.hpp"
#include "host/neighbors/cell_list_search.hpp"
#include "host/scene/scene_error.hpp"
#include "host/solver/common/current_configuration_solver.hpp"
#include "host/solver/rkpm/rkpm_recipe.hpp"
#include "kernels/core/owned_only.hpp"
#include "kernels/neighbors/bounding_box.hpp"
#include "kernels/rkpm/internal_force.hpp"
#include "kernels/rkpm/kronecker_ids.hpp"
#include "kernels/rkpm/node_rows.hpp"
#include "kernels/rkpm/step.hpp"

namespace mfsd {

template <class B, int D, class Real>
class RkpmSolver final : public CurrentConfigurationSolver<B, D, Real> {
  using Base = CurrentConfigurationSolver<B, D, Real>;
  using Base::acceleration, Base::displacement, Base::real, Base::reference, Base::velocity;
  using Base::body_total_, Base::cells_, Base::count_, Base::gravity_at_start_, Base::migration_travelled_,
      Base::neighbor_, Base::offsets_, Base::pairs_, Base::rebuild_due_, Base::search_;
  using Base::conditions_, Base::contact_, Base::dt_next_, Base::init_, Base::particles_, Base::ranges_, Base::report_,
      Base::results_, Base::scene_, Base::snapshot_fields_, Base::steps_, Base::time_;
  using Base::props, Base::run;
  using Op = rkpm::NodeOperator<D, Real>;
  using Grad = rkpm::ImplicitGradient<D, Real>;
  using SG = rkpm::StressGradient<D, Real>;

 public:
  RkpmSolver(const Scene& scene, const InitialParticles& init, const SolverOptions& options)
      : Base(scene, init, options), spec_(scene.solver.rkpm) {
    this->set_recipe(rkpm_recipe(scene));
    this->kinematic_volume_ = field::lumped_volume;
    conditions_.compile(scene_);
  }

  void initialize() override;

  // ---- the step (rkpm_recipe.cpp) ------------------------------------------
  // The strain of a step is that of the displacement between two operator
  // configurations (the mid-steps): du = dt v^n, centred.
  void forces(double dt) override {
    run("half_step", [&] {
      parallel_for<B>(particles_.size(),
                      rkpm::DriftFunctor<D, Real>{velocity(), displacement(), increment(), Real(0.5 * dt)});
    });
    run("stress", [&] {
      for (size_t b = 0; b < scene_.bodies.size(); ++b) stress(b, dt);
    });
    this->migrate_if_due();
    const Index n = particles_.size();  // a migration changes this rank's nodes
    if (rebuild_due_) {
      run("neighbors", [&] {
        parallel_for<B>(n, move_functor_all());
        rebuild(false);
      });
    }
    run("operators", [&] {
      if (!rebuild_due_) parallel_for<B>(n, move_functor_all());
      build_operators();
    });
    rebuild_due_ = false;
    run("force", [&] { force(dt); });
  }

  void prepare_contact() override {
    contact_.refresh_masses(real(field::lumped_volume));  // M_I of this step's force stage
  }

  void advance(double dt) override {
    stats_slots_.clear();
    run("advance", [&] {
      parallel_for<B>(particles_.size(),
                      rkpm::DriftFunctor<D, Real>{velocity(), displacement(), increment(), Real(0.5 * dt)});
      for (size_t b = 0; b < scene_.bodies.size(); ++b)
        stats_slots_.push_back(results_.reduce(ranges_[b].begin, ranges_[b].end, stats_functor(b, dt), stats_init(),
                                               rkpm::StepStatsCombine<D, Real>{}));
    });
  }

  void finish_step(double dt) override {
    std::vector<rkpm::StepStats<D, Real>> stats;
    for (auto& s : stats_slots_) stats.push_back(results_.get(s));
    stats_over_ranks(stats);
    double speed2 = 0;
    for (const auto& s : stats) speed2 = std::max(speed2, double(s.max_speed2));
    migration_travelled_ += dt * std::sqrt(speed2);
    for (const auto& s : stats)
      if (s.first_bad < particles_.size()) Base::fail(s.first_bad, {"cell_map", "J = det F_cell is not positive"});
    decide_rebuild(stats);
    dt_next_ = time_step(stats);
  }

  EnergySample energies() override {
    EnergySample e;
    for (size_t b = 0; b < scene_.bodies.size(); ++b) {
      const rkpm::EnergySums s = energy(b);
      BodyEnergy be;
      be.kinetic = s.kinetic;
      be.plastic = s.plastic;
      be.strain = s.internal - s.plastic;  // stored (elastic and NSNI) energy
      be.damping = s.damping;
      be.gravity_work = gravity_potential(b) - gravity_at_start_[b];
      this->add_shared_work(b, be);
      for (int a = 0; a < 3; ++a) be.momentum[a] = s.momentum[a];
      e.kinetic += be.kinetic;
      e.strain += be.strain;
      for (int a = 0; a < 3; ++a) e.momentum[a] += s.momentum[a];
      e.bodies.push_back(be);
    }
    return e;
  }

  void save_state(StateArchive& a) override {
    this->save_shared_state(a);
    a.put("solver/gravity_at_start", gravity_at_start_);
    a.put("rkpm/offsets", to_host<B>(offsets_));
    a.put("rkpm/neighbor", to_host<B>(neighbor_));
    a.put("rkpm/build_reach", build_reach_);
    a.put_value("rkpm/rebuild_due", rebuild_due_ ? 1L : 0L);
    // The last step's statistics: the next rebuild's grid and radius (a
    // grid of another box orders the rows otherwise, and the run would
    // continue with other round-off).
    std::vector<double> stats;
    for (const auto& s : last_stats_) {
      stats.insert(stats.end(), {double(s.max_speed2), double(s.max_drift2), double(s.max_support),
                                 double(s.max_cell_reach), double(s.min_dt)});
      for (int k = 0; k < D; ++k) stats.push_back(double(s.box.lo.v[k])), stats.push_back(double(s.box.hi.v[k]));
    }
    a.put("rkpm/last_stats", stats);
    a.put_value("rkpm/migration_travelled", migration_travelled_);
    a.put_value("rkpm/halo_radius", halo_radius_);
  }

  void restore_state(const StateArchive& a) override {
    this->restore_shared_state(a);
    gravity_at_start_ = a.get<double>("solver/gravity_at_start", long(scene_.bodies.size()));
    const auto offsets = a.get<PairIndex>("rkpm/offsets", long(particles_.size()) + 1);
    pairs_ = offsets.back();
    from_host<B>(offsets, offsets_);
    from_host<B>(a.get<Index>("rkpm/neighbor", long(pairs_) + kPairPrefetchDistance), neighbor_);
    build_reach_ = a.get<double>("rkpm/build_reach", long(scene_.bodies.size()));
    rebuild_due_ = a.get_value<long>("rkpm/rebuild_due") != 0;
    if (a.has("rkpm/last_stats")) {
      const size_t per = 5 + 2 * D;
      const std::vector<double> stats = a.get<double>("rkpm/last_stats", -1);
      last_stats_.clear();
      for (size_t k = 0; k + per <= stats.size(); k += per) {
        rkpm::StepStats<D, Real> s = stats_init();
        s.max_speed2 = Real(stats[k]), s.max_drift2 = Real(stats[k + 1]), s.max_support = Real(stats[k + 2]);
        s.max_cell_reach = Real(stats[k + 3]), s.min_dt = Real(stats[k + 4]);
        for (int d = 0; d < D; ++d)
          s.box.lo.v[d] = Real(stats[k + 5 + 2 * d]), s.box.hi.v[d] = Real(stats[k + 6 + 2 * d]);
        last_stats_.push_back(s);
      }
    }
    if (a.has("rkpm/migration_travelled")) migration_travelled_ = a.get_value<double>("rkpm/migration_travelled");
    if (a.has("rkpm/halo_radius")) halo_radius_ = a.get_value<double>("rkpm/halo_radius");
  }

 private:
  // ---- state --------------------------------------------------------------
  void add_state();

  // ---- list ---------------------------------------------------------------
  // The symmetric list (rkpm.md 2): radius max a + max r + skin per body.
  void rebuild(bool reorder);

  // ---- distributed runs (docs/distributed.md, "RKPM") ---------------------
  // The ghosts are the nodes within halo_radius_ of this rank's region at
  // the last migration; rkpm_recipe.cpp names the fields each stage's
  // refresh brings from the owners. The operators' Kronecker nodes travel
  // as global indices.
  void refresh_stage_ghosts(const std::vector<std::string>& names) override;

  // The list's radius at the next rebuild: max a + max r + skin (rkpm.md 2).
  double list_radius() const;
  // Room for the travel between migrations beyond the list (one spacing).
  double migration_margin() const;
  // A rebuild migrates first when its rows may reach past the ghosts. An
  // owned node is within d (the travel bound, sum dt max|v|) of the region,
  // and a node within the list radius R of it now was within R + 2d of the
  // region at the last migration: the ghosts hold every row while
  // R + 2d <= halo_radius_, with a fifth of the margin kept for the change
  // of v within a step (as ULSPH, docs/distributed.md). The supports grow
  // with J and the cells' reach with their stretch: a migration takes the
  // halo to the current list radius plus the margin. With contact, its
  // reach plus twice the travel until the next rebuild (at most half the
  // skin) stays within the halo too.
  double migration_radius() override;
  bool migration_due() override;

  // Every field of the ghosts from their owners (set-up), the operators'
  // Kronecker nodes by global index in between (kernels/rkpm/kronecker_ids.hpp).
  void refresh_all();
  // The operators' Kronecker nodes from local to global indices (the owned
  // operators, before a refresh) or from global to local (all, after it).
  void kronecker_ids(bool to_global);
  // The maps of kronecker_ids(), for the particles held now.
  void bind_kronecker_ids();

  void migrated() override { bind_kronecker_ids(); }

  // Distributed runs: the step's statistics over the whole scene (the
  // index of a failed node stays this rank's).
  void stats_over_ranks(std::vector<rkpm::StepStats<D, Real>>& stats);

  // Rebuild when 2 drift + growth of a + r > skin (rkpm.md 2).
  void decide_rebuild(const std::vector<rkpm::StepStats<D, Real>>& stats) {
    last_stats_ = stats;
    for (size_t b = 0; b < stats.size(); ++b) {
      const double drift = std::sqrt(double(stats[b].max_drift2));
      const double growth = double(stats[b].max_support) + double(stats[b].max_cell_reach) - build_reach_[b];
      if (2.0 * drift + std::max(growth, 0.0) > spec_.skin * scene_.bodies[b].spacing) rebuild_due_ = true;
    }
  }

  // ---- stages -------------------------------------------------------------
  rkpm::NodeFields<D, Real> nodes() {
    return {particles_.template get<Vec<D, Real>>(field::operator_position), real(field::support),
            particles_.template get<unsigned char>(field::singular), spec_.box_supports};
  }
  PairList<D, Real> rows() const {
    return PairList<D, Real>{raw(offsets_), raw(neighbor_), nullptr, nullptr, nullptr, nullptr};
  }

  rkpm::MoveAllFunctor<D, Real> move_functor_all() {
    if (support_lengths_.size() != scene_.bodies.size()) {
      std::vector<double> l;
      for (const auto& b : scene_.bodies) l.push_back(spec_.support_factor * b.spacing);  // a~ h0 (rkpm.md 1.2)
      from_host<B>(l, support_lengths_);
    }
    return rkpm::MoveAllFunctor<D, Real>{
        {reference(), displacement(), particles_.template get<Mat<D, Real>>(field::cell_map),
         particles_.template get<Vec<D, Real>>(field::operator_position), increment(), real(field::support), 0.0},
        particles_.template get<int>(field::body),
        raw(support_lengths_)};
  }

  void build_operators() {
    const int mode = spec_.quasi_linear == QuasiLinear::regularize ? 0
                     : spec_.quasi_linear == QuasiLinear::shepard  ? 1
                                                                   : 2;
    parallel_for<B>(
        particles_.size(),
        rkpm::OperatorFunctor<D, Real>{
            rows(), nodes(), particles_.template get<Mat<D, Real>>(field::cell_map),
            particles_.template get<Vec<D, Real>>(field::cell_lo),
            particles_.template get<Vec<D, Real>>(field::cell_hi), spec_.cells == SmoothingCells::box, mode,
            spec_.regularization, particles_.template get<Op>(field::node_operator),
            spec_.nsni ? particles_.template get<Grad>(field::implicit_gradient) : nullptr, real(field::reach),
            real(field::nearest), particles_.template get<unsigned char>(field::operator_status)});
  }

  // Nodes whose operator status has `bit` (set-up checks and report).
  // Distributed runs: the owned nodes of every rank (a ghost's row is cut).
  long count_status(unsigned char bit) {
    const auto status = to_host<B>(particles_.template buffer<unsigned char>(field::operator_status));
    const std::vector<unsigned char> none;
    const std::vector<unsigned char>& ghost = this->ghosts_ ? this->ghosts_->ghost_mask() : none;
    std::vector<double> c{0.0};
    for (size_t i = 0; i < status.size(); ++i) c[0] += (status[i] & bit) && (ghost.empty() || !ghost[i]) ? 1 : 0;
    if (this->ghosts_) this->ghosts_->sum_over_ranks(c);
    return long(c[0]);
  }

  rkpm::StressLaw law(size_t b) {
    const MaterialSpec& m = scene_.bodies[b].material;
    rkpm::StressLaw l;
    l.K = props(b).K;
    l.mu = props(b).G;
    if (m.model == MaterialModel::j2) {
      l.kind = rkpm::LawKind::j2;
      l.j2 = rkpm::J2Hardening{l.mu, m.yield_stress, m.hardening_modulus};
    }
    if (m.model == MaterialModel::drucker_prager) {
      // rkpm.md 4.4: the Mohr-Coulomb match of the cone and of the potential.
      const DruckerPragerSpec& d = m.drucker_prager;
      const double deg = M_PI / 180.0;
      auto cone = [&](double angle) {
        return d.match == ConeMatch::plane_strain ? rkpm::mohr_coulomb_plane_strain(angle * deg, d.cohesion)
               : d.match == ConeMatch::outer      ? rkpm::mohr_coulomb_outer_cone(angle * deg, d.cohesion)
                                                  : rkpm::mohr_coulomb_inner_cone(angle * deg, d.cohesion);
      };
      const rkpm::DruckerPragerMatch f = cone(d.friction_angle), g = cone(d.dilation_angle);
      l.kind = rkpm::LawKind::drucker_prager;
      l.dp = rkpm::DruckerPragerCone{l.K,         l.mu, f.alpha_bar,
                                     g.alpha_bar, f.k,  d.tension_cutoff > 0 ? d.tension_cutoff : double(INFINITY)};
    }
    l.damage = damage_law(b);
    return l;
  }

  rkpm::DamageLaw damage_law(size_t b) const {
    const DamageSpec& d = scene_.bodies[b].material.damage;
    switch (d.law) {
      case DamageModel::linear:
        return rkpm::DamageLaw::linear(d.onset_strain, d.failure_strain);
      case DamageModel::exponential:
        return rkpm::DamageLaw::exponential(d.onset_strain, d.decay_strain);
      case DamageModel::johnson_cook:
        return rkpm::DamageLaw::johnson_cook(d.d1, d.d2, d.d3, d.d4, d.reference_rate);
      default:
        return rkpm::DamageLaw{};
    }
  }

  void stress(size_t b, double dt) {
    const bool plastic = scene_.bodies[b].material.plastic();
    rkpm::StressFunctor<D, Real> f{rows(),
                                   nodes(),
                                   particles_.template get<Op>(field::node_operator),
                                   spec_.nsni ? particles_.template get<Grad>(field::implicit_gradient) : nullptr,
                                   increment(),
                                   real(field::volume),
                                   particles_.template get<Vec<D, Real>>(field::cell_lo),
                                   particles_.template get<Vec<D, Real>>(field::cell_hi),
                                   particles_.template get<Mat<D, Real>>(field::cell_map),
                                   particles_.template get<Mat<3, Real>>(field::effective_stress),
                                   plastic ? real(field::plastic_strain) : nullptr,
                                   this->optional_real(field::damage),
                                   spec_.nsni ? particles_.template get<SG>(field::stress_gradient) : nullptr,
                                   spec_.nsni ? particles_.template get<SG>(field::nsni_stress) : nullptr,
                                   real(field::internal_work),
                                   plastic ? real(field::plastic_work) : nullptr,
                                   law(b),
                                   spec_.nsni_scale,
                                   spec_.nsni_tangent,
                                   spec_.nsni_consistent,
                                   spec_.recell_condition,
                                   spec_.cells == SmoothingCells::box,
                                   dt};
    parallel_for<B>(ranges_[b].begin, ranges_[b].end, f);
  }

  void force(double dt) {
    Vec<D, Real> g;
    for (int a = 0; a < D; ++a) g.v[a] = Real(scene_.solver.gravity[a]);
    rkpm::ForceFunctor<D, Real> f{rows(),
                                  nodes(),
                                  particles_.template get<Op>(field::node_operator),
                                  spec_.nsni ? particles_.template get<Grad>(field::implicit_gradient) : nullptr,
                                  spec_.nsni ? particles_.template get<SG>(field::nsni_stress) : nullptr,
                                  particles_.template get<Mat<3, Real>>(field::effective_stress),
                                  this->optional_real(field::damage),
                                  rkpm::DamageLaw{},
                                  particles_.template get<unsigned char>(field::cell_surface),
                                  particles_.template get<unsigned char>(field::operator_status),
                                  real(field::mass),
                                  real(field::lumped_mass),
                                  real(field::lumped_volume),
                                  real(field::density0),
                                  velocity(),
                                  acceleration(),
                                  this->optional_real(field::damping_work),
                                  g,
                                  spec_.variational_correction,
                                  spec_.row_sum_mass,
                                  spec_.damping,
                                  dt};
    parallel_for<B>(particles_.size(), f);
  }

  // ---- reductions ---------------------------------------------------------
  rkpm::StepStatsFunctor<D, Real> stats_functor(size_t b, double dt) {
    const BodyProperties& p = props(b);
    rkpm::StepStatsFunctor<D, Real> f{reference(),
                                      displacement(),
                                      velocity(),
                                      particles_.template get<Vec<D, Real>>(field::build_position),
                                      particles_.template get<Mat<D, Real>>(field::cell_map),
                                      real(field::support),
                                      real(field::reach),
                                      spec_.nearest_time_step ? real(field::nearest) : nullptr,
                                      scene_.bodies[b].spacing,
                                      std::sqrt(scene_.bodies[b].material.density / (p.K + 4.0 * p.G / 3.0)),
                                      dt,
                                      {},
                                      {},
                                      particles_.size()};
    f.ghost = this->ghost_flags();
    for (int a = 0; a < D; ++a) {
      f.lower.v[a] = Real(scene_.bounds.min[a]);
      f.upper.v[a] = Real(scene_.bounds.max[a]);
    }
    return f;
  }
  rkpm::StepStats<D, Real> stats_init() const {
    const BoundingBox<D, Real> e = BoundingBox<D, Real>::empty();
    return rkpm::StepStats<D, Real>{Real(0), Real(0), Real(0), Real(0), Real(INFINITY), particles_.size(), e};
  }
  std::vector<rkpm::StepStats<D, Real>> host_stats(double dt) {
    std::vector<rkpm::StepStats<D, Real>> s;
    for (size_t b = 0; b < scene_.bodies.size(); ++b)
      s.push_back(transform_reduce<B>(ranges_[b].begin, ranges_[b].end, stats_functor(b, dt), stats_init(),
                                      rkpm::StepStatsCombine<D, Real>{}));
    stats_over_ranks(s);
    return s;
  }

  // dt = CFL min_L h_L / c_L (rkpm.md 5.3), and the contact's bound.
  double time_step(const std::vector<rkpm::StepStats<D, Real>>& stats) {
    double dt = std::numeric_limits<double>::infinity();
    for (const auto& s : stats) dt = std::min(dt, double(s.min_dt));
    dt *= scene_.solver.cfl;
    if (contact_.inverse_stable_step() > 0) dt = std::min(dt, 1.0 / contact_.inverse_stable_step());
    return dt;
  }

  rkpm::EnergySums energy(size_t b) {
    using Energy = rkpm::EnergyFunctor<D, Real>;
    return transform_reduce<B>(
        ranges_[b].begin, ranges_[b].end,
        OwnedOnly<Energy>{Energy{velocity(), real(field::lumped_mass), real(field::internal_work),
                                 this->optional_real(field::plastic_work), this->optional_real(field::damping_work)},
                          this->ghost_flags()},
        rkpm::EnergySums{0, 0, 0, 0, {0, 0, 0}}, rkpm::EnergySumsPlus{});
  }

  // sum m g . u with the nodal masses (the gravity's work since the start
  // is its change).
  double gravity_potential(size_t b) {
    Vec<D, Real> g;
    for (int a = 0; a < D; ++a) g.v[a] = Real(scene_.solver.gravity[a]);
    using Potential = rkpm::GravityPotentialFunctor<D, Real>;
    return transform_reduce<B>(
        ranges_[b].begin, ranges_[b].end,
        OwnedOnly<Potential>{Potential{displacement(), real(field::mass), g}, this->ghost_flags()}, 0.0,
        rkpm::PlusDouble{});
  }

  void update_observables() override {
    parallel_for<B>(particles_.size(), rkpm::ObservablesFunctor<D, Real>{
                                           particles_.template get<Mat<3, Real>>(field::effective_stress),
                                           this->optional_real(field::damage), rkpm::DamageLaw{},
                                           particles_.template get<Mat<D, Real>>(field::cell_map),
                                           real(field::von_mises), real(field::pressure), real(field::jacobian)});
  }
  void update_stress_observables() override { update_observables(); }

  Vec<D, Real>* increment() { return particles_.template get<Vec<D, Real>>(field::increment); }

  RkpmSpec spec_;
  std::vector<double> build_reach_;  // per body, max a + max r at the list's build
  DeviceVector<B, double> support_lengths_;
  DeviceVector<B, Index> global_of_local_, sorted_global_, local_of_sorted_;  // kronecker_ids()
  long regularized_at_setup_ = 0;
  std::vector<rkpm::StepStats<D, Real>> last_stats_;               // per body, of the last step
  std::vector<ResultSlot<rkpm::StepStats<D, Real>>> stats_slots_;  // between advance() and finish_step()
  double halo_radius_ = 0;  // distributed runs: the ghosts' reach at the last migration
};

}  // namespace mfsd

#include "host/solver/rkpm/rkpm_distributed.hpp"
#include "host/solver/rkpm/rkpm_setup.hpp"
