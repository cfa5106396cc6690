// CUDA device queries and the CUDA backend's process-wide resources: the
// checked mode's switch, Thrust's caching allocator and the reduction scratch
// (compiled only in CUDA builds).
#include <cuda_runtime.h>
#include <cxxabi.h>

#include <cstdlib>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "host/backend/cuda.cuh"
#include "host/solver/solver.hpp"

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

// Free blocks by size; blocks in use by address. One allocator per process
// (a solver's temporaries are allocated and freed by its own thread).
struct Cache {
  std::mutex mutex;
  std::multimap<size_t, char*> free;
  std::map<char*, size_t> used;
  ~Cache() {
    for (auto& [bytes, p] : free) cudaFree(p);
  }
};
Cache& cache() {
  static Cache c;
  return c;
}

}  // namespace

char* CachingAllocator::allocate(std::ptrdiff_t bytes) {
  Cache& c = cache();
  std::lock_guard<std::mutex> lock(c.mutex);
  const size_t n = size_t(bytes);
  auto it = c.free.lower_bound(n);
  if (it != c.free.end() && it->first <= 2 * n + 4096) {  // reuse a block of about this size
    char* p = it->second;
    c.used[p] = it->first;
    c.free.erase(it);
    return p;
  }
  char* p = nullptr;
  cudaError_t e = cudaMalloc(&p, n);
  if (e != cudaSuccess) {  // return the cache to the device and try once more
    cudaGetLastError();
    for (auto& [size, q] : c.free) cudaFree(q);
    c.free.clear();
    cuda_check(cudaMalloc(&p, n), "temporary allocation");
  }
  c.used[p] = n;
  return p;
}

void CachingAllocator::deallocate(char* p, size_t) {
  Cache& c = cache();
  std::lock_guard<std::mutex> lock(c.mutex);
  auto it = c.used.find(p);
  if (it == c.used.end()) return;
  c.free.emplace(it->second, p);
  c.used.erase(it);
}

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
