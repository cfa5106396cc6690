// The Kronecker nodes of RKPM operators across the ranks of a distributed
// run (docs/distributed.md, "RKPM"). An operator names the singular node
// that sits at one of its points (rkpm.md 1.7) by its local index, which
// means nothing on another rank: before a ghost refresh the owned operators
// name it by global index, and after it every operator by the local index
// here, or by kKroneckerElsewhere where that node is not held (then it is no
// partner of any owned row either: Psi_I(x_p) = 0 for every held I).
#pragma once
#include "kernels/rkpm/node_operator.hpp"

namespace mfsd::rkpm {

constexpr Index kKroneckerElsewhere = -2;

template <int D, class Real>
struct KroneckerToGlobal {
  NodeOperator<D, Real>* op;
  const Index* global_of_local;
  MFSD_HD void operator()(Index L) const {
    for (int p = 0; p < NodeOperator<D, Real>::kPoints; ++p)
      if (op[L].kronecker[p] >= 0) op[L].kronecker[p] = global_of_local[op[L].kronecker[p]];
  }
};

// `sorted_global` ascending, `local_of_sorted` the local index of each.
template <int D, class Real>
struct KroneckerToLocal {
  NodeOperator<D, Real>* op;
  const Index* sorted_global;
  const Index* local_of_sorted;
  Index held;
  MFSD_HD void operator()(Index L) const {
    for (int p = 0; p < NodeOperator<D, Real>::kPoints; ++p) {
      const Index g = op[L].kronecker[p];
      if (g < 0) continue;
      Index lo = 0, hi = held;  // the first sorted_global >= g
      while (lo < hi) {
        const Index mid = lo + (hi - lo) / 2;
        if (sorted_global[mid] < g)
          lo = mid + 1;
        else
          hi = mid;
      }
      op[L].kronecker[p] = lo < held && sorted_global[lo] == g ? local_of_sorted[lo] : kKroneckerElsewhere;
    }
  }
};

}  // namespace mfsd::rkpm
