// One run of a scene, a step at a time: the set-up, the time loop's steps
// with their outputs (VTU + PVD, the CSV series), checkpoints, progress, and
// at the end run.json, timing.json and the summary. `mfsd run` (run_scene)
// steps it to the end; the Python module (python/) steps it as a script
// asks, so both are the same code.
#pragma once
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "host/driver/run.hpp"
#include "host/solver/numerical_failure.hpp"

namespace mfsd {

class RunSession {
 public:
  // The set-up. Input problems throw before the output folder is created or,
  // for a restart, changed (as run_scene). A numerical failure at set-up
  // (an expression that fails at t = 0) does not throw: the session has
  // stopped, and finish() returns exit code 3 with the message.
  RunSession(const SceneDocument& doc, const RunOptions& options);
  ~RunSession();
  RunSession(const RunSession&) = delete;
  RunSession& operator=(const RunSession&) = delete;

  // Whether another step would run: before the end time and the step limit,
  // without an interruption, a failure or finish().
  bool running() const;
  // One step with the outputs and checkpoints due after it; false when the
  // run has stopped (then finish() ends it). A numerical failure stops the run.
  bool step();
  // Ends the run: on an interruption a checkpoint, the last snapshot of a run
  // stopped early, run.json, timing.json and (unless quiet) the summary.
  // Called once; later calls return the same result.
  const RunResult& finish();

  // The snapshot and series rows of the current time, outside the scene's
  // output times (the Python module's write_snapshot()).
  void write_snapshot();
  // A checkpoint of the current state in the output folder's checkpoint/
  // (what --restart continues); returns that folder. With `folder`, a copy
  // of the outputs so far (the CSV series, the PVD indices, the snapshots)
  // goes to that folder with the checkpoint in its checkpoint/: `mfsd run
  // --restart FOLDER` continues the run there, a branch of this one.
  std::string write_checkpoint(const std::string& folder = "");

  // One CSV series (its file name: "energies.csv", "probes.csv", ...) as
  // written since this session began, with RunOptions::keep_series.
  struct Series {
    std::vector<std::string> columns;
    std::vector<std::vector<double>> rows;
  };
  const std::map<std::string, Series>& series() const;
  // The numerical failure that stopped the run, if one did.
  const std::optional<NumericalFailure>& failure() const;

  Solver& solver();
  const std::string& output_dir() const;
  const SetupReport& setup() const;
  double end_time() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mfsd
