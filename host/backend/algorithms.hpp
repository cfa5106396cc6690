// Backend-generic algorithms over Thrust: parallel_for, reductions, sort,
// gather and scans. The backend's BackendTraits come from backend/cpu.hpp or
// backend/cuda.cuh (include one of them). Every function here that makes the
// host wait for the device (a result on the host, a blocking copy) counts a
// round trip (round_trips.hpp), the same on every backend.
#pragma once
#include <thrust/copy.h>
#include <thrust/count.h>
#include <thrust/gather.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/reduce.h>
#include <thrust/scan.h>
#include <thrust/scatter.h>
#include <thrust/sequence.h>
#include <thrust/sort.h>
#include <thrust/transform_reduce.h>

#include <vector>

#include "host/backend/backend.hpp"
#include "host/backend/round_trips.hpp"

namespace mfsd {

template <class B, class F>
inline void parallel_for(Index begin, Index end, const F& f) {
  parallel_for(B{}, begin, end, f);
}
template <class B, class F>
inline void parallel_for(Index n, const F& f) {
  parallel_for(B{}, Index(0), n, f);
}

// f(i) exactly once for each i in [begin, end), where f may write element i's
// state as in a parallel_for, its results combined with the associative,
// commutative op from init (op's identity) into *out in backend memory,
// without a host wait (backend/cpu.hpp, backend/cuda.cuh). The only form of
// reduction whose functor may have side effects.
template <class B, class T, class F, class Op>
inline void parallel_reduce(Index begin, Index end, const F& f, T init, Op op, T* out) {
  parallel_reduce(B{}, begin, end, f, init, op, out);
}

// Reduction of a pure f(i) over [begin, end) with the associative, commutative
// op, returned to the host (a round trip). Thrust may evaluate f any number of
// times per element: f must not write anything (parallel_reduce does).
template <class B, class T, class F, class Op>
inline T transform_reduce(Index begin, Index end, const F& f, T init, Op op) {
  if (end <= begin) return init;
  count_round_trip();
  return thrust::transform_reduce(BackendTraits<B>::policy(), thrust::counting_iterator<Index>(begin),
                                  thrust::counting_iterator<Index>(end), f, init, op);
}

template <class B, class K, class V>
inline void sort_by_key(DeviceVector<B, K>& keys, DeviceVector<B, V>& values) {
  thrust::sort_by_key(BackendTraits<B>::policy(), keys.begin(), keys.end(), values.begin());
}

// Keeps the order of equal keys: the same order on every backend (contact
// gathers sum in it, so the cpu and cuda results agree to round-off).
template <class B, class K, class V>
inline void stable_sort_by_key(DeviceVector<B, K>& keys, DeviceVector<B, V>& values) {
  thrust::stable_sort_by_key(BackendTraits<B>::policy(), keys.begin(), keys.end(), values.begin());
}

template <class B, class T>
inline void sequence(DeviceVector<B, T>& v) {
  thrust::sequence(BackendTraits<B>::policy(), v.begin(), v.end());
}

// out[k] = in[map[k]]
template <class B, class T>
inline void gather(const DeviceVector<B, Index>& map, const DeviceVector<B, T>& in, DeviceVector<B, T>& out) {
  thrust::gather(BackendTraits<B>::policy(), map.begin(), map.end(), in.begin(), out.begin());
}

// out[map[k]] = in[k] (the inverse of gather).
template <class B, class T>
inline void scatter(const DeviceVector<B, T>& in, const DeviceVector<B, Index>& map, DeviceVector<B, T>& out) {
  thrust::scatter(BackendTraits<B>::policy(), in.begin(), in.end(), map.begin(), out.begin());
}

// out[k] = sum_{m<k} in[m]; returns the total.
template <class B, class TIn, class TOut>
inline TOut exclusive_scan(const DeviceVector<B, TIn>& in, DeviceVector<B, TOut>& out) {
  if (in.empty()) return TOut(0);
  count_round_trip();
  thrust::exclusive_scan(BackendTraits<B>::policy(), in.begin(), in.end(), out.begin(), TOut(0));
  const TOut last_out = out[in.size() - 1];
  const TIn last_in = in[in.size() - 1];
  return last_out + TOut(last_in);
}

template <class B, class T>
inline std::vector<T> to_host(const DeviceVector<B, T>& v) {
  std::vector<T> h(v.size());
  count_round_trip();
  thrust::copy(v.begin(), v.end(), h.begin());
  return h;
}

template <class B, class T>
inline void from_host(const std::vector<T>& h, DeviceVector<B, T>& v) {
  v.resize(h.size());
  count_round_trip();
  thrust::copy(h.begin(), h.end(), v.begin());
}

template <class T>
struct CopyOneFunctor {
  const T* from;
  T* to;
  MFSD_HD void operator()(Index) const { *to = *from; }
};

// One element of a device array (error reports; not for hot paths).
template <class B, class T>
inline T copy_element(const T* array, Index i) {
  DeviceVector<B, T> one(1);
  parallel_for<B>(1, CopyOneFunctor<T>{array + i, raw(one)});
  return to_host<B>(one)[0];
}

}  // namespace mfsd
