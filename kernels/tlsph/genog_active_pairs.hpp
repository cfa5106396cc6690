// The pairs of one particle that genog's first pass found active, so that
// its second pass (phi_ij (S_i + S_j) h_ij, seed 000 eq. 32) visits those
// instead of every pair (issue 24, item 2; kernels/tlsph/acceleration.hpp).
// The record keeps each pair with |h|^2 > (1 - margin) 0.05^2 |g|^2: a test
// looser than the second pass's own |h|^2 > 0.05^2 |g|^2 by far more than the
// rounding difference between the two passes' arithmetic for h (about 40
// epsilon relative where |h| = 0.05 |g|: 5e-15 in double, 2e-6 in float,
// against the margin 1e-3), so every pair the second pass accepts is in it
// and the sums are those of a second pass over all pairs, bit for bit. More
// than `capacity` recorded pairs: overflowed, and the second pass visits all.
#pragma once
#include "kernels/core/math.hpp"
#include "kernels/neighbors/pair_list.hpp"

namespace mfsd {

template <class Real>
struct GenogActivePairs {
  static constexpr int capacity = 32;
  static constexpr Real loose_threshold2 = Real(0.05 * 0.05 * (1.0 - 1e-3));

  int count = 0;
  Index offset[capacity + 1];  // pair index - the row's first, in ascending order; [capacity]: scratch

  // Pair k of the row with |h|^2 = hh and |g|^2 = gg: stored without a branch
  // (a pair that fails is overwritten by the next; once full, every store
  // goes to the scratch slot).
  MFSD_HD void add(PairIndex k, Real hh, Real gg) {
    offset[count < capacity ? count : capacity] = Index(k);
    count += hh > loose_threshold2 * gg ? 1 : 0;
  }

  MFSD_HD bool overflowed() const { return count > capacity; }
};

}  // namespace mfsd
