// run.json (provenance: resolved scene, version, backend, counts, status) and
// timing.json (per-stage and per-step times, particle-steps/s).
#pragma once
#include <string>
#include <vector>

#include "host/driver/run.hpp"
#include "host/scene/json_node.hpp"

namespace mfsd {

struct RunStatus {
  std::string state;  // running | completed | failed | interrupted
  long steps = 0;
  long start_steps = 0;                                 // a continued run: the checkpoint's step
  double start_time = 0;                                // and time
  std::string restarted_from;                           // its checkpoint folder
  long checkpoints = 0;                                 // written by this run
  double checkpoint_bytes = 0, checkpoint_seconds = 0;  // the last one's size; all of them's time
  std::string checkpoint;                               // the folder of the last one
  double simulated_time = 0;
  std::string message;
  double setup_seconds = 0, step_seconds = 0, output_seconds = 0, wall_seconds = 0;
  long warmup_steps = 0;           // steps before timing started
  std::vector<double> step_times;  // wall seconds of each timed step
  // CPU: the thread count at the start and, when the governor chose it
  // (thread_governor.hpp), every count it ran with as (step, threads).
  int threads = 0;
  bool governed = false;
  std::vector<std::pair<long, int>> thread_changes;
};

Json machine_description();
void write_run_json(const std::string& dir, const SceneDocument& doc, const RunOptions& options,
                    const SetupReport& setup, const RunStatus& status);
void write_timing_json(const std::string& dir, const SetupReport& setup, const StageTimers& timers,
                       const RunOptions& options, const RunStatus& status);

}  // namespace mfsd
