// Fills one particle's CSR row of the ULSPH neighbour list in the current
// configuration (rebuilt every advection step): the PairList data
// (kernels/neighbors/pair_list.hpp) with V_j = m_j / rho_j,
//   grad_ij = V_j dW/dr(r_ij) e_ij,  stretch_ij = V_j dW/dr(r_ij) / r_ij,
// and the row's gradient sum, in Real from the current positions.
#pragma once
#include "kernels/neighbors/cell_list.hpp"
#include "kernels/neighbors/pair_list.hpp"
#include "kernels/sph/wendland_c2.hpp"

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

// x = X + u, the positions the current-configuration search reads.
template <int D, class Real>
struct CurrentPositionFunctor {
  const Vec<D, Real>* reference_position;
  const Vec<D, Real>* displacement;
  Vec<D, Real>* position;
  MFSD_HD void operator()(Index i) const { position[i] = reference_position[i] + displacement[i]; }
};

}  // namespace mfsd::ulsph
