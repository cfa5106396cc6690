// The CPU backend: Thrust's OpenMP system for storage, sort, scan and
// reductions; parallel_for is a static OpenMP loop (one pass over particles,
// same functor as on the GPU).
#pragma once
#include <omp.h>
#include <thrust/count.h>
#include <thrust/execution_policy.h>
#include <thrust/gather.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/reduce.h>
#include <thrust/scan.h>
#include <thrust/sequence.h>
#include <thrust/sort.h>
#include <thrust/system/omp/execution_policy.h>
#include <thrust/system/omp/vector.h>
#include <thrust/transform_reduce.h>

#include "host/backend/backend.hpp"

namespace mfsd {

template <>
struct BackendTraits<Cpu> {
  template <class T>
  using vector = thrust::omp::vector<T>;
  static auto policy() { return thrust::omp::par; }
  static void synchronize() {}
};

template <class F>
inline void parallel_for(Cpu, Index begin, Index end, const F& f) {
#pragma omp parallel for schedule(static)
  for (Index i = begin; i < end; ++i) f(i);
}

}  // namespace mfsd
