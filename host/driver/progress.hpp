// Progress of a long run: a live line on a terminal (simulated time,
// percent, steps/s, ETA), plain lines at every 10 % (or each minute) when
// the output is not a terminal.
#pragma once
#include <chrono>
#include <cstdio>

namespace mfsd {

class Progress {
 public:
  Progress(double end_time, bool enabled);
  void update(double time, long steps);
  void finish();  // ends the live line

 private:
  void print(double time, long steps, bool live);
  double end_time_;
  bool enabled_, tty_;
  std::chrono::steady_clock::time_point start_, last_;
  int last_decile_ = 0;
  bool live_open_ = false;
};

// "1h02m", "3m05s", "12.3s"
void format_duration(double seconds, char* buf, size_t n);

}  // namespace mfsd
