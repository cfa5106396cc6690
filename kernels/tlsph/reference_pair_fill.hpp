// Fills the per-pair reference data of one particle's CSR row, computed in
// double from the reference positions and cast to Real once (see
// reference_pairs.hpp for the quantities).
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
  Vec<D, Real>* e0;
  Real* dwv;
  Real* inv_r0;
  Real* beta;  // may be null

  struct Writer {
    const ReferencePairFillFunctor* f;
    PairIndex p;
    MFSD_HD void operator()(Index j, const Vec<D, double>& d, double r) {
      const double inv_r = 1.0 / r;
      f->neighbor[p] = j;
      f->e0[p] = cast<Real>(d * inv_r);
      f->dwv[p] = Real(double(f->volume[j]) * f->kernel.dW(r));
      f->inv_r0[p] = Real(inv_r);
      if (f->beta) f->beta[p] = Real(f->kernel.W(r) / f->kernel.W(0.0));
      ++p;
    }
  };

  MFSD_HD void operator()(Index i) const {
    Writer w{this, offsets[i]};
    hood.for_each(i, w);
  }
};

}  // namespace mfsd
