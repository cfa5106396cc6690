// Fills one particle's CSR row of the ULSPH neighbour list in the current
// configuration (rebuilt every advection step): the PairList data
// (kernels/neighbors/pair_list.hpp) with V_j = m_j / rho_j,
//   grad_ij = V_j dW/dr(r_ij) e_ij,  stretch_ij = V_j dW/dr(r_ij) / r_ij,
// and the row's gradient sum, in Real from the current positions.
#pragma once
#include "kernels/core/mat.hpp"
#include "kernels/neighbors/cell_list.hpp"
#include "kernels/neighbors/pair_list.hpp"
#include "kernels/sph/wendland_c2.hpp"
#include "kernels/ulsph/continuity.hpp"

namespace mfsd::ulsph {

template <int D, class Real>
struct CurrentPairFillFunctor {
  CellNeighborhood<D, Real> hood;
  WendlandC2<D, Real> kernel;
  const Real* mass;
  const Real* density;
  const PairIndex* offsets;
  Index* neighbor;
  Vec<D, Real>* grad;
  Real* stretch;
  Vec<D, Real>* gradient_sum;

  struct Writer {
    const CurrentPairFillFunctor* f;
    PairIndex p;
    Vec<D, Real> sum;
    MFSD_HD void operator()(Index j, const Vec<D, Real>& d, Real r) {
      const Real dwv_r = f->mass[j] / f->density[j] * f->kernel.dW(r) / r;  // V_j dW/dr / r (< 0)
      f->neighbor[p] = j;
      f->grad[p] = d * dwv_r;
      f->stretch[p] = dwv_r;
      sum += d * dwv_r;
      ++p;
    }
  };

  MFSD_HD void operator()(Index i) const {
    Writer w{this, offsets[i], Vec<D, Real>::zero()};
    hood.for_each(i, w);
    gradient_sum[i] = w.sum;
  }
};

// x = X + u and V = m / rho per particle: what PairRefreshFunctor reads, one
// gather each per pair instead of four and a division.
template <int D, class Real>
struct PositionVolumeFunctor {
  const Vec<D, Real>* reference_position;
  const Vec<D, Real>* displacement;
  const Real* mass;
  const Real* density;
  Vec<D, Real>* position;
  Real* volume;
  MFSD_HD void operator()(Index i) const {
    position[i] = reference_position[i] + displacement[i];
    volume[i] = mass[i] / density[i];
  }
};

// The first position half step u += dt/2 v (seed 002 eq. 30) with x and V
// of the step's start for the refresh that follows (one pass).
template <int D, class Real>
struct DisplacementHalfStepPositionVolumeFunctor {
  const Vec<D, Real>* velocity;
  Vec<D, Real>* displacement;
  Real half_dt;
  PositionVolumeFunctor<D, Real> current;
  MFSD_HD void operator()(Index i) const {
    displacement[i] += velocity[i] * half_dt;  // seed 002 eq. 30
    current(i);
  }
};

// Between two searches of a dual-criteria step: the pair data of the
// existing pairs of row i formed again at the current positions (x = X + u)
// and volumes, and B_i from them (velocity_gradient.hpp); a pair that has
// left the support gets dW = 0. Pair directions then follow a turning body
// instead of lagging it by the advection step (docs/theory.md, "ULSPH").
template <int D, class Real>
struct PairRefreshFunctor {
  const Vec<D, Real>* position;  // x = X + u (PositionVolumeFunctor)
  const Real* volume;            // V = m / rho
  WendlandC2<D, Real> kernel;
  const PairIndex* offsets;
  const Index* neighbor;
  Vec<D, Real>* grad;
  Real* stretch;
  Vec<D, Real>* gradient_sum;

  // Row i again; returns the moment matrix A_i = -sum_j grad (x) grad / stretch
  // of the row just formed (velocity_gradient.hpp), in the same loop, and
  // with a velocity field also sum_j v_j . grad_ij (continuity.hpp) in
  // *velocity_sum.
  MFSD_HD Mat<D, Real> refresh(Index i, const Vec<D, Real>* velocity = nullptr, Real* velocity_sum = nullptr) const {
    const Vec<D, Real> xi = position[i];
    Vec<D, Real> sum = Vec<D, Real>::zero();
    Mat<D, Real> A = Mat<D, Real>::zero();
    Real vsum = Real(0);
    for (PairIndex k = offsets[i]; k < offsets[i + 1]; ++k) {
      const Index j = neighbor[k];
      const Index ahead = neighbor[k + kPairPrefetchDistance];
      prefetch(&position[ahead]);
      if (velocity) prefetch(&velocity[ahead]);
      const Vec<D, Real> d = xi - position[j];
      const Real r = norm(d);
      const Real dwv_r = r > Real(0) ? volume[j] * kernel.dW_over_r(r) : Real(0);  // V_j dW/dr / r
      const Vec<D, Real> g = d * dwv_r;
      grad[k] = g;
      stretch[k] = dwv_r;
      sum += g;
      if (velocity) vsum += dot(velocity[j], g);
      for (int a = 0; a < D; ++a)
        for (int b = 0; b < D; ++b) A.m[a][b] -= d.v[a] * g.v[b];  // seed 002 eq. 21: -(x_i - x_j) (x) grad
    }
    gradient_sum[i] = sum;
    if (velocity_sum) *velocity_sum = vsum;
    return A;
  }

  MFSD_HD void operator()(Index i) const { refresh(i); }
};

// The first half step of a dual-criteria step between searches, fused per
// row: the pair data of row i at the half-step positions, B_i from them
// (B = I where det A_i < min_determinant, as CorrectionMatrixFunctor), and
// rho_i through half a step (continuity, in the same loop over the row).
// The volumes V_j = m_j / rho_j it reads were taken before the pass
// (PositionVolumeFunctor), so rho is updated in place.
template <int D, class Real>
struct RefreshHalfStepFunctor {
  PairRefreshFunctor<D, Real> pairs;
  const Vec<D, Real>* velocity;
  Real* density;
  Real* pair_density;  // rho_i of the pair data (the forces divide by it)
  Mat<D, Real>* correction;
  Real min_determinant;
  Real half_dt;

  MFSD_HD void operator()(Index i) const {
    Real vsum;  // sum_j v_j . grad_ij
    const Mat<D, Real> A = pairs.refresh(i, velocity, &vsum);
    const Real d = det(A);
    correction[i] = d >= min_determinant ? inverse(A) : Mat<D, Real>::identity();  // seed 002 eq. 21
    const Real rho = density[i];
    pair_density[i] = rho;
    // seed 002 eq. 14 (continuity.hpp: rho_i (v_i . G_i - sum_j v_j . grad_ij))
    density[i] = rho + half_dt * rho * (dot(velocity[i], pairs.gradient_sum[i]) - vsum);
  }
};

// x = X + u, the positions the current-configuration search reads.
template <int D, class Real>
struct CurrentPositionFunctor {
  const Vec<D, Real>* reference_position;
  const Vec<D, Real>* displacement;
  Vec<D, Real>* position;
  MFSD_HD void operator()(Index i) const { position[i] = reference_position[i] + displacement[i]; }
};

}  // namespace mfsd::ulsph
