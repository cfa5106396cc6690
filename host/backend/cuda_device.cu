// CUDA device queries (compiled only in CUDA builds).
#include <cuda_runtime.h>

#include <string>

#include "host/solver/solver.hpp"

namespace mfsd {

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
