// Hyperbolic phase-field equation of brittle fracture (seed 001 eq. 6-9,
// 61-62), per particle of a fracturing body, advanced with the motion's
// position-based Verlet step (seed 000 eq. 35-37):
//   s_{n+1/2} = s_n + dt/2 s'_n                  (stress stage, fracture_stress.hpp)
//   eq. 61 with M at its bound (eq. 9) reads s'' + 2 w s' + w^2 s = f, with
//     w = c/(2 eps0) sqrt(1 + 4 eps0 H/Gc),  f = c^2 lap(s) + c^2/(4 eps0^2):
//   a critically damped oscillator about s_eq = f/w^2, driven by the
//   Laplacian. Its local part is integrated exactly over the step with the
//   Laplacian of s_{n+1/2} held fixed (PhaseFieldRateFunctor), from s_n, s'_n
//   to s_{n+1}, s'_{n+1}; s_{n+1} is stored once every particle has read the
//   half-step field (PhaseFieldHalfStepFunctor).
// Why not the paper's explicit update: w dt = (c dt/(2 eps0)) sqrt(1 + 4 eps0 H/Gc)
// grows without bound with H at a crack tip, and the explicit update is stable
// only for w dt below about 1 (docs/theory.md, "Phase-field fracture": at
// dp = 0.5 mm, CFL 0.6 the crack-branching plate's energy balance drifts by
// 2e4 J against 6 J of work). The Laplacian, a wave of speed c, stays
// explicit: the time step uses max(c0, c).
// Laplacian (eq. 62) on the reference pairs, with r0_ij . grad0_i W_ij V0_j / r0^2
// = stretch_ij (reference_pairs.hpp):  lap(s)_i = 2 sum_j (s_i - s_j) stretch_ij.
// s stays in [lower_i, 1]: lower_i is 0, or the scene's restrict_phase_field
// bound (seed 001 "restrictphi"); at a bound the rate is set to zero.
#pragma once
#include "kernels/core/mat.hpp"
#include "kernels/tlsph/reference_pairs.hpp"

namespace mfsd {

template <class Real>
struct FractureParameters {
  Real Gc;       // critical energy release rate [J/m^2]
  Real eps0;     // length scale [m]
  Real speed;    // c, the phase field's speed limit [m/s]
  Real s_limit;  // s_l: at or below it F is frozen to I (seed 001 eq. 63)
};

// The per-particle phase-field state (fields registered for fracturing bodies).
template <class Real>
struct PhaseFieldViews {
  Real* s;               // phase field (1 intact, 0 broken)
  Real* rate;            // ds/dt
  Real* history;         // H = max over time of psi_plus (eq. 8)
  Real* tensile_energy;  // psi_plus at the step's half step (0 where frozen)
  Real* released;        // elastic energy released by the degradation, per V0 (dissipation)
  const Real* lower;     // restrict_phase_field lower bound, null = 0
  Real* next;            // s_{n+1}, between the two passes of a step
};

// Eq. 61 as s'' + 2 w s' + w^2 s = f (M at the bound of eq. 9).
template <class Real>
struct PhaseFieldOscillator {
  Real omega, forcing;
};
template <class Real>
MFSD_HD inline PhaseFieldOscillator<Real> phase_field_oscillator(const FractureParameters<Real>& f, Real H, Real lap) {
  const Real half_inv = Real(0.5) / f.eps0;  // 1/(2 eps0)
  const Real c2 = f.speed * f.speed;
  PhaseFieldOscillator<Real> r;
  r.omega = f.speed * half_inv * math::sqrt(Real(1) + Real(4) * f.eps0 * H / f.Gc);
  r.forcing = c2 * (lap + half_inv * half_inv);
  return r;
}

// Laplacian of s at i (eq. 62).
template <int D, class Real>
MFSD_HD inline Real phase_field_laplacian(const ReferencePairs<D, Real>& pairs, const Real* s, Index i) {
  const Real si = s[i];
  Real sum = Real(0);
  const PairRow r = pairs.row(i);
  for (Index k = 0; k < r.count; ++k) {
    const PairIndex q = r.at(k);
    sum += (si - s[pairs.neighbor[q]]) * pairs.stretch[q];
  }
  return Real(2) * sum;
}

// s_{n+1}, s'_{n+1} from s_n = s_{n+1/2} - dt/2 s'_n and s'_n, exactly for the
// local oscillator: with y = s - s_eq, y(t) = (y0 + (s'_0 + w y0) t) e^{-w t}.
// Reads the neighbours' s_{n+1/2}; writes only its own rate and next.
template <int D, class Real>
struct PhaseFieldRateFunctor {
  ReferencePairs<D, Real> pairs;
  PhaseFieldViews<Real> p;
  FractureParameters<Real> f;
  Real dt;
  MFSD_HD void operator()(Index i) const {
    const PhaseFieldOscillator<Real> q = phase_field_oscillator(f, p.history[i], phase_field_laplacian(pairs, p.s, i));
    const Real w = q.omega;
    const Real v0 = p.rate[i];
    const Real s_eq = q.forcing / (w * w);
    const Real y0 = p.s[i] - Real(0.5) * dt * v0 - s_eq;
    const Real a = v0 + w * y0;
    const Real e = math::exp(-w * dt);
    p.next[i] = s_eq + (y0 + a * dt) * e;
    p.rate[i] = (v0 - w * a * dt) * e;
  }
};

// s to the full step, kept in [lower, 1]; the release of the second half.
template <class Real>
struct PhaseFieldHalfStepFunctor {
  PhaseFieldViews<Real> p;
  MFSD_HD void operator()(Index i) const {
    const Real s_half = math::min(math::max(p.s[i], Real(0)), Real(1));  // as the stress stage used it
    Real s = p.next[i];
    const Real lo = p.lower ? p.lower[i] : Real(0);
    if (s < lo || s > Real(1)) {
      s = math::min(math::max(s, lo), Real(1));
      p.rate[i] = Real(0);
    }
    p.s[i] = s;
    p.released[i] += p.tensile_energy[i] * (s_half * s_half - s * s);
  }
};

// Crack surface energy density Gc [ (1 - s)^2/(4 eps0) + eps0 |grad s|^2 ]
// (the functional whose variation gives eq. 6), grad s with the corrected
// SPH gradient sum_j (s_j - s_i) grad_ij B0_i.
template <int D, class Real>
MFSD_HD inline Real crack_surface_density(const ReferencePairs<D, Real>& pairs, const Mat<D, Real>& B0, const Real* s,
                                          const FractureParameters<Real>& f, Index i) {
  Vec<D, Real> g = Vec<D, Real>::zero();
  const Real si = s[i];
  const PairRow r = pairs.row(i);
  for (Index k = 0; k < r.count; ++k) {
    const PairIndex q = r.at(k);
    g += pairs.grad[q] * (s[pairs.neighbor[q]] - si);
  }
  Vec<D, Real> grad_s;  // B0^T g = B0 g (B0 symmetric)
  grad_s = B0 * g;
  const Real one = Real(1) - si;
  return f.Gc * (one * one / (Real(4) * f.eps0) + f.eps0 * squared_norm(grad_s));
}

}  // namespace mfsd
