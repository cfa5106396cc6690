// TlsphSolver's set-up (initialize()): the reference neighbour list and
// its correction matrices, the model fields (plastic state, phase field,
// fibres), the views the kernels read, each body's kernels for its
// material and hourglass form, the conditions and the initial rates and
// forces. Included at the end of tlsph_solver.hpp.
#pragma once

namespace mfsd {

template <class B, int D, class Real>
void TlsphSolver<B, D, Real>::initialize() {
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
  const bool half_loop = std::is_same<B, Cpu>::value && options_.pair_loop != SolverOptions::PairLoop::full && !sliced;
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
  pairs_ = build_reference_neighbor_list<B, D, Real>(particles_, search, scene_.solver.reorder, paper_limiter, notches,
                                                     field::correction_matrix, half_only, half_float);
  particles_.remove(field::reference_position_double);
  this->bind_ghosts();  // distributed runs: the exchange in the reordered indices
  if constexpr (std::is_same<B, Cpu>::value)
    if (half_loop && !half_only) build_half_pair_list(pairs_, n);

  DeviceVector<B, unsigned char> regularized(size_t(n), 0);
  parallel_for<B>(n,
                  CorrectionFromMomentFunctor<D, Real>{particles_.template get<Mat<D, Real>>(field::correction_matrix),
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
      viscosity.push_back(r.factor > 0 ? r.factor * r.random_ratio * rho * props(b).c0 * props(b).h / scene_.solver.cfl
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

template <class B, int D, class Real>
void TlsphSolver<B, D, Real>::upload_model_fields() {
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

template <class B, int D, class Real>
void TlsphSolver<B, D, Real>::bind_views() {
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

template <class B, int D, class Real>
std::unique_ptr<BodyKernels<B, D, Real>> TlsphSolver<B, D, Real>::make_body_kernels(size_t b) {
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
    return make_variant(
        HolzapfelOgden<D, Real>{hp, Real(reference), v_.fibre, v_.sheet, h.active.enabled ? v_.active_tension : nullptr,
                                Real(1), h.active.enabled ? h.active.ramp_time : -1.0},
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
}  // namespace mfsd
