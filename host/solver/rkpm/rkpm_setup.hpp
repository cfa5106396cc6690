// RkpmSolver's set-up: initialize(), its nodal state (the nodes' masses, smoothing
// cells, essential boundaries and fields; rkpm.md 3.2, 6) and its
// neighbour list (the symmetric list of radius max a + max r + skin,
// rkpm.md 2). Included at the end of rkpm_solver.hpp.
#pragma once

namespace mfsd {

template <class B, int D, class Real>
void RkpmSolver<B, D, Real>::add_state() {
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

template <class B, int D, class Real>
void RkpmSolver<B, D, Real>::rebuild(bool reorder) {
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
      a_max = double(
          transform_reduce<B>(r.begin, r.end, rkpm::ValueOf<Real>{real(field::support)}, Real(0), rkpm::MaxOf<Real>{}));
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
template <class B, int D, class Real>
void RkpmSolver<B, D, Real>::initialize() {
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
}  // namespace mfsd
