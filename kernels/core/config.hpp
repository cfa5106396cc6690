// Basic configuration shared by every kernel: the host/device annotation and
// the index types. Header-only, no allocation, no I/O (design.md, kernels/).
#pragma once
#include <cstdint>

#if defined(__CUDACC__)
#define MFSD_HD __host__ __device__
#define MFSD_FORCEINLINE __forceinline__
#else
#define MFSD_HD
#define MFSD_FORCEINLINE inline __attribute__((always_inline))
#endif

namespace mfsd {
// Software prefetch into the CPU caches (a hint; nothing on the GPU, whose
// many resident warps hide memory latency instead).
MFSD_HD inline void prefetch(const void* address) {
#if !defined(__CUDA_ARCH__)
  __builtin_prefetch(address);
#else
  (void)address;
#endif
}

// Particle index. 32 bits: one process holds far fewer than 2^31 particles.
using Index = std::int32_t;
// Offset into per-pair (CSR) arrays: can exceed 2^31 for large 3-D runs.
using PairIndex = std::int64_t;
}  // namespace mfsd
