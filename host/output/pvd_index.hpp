// ParaView collection (.pvd): the time index of the VTU snapshots. Rewritten
// (atomically) after every snapshot so it is valid at any moment of a run.
#pragma once
#include <string>
#include <utility>
#include <vector>

namespace mfsd {

class PvdIndex {
 public:
  explicit PvdIndex(std::string path) : path_(std::move(path)) {}
  void add(double time, const std::string& relative_file);

 private:
  std::string path_;
  std::vector<std::pair<double, std::string>> entries_;
};

}  // namespace mfsd
