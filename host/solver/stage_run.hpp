// Runs one stage of a step and names it in device errors: a fault found
// while the stage runs (a failed launch, a Thrust algorithm's error, or, in
// the checked mode MFSD_CUDA_SYNC_CHECK=1, any kernel of the stage, because
// the stage then ends with a synchronisation) is reported as the stage's; a
// fault found only at the step's synchronisation (deferred) is reported with
// the stages it may come from. Include after the backend header.
#pragma once
#include <thrust/system_error.h>

#include <string>
#include <utility>

#include "host/backend/backend_error.hpp"

namespace mfsd {

template <class B, class F>
void run_stage(const std::string& name, const std::string& step_stages, F&& f) {
  try {
    std::forward<F>(f)();
    if (BackendTraits<B>::sync_check()) BackendTraits<B>::synchronize();
  } catch (const BackendError& e) {
    if (e.deferred())
      throw BackendError(std::string(e.what()) + "; found at the step's synchronisation, raised by a kernel of one of " +
                             "the step's stages (" + step_stages +
                             "); run with MFSD_CUDA_SYNC_CHECK=1 to stop at the failing stage and kernel",
                         true);
    throw BackendError("in stage '" + name + "': " + e.what());
  } catch (const thrust::system_error& e) {
    throw BackendError("in stage '" + name + "': " + e.what());
  }
}

}  // namespace mfsd
