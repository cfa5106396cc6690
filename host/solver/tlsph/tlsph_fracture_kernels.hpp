// The kernels of a fracturing body (seed 001 sections 2.2-2.4): the standard
// TLSPH force of BodyKernelsImpl with hourglass "none", the degraded stress
// (kernels/fracture/fracture_stress.hpp) and the two phase-field passes of a
// step (kernels/fracture/phase_field.hpp).
#pragma once
#include "host/solver/tlsph/tlsph_body_kernels.hpp"
#include "kernels/fracture/fracture_stress.hpp"
#include "kernels/fracture/phase_field.hpp"

namespace mfsd {

template <class B, int D, class Real, class Material>
class FractureBodyKernels final : public BodyKernelsImpl<B, D, Real, Material, HourglassNone> {
  using Base = BodyKernelsImpl<B, D, Real, Material, HourglassNone>;

 public:
  FractureBodyKernels(const Material& m, const BodyKernelSettings& s, const FractureParameters<Real>& f)
      : Base(m, s), fracture_(f) {}

  void stress(const TlsphViews<D, Real>& v, Real half_dt) const override {
    const BodyKernelSettings& s = this->s_;
    FractureStressFunctor<D, Real, Material> f{this->material_,
                                               {Real(s.damping_normal), Real(s.damping_shear)},
                                               fracture_,
                                               s.correction_in_force,
                                               half_dt,
                                               v.deformation_gradient,
                                               v.displacement,
                                               v.velocity,
                                               v.deformation_rate,
                                               v.correction,
                                               v.force_stress,
                                               v.damping_work,
                                               v.phase};
    parallel_for<B>(s.range.begin, s.range.end, f);
  }

  void phase_field_rate(const TlsphViews<D, Real>& v, Real dt) const override {
    parallel_for<B>(this->s_.range.begin, this->s_.range.end,
                    PhaseFieldRateFunctor<D, Real>{v.pairs, v.phase, fracture_, dt});
  }

  void phase_field_half_step(const TlsphViews<D, Real>& v, Real) const override {
    parallel_for<B>(this->s_.range.begin, this->s_.range.end, PhaseFieldHalfStepFunctor<Real>{v.phase});
  }

  void stress_observables(const TlsphViews<D, Real>& v) const override {
    parallel_for<B>(this->s_.range.begin, this->s_.range.end,
                    FractureObservablesFunctor<D, Real, Material>{this->material_, v.deformation_gradient, v.phase.s,
                                                                  v.von_mises, v.jacobian, v.von_mises_strain});
  }

  EnergySums energy(const TlsphViews<D, Real>& v) const override {
    using Energy = FractureEnergyFunctor<D, Real, Material>;
    return transform_reduce<B>(
        this->s_.range.begin, this->s_.range.end,
        OwnedOnly<Energy>{Energy{this->energy_functor(v), v.pairs, v.correction, fracture_, v.phase}, v.ghost},
        EnergySums{}, EnergySumsPlus{});
  }

 private:
  FractureParameters<Real> fracture_;
};

}  // namespace mfsd
