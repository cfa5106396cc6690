// Dynamic relaxation by operator splitting (seed 003 section 4.2 and 4.3,
// its ref. [68]: Zhu, Zhang and Hu, J. Comput. Phys. 2022): a viscous
// damping of the velocity,
//   m_i dv_i/dt = sum_j 2 eta V_i V_j (dW/dr / r)(r0_ij) (v_i - v_j),
// the pairwise SPH Laplacian of v in the reference configuration (dW/dr < 0,
// so the sum pulls v_i towards its neighbours' velocities), is split off the
// step and integrated implicitly one pair at a time. For the pair (i, j)
// alone the backward-Euler step over tau has the closed form
//   d' = d / (1 + b (1/m_i + 1/m_j)),   b = 2 eta tau V_i V_j |dW/dr| / r,
// with d = v_i - v_j; i and j share the change in the ratio of their masses,
// so the pair's momentum is kept to round-off and its kinetic energy falls by
// (1/2) mu (|d|^2 - |d'|^2), mu = m_i m_j / (m_i + m_j) (unconditionally
// stable: any eta, any tau). Particles whose velocity a
// clamp or a velocity condition sets are held: the relaxation runs after
// those conditions and moves only their free neighbours (relax_against_held;
// such pairs exchange momentum with the holder). One step is a forward sweep of
// every pair (each once, from its lower index) over tau = dt/2, then the same
// pairs in exactly the reverse order over dt/2 (a symmetric Gauss-Seidel
// sweep). The ref.'s random choice applies the whole operator in a step with
// probability p, with eta / p (host/solver/tlsph/tlsph_relaxation.hpp).
//
// Gauss-Seidel updates two particles per pair, so the sweep runs in colours:
// cells of the reference grid with an edge >= the support radius, coloured by
// their coordinates mod 3. The pairs of a cell's particles reach the
// neighbouring cells only, so two cells of one colour touch disjoint
// particles and run in parallel; the particles of a cell run in order.
#pragma once
#include "kernels/core/vec.hpp"
#include "kernels/tlsph/reference_pairs.hpp"

namespace mfsd {

// The pair update when j is held (a clamp or a velocity condition sets its
// velocity): only v_i changes, as if m_j were infinite, d' = d / (1 + b/m_i).
template <int D, class Real>
MFSD_HD inline void relax_against_held(Vec<D, Real>& vi, const Vec<D, Real>& vj, Real mi, Real b) {
  const Real f = b / mi;
  vi = vi - (vi - vj) * (f / (Real(1) + f));
}

// The implicit pair update.
template <int D, class Real>
MFSD_HD inline void relax_pair(Vec<D, Real>& vi, Vec<D, Real>& vj, Real mi, Real mj, Real b) {
  const Real f = b * (Real(1) / mi + Real(1) / mj);
  const Vec<D, Real> change = (vi - vj) * (f / (Real(1) + f));  // d - d'
  const Real total = mi + mj;
  vi = vi - change * (mj / total);
  vj = vj + change * (mi / total);
}

// The energy a relaxed step took from particle i, in the discrete balance of
// the position Verlet step: the relaxation's impulse m (v* - v) times the
// step's mean velocity (v^n + v*)/2, v^n = v - a dt the velocity at the start
// of the step (as the reactions of velocity conditions count their work).
// Without forces this is the kinetic energy removed; where a force keeps
// pushing what the relaxation stops (next to held particles) it is less.
template <int D, class Real>
struct RelaxationWorkFunctor {
  const Vec<D, Real>* before;    // v after the forces and conditions
  const Vec<D, Real>* velocity;  // v* after the sweeps
  const Vec<D, Real>* acceleration;
  const Real* volume;
  Real density;
  Real dt;
  MFSD_HD Real operator()(Index i) const {
    const Vec<D, Real> start = before[i] - acceleration[i] * dt;
    return Real(0.5) * (density * volume[i]) * dot(before[i] - velocity[i], start + velocity[i]);
  }
};

// One colour of a sweep: work item k is a cell (of one body) holding the
// particles item_particle[item_offset[k] .. item_offset[k + 1]).
template <int D, class Real>
struct RelaxationSweepFunctor {
  ReferencePairs<D, Real> pairs;
  Vec<D, Real>* velocity;
  const Real* volume;
  const Index* item_offset;
  const Index* item_particle;
  const Real* item_density;    // rho0 of the item's body
  const Real* item_viscosity;  // eta of the item's body
  const unsigned char* held;   // per particle: velocity set by a clamp or condition (null: none)
  Real step;                   // 2 tau / p: b = 2 eta tau / p V_i V_j |dW/dr| / r (tau = dt/2)
  bool forward;

  MFSD_HD void operator()(Index k) const {
    const Index begin = item_offset[k], end = item_offset[k + 1];
    const Real rho = item_density[k];
    const Real coefficient = item_viscosity[k] * step;
    for (Index q = 0; q < end - begin; ++q) {
      const Index i = item_particle[forward ? begin + q : end - 1 - q];
      const Real mi = rho * volume[i];
      const PairRow r = pairs.row(i);
      for (Index s = 0; s < r.count; ++s) {
        const PairIndex p = r.at(forward ? s : r.count - 1 - s);
        const Index j = pairs.neighbor[p];
        if (j <= i) continue;  // each pair once, from its lower index
        // stretch_ij = V0_j dW/dr / r0 <= 0 (reference_pairs.hpp)
        const Real b = -coefficient * volume[i] * pairs.stretch[p];
        const bool hi = held && held[i], hj = held && held[j];
        if (hi && hj) continue;
        if (hj)
          relax_against_held(velocity[i], velocity[j], mi, b);
        else if (hi)
          relax_against_held(velocity[j], velocity[i], rho * volume[j], b);
        else
          relax_pair(velocity[i], velocity[j], mi, rho * volume[j], b);
      }
    }
  }
};

}  // namespace mfsd
