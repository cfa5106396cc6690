// CUDA availability, answered by cuda_device.cu in a CUDA build and by
// cuda_stub.cpp in a CPU-only one: compiled in, and a device present.
#pragma once
#include <string>

namespace mfsd {

bool cuda_compiled();
int cuda_device_count();
std::string cuda_device_name();
double cuda_device_free_bytes();  // of device 0; 0 without one

}  // namespace mfsd
