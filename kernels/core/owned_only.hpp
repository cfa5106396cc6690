// A per-particle sum's term, zero for a ghost (a copy of another rank's
// particle in a distributed run, docs/distributed.md; ghost null otherwise).
#pragma once
#include "kernels/core/config.hpp"

namespace mfsd {

template <class F>
struct OwnedOnly {
  F f;
  const unsigned char* ghost;
  MFSD_HD auto operator()(Index i) const -> decltype(f(i)) { return ghost && ghost[i] ? decltype(f(i)){} : f(i); }
};

}  // namespace mfsd
