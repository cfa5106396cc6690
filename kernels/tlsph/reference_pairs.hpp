// The total-Lagrangian reference neighbour list: a PairList
// (kernels/neighbors/pair_list.hpp) built once in the reference
// configuration, so that grad_ij = V0_j grad0_i W_ij and
// stretch_ij = V0_j dW/dr(r0_ij) / r0_ij, and with the displacements
// V0_j dW r_ij/r0_ij = grad + (u_i - u_j) stretch and
// V0_j (X_j - X_i) = -grad / stretch.
#pragma once
#include "kernels/neighbors/pair_list.hpp"

namespace mfsd {

template <int D, class Real>
using ReferencePairs = PairList<D, Real>;

}  // namespace mfsd
