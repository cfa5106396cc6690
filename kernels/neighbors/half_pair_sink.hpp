// Where one row of a half-pair loop writes (host/backend/cpu.hpp,
// half_pair_for): the row of particle i visits only its pairs with j > i and
// gives each pair's share to both particles, i's into acc[i] and j's through
// add(j, x). The thread that runs the row owns acc over its block of rows,
// [.., hi); a neighbour beyond the block goes to the thread's own buffer,
// remote[j - hi], which the loop adds to acc after a barrier. So no two
// threads write one element and no atomics are needed.
#pragma once
#include "kernels/core/config.hpp"

namespace mfsd {

template <class T>
struct HalfPairSink {
  T* acc;
  T* remote;
  Index hi;

  MFSD_HD void add(Index j, const T& x) const {
    if (j < hi)
      acc[j] += x;
    else
      remote[j - hi] += x;
  }
};

}  // namespace mfsd
