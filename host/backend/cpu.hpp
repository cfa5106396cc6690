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

#include <cstring>
#include <vector>

#include "host/backend/backend.hpp"

namespace mfsd {

template <>
struct BackendTraits<Cpu> {
  template <class T>
  using vector = thrust::omp::vector<T>;
  static auto policy() { return thrust::omp::par; }
  static void synchronize() {}
  static bool sync_check() { return false; }  // nothing is asynchronous
};

template <class F>
inline void parallel_for(Cpu, Index begin, Index end, const F& f) {
#pragma omp parallel for schedule(static)
  for (Index i = begin; i < end; ++i) f(i);
}

// f(i) once for every i in [begin, end), in the static schedule of
// parallel_for (so f may write the state of element i, as in a parallel_for),
// combined with op, starting from init (op's identity): each thread reduces
// its contiguous block, then the blocks are combined in thread order. The
// result is written to *out (backend memory); the host does not wait.
template <class T, class F, class Op>
inline void parallel_reduce(Cpu, Index begin, Index end, const F& f, T init, Op op, T* out) {
  if (end <= begin) {
    *out = init;
    return;
  }
  std::vector<T> partial(size_t(omp_get_max_threads()), init);
#pragma omp parallel
  {
    T acc = init;
#pragma omp for schedule(static) nowait
    for (Index i = begin; i < end; ++i) acc = op(acc, f(i));
    partial[size_t(omp_get_thread_num())] = acc;
  }
  T r = init;
  for (const T& p : partial) r = op(r, p);
  *out = r;
}

// Host-to-backend copies that do not make the host wait (per-step data such
// as rigid-body placements). On the CPU a plain copy.
template <>
class HostStaging<Cpu> {
 public:
  template <class T>
  void upload(const T* host, size_t n, T* device) {
    if (n) std::memcpy(static_cast<void*>(device), static_cast<const void*>(host), n * sizeof(T));
  }
};

}  // namespace mfsd
