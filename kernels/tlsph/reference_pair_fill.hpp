// Fills the per-pair reference data of one particle's CSR row, computed in
// double from the reference positions and cast to Real once (see
// reference_pairs.hpp for the quantities), and, over the particle's whole
// neighbourhood, the sum of the gradients and the moment matrix whose inverse
// is the kernel-gradient correction (correction_matrix.hpp). With
// `upper_only` the row holds only the pairs with j > i: the half-pair loop's
// list, built straight from the search (issue 24), while the per-particle sums
// still see every neighbour.
#pragma once
#include "kernels/core/mat.hpp"
#include "kernels/neighbors/cell_list.hpp"
#include "kernels/sph/wendland_c2.hpp"
#include "kernels/tlsph/reference_pairs.hpp"

namespace mfsd {

// P: the stored pair data's type (Real, or float in a double run).
template <int D, class Real, class P = Real>
struct ReferencePairFillFunctor {
  CellNeighborhood<D> hood;
  WendlandC2<D, double> kernel;
  const Real* volume;  // V0 per particle
  const PairIndex* offsets;
  Index* neighbor;
  Vec<D, P>* grad;
  P* stretch;
  Vec<D, Real>* gradient_sum;
  P* beta;               // may be null
  Mat<D, Real>* moment;  // may be null: A_i = sum_j V0_j (X_j - X_i) (x) grad0_i W_ij
  bool upper_only;       // store only the pairs with j > i

  struct Writer {
    const ReferencePairFillFunctor* f;
    Index i;
    PairIndex p;
    Vec<D, double> sum;
    Mat<D, double> A;
    MFSD_HD void operator()(Index j, const Vec<D, double>& d, double r) {
      const double inv_r = 1.0 / r;
      const double dwv = double(f->volume[j]) * f->kernel.dW(r);  // V0_j dW/dr (< 0)
      const double s = dwv * inv_r;
      sum += d * s;
      // seed 000 eq. 21: V0_j (X_j - X_i) (x) grad0_i W_ij = -s d (x) d, d = X_i - X_j
      for (int a = 0; a < D; ++a)
        for (int b = 0; b < D; ++b) A.m[a][b] -= s * d.v[a] * d.v[b];
      if (f->upper_only && j < i) return;
      f->neighbor[p] = j;
      f->grad[p] = cast<P>(d * s);
      f->stretch[p] = P(s);
      if (f->beta) f->beta[p] = P(f->kernel.W(r) / f->kernel.W(0.0));
      ++p;
    }
  };

  MFSD_HD void operator()(Index i) const {
    Writer w{this, i, offsets[i], Vec<D, double>::zero(), Mat<D, double>::zero()};
    hood.for_each(i, w);
    gradient_sum[i] = cast<Real>(w.sum);
    if (moment) moment[i] = cast<Real>(w.A);
  }
};

}  // namespace mfsd
