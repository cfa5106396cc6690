// A CSV file with a header row, flushed after every row so that a running
// simulation can be plotted (and a failed one keeps its history).
#pragma once
#include <fstream>
#include <string>
#include <vector>

namespace mfsd {

class CsvWriter {
 public:
  CsvWriter(const std::string& path, const std::vector<std::string>& columns);
  void row(const std::vector<double>& values);
  size_t columns() const { return columns_; }

 private:
  std::ofstream out_;
  std::string path_;
  size_t columns_;
};

}  // namespace mfsd
