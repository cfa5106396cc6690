// Stage clock of the CUDA backend: a pair of events around each stage; the
// elapsed times are collected once per step, after the time-step reduction
// has synchronized, so timing adds no synchronization of its own.
#pragma once
#include <cuda_runtime.h>

#include <vector>

#include "host/backend/cuda.cuh"
#include "host/backend/stage_timers.hpp"

namespace mfsd {

template <class B>
class StageClock;

template <>
class StageClock<Cuda> {
 public:
  StageClock() = default;
  StageClock(const StageClock&) = delete;
  StageClock& operator=(const StageClock&) = delete;
  ~StageClock() {
    for (auto& r : records_) {
      cudaEventDestroy(r.begin);
      cudaEventDestroy(r.end);
    }
  }
  void start(int id) {
    Record& r = record(id);
    cuda_check(cudaEventRecord(r.begin), "event record");
  }
  void stop(int id, StageTimers&) {
    Record& r = record(id);
    cuda_check(cudaEventRecord(r.end), "event record");
    r.pending = true;
  }
  void collect(StageTimers& timers) {
    for (size_t k = 0; k < records_.size(); ++k) {
      Record& r = records_[k];
      if (!r.pending) continue;
      cuda_check(cudaEventSynchronize(r.end), "event synchronize");
      float ms = 0;
      cuda_check(cudaEventElapsedTime(&ms, r.begin, r.end), "event elapsed");
      timers.add(int(k), 1e-3 * double(ms));
      r.pending = false;
    }
  }

 private:
  struct Record {
    cudaEvent_t begin{}, end{};
    bool pending = false;
  };
  Record& record(int id) {
    while (records_.size() <= size_t(id)) {
      Record r;
      cuda_check(cudaEventCreate(&r.begin), "event create");
      cuda_check(cudaEventCreate(&r.end), "event create");
      records_.push_back(r);
    }
    return records_[size_t(id)];
  }
  std::vector<Record> records_;
};

}  // namespace mfsd
