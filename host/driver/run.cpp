#include "host/driver/run.hpp"

#include <unistd.h>

#include <filesystem>

#include "host/driver/run_session.hpp"
#include "host/scene/scene_error.hpp"

namespace mfsd {

namespace fs = std::filesystem;

void prepare_output_dir(const std::string& dir) {
  // A name the file system cannot hold is found before anything is created.
  for (const auto& part : fs::path(dir))
    if (part.string().size() > 255)
      throw SceneError("output folder '" + dir.substr(0, 60) + "...'", "",
                       "folder names of at most 255 characters (one has " + std::to_string(part.string().size()) +
                           "; shorten the scene's name or give -o DIR)");
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw SceneError("output folder '" + dir + "'", "", "a folder that can be created (" + ec.message() + ")");
  if (access(dir.c_str(), W_OK) != 0)
    throw SceneError("output folder '" + dir + "'", "", "a writable folder (permission denied)");
}

RunResult run_scene(const SceneDocument& doc, const RunOptions& options) {
  RunSession session(doc, options);
  while (session.step()) {
  }
  return session.finish();
}

}  // namespace mfsd
