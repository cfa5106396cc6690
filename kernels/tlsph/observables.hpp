// Output quantities: von Mises stress, J, energies.
#pragma once
#include "kernels/core/mat.hpp"
#include "kernels/core/owned_only.hpp"
#include "kernels/materials/j2_plastic.hpp"
#include "kernels/materials/material_interface.hpp"

namespace mfsd {

// Von Mises stress of the Cauchy stress sigma = tau / J. 3-D:
// sqrt(3/2 dev(sigma):dev(sigma)). 2-D: the plane-stress formula
// sqrt(s_xx^2 + s_yy^2 - s_xx s_yy + 3 s_xy^2), as the authors' code reports
// it (formulations.md section 1).
template <class Real>
MFSD_HD inline Real von_mises(const Mat<3, Real>& sigma) {
  const Mat<3, Real> s = deviator(sigma);
  return math::sqrt(Real(1.5) * ddot(s, s));
}
template <class Real>
MFSD_HD inline Real von_mises(const Mat<2, Real>& sigma) {
  const Real xx = sigma.m[0][0], yy = sigma.m[1][1], xy = Real(0.5) * (sigma.m[0][1] + sigma.m[1][0]);
  return math::sqrt(math::max(xx * xx + yy * yy - xx * yy + Real(3) * xy * xy, Real(0)));
}

// Von Mises strain as the authors' code reports it: |dev E| of the
// Green-Lagrange strain E = (F^T F - I)/2, with E_zz = 0 in 2-D, i.e.
// sqrt(1/3 sum_(a<b) (E_aa - E_bb)^2 + 2 sum_(a<b) E_ab^2).
template <int D, class Real>
MFSD_HD inline Real von_mises_strain(const Mat<D, Real>& F) {
  Mat<3, Real> E = Mat<3, Real>::zero();
  const Mat<D, Real> C = transpose(F) * F;
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) E.m[a][b] = Real(0.5) * (C.m[a][b] - (a == b ? Real(1) : Real(0)));
  return frobenius_norm(deviator(E));
}

template <int D, class Real, class Material>
MFSD_HD inline Mat<D, Real> kirchhoff_of(const Material& m, const Mat<D, Real>& F, const J2State<Real>* state,
                                         Index i) {
  if constexpr (IsPlastic<Material>::value)
    return m.kirchhoff(F, state[i]);
  else
    return m.at(i).kirchhoff(F);  // material_interface.hpp
}

template <int D, class Real, class Material>
MFSD_HD inline Real strain_energy_of(const Material& m, const Mat<D, Real>& F, const J2State<Real>* state, Index i) {
  if constexpr (IsPlastic<Material>::value)
    return m.strain_energy_density(F, state[i]);
  else
    return m.at(i).strain_energy_density(F);
}

template <int D, class Real, class Material>
struct StressObservablesFunctor {
  Material material;
  const Mat<D, Real>* deformation_gradient;
  const J2State<Real>* plastic_state;  // plastic materials, else null
  Real* von_mises_stress;
  Real* jacobian;
  Real* strain;          // von Mises strain
  Real* plastic_strain;  // null unless some body is plastic

  MFSD_HD void operator()(Index i) const {
    const Mat<D, Real> F = deformation_gradient[i];
    const Real J = det(F);
    von_mises_stress[i] = von_mises(kirchhoff_of(material, F, plastic_state, i) * (Real(1) / J));
    jacobian[i] = J;
    strain[i] = von_mises_strain(F);
    if (plastic_strain) {
      if constexpr (IsPlastic<Material>::value)
        plastic_strain[i] = plastic_state[i].alpha;
      else
        plastic_strain[i] = Real(0);
    }
  }
};

// Kinetic and strain energy and linear momentum of a set of particles.
struct EnergySums {
  double kinetic;
  double strain;
  double plastic;  // plastic work
  double momentum[3];
  double gravity;         // sum m g . u: the work of a uniform gravity since u = 0 (a state function)
  double damping;         // work taken by the Kelvin-Voigt damping
  double fracture = 0.0;  // elastic energy released by phase-field degradation (fracture_stress.hpp)
  double surface = 0.0;   // crack surface energy Gc int (1-s)^2/(4 eps0) + eps0 |grad s|^2
  double active = 0.0;    // work done on the body by its active stress (Holzapfel-Ogden muscle)
};

struct EnergySumsPlus {
  MFSD_HD EnergySums operator()(const EnergySums& a, const EnergySums& b) const {
    return EnergySums{a.kinetic + b.kinetic,
                      a.strain + b.strain,
                      a.plastic + b.plastic,
                      {a.momentum[0] + b.momentum[0], a.momentum[1] + b.momentum[1], a.momentum[2] + b.momentum[2]},
                      a.gravity + b.gravity,
                      a.damping + b.damping,
                      a.fracture + b.fracture,
                      a.surface + b.surface,
                      a.active + b.active};
  }
};

// Kinetic 1/2 m v^2, strain energy V0 W(F), plastic work, momentum m v,
// gravity's work m g . u and the damping's work of particle i (accumulated in
// double).
template <int D, class Real, class Material>
struct EnergyFunctor {
  Material material;
  const Mat<D, Real>* deformation_gradient;
  const J2State<Real>* plastic_state;  // plastic materials, else null
  const Vec<D, Real>* velocity;
  const Vec<D, Real>* displacement;
  const Real* volume;
  const Real* damping_work;  // null without damping
  Real density;
  Vec<D, Real> gravity;
  const Real* active_work = nullptr;  // per V0, Holzapfel-Ogden bodies with active stress, else null

  MFSD_HD EnergySums operator()(Index i) const {
    const double V0 = double(volume[i]);
    const double m = double(density) * V0;
    const Vec<D, Real> v = velocity[i];
    double plastic = 0.0;
    if constexpr (IsPlastic<Material>::value) plastic = V0 * double(plastic_state[i].work);
    EnergySums s{0.5 * m * double(squared_norm(v)),
                 V0 * double(strain_energy_of(material, deformation_gradient[i], plastic_state, i)),
                 plastic,
                 {0.0, 0.0, 0.0},
                 0.0,
                 damping_work ? V0 * double(damping_work[i]) : 0.0,
                 0.0,
                 0.0,
                 active_work ? V0 * double(active_work[i]) : 0.0};
    for (int a = 0; a < D; ++a) {
      s.momentum[a] = m * double(v.v[a]);
      s.gravity += m * double(gravity.v[a]) * double(displacement[i].v[a]);
    }
    return s;
  }
};

}  // namespace mfsd
