// Pairwise particle contact (theory.md "Contact"; seed 001 section 4.3.1 and
// Listing 1: DEM-type pair interaction with a restitution coefficient
// `restcoef`, a friction coefficient `kfric` and the stiffness multiplier
// `contcoeff`). Two particles i, j of different bodies (or of one body with
// self-contact, reference distance beyond the kernel support) touch when
// their centres are closer than d0 = (dp_i + dp_j) / 2. With
//   r = x_i - x_j, n = r / |r|, overlap delta = d0 - |r| > 0,
//   v = v_i - v_j, v_n = v . n, v_t = v - v_n n,
// the force on i is a linear spring-dashpot with a regularized Coulomb limit:
//   k      = kappa M_ij dp_ij^(D-2)        (M_ij: harmonic mean of the two
//            bodies' moduli M = rho0 c0^2, twice the body's M against a rigid
//            body; kappa = contcoeff; dp_ij = d0)
//   m*     = m_i m_j / (m_i + m_j)         (m_i for a rigid partner)
//   f_n    = max(0, k delta - 2 zeta sqrt(k m*) v_n)
//            zeta = -ln e / sqrt(pi^2 + ln^2 e): an isolated pair leaves with
//            restitution e (linear spring-dashpot, no adhesion)
//   f_t    = -min(mu f_n, c_t |v_t|) v_t / |v_t|,  c_t = 2 zeta_t sqrt(k m*)
//            (Coulomb with a viscous regularization of sticking, zeta_t = 1/2:
//            slow slip stops within about 1 / (2 zeta_t w) = 1 / w)
//   f_i    = f_n n + f_t,  f_j = -f_i.
// A first try capped the tangential force at m* |v_t| / dt (stop the pair's
// slip in one step): with several contacts per particle the caps add up, the
// slip overshoots and flips sign every step, and friction pushed the bodies
// the wrong way (measured on colliding_blocks_2d). The dashpot instead enters
// the time-step bound with the normal spring and dashpot: per particle
//   W^2 = sum_j k / m*,  G = sum_j (c_n + c_t) / m*,  c_n = 2 zeta sqrt(k m*),
// and a leapfrog step of a damped oscillator is stable for
//   dt <= 2 / (sqrt(W^2 + G^2 / 4) + G / 2)   (= 2 (sqrt(1 + z^2) - z) / W, z = G / 2W).
// The expression is odd in (r, v), so the force j computes is exactly -f_i in
// floating point: contact conserves momentum to round-off.
#pragma once
#include "kernels/core/vec.hpp"

namespace mfsd {

// zeta of a linear spring-dashpot pair that leaves with restitution e in (0, 1].
MFSD_HD inline double contact_damping_ratio(double e) {
  if (e >= 1.0) return 0.0;
  const double l = math::log(e);
  return -l / math::sqrt(3.14159265358979323846 * 3.14159265358979323846 + l * l);
}

template <class Real>
struct ContactPairLaw {
  Real damping_ratio;  // zeta
  Real friction;       // mu
  static constexpr Real tangential_damping_ratio = Real(0.5);
};

// What one particle's contacts add to its stability bound.
template <class Real>
struct ContactRates {
  Real omega2;  // sum k / m*
  Real gamma;   // sum (c_n + c_t) / m*
  // 1 / (the largest stable leapfrog step).
  MFSD_HD Real inverse_step() const {
    return Real(0.5) * (math::sqrt(omega2 + Real(0.25) * gamma * gamma) + Real(0.5) * gamma);
  }
};

// Adds a pair's spring and dashpots to `rates` (pairs in contact, and pairs
// about to touch: the step on which a pair first touches must be stable).
template <class Real>
MFSD_HD inline void add_contact_rates(const ContactPairLaw<Real>& law, Real k, Real m_eff, ContactRates<Real>& rates) {
  const Real critical = Real(2) * math::sqrt(k * m_eff);
  const Real zeta_t = law.friction > Real(0) ? ContactPairLaw<Real>::tangential_damping_ratio : Real(0);
  rates.omega2 += k / m_eff;
  rates.gamma += (law.damping_ratio + zeta_t) * critical / m_eff;
}

// The force on i from j (touching: overlap > 0).
template <int D, class Real>
MFSD_HD inline Vec<D, Real> contact_pair_force(const ContactPairLaw<Real>& law, const Vec<D, Real>& r, Real distance,
                                               Real overlap, const Vec<D, Real>& v, Real k, Real m_eff) {
  const Vec<D, Real> n = r / distance;
  const Real vn = dot(v, n);
  const Real critical = Real(2) * math::sqrt(k * m_eff);                                // 2 sqrt(k m*)
  const Real fn = math::max(Real(0), k * overlap - law.damping_ratio * critical * vn);  // normal
  Vec<D, Real> f = n * fn;
  if (law.friction > Real(0)) {
    const Real ct = ContactPairLaw<Real>::tangential_damping_ratio * critical;
    const Vec<D, Real> vt = v - n * vn;
    const Real vt_norm = norm(vt);
    if (vt_norm > Real(0)) {
      const Real ft = math::min(law.friction * fn, ct * vt_norm);  // Coulomb, regularized
      f -= vt * (ft / vt_norm);
    }
  }
  return f;
}

// Harmonic mean of two moduli; a rigid partner (modulus 0 = infinite) gives 2 M.
template <class Real>
MFSD_HD inline Real contact_modulus(Real Mi, Real Mj) {
  if (Mi <= Real(0)) return Real(2) * Mj;
  if (Mj <= Real(0)) return Real(2) * Mi;
  return Real(2) * Mi * Mj / (Mi + Mj);
}

// Reduced mass; a rigid partner has mass 0 (infinite).
template <class Real>
MFSD_HD inline Real contact_reduced_mass(Real mi, Real mj) {
  if (mi <= Real(0)) return mj;
  if (mj <= Real(0)) return mi;
  return mi * mj / (mi + mj);
}

}  // namespace mfsd
