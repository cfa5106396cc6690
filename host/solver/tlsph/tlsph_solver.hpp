// Total-Lagrangian SPH solver for one backend, precision and dimension.
// A step is the position-based Verlet pipeline of seed 000 eq. 35-38 in three
// passes over the particles plus the clamps, each stage fused so that a
// particle's fields are read once per pass; tlsph_recipe.cpp lists the
// stages with their equations and halo refreshes: stress, force,
// phase_field, contact, loads, boundary, relaxation, deformation_rate,
// time_step.
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
#include "host/solver/tlsph/tlsph_recipe.hpp"
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
  using Base::props, Base::run;

 public:
  TlsphSolver(const Scene& scene, const InitialParticles& init, const SolverOptions& options)
      : Base(scene, init, options) {
    has_fracture_ = has_fracture_body(scene);
    cracks_ = crack_specs(scene);
    this->set_recipe(tlsph_recipe(scene));
    conditions_.compile(scene_);
  }

  void initialize() override;

  // ---- the step (tlsph_recipe.cpp) -----------------------------------------
  void forces(double dt) override {
    const Real half_dt = Real(0.5 * dt);
    run("stress", [&] {
      conditions_.apply_fields(v_, v_.active_tension, time_ + 0.5 * dt, dt, steps_ + 1, results_);
      for (auto& k : bodies_) k->prepare_step(time_ + 0.5 * dt);
      for (auto& k : bodies_) k->stress(v_, half_dt);
    });
    run("force", [&] {
      for (auto& k : bodies_) k->acceleration(v_, Real(dt));
    });
    if (has_fracture_)
      run("phase_field", [&] {
        for (auto& k : bodies_) k->phase_field_rate(v_, Real(dt));
        for (auto& k : bodies_) k->phase_field_half_step(v_, half_dt);
      });
  }

  Kinematics<D, Real> step_kinematics() override { return v_; }

  void advance(double dt) override {
    const Index n = particles_.size();
    const Real half_dt = Real(0.5 * dt);
    if (relaxation_.enabled()) run("relaxation", [&] { relaxation_.apply(v_, time_, dt, results_); });
    run("deformation_rate", [&] {
      RateHalfStepFunctor<D, Real> f{
          v_.pairs,        v_.velocity, v_.correction,       v_.deformation_rate, v_.deformation_gradient,
          v_.displacement, half_dt,     statistics_functor()};
      const StepStatistics<Real> init{Real(0), Real(0), Real(0), Real(0), n};
      if constexpr (std::is_same<B, Cpu>::value) {
        if (v_.half_bandwidth >= 0) {  // the half-pair loop, dF/dt summed in place of the rate
          auto loop = [&](const auto& h) {
            stats_slot_ = results_.template reduce_into<StepStatistics<Real>>([&](StepStatistics<Real>* out) {
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
      stats_slot_ = results_.reduce(Index(0), n, f, init, StepStatisticsCombine<Real>{});
    });
  }

  void finish_step(double) override {
    relaxation_.collect(results_);
    const StepStatistics<Real> stats = results_.get(stats_slot_);
    if (stats.first_bad < particles_.size()) fail(stats.first_bad);
    update_time_step(stats);
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
  void upload_model_fields();

  void bind_views();

  std::unique_ptr<BodyKernels<B, D, Real>> make_body_kernels(size_t b);

  template <class Material>
  std::unique_ptr<BodyKernels<B, D, Real>> make_variant(const Material& m, const BodyKernelSettings& k) {
    switch (scene_.solver.hourglass) {
      case HourglassControl::none:
        return std::make_unique<BodyKernelsImpl<B, D, Real, Material, HourglassNone>>(m, k);
      case HourglassControl::laplacian:
        if constexpr (IsPlastic<Material>::value || !IsIsotropic<Material>::value)
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
  bool has_fracture_ = false;
  ResultSlot<StepStatistics<Real>> stats_slot_;  // between advance() and finish_step()
  std::vector<CrackSpec> cracks_;                // crack-tip outputs
  TlsphViews<D, Real> v_{};
};

}  // namespace mfsd

#include "host/solver/tlsph/tlsph_setup.hpp"
