// Output quantities: von Mises stress, J, energies.
#pragma once
#include "kernels/core/mat.hpp"

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

template <int D, class Real, class Material>
struct StressObservablesFunctor {
  Material material;
  const Mat<D, Real>* deformation_gradient;
  Real* von_mises_stress;
  Real* jacobian;

  MFSD_HD void operator()(Index i) const {
    const Mat<D, Real> F = deformation_gradient[i];
    const Real J = det(F);
    von_mises_stress[i] = von_mises(material.kirchhoff(F) * (Real(1) / J));
    jacobian[i] = J;
  }
};

// Kinetic and strain energy and linear momentum of a set of particles.
struct EnergySums {
  double kinetic;
  double strain;
  double momentum[3];
};

struct EnergySumsPlus {
  MFSD_HD EnergySums operator()(const EnergySums& a, const EnergySums& b) const {
    return EnergySums{a.kinetic + b.kinetic,
                      a.strain + b.strain,
                      {a.momentum[0] + b.momentum[0], a.momentum[1] + b.momentum[1], a.momentum[2] + b.momentum[2]}};
  }
};

// Kinetic 1/2 m v^2, strain energy V0 W(F) and momentum m v of particle i (accumulated in double).
template <int D, class Real, class Material>
struct EnergyFunctor {
  Material material;
  const Mat<D, Real>* deformation_gradient;
  const Vec<D, Real>* velocity;
  const Real* volume;
  Real density;

  MFSD_HD EnergySums operator()(Index i) const {
    const double V0 = double(volume[i]);
    const double m = double(density) * V0;
    const Vec<D, Real> v = velocity[i];
    EnergySums s{0.5 * m * double(squared_norm(v)),
                 V0 * double(material.strain_energy_density(deformation_gradient[i])),
                 {0.0, 0.0, 0.0}};
    for (int a = 0; a < D; ++a) s.momentum[a] = m * double(v.v[a]);
    return s;
  }
};

}  // namespace mfsd
