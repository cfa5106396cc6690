// Energies of a ULSPH body (accumulated in double): kinetic 1/2 m v^2, the
// elastic energy stored by the hypo-elastic solid, V (p^2/(2K) + tau:tau/(4G))
// with V = m/rho (the linear equation of state and the linear shear law of
// seed 002 eq. 6-7 integrated at small strain), momentum m v and gravity's
// work m g . u since u = 0; the work the Riemann dissipation and the GNOG
// penalty took and the plastic work, accumulated per particle by the step.
#pragma once
#include "kernels/core/mat.hpp"

namespace mfsd::ulsph {

struct EnergySums {
  double kinetic;
  double strain;
  double momentum[3];
  double gravity;
  double dissipated;
  double plastic;
  double shear_mismatch;  // solver.ulsph.energy_audit (kernels/ulsph/step.hpp), else 0
};

struct EnergySumsPlus {
  MFSD_HD EnergySums operator()(const EnergySums& a, const EnergySums& b) const {
    return EnergySums{a.kinetic + b.kinetic,
                      a.strain + b.strain,
                      {a.momentum[0] + b.momentum[0], a.momentum[1] + b.momentum[1], a.momentum[2] + b.momentum[2]},
                      a.gravity + b.gravity,
                      a.dissipated + b.dissipated,
                      a.plastic + b.plastic,
                      a.shear_mismatch + b.shear_mismatch};
  }
};

template <int D, class Real>
struct EnergyFunctor {
  const Vec<D, Real>* velocity;
  const Vec<D, Real>* displacement;
  const Real* mass;
  const Real* density;
  const Real* pressure;
  const Mat<D, Real>* shear_stress;
  const Real* dissipated_work;
  const Real* plastic_work;  // null without J2 bodies
  double bulk_modulus, shear_modulus;
  Vec<D, Real> gravity;
  const Real* shear_mismatch = nullptr;  // solver.ulsph.energy_audit, else null

  MFSD_HD EnergySums operator()(Index i) const {
    const double m = double(mass[i]);
    const double V = m / double(density[i]);
    const double p = double(pressure[i]);
    const double tt = double(ddot(shear_stress[i], shear_stress[i]));
    EnergySums s{0.0,
                 V * (p * p / (2.0 * bulk_modulus) + tt / (4.0 * shear_modulus)),
                 {0.0, 0.0, 0.0},
                 0.0,
                 double(dissipated_work[i]),
                 plastic_work ? double(plastic_work[i]) : 0.0,
                 shear_mismatch ? double(shear_mismatch[i]) : 0.0};
    for (int a = 0; a < D; ++a) {
      const double v = double(velocity[i].v[a]);
      s.kinetic += 0.5 * m * v * v;
      s.momentum[a] = m * v;
      s.gravity += m * double(gravity.v[a]) * double(displacement[i].v[a]);
    }
    return s;
  }
};

}  // namespace mfsd::ulsph
