// The pairs of one particle that genog's first pass found active, so that
// its second pass (phi_ij (S_i + S_j) h_ij, seed 000 eq. 32) visits those
// instead of every pair (issue 24, item 2; kernels/tlsph/acceleration.hpp).
// The first pass stores each pair's excess |h|^2 - t |g|^2 with
// t = (1 - 1e-3) 0.05^2 (one store per pair, off its dependency chains); the
// second pass, taken only by a particle with a positive excess, compacts the
// positive ones and visits them. The test is looser than the second pass's
// own |h|^2 > 0.05^2 |g|^2 by far more than the rounding difference between
// the two passes' arithmetic for h (about 40 epsilon relative where
// |h| = 0.05 |g|: 5e-15 in double, 2e-6 in float), so every pair the second
// pass accepts is visited: the sums are those of a second pass over every
// pair. Rows longer than `capacity` pairs: overflowed, the second pass visits all.
#pragma once
#include "kernels/core/math.hpp"
#include "kernels/neighbors/pair_list.hpp"

namespace mfsd {

template <class Real>
struct GenogActivePairs {
  static constexpr int capacity = 256;  // pairs per row
  static constexpr Real loose_threshold2 = Real(0.05 * 0.05 * (1.0 - 1e-3));

  Real excess[capacity + 1];  // [capacity]: where the pairs beyond it go

  // Pair k of the row (k = 0, 1, ...): |h|^2 - loose_threshold2 |g|^2.
  MFSD_HD void put(PairIndex k, Real e) { excess[k < capacity ? k : capacity] = e; }

  MFSD_HD static bool overflowed(PairIndex n) { return n > capacity; }

  // f(k) for each k < n (n <= capacity) with a positive excess, in order.
  template <class F>
  void for_each(PairIndex n, F&& f) const {
    Index k_active[capacity];
    int m = 0;
    for (Index k = 0; k < Index(n); ++k) {  // compaction without a branch
      k_active[m] = k;
      m += excess[k] > Real(0) ? 1 : 0;
    }
    for (int r = 0; r < m; ++r) f(PairIndex(k_active[r]));
  }
};

}  // namespace mfsd
