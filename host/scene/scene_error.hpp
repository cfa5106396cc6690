// A problem with the user's input. The message names the JSON path, the value
// found and what was expected; the CLI prints it and exits with code 2.
#pragma once
#include <stdexcept>
#include <string>

namespace mfsd {

class SceneError : public std::runtime_error {
 public:
  SceneError(const std::string& path, const std::string& found, const std::string& expected)
      : std::runtime_error(format(path, found, expected)), path_(path) {}
  explicit SceneError(const std::string& message) : std::runtime_error(message) {}
  const std::string& path() const { return path_; }

 private:
  static std::string format(const std::string& path, const std::string& found, const std::string& expected) {
    std::string m = (path.empty() ? std::string("scene") : path) + ": ";
    if (!found.empty()) m += "got " + found + "; ";
    return m + "expected " + expected;
  }
  std::string path_;
};

}  // namespace mfsd

namespace mfsd {
// A command-line problem (unknown option, unavailable backend): exit code 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};
}  // namespace mfsd
