// The interface of a TLSPH material: what the stress stage
// (kernels/tlsph/stress.hpp), the observables and the energies
// (kernels/tlsph/observables.hpp) read, so that a new material is added in
// its own header with no special case in the kernels.
//   material.at(i)               the material at particle i (a uniform
//                                material returns itself)
// and what at(i) returns:
//   kirchhoff(F)                 tau (hourglass form "none")
//   genog_split(F)               {tau_r, c}: tau = tau_r + c F F^T, the
//                                GENOG split of seed 000 eq. 25
//   strain_energy_density(F)     W per reference volume
// optional, detected below (a material without them has none):
//   stiffening(F)                the longitudinal modulus over its value at
//                                F = I (the time step's wave speed grows with it)
//   active_work(F, L, dt)        the work of an active stress over dt per
//                                reference volume, tau_a : L dt
//   material.set_time(t)         a time-dependent material (host, before a step)
// Plastic materials (IsPlastic, j2_plastic.hpp) carry a state and are read
// through it. The Laplacian form (seed 003 eq. 27-28) needs an isotropic
// material's volumetric_kirchhoff(J) and shear_coefficient(J) (IsIsotropic).
#pragma once
#include <type_traits>

#include "kernels/core/mat.hpp"

namespace mfsd {

// tau = remainder + coefficient F F^T.
template <int D, class Real>
struct KirchhoffSplit {
  Mat<D, Real> remainder;
  Real coefficient;
};

// The split of an isotropic material whose tau is tau_vol(J) I + c dev(b):
// c = shear_coefficient(J), tau_r = (tau_vol - c tr(b)/d) I (seed 000 eq. 25).
template <int D, class Real, class Material>
MFSD_HD inline KirchhoffSplit<D, Real> isotropic_genog_split(const Material& m, const Mat<D, Real>& F) {
  const Real J = det(F);
  const Real c = m.shear_coefficient(J);
  const Real tr_b = ddot(F, F);  // tr(F F^T)
  return {Mat<D, Real>::diagonal(m.volumetric_kirchhoff(J) - c * tr_b / Real(D)), c};
}

template <class Point, class = void>
struct Stiffens : std::false_type {};
template <class Point>
struct Stiffens<Point, std::void_t<decltype(&Point::stiffening)>> : std::true_type {};

template <class Point, class = void>
struct HasActiveWork : std::false_type {};
template <class Point>
struct HasActiveWork<Point, std::void_t<decltype(&Point::active_work)>> : std::true_type {};

template <class Material, class = void>
struct IsTimeDependent : std::false_type {};
template <class Material>
struct IsTimeDependent<Material, std::void_t<decltype(&Material::set_time)>> : std::true_type {};

template <class Material, class = void>
struct IsIsotropic : std::false_type {};
template <class Material>
struct IsIsotropic<Material, std::void_t<decltype(&Material::volumetric_kirchhoff)>> : std::true_type {};

}  // namespace mfsd
