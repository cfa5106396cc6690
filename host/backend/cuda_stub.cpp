// CUDA device queries of a CPU-only build.
#include <string>

#include "host/backend/cuda_devices.hpp"

namespace mfsd {
bool cuda_compiled() { return false; }
int cuda_device_count() { return 0; }
std::string cuda_device_name() { return "built without CUDA"; }
double cuda_device_free_bytes() { return 0; }
}  // namespace mfsd
