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

#include <algorithm>
#include <cstring>
#include <vector>

#include "host/backend/backend.hpp"
#include "kernels/neighbors/half_pair_sink.hpp"

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

// The half-pair loop (Cabana's "half neighbour" tag; issue 24): every pair
// once, from the row of its smaller index, its share given to both particles
// through a HalfPairSink (kernels/neighbors/half_pair_sink.hpp). Each thread
// takes a contiguous block [lo, hi) of [begin, end), zeroes acc over it and its
// own buffer for the neighbours beyond it (j - hi < bandwidth, the largest
// j - i of a pair), runs row(i, sink) over the block; after one barrier,
// finish(i, total) over the block, total = acc[i] plus what the blocks before
// it put in their buffers for i. No atomics; the sums' order depends on the
// thread count only. workspace: the buffers, kept between calls. What finish
// returns is combined with op, each thread's block in order and then the
// blocks in thread order (as parallel_reduce), into *out.
template <class T, class Row, class Finish, class R, class Op>
inline void half_pair_reduce(Cpu, Index begin, Index end, Index bandwidth, T zero, T* acc, std::vector<T>& workspace,
                             const Row& row, const Finish& finish, R init, Op op, R* out) {
  if (end <= begin) {
    *out = init;
    return;
  }
  const int threads = omp_get_max_threads();
  const size_t width = size_t(bandwidth > 0 ? bandwidth : 0);
  if (workspace.size() < size_t(threads) * width) workspace.resize(size_t(threads) * width);
  std::vector<R> partial(size_t(threads), init);
  T* buffers = workspace.data();
  const std::int64_t n = std::int64_t(end) - begin;
#pragma omp parallel
  {
    const int count = omp_get_num_threads(), t = omp_get_thread_num();
    auto block_end = [&](int k) { return Index(begin + n * (k + 1) / count); };
    const Index lo = Index(begin + n * t / count), hi = block_end(t);
    T* remote = buffers + size_t(t) * width;
    const size_t used = std::min(width, size_t(end - hi));
    for (Index i = lo; i < hi; ++i) acc[i] = zero;
    for (size_t k = 0; k < used; ++k) remote[k] = zero;
    const HalfPairSink<T> sink{acc, remote, hi};
    for (Index i = lo; i < hi; ++i) row(i, sink);
#pragma omp barrier
    R r = init;
    for (Index i = lo; i < hi; ++i) {
      T total = acc[i];
      for (int s = 0; s < t; ++s) {
        const std::int64_t k = std::int64_t(i) - block_end(s);
        if (k >= 0 && k < std::int64_t(width)) total += buffers[size_t(s) * width + size_t(k)];
      }
      r = op(r, finish(i, total));
    }
    partial[size_t(t)] = r;
  }
  R r = init;
  for (const R& p : partial) r = op(r, p);
  *out = r;
}

// The same without a result: finish(i, total) returns nothing.
template <class T, class Row, class Finish>
inline void half_pair_for(Cpu, Index begin, Index end, Index bandwidth, T zero, T* acc, std::vector<T>& workspace,
                          const Row& row, const Finish& finish) {
  char none = 0;
  half_pair_reduce(
      Cpu{}, begin, end, bandwidth, zero, acc, workspace, row,
      [&](Index i, const T& total) {
        finish(i, total);
        return char(0);
      },
      char(0), [](char, char) { return char(0); }, &none);
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
