// A checkpoint on disk: a folder with checkpoint.json (what the run was and
// where it stood: written by the driver) and state.bin (the solver's state
// archive, named blobs, with an FNV-1a checksum that checkpoint.json records).
// Written atomically: into <folder>.new, then the folder in place is renamed
// to <folder>.previous and <folder>.new to <folder>, so that a stop at any
// moment leaves at least one whole checkpoint.
#pragma once
#include <cstdint>
#include <stdexcept>
#include <string>

#include "host/particles/state_archive.hpp"

namespace mfsd {

// A checkpoint that cannot be read (missing, damaged, another format).
class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct CheckpointWriteReport {
  std::uint64_t bytes = 0;  // state.bin + checkpoint.json
  double seconds = 0;
};

// `meta_json` is checkpoint.json's text without the state file's size and
// checksum, which are added under "state": {"bytes", "fnv1a64"}.
CheckpointWriteReport write_checkpoint(const std::string& folder, const std::string& meta_json,
                                       const StateArchive& archive);

struct CheckpointContents {
  std::string meta_json;  // checkpoint.json as written
  StateArchive archive;
};

// Reads and verifies (size, checksum, format) a checkpoint folder.
CheckpointContents read_checkpoint(const std::string& folder);
// checkpoint.json only (cheap: checked before the run is set up).
std::string read_checkpoint_meta(const std::string& folder);

}  // namespace mfsd
