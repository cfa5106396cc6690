// The CUDA backend: Thrust's CUDA system (CUB underneath) for storage, sort,
// scan and reductions; parallel_for launches one kernel per pass over
// particles with the block size of launch_config.hpp. nvcc only.
#pragma once
#if !defined(__CUDACC__)
#error "host/backend/cuda.cuh is compiled by nvcc only"
#endif
#include <cub/block/block_reduce.cuh>
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

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <string>
#include <typeinfo>

#include "host/backend/backend.hpp"
#include "host/backend/backend_error.hpp"
#include "host/backend/launch_config.hpp"

namespace mfsd {

inline void cuda_check(cudaError_t e, const char* what) {
  if (e != cudaSuccess) throw BackendError(std::string("CUDA error in ") + what + ": " + cudaGetErrorString(e));
}

// MFSD_CUDA_SYNC_CHECK=1: synchronise after every kernel and name the kernel
// (and the solver its stage) where it fails; read once (cuda_device.cu).
bool cuda_sync_check();
// The readable name of a functor type (for the checked mode's messages).
std::string demangled_name(const char* mangled);

// Temporary storage of Thrust's algorithms, kept for reuse instead of a
// cudaMalloc/cudaFree pair per call (cudaFree synchronises the device).
// CUB's CachingDeviceAllocator keeps them (bins in cuda_device.cu).
class CachingAllocator {
 public:
  using value_type = char;
  char* allocate(std::ptrdiff_t bytes);
  void deallocate(char* p, size_t bytes);
};
CachingAllocator& caching_allocator();

template <>
struct BackendTraits<Cuda> {
  template <class T>
  using vector = thrust::cuda::vector<T>;
  // par_nosync: an algorithm returns without waiting unless its result goes
  // to the host (a reduction to a host value, a count); stream order keeps
  // every later kernel after it.
  static auto policy() { return thrust::cuda::par_nosync(caching_allocator()); }
  static void synchronize() { cuda_check(cudaDeviceSynchronize(), "synchronize"); }
  static bool sync_check() { return cuda_sync_check(); }
};

// After a launch: the launch's own error, and in the checked mode the kernel's.
template <class F>
inline void check_kernel(const char* kind) {
  cuda_check(cudaGetLastError(), kind);
  if (cuda_sync_check())
    cuda_check(cudaDeviceSynchronize(), (std::string(kind) + " of " + demangled_name(typeid(F).name())).c_str());
}

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
  check_kernel<F>("kernel launch");
}

// parallel_reduce: at most this many blocks, each thread striding over the
// range; the blocks' partial results go to a scratch buffer that one block
// reduces into *out. The grid depends only on n, so the order of the sums,
// and the result, is the same on every device.
namespace reduce {
inline constexpr unsigned max_blocks = 1024;
inline constexpr size_t max_bytes = 128;  // largest T (the scratch holds max_blocks of them)
void* scratch();                          // max_blocks * max_bytes bytes of device memory (cuda_device.cu)
}  // namespace reduce

template <class T, class F, class Op>
__global__ void __launch_bounds__(launch::block_size)
    reduce_blocks_kernel(Index begin, Index end, F f, T init, Op op, T* partial) {
  using BlockReduce = cub::BlockReduce<T, launch::block_size>;
  __shared__ typename BlockReduce::TempStorage temp;
  T acc = init;
  const long long stride = (long long)gridDim.x * blockDim.x;
  for (long long i = begin + (long long)blockIdx.x * blockDim.x + threadIdx.x; i < end; i += stride)
    acc = op(acc, f(Index(i)));
  const T block = BlockReduce(temp).Reduce(acc, op);
  if (threadIdx.x == 0) partial[blockIdx.x] = block;
}

template <class T, class Op>
__global__ void __launch_bounds__(launch::block_size)
    reduce_partials_kernel(const T* partial, unsigned count, T init, Op op, T* out) {
  using BlockReduce = cub::BlockReduce<T, launch::block_size>;
  __shared__ typename BlockReduce::TempStorage temp;
  T acc = init;
  for (unsigned k = threadIdx.x; k < count; k += blockDim.x) acc = op(acc, partial[k]);
  const T r = BlockReduce(temp).Reduce(acc, op);
  if (threadIdx.x == 0) *out = r;
}

// f(i) exactly once for every i in [begin, end) (f may write element i's
// state, as in a parallel_for), combined with op from init (op's identity),
// the result written to *out in device memory: no host wait.
template <class T, class F, class Op>
inline void parallel_reduce(Cuda, Index begin, Index end, const F& f, T init, Op op, T* out) {
  static_assert(sizeof(T) <= reduce::max_bytes, "parallel_reduce: result type larger than the scratch allows");
  T* partial = static_cast<T*>(reduce::scratch());
  unsigned blocks = 0;
  if (end > begin) {
    const long long n = (long long)end - begin;
    blocks = unsigned(std::min<long long>((n + launch::block_size - 1) / launch::block_size, reduce::max_blocks));
    reduce_blocks_kernel<<<blocks, launch::block_size>>>(begin, end, f, init, op, partial);
    check_kernel<F>("reduction");
  }
  reduce_partials_kernel<<<1, launch::block_size>>>(partial, blocks, init, op, out);
  check_kernel<F>("reduction");
}

// Host-to-device copies without a host wait: the data are staged in pinned
// host memory and copied asynchronously in stream order. Before the staging
// memory is reused the previous copy must have finished: normally long ago
// (every step ends with a synchronisation), so the wait costs nothing.
template <>
class HostStaging<Cuda> {
 public:
  HostStaging() = default;
  HostStaging(const HostStaging&) = delete;
  HostStaging& operator=(const HostStaging&) = delete;
  ~HostStaging() {
    if (done_) cudaEventDestroy(done_);
    if (pinned_) cudaFreeHost(pinned_);
  }
  template <class T>
  void upload(const T* host, size_t n, T* device) {
    const size_t bytes = n * sizeof(T);
    if (!bytes) return;
    if (done_) cuda_check(cudaEventSynchronize(done_), "staging reuse");
    if (bytes > capacity_) {
      if (pinned_) cuda_check(cudaFreeHost(pinned_), "staging free");
      pinned_ = nullptr;
      cuda_check(cudaMallocHost(&pinned_, bytes), "staging allocation");
      capacity_ = bytes;
    }
    std::memcpy(pinned_, static_cast<const void*>(host), bytes);
    cuda_check(cudaMemcpyAsync(static_cast<void*>(device), pinned_, bytes, cudaMemcpyHostToDevice), "staged upload");
    if (!done_) cuda_check(cudaEventCreateWithFlags(&done_, cudaEventDisableTiming), "event create");
    cuda_check(cudaEventRecord(done_), "event record");
  }

 private:
  void* pinned_ = nullptr;
  size_t capacity_ = 0;
  cudaEvent_t done_ = nullptr;
};

}  // namespace mfsd
