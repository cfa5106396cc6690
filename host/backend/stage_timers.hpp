// Accumulated wall time per named stage, in the order stages first ran.
// Backends measure and add; the report divides by steps and particles.
#pragma once
#include <string>
#include <utility>
#include <vector>

namespace mfsd {

class StageTimers {
 public:
  // Index of a stage (registered on first use).
  int id(const std::string& name) {
    for (size_t k = 0; k < stages_.size(); ++k)
      if (stages_[k].first == name) return int(k);
    stages_.emplace_back(name, 0.0);
    return int(stages_.size() - 1);
  }
  void add(int id, double seconds) { stages_[size_t(id)].second += seconds; }
  const std::vector<std::pair<std::string, double>>& stages() const { return stages_; }
  double total() const {
    double s = 0;
    for (auto& st : stages_) s += st.second;
    return s;
  }
  void reset() {
    for (auto& st : stages_) st.second = 0;
    round_trips_ = 0;
  }
  // Host round trips inside steps (host/backend/round_trips.hpp), since the last reset.
  void add_round_trips(long n) { round_trips_ += n; }
  long round_trips() const { return round_trips_; }

 private:
  std::vector<std::pair<std::string, double>> stages_;
  long round_trips_ = 0;
};

}  // namespace mfsd
