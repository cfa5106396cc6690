// Runs a scene: set-up, the time loop with outputs (VTU + PVD, probes.csv,
// energies.csv), progress, run.json and timing.json, and the summary.
#pragma once
#include <string>
#include <vector>

#include "host/scene/scene_reader.hpp"
#include "host/solver/solver.hpp"

namespace mfsd {

struct RunOptions {
  std::string output_dir;  // default out/<scene name>
  SolverOptions solver;
  bool precision_given = false;  // --precision overrides the scene's solver.precision
  long max_steps = 0;            // 0 = until end_time
  long warmup_steps = 0;         // steps left out of timing.json (caches, page faults, clocks)
  bool quiet = false;            // no progress and no summary
  std::string command_line;
  std::string restart;                  // continue from this output or checkpoint folder
  double checkpoint_every_minutes = 0;  // wall-clock checkpoints (0: none)
  // A language binding steps the run itself (host/driver/run_session.hpp):
  bool handle_signals = true;  // false: the caller installs InterruptHandling around its steps
  bool keep_series = false;    // the CSV rows also in memory (RunSession::series)
};

struct RunResult {
  int exit_code = 0;  // 0 ok, 3 numerical failure, 128 + signal when interrupted (130 SIGINT, 143 SIGTERM)
  long steps = 0;
  double time = 0;
  std::string output_dir;
  std::string message;
};

// Input problems (SceneError, unavailable backend, unwritable folder, a
// checkpoint that does not fit: CheckpointError) are thrown before the output
// folder is created or, for a restart, changed.
RunResult run_scene(const SceneDocument& doc, const RunOptions& options);

// Creates the folder (and parents) and checks it is writable; throws SceneError.
void prepare_output_dir(const std::string& dir);

}  // namespace mfsd
