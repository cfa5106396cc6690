// Fills the per-pair reference data of one particle's CSR row, computed in
// double from the reference positions and cast to Real once (see
// reference_pairs.hpp for the quantities), and the per-particle sum of the
// gradients.
#pragma once
#include "kernels/neighbors/cell_list.hpp"
#include "kernels/sph/wendland_c2.hpp"
#include "kernels/tlsph/reference_pairs.hpp"

namespace mfsd {

template <int D, class Real>
struct ReferencePairFillFunctor {
  CellNeighborhood<D> hood;
  WendlandC2<D, double> kernel;
  const Real* volume;  // V0 per particle
  const PairIndex* offsets;
  Index* neighbor;
  Vec<D, Real>* grad;
  Real* stretch;
  Vec<D, Real>* gradient_sum;
  Real* beta;  // may be null

  struct Writer {
    const ReferencePairFillFunctor* f;
    PairIndex p;
    Vec<D, double> sum;
    MFSD_HD void operator()(Index j, const Vec<D, double>& d, double r) {
      const double inv_r = 1.0 / r;
      const double dwv = double(f->volume[j]) * f->kernel.dW(r);  // V0_j dW/dr (< 0)
      f->neighbor[p] = j;
      f->grad[p] = cast<Real>(d * (dwv * inv_r));
      f->stretch[p] = Real(dwv * inv_r);
      if (f->beta) f->beta[p] = Real(f->kernel.W(r) / f->kernel.W(0.0));
      sum += d * (dwv * inv_r);
      ++p;
    }
  };

  MFSD_HD void operator()(Index i) const {
    Writer w{this, offsets[i], Vec<D, double>::zero()};
    hood.for_each(i, w);
    gradient_sum[i] = cast<Real>(w.sum);
  }
};

}  // namespace mfsd
