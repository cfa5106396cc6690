// Stage clock of the CPU backend: wall time around each stage (the OpenMP
// loops have finished when the stage returns).
#pragma once
#include <chrono>
#include <vector>

#include "host/backend/backend.hpp"
#include "host/backend/stage_timers.hpp"

namespace mfsd {

template <class B>
class StageClock;

template <>
class StageClock<Cpu> {
 public:
  void start(int) { t0_ = std::chrono::steady_clock::now(); }
  void stop(int id, StageTimers& timers) {
    timers.add(id, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count());
  }
  void collect(StageTimers&) {}

 private:
  std::chrono::steady_clock::time_point t0_;
};

}  // namespace mfsd
