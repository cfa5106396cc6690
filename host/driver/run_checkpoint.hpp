// Checkpoints of a run (issue 19): what checkpoint.json records beside the
// solver's state archive (the binary's version and commit, the resolved scene,
// backend, precision and threads, and the driver's place in its output
// series), and the checks that a restart fits the run it continues.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "host/driver/run.hpp"
#include "host/output/pvd_index.hpp"
#include "host/scene/json_node.hpp"

namespace mfsd {

// Where the driver stands in its outputs at a checkpoint.
struct OutputPosition {
  double next_output = 0, next_probe = 0, next_checkpoint = 0;
  int snapshot_count = 0;
  std::vector<PvdIndex::Entry> snapshots, rigid_snapshots;
  std::map<std::string, std::uint64_t> csv_bytes;  // file name in the output folder -> its length
};

// The checkpoint folder of an output folder.
std::string checkpoint_folder(const std::string& output_dir);

// checkpoint.json's content (write_checkpoint adds the state file's checksum).
Json checkpoint_meta(const SceneDocument& doc, const RunOptions& options, double time, long steps,
                     const OutputPosition& position);

struct RestartPoint {
  std::string folder;      // the checkpoint folder
  std::string output_dir;  // the run's output folder (the folder above it)
  double time = 0;
  long steps = 0;
  OutputPosition position;
  std::vector<std::string> warnings;  // accepted differences (threads, end time)
};

// `where` is an output folder or a checkpoint folder. Throws CheckpointError
// (an input error) when there is no readable checkpoint, or when it was
// written by another version, for another scene (the first differing JSON
// path is named; solver.end_time and output.checkpoint_interval may differ),
// precision or backend.
RestartPoint find_restart(const std::string& where, const SceneDocument& doc, const RunOptions& options);

}  // namespace mfsd
