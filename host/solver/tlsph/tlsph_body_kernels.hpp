// The kernels of one body, specialized at compile time on its material and
// hourglass variant (design.md: "the material model and the hourglass variant
// are template parameters of the stress and force functors"). The solver
// holds one BodyKernels per body behind a host-side virtual interface; the
// kernels themselves contain no run-time switches on the model.
#pragma once
#include <algorithm>
#include <memory>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "host/backend/algorithms.hpp"
#include "host/particles/particle_set.hpp"
#include "host/scene/body_properties.hpp"
#include "host/solver/tlsph/tlsph_views.hpp"
#include "kernels/materials/holzapfel_ogden.hpp"
#include "kernels/materials/j2_plastic.hpp"
#include "kernels/materials/neo_hookean.hpp"
#include "kernels/materials/saint_venant_kirchhoff.hpp"
#include "kernels/tlsph/acceleration.hpp"
#include "kernels/tlsph/acceleration_half.hpp"
#include "kernels/tlsph/observables.hpp"
#include "kernels/tlsph/stress.hpp"

namespace mfsd {

template <class B, int D, class Real>
class BodyKernels {
 public:
  virtual ~BodyKernels() = default;
  // First half step (F, u to t + dt/2) and stress; half_dt = 0 only evaluates.
  virtual void stress(const TlsphViews<D, Real>& v, Real half_dt) const = 0;
  // Acceleration and velocity update v += dt a; dt = 0 only evaluates.
  virtual void acceleration(const TlsphViews<D, Real>& v, Real dt) const = 0;
  virtual void stress_observables(const TlsphViews<D, Real>& v) const = 0;
  virtual EnergySums energy(const TlsphViews<D, Real>& v) const = 0;
  // Phase-field fracture (tlsph_fracture_kernels.hpp); nothing for other bodies:
  // ds/dt to t + dt, then s to t + dt.
  // Before the stress stage of a step whose stress is taken at time t
  // (t + dt/2; 0 at set-up): the active stress's ramp.
  virtual void prepare_step(double /*t*/) {}
  virtual void phase_field_rate(const TlsphViews<D, Real>&, Real /*dt*/) const {}
  virtual void phase_field_half_step(const TlsphViews<D, Real>&, Real /*half_dt*/) const {}
};

struct BodyKernelSettings {
  BodyRange range;
  double density;
  Point3 gravity;
  double zeta;
  bool correction_in_force;
  GenogLimiter genog_limiter;
  GenogForm genog_form;
  double genog_alpha;
  double damping_normal;  // factor rho0 h c0 / 2
  double damping_shear;   // factor rho0 h c / 2 on off-diagonal components
};

template <class B, int D, class Real, class Material, class Hourglass>
class BodyKernelsImpl : public BodyKernels<B, D, Real> {
 public:
  BodyKernelsImpl(const Material& m, const BodyKernelSettings& s) : material_(m), s_(s) {}

  void prepare_step(double t) override {
    if constexpr (IsTimeDependent<Material>::value) material_.set_time(t);  // material_interface.hpp
  }

  void stress(const TlsphViews<D, Real>& v, Real half_dt) const override {
    StressFunctor<D, Real, Material, Hourglass> f{material_,
                                                  {Real(s_.damping_normal), Real(s_.damping_shear)},
                                                  Real(s_.zeta),
                                                  s_.correction_in_force,
                                                  half_dt,
                                                  v.deformation_gradient,
                                                  v.displacement,
                                                  v.velocity,
                                                  v.deformation_rate,
                                                  v.correction,
                                                  v.force_stress,
                                                  v.shear_coefficient,
                                                  v.shear_stress,
                                                  v.inverse_F,
                                                  v.neighbor_record,
                                                  v.plastic_state,
                                                  v.damping_work,
                                                  v.stiffening,
                                                  v.active_work};
    parallel_for<B>(s_.range.begin, s_.range.end, f);
  }

  void acceleration(const TlsphViews<D, Real>& v, Real dt) const override {
    Vec<D, Real> g;
    for (int a = 0; a < D; ++a) g.v[a] = Real(s_.gravity[a]);
    AccelerationFunctor<D, Real, Hourglass> f{
        v.pairs,
        v.force_stress,
        v.shear_coefficient,
        v.shear_stress,
        v.inverse_F,
        v.displacement,
        v.neighbor_record,
        Real(1.0 / s_.density),
        g,
        GenogWeight<Real>{s_.genog_limiter, Real(s_.genog_alpha * D), s_.genog_form},
        dt,
        v.acceleration,
        v.velocity};
    if constexpr (std::is_same<B, Cpu>::value) {
      if (v.half_bandwidth >= 0) {
        auto loop = [&](const auto& half) {
          half_pair_for(Cpu{}, s_.range.begin, s_.range.end, v.half_bandwidth, Vec<D, Real>::zero(), v.acceleration,
                        half_workspace_, half, [&](Index i, const Vec<D, Real>& total) { half.finish(i, total); });
        };
        v.with_half_pairs([&](const auto& pairs) {
          loop(AccelerationHalfFunctor<D, Real, Hourglass, HalfPairReal<decltype(pairs)>>{f, pairs, v.volume});
        });
        return;
      }
    }
    parallel_for<B>(s_.range.begin, s_.range.end, f);
  }

  void stress_observables(const TlsphViews<D, Real>& v) const override {
    parallel_for<B>(
        s_.range.begin, s_.range.end,
        StressObservablesFunctor<D, Real, Material>{material_, v.deformation_gradient, v.plastic_state, v.von_mises,
                                                    v.jacobian, v.von_mises_strain, v.plastic_strain});
  }

  EnergySums energy(const TlsphViews<D, Real>& v) const override {
    return transform_reduce<B>(s_.range.begin, s_.range.end,
                               OwnedOnly<EnergyFunctor<D, Real, Material>>{energy_functor(v), v.ghost}, EnergySums{},
                               EnergySumsPlus{});
  }

 protected:
  // Per-particle energies of the body (kernels/tlsph/observables.hpp).
  EnergyFunctor<D, Real, Material> energy_functor(const TlsphViews<D, Real>& v) const {
    Vec<D, Real> g;
    for (int a = 0; a < D; ++a) g.v[a] = Real(s_.gravity[a]);
    return {material_, v.deformation_gradient, v.plastic_state,  v.velocity, v.displacement,
            v.volume,  v.damping_work,         Real(s_.density), g,          v.active_work};
  }

  Material material_;
  BodyKernelSettings s_;
  mutable std::vector<Vec<D, Real>> half_workspace_;  // the half-pair loop's buffers (CPU)
};

}  // namespace mfsd
