// Writes a file through a temporary name and a rename, so that a reader (or a
// crash) never sees a half-written file.
#pragma once
#include <string>

namespace mfsd {

// Throws std::runtime_error naming the path when the file cannot be written.
void write_file_atomically(const std::string& path, const std::string& content);

}  // namespace mfsd
