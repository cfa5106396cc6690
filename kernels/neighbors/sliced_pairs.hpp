// The sliced pair layout (sliced ELLPACK; issue 24 item 3): the rows of a
// slice of `height` consecutive particles are stored interleaved, the k-th
// pair of row i at slice_start[i / height] + k * height + i % height, each
// slice as wide as its longest row (shorter rows leave padding that no loop
// reads). A pair loop reads its row through PairList::row (pair_list.hpp),
// so the same physics functors run on compressed or sliced rows, and with
// the same pair order in a row both give the same sums bit for bit. On the
// GPU, one thread per row and a warp per slice make the threads of a warp
// read adjacent pair data at each k (coalesced), where compressed rows have
// them a row length apart. Built from compressed rows by the functors below.
#pragma once
#include "kernels/neighbors/pair_list.hpp"

namespace mfsd {

constexpr Index kSliceHeight = 32;  // the rows of a slice: a CUDA warp

// size[s] = height x the longest row of slice s.
struct SliceSizeFunctor {
  const PairIndex* offsets;  // compressed rows, n + 1
  Index n, height;
  PairIndex* size;
  MFSD_HD void operator()(Index s) const {
    Index width = 0;
    const Index end = (s + 1) * height < n ? (s + 1) * height : n;
    for (Index i = s * height; i < end; ++i) {
      const Index c = Index(offsets[i + 1] - offsets[i]);
      width = c > width ? c : width;
    }
    size[s] = PairIndex(width) * height;
  }
};

// Row i's first pair and count in the sliced layout, from the slices' starts.
struct SlicedRowFunctor {
  const PairIndex* offsets;
  const PairIndex* slice_start;
  Index height;
  PairIndex* first;
  Index* count;
  MFSD_HD void operator()(Index i) const {
    first[i] = slice_start[i / height] + PairIndex(i % height);
    count[i] = Index(offsets[i + 1] - offsets[i]);
  }
};

// Copies row i's pair data from compressed into sliced order.
template <int D, class Real>
struct SlicedScatterFunctor {
  const PairIndex* offsets;
  const PairIndex* first;
  Index height;
  const Index* neighbor_in;
  const Vec<D, Real>* grad_in;
  const Real* stretch_in;
  const Real* beta_in;  // may be null
  Index* neighbor;
  Vec<D, Real>* grad;
  Real* stretch;
  Real* beta;
  MFSD_HD void operator()(Index i) const {
    const PairIndex from = offsets[i];
    const Index count = Index(offsets[i + 1] - from);
    for (Index k = 0; k < count; ++k) {
      const PairIndex to = first[i] + PairIndex(k) * height;
      neighbor[to] = neighbor_in[from + k];
      grad[to] = grad_in[from + k];
      stretch[to] = stretch_in[from + k];
      if (beta_in) beta[to] = beta_in[from + k];
    }
  }
};

}  // namespace mfsd
