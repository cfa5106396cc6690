// UlsphSolver's set-up (initialize()): the state (rho = rho0, m = rho0 V0,
// tau = 0), the first search with the reordering of the particles, the
// ghosts, the conditions, contact and the first time step.
// Included at the end of ulsph_solver.hpp.
#pragma once

namespace mfsd {

template <class B, int D, class Real>
void UlsphSolver<B, D, Real>::initialize() {
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
  if (scene_.solver.ulsph.energy_audit) particles_.template add<Real>(field::shear_mismatch);  // zero
  particles_.template add<Real>(field::dissipated_work);                                       // zero
  particles_.template add<Vec<D, Real>>(field::numerical_acceleration);                        // a_num of the step
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
}  // namespace mfsd
