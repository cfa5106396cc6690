// The CUDA backend: Thrust's CUDA system (CUB underneath) for storage, sort,
// scan and reductions; parallel_for launches one kernel per pass over
// particles with the block size of launch_config.hpp. nvcc only.
#pragma once
#if !defined(__CUDACC__)
#error "host/backend/cuda.cuh is compiled by nvcc only"
#endif
#include <cuda_runtime.h>
#include <thrust/count.h>
#include <thrust/execution_policy.h>
#include <thrust/gather.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/reduce.h>
#include <thrust/scan.h>
#include <thrust/sequence.h>
#include <thrust/sort.h>
#include <thrust/system/cuda/execution_policy.h>
#include <thrust/system/cuda/vector.h>
#include <thrust/transform_reduce.h>

#include <stdexcept>
#include <string>

#include "host/backend/backend.hpp"
#include "host/backend/launch_config.hpp"

namespace mfsd {

inline void cuda_check(cudaError_t e, const char* what) {
  if (e != cudaSuccess) throw std::runtime_error(std::string("CUDA error in ") + what + ": " + cudaGetErrorString(e));
}

template <>
struct BackendTraits<Cuda> {
  template <class T>
  using vector = thrust::cuda::vector<T>;
  static auto policy() { return thrust::cuda::par; }
  static void synchronize() { cuda_check(cudaDeviceSynchronize(), "synchronize"); }
};

template <class F>
__global__ void __launch_bounds__(launch::block_size) for_each_index_kernel(Index begin, Index end, F f) {
  const Index i = begin + Index(blockIdx.x) * Index(blockDim.x) + Index(threadIdx.x);
  if (i < end) f(i);
}

template <class F>
inline void parallel_for(Cuda, Index begin, Index end, const F& f) {
  if (end <= begin) return;
  const Index n = end - begin;
  const unsigned blocks = unsigned((n + launch::block_size - 1) / launch::block_size);
  for_each_index_kernel<<<blocks, launch::block_size>>>(begin, end, f);
  cuda_check(cudaGetLastError(), "kernel launch");
}

}  // namespace mfsd
