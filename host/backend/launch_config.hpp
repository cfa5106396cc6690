// Kernel launch configuration, in one place for every CUDA launch
// (issue 3: "kernel launch configuration in one place").
#pragma once

namespace mfsd::launch {
// Threads per block for particle loops. 128 keeps register-heavy pair loops
// (3-D matrices per thread) at good occupancy on sm_80/sm_90.
inline constexpr int block_size = 128;
}  // namespace mfsd::launch
