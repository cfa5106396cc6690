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
  using Entry = std::pair<double, std::string>;  // time, file relative to the .pvd
  void add(double time, const std::string& relative_file);
  const std::vector<Entry>& entries() const { return entries_; }
  // A continued run: the entries up to its checkpoint (the file is rewritten).
  void restore(std::vector<Entry> entries);

 private:
  void write() const;
  std::string path_;
  std::vector<Entry> entries_;
};

}  // namespace mfsd
