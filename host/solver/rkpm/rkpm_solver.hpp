// Semi-Lagrangian RKPM solver with stabilized nodal integration (seed 004,
// the MEGA method; ../shared/reference/rkpm.md) for one backend, precision
// and dimension, on the shared platform (host/solver/common/). One call of
// step() is a drift-kick-drift step (the scheme of the SPH methods, so that
// the shared conditions, loads, walls and contact act as they do there):
//   half_step   u += dt/2 v                                          (drift)
//   stress      per node, row L, with the operators they were built with:
//               L_n, Hughes-Winget, return mapping, F_cell, NSNI sigma^(i)
//                                               (rkpm.md 4; seed 004 eq. 25-26)
//   operators   x_ops = X + u, a = a~ h0 J^(1/d); the list when the skin is
//               exceeded; faces, RK coefficients at the 2d face points and
//               the node, NSNI coefficients          (rkpm.md 1, 3.2, 5.2 stage 5)
//   force       f_int (SNNI + VC + NSNI), row-sum mass M_I, gravity, damping,
//               v += dt a                            (rkpm.md 3.3-3.5, 5.1)
//   contact, loads, boundary   the shared services
//   advance     u += dt/2 v, the step's reduction    (drift)
//   time_step   the one synchronisation; dt = CFL min h_L/c_L (rkpm.md 5.3)
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
#include "host/solver/common/particle_solver.hpp"
#include "kernels/core/owned_only.hpp"
#include "kernels/neighbors/bounding_box.hpp"
#include "kernels/rkpm/internal_force.hpp"
#include "kernels/rkpm/kronecker_ids.hpp"
#include "kernels/rkpm/node_rows.hpp"
#include "kernels/rkpm/step.hpp"

namespace mfsd {

template <class B, int D, class Real>
class RkpmSolver final : public ParticleSolver<B, D, Real> {
  using Base = ParticleSolver<B, D, Real>;
  using Base::conditions_, Base::contact_, Base::dt_next_, Base::init_, Base::particles_, Base::ranges_, Base::report_,
      Base::results_, Base::scene_, Base::snapshot_fields_, Base::steps_, Base::time_;
  using Base::declare_stage, Base::props, Base::run;
  using Op = rkpm::NodeOperator<D, Real>;
  using Grad = rkpm::ImplicitGradient<D, Real>;
  using SG = rkpm::StressGradient<D, Real>;

 public:
  RkpmSolver(const Scene& scene, const InitialParticles& init, const SolverOptions& options)
      : Base(scene, init, options), spec_(scene.solver.rkpm) {
    for (const auto& c : scene.conditions) has_loads_ = has_loads_ || c.type != ConditionSpec::Type::velocity;
    for (const char* name : {"half_step", "stress", "neighbors", "operators", "force", "contact", "loads", "boundary",
                             "advance", "time_step"})
      if ((has_loads_ || std::string(name) != "loads") && (scene.contact.enabled || std::string(name) != "contact"))
        declare_stage(name);
    this->kinematic_volume_ = field::lumped_volume;
    conditions_.compile(scene_);
  }

  void initialize() override {
    const Index n = particles_.size();
    this->upload_kinematics();
    add_state();
    for (size_t b = 0; b < scene_.bodies.size(); ++b)
      body_total_.push_back(double(this->owned_in(ranges_[b].begin, ranges_[b].end)));
    if (this->ghosts_) this->ghosts_->sum_over_ranks(body_total_);  // the cell grid of the whole body
    halo_radius_ = distributed::halo_radius(scene_);
    // Initial cells, supports and the first list, sorted and reordered by cell.
    parallel_for<B>(n, move_functor_all());
    rebuild(scene_.solver.reorder);
    particles_.remove(field::reference_position_double);
    if (this->ghosts_) {  // each node's place in the single-process order (migrate_particles)
      particles_.template add<std::int64_t>(field::order_key);
      if (scene_.solver.reorder)
        thrust::copy(BackendTraits<B>::policy(), cells_.keys.begin(), cells_.keys.end(),
                     particles_.template buffer<std::int64_t>(field::order_key).begin());
    }
    this->bind_ghosts();  // distributed runs: the exchange in the sorted order
    // The singular kernels of the essential nodes: the conditions' lists
    // hold this rank's owned nodes only, so a ghost learns it from its owner.
    this->refresh_ghosts({field::singular});
    bind_kronecker_ids();
    build_operators();
    refresh_all();  // the ghosts' operators (their rows are cut) from their owners
    const long under = count_status(4u);
    if (under > 0)
      throw SceneError("/solver/rkpm/support_factor",
                       std::to_string(spec_.support_factor) + ": " + std::to_string(under) +
                           " nodes have evaluation points covered by fewer than " + std::to_string(D + 1) + " kernels",
                       "a support large enough for the linear basis (1.5 to 2.0; rkpm.md 1.2)");
    const long failed = count_status(2u);
    if (failed > 0)
      throw SceneError("/solver/rkpm/quasi_linear",
                       "\"off\" with " + std::to_string(failed) + " nodes whose moment matrix is singular",
                       "\"regularize\" or \"shepard\", or a larger support_factor (rkpm.md 1.6)");
    regularized_at_setup_ = count_status(1u);
    force(0.0);  // the lumped masses
    refresh_all();

    snapshot_fields_ = {{"von_mises", field::von_mises}, {"J", field::jacobian}, {"pressure", field::pressure}};
    if (particles_.has(field::plastic_strain)) snapshot_fields_.emplace_back("plastic_strain", field::plastic_strain);
    if (particles_.has(field::damage)) snapshot_fields_.emplace_back("damage", field::damage);

    const std::vector<Index> where = this->locate();
    conditions_.setup(init_, where, particles_.template get<Index>(field::id), ranges_);
    if (scene_.contact.enabled) this->setup_contact(std::vector<unsigned char>(size_t(n), 1));
    this->locate_probes(where);
    results_.clear();
    conditions_.apply_initial(this->kinematics(), results_);
    results_.fetch();
    conditions_.collect(results_, this->kinematics());
    refresh_all();
    for (size_t b = 0; b < scene_.bodies.size(); ++b) gravity_at_start_.push_back(gravity_potential(b));
    const auto stats = host_stats(0.0);
    dt_next_ = time_step(stats);

    report_.regularized_corrections = regularized_at_setup_;
    report_.pair_loop = "full";
    this->release_initial_particles();
    this->report_particles_and_pairs(to_host<B>(offsets_),
                                     double(pairs_) * sizeof(Index) + double(n) * sizeof(PairIndex));
  }

  void begin_step() override {
    this->round_trips_before_ = round_trips();
    const double dt = this->step_dt_ = dt_next_;
    results_.clear();
    run("half_step", [&] {
      parallel_for<B>(particles_.size(),
                      rkpm::DriftFunctor<D, Real>{velocity(), displacement(), increment(), Real(0.5 * dt)});
    });
    run("stress", [&] {
      for (size_t b = 0; b < scene_.bodies.size(); ++b) stress(b, dt);
    });
    halo({field::effective_stress, field::nsni_stress, field::damage, field::cell_map});
    if (rebuild_due_ && this->ghosts_ && !distributed::migration_switched_off() && migration_due()) {
      run("migrate", [&] {
        halo_radius_ = std::max(distributed::halo_radius(scene_), list_radius() + migration_margin());
        this->migrate_particles(halo_radius_);
      });
      migration_travelled_ = 0;
    }
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
    if (this->ghosts_)
      run("halo", [&] {
        kronecker_ids(true);
        this->refresh_ghosts({field::node_operator, field::implicit_gradient, field::operator_status});
        kronecker_ids(false);
      });
    rebuild_due_ = false;
    run("force", [&] { force(dt); });
    if (contact_.enabled()) {
      if (this->ghosts_ && distributed::halo_check_requested()) verify_contact_halo();
      halo({field::velocity, field::lumped_volume});  // the contact's partners across the cut
      run("contact", [&] {
        contact_.refresh_masses(real(field::lumped_volume));  // M_I of this step's force stage
        contact_.apply(this->kinematics(), time_, dt, results_);
      });
    }
  }

  void end_step() override {
    const Index n = particles_.size();
    const double dt = this->step_dt_;
    const Kinematics<D, Real> k = this->kinematics();
    if (has_loads_) run("loads", [&] { conditions_.apply_loads(k, time_, dt, steps_ + 1, results_); });
    run("boundary", [&] { conditions_.apply_boundary(k, time_, dt, steps_ + 1, results_); });
    halo({field::velocity});
    std::vector<ResultSlot<rkpm::StepStats<D, Real>>> slots;
    run("advance", [&] {
      parallel_for<B>(n, rkpm::DriftFunctor<D, Real>{velocity(), displacement(), increment(), Real(0.5 * dt)});
      for (size_t b = 0; b < scene_.bodies.size(); ++b)
        slots.push_back(results_.reduce(ranges_[b].begin, ranges_[b].end, stats_functor(b, dt), stats_init(),
                                        rkpm::StepStatsCombine<D, Real>{}));
    });
    run("time_step", [&] {
      results_.fetch();
      conditions_.collect(results_, k);
      contact_.collect(results_);
      std::vector<rkpm::StepStats<D, Real>> stats;
      for (auto& s : slots) stats.push_back(results_.get(s));
      stats_over_ranks(stats);
      time_ += dt;
      ++steps_;
      double speed2 = 0;
      for (const auto& s : stats) speed2 = std::max(speed2, double(s.max_speed2));
      migration_travelled_ += dt * std::sqrt(speed2);
      for (const auto& s : stats)
        if (s.first_bad < n) Base::fail(s.first_bad, {"cell_map", "J = det F_cell is not positive"});
      decide_rebuild(stats);
      dt_next_ = time_step(stats);
    });
    this->clock_.collect(this->timers_);
    this->timers_.add_round_trips(round_trips() - this->round_trips_before_);
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
  void add_state() {
    const Index n = particles_.size();
    const size_t N = size_t(n);
    std::vector<Real> mass(N), rho0(N);
    std::vector<Vec<D, Real>> lo(N), hi(N);
    std::vector<unsigned char> surface(N, 0), singular(N, 0);
    // Nodes on essential boundaries (rkpm.md 6): clamped, or selected by a
    // velocity condition; ids are still indices here (before the sort).
    std::vector<unsigned char> essential(init_.constrained.begin(), init_.constrained.end());
    for (size_t c = 0; c < scene_.conditions.size() && c < init_.condition_particles.size(); ++c)
      if (scene_.conditions[c].type == ConditionSpec::Type::velocity)
        for (long id : init_.condition_particles[c].ids) essential[size_t(id)] = 1;
    for (size_t b = 0; b < scene_.bodies.size(); ++b) {
      const BodySpec& body = scene_.bodies[b];
      const double dp = body.spacing, full = std::pow(dp, D);
      for (Index i = ranges_[b].begin; i < ranges_[b].end; ++i) {
        const size_t k = size_t(i);
        const double V0 = init_.volume[k];
        mass[k] = Real(body.material.density * V0);
        rho0[k] = Real(body.material.density);
        surface[k] = init_.surface.empty() ? 0 : init_.surface[k];
        singular[k] = spec_.singular_kernel && essential[k] ? 1 : 0;
        // The node's initial cell (rkpm.md 3.2): a full box of the lattice,
        // or, for a smaller volume, clipped to 0 on the exposed sides.
        const bool clipped = std::abs(V0 - full) > 1e-9 * full;
        double cell = 1;
        for (int a = 0; a < D; ++a) {
          lo[k].v[a] = Real(clipped && (surface[k] >> (2 * a) & 1u) ? 0.0 : 0.5 * dp);
          hi[k].v[a] = Real(clipped && (surface[k] >> (2 * a + 1) & 1u) ? 0.0 : 0.5 * dp);
          cell *= double(lo[k].v[a]) + double(hi[k].v[a]);
        }
        if (!(std::abs(cell - V0) <= 1e-6 * full))
          throw SceneError("/bodies/" + std::to_string(b) + "/spacing",
                           "a node of volume " + std::to_string(V0) + " that is no lattice cell",
                           "lattice nodes (RKPM's smoothing cells are the lattice's boxes, rkpm.md 3.2)");
      }
    }
    auto upload = [&](const char* name, const auto& host) {
      using T = typename std::decay_t<decltype(host)>::value_type;
      particles_.template add<T>(name);
      from_host<B>(host, particles_.template buffer<T>(name));
    };
    upload(field::mass, mass);
    upload(field::density0, rho0);
    upload(field::cell_lo, lo);
    upload(field::cell_hi, hi);
    upload(field::cell_surface, surface);
    upload(field::singular, singular);
    upload(field::cell_map, std::vector<Mat<D, Real>>(N, Mat<D, Real>::identity()));
    upload(field::lumped_mass, mass);
    std::vector<Real> volume0(N);
    for (size_t k = 0; k < N; ++k) volume0[k] = Real(init_.volume[k]);
    upload(field::lumped_volume, volume0);
    particles_.template add<Vec<D, Real>>(field::acceleration);
    particles_.template add<Real>(field::support);
    particles_.template add<Vec<D, Real>>(field::operator_position);
    particles_.template add<Vec<D, Real>>(field::build_position);
    particles_.template add<Vec<D, Real>>(field::increment);
    particles_.template add<Op>(field::node_operator);
    if (spec_.nsni) {
      particles_.template add<Grad>(field::implicit_gradient);
      particles_.template add<SG>(field::stress_gradient);
      particles_.template add<SG>(field::nsni_stress);
    }
    particles_.template add<unsigned char>(field::operator_status);
    particles_.template add<Real>(field::reach);
    particles_.template add<Real>(field::nearest);
    particles_.template add<Mat<3, Real>>(field::effective_stress);
    particles_.template add<Real>(field::internal_work);
    particles_.template add<Real>(field::von_mises);
    particles_.template add<Real>(field::pressure);
    particles_.template add<Real>(field::jacobian);
    if (spec_.damping > 0) particles_.template add<Real>(field::damping_work);
    if (has_plastic_body(scene_)) {
      particles_.template add<Real>(field::plastic_strain);
      particles_.template add<Real>(field::plastic_work);
    }
    for (const auto& b : scene_.bodies)
      if (b.material.damage.law != DamageModel::none) particles_.template add<Real>(field::damage);
    for (size_t b = 0; b < scene_.bodies.size(); ++b) {
      search_.push_back(BodySearch{ranges_[b], 0.0});
      build_reach_.push_back(0.0);
    }
  }

  // ---- list ---------------------------------------------------------------
  // The symmetric list (rkpm.md 2): radius max a + max r + skin per body.
  void rebuild(bool reorder) {
    const Index n = particles_.size();
    std::vector<CellGrid<D, Real>> grids;
    std::int64_t first = 0;
    for (size_t b = 0; b < search_.size(); ++b) {
      const BodyRange r = ranges_[b];
      const double dp = scene_.bodies[b].spacing;
      // In a run the last step's reduction has the box and the largest
      // support and cell reach (no round trip: the list's only ones are the
      // grids' upload and the count's scan); at set-up they are reduced here.
      double a_max, r_max;
      BoundingBox<D, Real> box;
      if (last_stats_.size() == search_.size()) {
        const rkpm::StepStats<D, Real>& s = last_stats_[b];
        a_max = double(s.max_support);
        r_max = double(s.max_cell_reach);
        box = s.box;
        const Real margin = Real(0.5 * this->step_dt_ * std::sqrt(double(s.max_speed2)));  // the half drift since
        for (int k = 0; k < D; ++k) box.lo.v[k] -= margin, box.hi.v[k] += margin;
      } else {
        a_max = double(transform_reduce<B>(r.begin, r.end, rkpm::ValueOf<Real>{real(field::support)}, Real(0),
                                           rkpm::MaxOf<Real>{}));
        // The initial cells' half diagonal bounds their reach; a box kernel reaches a sqrt(d).
        r_max = 0.5 * dp * std::sqrt(double(D)) + a_max * (rkpm::kernel_reach_factor<D>(spec_.box_supports) - 1.0);
        box = transform_reduce<B>(r.begin, r.end, BoundingBoxFunctor<D, Real>{reference(), displacement()},
                                  BoundingBox<D, Real>::empty(), BoundingBoxCombine<D, Real>{});
        if (this->ghosts_) {  // the whole body's (every rank's cells are the single-process run's)
          std::vector<double> v{a_max, r_max};
          for (int a = 0; a < D; ++a) v.push_back(-double(box.lo.v[a])), v.push_back(double(box.hi.v[a]));
          this->ghosts_->max_over_ranks(v);
          a_max = v[0], r_max = v[1];
          for (int a = 0; a < D; ++a) box.lo.v[a] = Real(-v[2 + 2 * a]), box.hi.v[a] = Real(v[3 + 2 * a]);
        }
      }
      // The supports grow with J after the reduction, by far less than the skin.
      build_reach_[b] = a_max + r_max;
      const double radius = build_reach_[b] + spec_.skin * dp;
      search_[b].smoothing_length = 0.5 * radius;
      double lo[D], hi[D], cell = radius, cells = 1;
      for (int a = 0; a < D; ++a) {
        lo[a] = double(box.lo.v[a]);
        hi[a] = std::max(lo[a], double(box.hi.v[a]));
        cells *= std::floor((hi[a] - lo[a]) / cell) + 1;
      }
      const double limit = std::max(64.0, 4.0 * body_total_[b]);
      if (cells > limit) cell *= std::pow(cells / limit, 1.0 / D);
      grids.push_back(make_cell_grid<D, Real>(lo, hi, cell, first));
      first += grids.back().cells;
    }
    sort_into_cells<B, D, Real>(particles_, field::operator_position, grids, reorder, cells_);
    CellNeighborhood<D, Real> hood = cell_neighborhood<B, D, Real>(particles_, field::operator_position, cells_);
    pairs_ = count_pairs<B, D, Real>(hood, search_, n, count_, offsets_) + PairIndex(n);  // + each row's node
    parallel_for<B>(n + 1, rkpm::SelfOffsetsFunctor{raw(offsets_)});
    neighbor_.resize(size_t(pairs_) + kPairPrefetchDistance, 0);
    for (const auto& s : search_) {
      hood.radius2 = support_radius2<Real>(s.smoothing_length);
      parallel_for<B>(s.range.begin, s.range.end, rkpm::RowFillFunctor<D, Real>{hood, raw(offsets_), raw(neighbor_)});
    }
    const Vec<D, Real>* x = particles_.template get<Vec<D, Real>>(field::operator_position);
    thrust::copy(BackendTraits<B>::policy(), x, x + n, particles_.template get<Vec<D, Real>>(field::build_position));
    if (this->ghosts_ && distributed::halo_check_requested()) {  // every owned row complete
      std::vector<double> radius;
      for (const auto& s : search_) radius.push_back(2.0 * s.smoothing_length);
      Base::verify_halo(to_host<B>(particles_.template buffer<Vec<D, Real>>(field::operator_position)), radius, false);
    }
  }

  // ---- distributed runs (docs/distributed.md, "RKPM") ---------------------
  // The ghosts are the nodes within halo_radius_ of this rank's region at
  // the last migration. Each refresh holds what the gathers until the next
  // one read of a partner and a ghost's own cut row got wrong:
  //   after the stress: sigma_bar, tau^(i), the damage (the force reads
  //     them of row I's nodes) and F_cell (the move's supports a = a~ h0 J^(1/d));
  //   after the operators: each node's RK coefficients, its NSNI implicit
  //     gradients and status (the force evaluates Psi_I at x_L from L's);
  //   with contact, after the force: v and M_I / rho0 (the contact's partners);
  //   after the boundary conditions: v (the drifts, du and so the stress).
  // Every other field a ghost holds is its own function of these (x, a,
  // du) or is read of no partner (the work sums, eps_p, sigma^(i)).
  void halo(std::initializer_list<const char*> names) {
    if (this->ghosts_) run("halo", [&] { this->refresh_ghosts(names); });
  }

  // The list's radius at the next rebuild: max a + max r + skin (rkpm.md 2).
  double list_radius() const {
    double r = 0;
    for (size_t b = 0; b < scene_.bodies.size(); ++b) {
      const double reach = b < last_stats_.size()
                               ? double(last_stats_[b].max_support) + double(last_stats_[b].max_cell_reach)
                               : build_reach_[b];
      r = std::max(r, reach + spec_.skin * scene_.bodies[b].spacing);
    }
    return r;
  }
  // Room for the travel between migrations beyond the list (one spacing).
  double migration_margin() const {
    double dp = 0;
    for (const auto& b : scene_.bodies) dp = std::max(dp, b.spacing);
    return dp;
  }
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
  bool migration_due() const {
    double spacing = 0, skin = 0;
    for (const auto& b : scene_.bodies) spacing = std::max(spacing, b.spacing);
    skin = spec_.skin * spacing;
    double reach = 0.4 * (halo_radius_ - list_radius());
    if (scene_.contact.enabled)
      reach = std::min(reach, 0.4 * (halo_radius_ - kContactRateReach * spacing) - 0.5 * skin);
    return migration_travelled_ > reach;
  }

  // Every field of the ghosts from their owners (set-up), the operators'
  // Kronecker nodes by global index in between (kernels/rkpm/kronecker_ids.hpp).
  void refresh_all() {
    if (!this->ghosts_) return;
    kronecker_ids(true);
    this->refresh_all_ghosts();
    kronecker_ids(false);
  }
  // The operators' Kronecker nodes from local to global indices (the owned
  // operators, before a refresh) or from global to local (all, after it).
  void kronecker_ids(bool to_global) {
    Op* op = particles_.template get<Op>(field::node_operator);
    if (to_global)
      parallel_for<B>(particles_.size(), rkpm::KroneckerToGlobal<D, Real>{op, raw(global_of_local_)});
    else
      parallel_for<B>(particles_.size(), rkpm::KroneckerToLocal<D, Real>{op, raw(sorted_global_), raw(local_of_sorted_),
                                                                         Index(sorted_global_.size())});
  }
  // The maps of kronecker_ids(), for the particles held now.
  void bind_kronecker_ids() {
    if (!this->ghosts_) return;
    const auto ids = to_host<B>(particles_.template buffer<Index>(field::id));
    std::vector<Index> global(ids.size()), order(ids.size());
    for (size_t i = 0; i < ids.size(); ++i) global[i] = Index(this->ghosts_->global_id(long(ids[i])));
    std::iota(order.begin(), order.end(), Index(0));
    std::sort(order.begin(), order.end(), [&](Index a, Index b) { return global[size_t(a)] < global[size_t(b)]; });
    std::vector<Index> sorted(ids.size());
    for (size_t k = 0; k < order.size(); ++k) sorted[k] = global[size_t(order[k])];
    from_host<B>(global, global_of_local_);
    from_host<B>(sorted, sorted_global_);
    from_host<B>(order, local_of_sorted_);
  }

  void after_migration() override {
    for (size_t b = 0; b < search_.size(); ++b) search_[b].range = ranges_[b];
    bind_kronecker_ids();
    if (scene_.contact.enabled) this->setup_contact_again(std::vector<unsigned char>(size_t(particles_.size()), 1));
  }

  // MFSD_VERIFY_HALO=1 with contact: at every step, every node of any body
  // within the contact's reach of an owned node is held here.
  void verify_contact_halo() {
    double spacing = 0;
    for (const auto& b : scene_.bodies) spacing = std::max(spacing, b.spacing);
    const auto X = to_host<B>(particles_.template buffer<Vec<D, Real>>(field::reference_position));
    auto x = to_host<B>(particles_.template buffer<Vec<D, Real>>(field::displacement));
    for (size_t i = 0; i < x.size(); ++i) x[i] += X[i];
    Base::verify_halo(x, std::vector<double>(scene_.bodies.size(), kContactRateReach * spacing), true);
  }

  bool ghosts_supported() const override { return true; }
  bool ghosts_are_current_neighbours() const override { return true; }

  // Distributed runs: the step's statistics over the whole scene (the
  // index of a failed node stays this rank's).
  void stats_over_ranks(std::vector<rkpm::StepStats<D, Real>>& stats) {
    if (!this->ghosts_) return;
    std::vector<double> v;
    for (const auto& s : stats) {
      v.insert(v.end(), {double(s.max_speed2), double(s.max_drift2), double(s.max_support), double(s.max_cell_reach),
                         -double(s.min_dt)});
      for (int a = 0; a < D; ++a) v.push_back(-double(s.box.lo.v[a])), v.push_back(double(s.box.hi.v[a]));
    }
    this->ghosts_->max_over_ranks(v);
    size_t k = 0;
    for (auto& s : stats) {
      s.max_speed2 = Real(v[k++]), s.max_drift2 = Real(v[k++]), s.max_support = Real(v[k++]);
      s.max_cell_reach = Real(v[k++]), s.min_dt = Real(-v[k++]);
      for (int a = 0; a < D; ++a) s.box.lo.v[a] = Real(-v[k++]), s.box.hi.v[a] = Real(v[k++]);
    }
  }

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

  Real* real(const char* name) { return particles_.template get<Real>(name); }
  Vec<D, Real>* velocity() { return particles_.template get<Vec<D, Real>>(field::velocity); }
  Vec<D, Real>* acceleration() { return particles_.template get<Vec<D, Real>>(field::acceleration); }
  Vec<D, Real>* displacement() { return particles_.template get<Vec<D, Real>>(field::displacement); }
  Vec<D, Real>* increment() { return particles_.template get<Vec<D, Real>>(field::increment); }
  const Vec<D, Real>* reference() { return particles_.template get<Vec<D, Real>>(field::reference_position); }

  RkpmSpec spec_;
  std::vector<BodySearch> search_;
  std::vector<double> build_reach_;  // per body, max a + max r at the list's build
  CellIndex<B, D, Real> cells_;
  DeviceVector<B, Index> count_;
  DeviceVector<B, PairIndex> offsets_;
  DeviceVector<B, Index> neighbor_;
  DeviceVector<B, double> support_lengths_;
  DeviceVector<B, Index> global_of_local_, sorted_global_, local_of_sorted_;  // kronecker_ids()
  PairIndex pairs_ = 0;
  long regularized_at_setup_ = 0;
  bool has_loads_ = false;
  bool rebuild_due_ = false;
  std::vector<double> gravity_at_start_;
  std::vector<rkpm::StepStats<D, Real>> last_stats_;  // per body, of the last step
  std::vector<double> body_total_;  // nodes of each body in the whole scene (distributed runs: all ranks')
  double halo_radius_ = 0;          // distributed runs: the ghosts' reach at the last migration
  double migration_travelled_ = 0;  // distributed runs: sum dt |v|max since the last migration
};

}  // namespace mfsd
