// A failure of the device or its runtime (a CUDA error), as opposed to bad
// input or a numerical failure of the model. `deferred`: found at a step's
// synchronisation, after the kernels of the step were queued, so that the
// failing stage is not known (MFSD_CUDA_SYNC_CHECK=1 finds it; docs/architecture.md).
#pragma once
#include <stdexcept>
#include <string>

namespace mfsd {

class BackendError : public std::runtime_error {
 public:
  explicit BackendError(const std::string& what, bool deferred = false)
      : std::runtime_error(what), deferred_(deferred) {}
  bool deferred() const { return deferred_; }

 private:
  bool deferred_;
};

}  // namespace mfsd
