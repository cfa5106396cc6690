// Backend tags and the operations every backend provides. A backend is a
// Thrust execution system: Cpu = Thrust's OpenMP system, Cuda = Thrust's CUDA
// system (design.md, "One kernel source, two backends"). Kernels are plain
// functors with `MFSD_HD void operator()(Index i) const`; the host launches
// them with parallel_for<Backend>(begin, end, functor).
//
// This header declares only the tags; include backend/cpu.hpp (any compiler)
// or backend/cuda.cuh (nvcc only) for the operations.
#pragma once
#include <thrust/memory.h>

#include <string>

#include "kernels/core/config.hpp"

namespace mfsd {

struct Cpu {
  static constexpr const char* name = "cpu";
};
struct Cuda {
  static constexpr const char* name = "cuda";
};

// Storage of the backend's memory space: BackendTraits<B>::vector<T>.
template <class B>
struct BackendTraits;

// Uploads without a host wait (backend/cpu.hpp, backend/cuda.cuh).
template <class B>
class HostStaging;

template <class B, class T>
using DeviceVector = typename BackendTraits<B>::template vector<T>;

// Raw pointer of a backend vector (for functor views).
template <class V>
inline auto raw(V& v) {
  return thrust::raw_pointer_cast(v.data());
}
template <class V>
inline auto raw(const V& v) {
  return thrust::raw_pointer_cast(v.data());
}

}  // namespace mfsd
