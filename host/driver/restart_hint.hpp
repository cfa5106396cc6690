// The command that continues an interrupted run: every option that shaped
// the scene (--set, --precision) and the run's results (backend, threads,
// pair options), the scene file, and --restart with the output folder.
// Followed as printed it continues the run (issue 47: the hint dropped --set,
// and the checkpoint then said it was "written for another scene").
#pragma once
#include <string>

#include "host/driver/run.hpp"

namespace mfsd {

// `text` quoted for a POSIX shell where it needs it (spaces, quotes, $...).
std::string shell_quote(const std::string& text);

// "mfsd run SCENE [options] --restart DIR" (without "mpiexec -n N").
std::string restart_command(const SceneDocument& doc, const RunOptions& options, const std::string& dir);

}  // namespace mfsd
