// CUDA device queries and the CUDA backend's process-wide resources: the
// checked mode's switch, Thrust's caching allocator and the reduction scratch
// (compiled only in CUDA builds).
#include <cuda_runtime.h>
#include <cxxabi.h>

#include <cub/util_allocator.cuh>

#include <cstdlib>
#include <memory>
#include <string>

#include "host/backend/cuda.cuh"
#include "host/backend/cuda_devices.hpp"

namespace mfsd {

bool cuda_sync_check() {
  static const bool on = [] {
    const char* v = std::getenv("MFSD_CUDA_SYNC_CHECK");
    return v && std::string(v) == "1";
  }();
  return on;
}

std::string demangled_name(const char* mangled) {
  int status = 0;
  std::unique_ptr<char, void (*)(void*)> name(abi::__cxa_demangle(mangled, nullptr, nullptr, &status), std::free);
  return status == 0 && name ? std::string(name.get()) : std::string(mangled);
}

namespace {

// CUB's caching allocator with power-of-two bins from 1 KiB to 2 GiB (CUB's
// default bins stop at 2 MiB, below a sort's temporaries at a million
// particles), no limit on the bytes it keeps (it frees its cache and retries
// when the device runs out), kept until exit (skip_cleanup: at static
// destruction the CUDA context may already be gone). Thread-safe.
cub::CachingDeviceAllocator& cub_cache() {
  static auto* a = new cub::CachingDeviceAllocator(2, 10, 31, cub::CachingDeviceAllocator::INVALID_SIZE, true);
  return *a;
}

}  // namespace

char* CachingAllocator::allocate(std::ptrdiff_t bytes) {
  void* p = nullptr;
  cuda_check(cub_cache().DeviceAllocate(&p, size_t(bytes)), "temporary allocation");
  return static_cast<char*>(p);
}

// Called from destructors: never throws (a device fault shows at the next check).
void CachingAllocator::deallocate(char* p, size_t) { (void)cub_cache().DeviceFree(p); }

CachingAllocator& caching_allocator() {
  static CachingAllocator a;
  return a;
}

void* reduce::scratch() {
  static void* p = [] {
    void* q = nullptr;
    cuda_check(cudaMalloc(&q, size_t(reduce::max_blocks) * reduce::max_bytes), "reduction scratch");
    return q;
  }();
  return p;
}

bool cuda_compiled() { return true; }

int cuda_device_count() {
  int n = 0;
  if (cudaGetDeviceCount(&n) != cudaSuccess) {
    cudaGetLastError();  // clear the sticky error
    return 0;
  }
  return n;
}

std::string cuda_device_name() {
  int n = 0;
  const cudaError_t e = cudaGetDeviceCount(&n);
  if (e != cudaSuccess) {
    cudaGetLastError();
    return cudaGetErrorString(e);
  }
  if (n == 0) return "no device";
  cudaDeviceProp p{};
  cudaGetDeviceProperties(&p, 0);
  return p.name;
}

double cuda_device_free_bytes() {
  size_t free = 0, total = 0;
  if (cuda_device_count() == 0 || cudaMemGetInfo(&free, &total) != cudaSuccess) {
    cudaGetLastError();
    return 0;
  }
  return double(free);
}

}  // namespace mfsd
