// Progress of a long run: a live line on a terminal (simulated time,
// percent, steps/s, ETA), plain lines at every 10 % (or each minute) when
// the output is not a terminal.
#pragma once
#include <chrono>
#include <cstdio>

namespace mfsd {

class Progress {
 public:
  // start_time, start_steps: where a continued run starts (rates and ETA count from there).
  Progress(double end_time, bool enabled, double start_time = 0, long start_steps = 0);
  void update(double time, long steps);
  void finish();  // ends the live line

 private:
  void print(double time, long steps, bool live);
  double end_time_, start_time_;
  long start_steps_;
  bool enabled_, tty_;
  std::chrono::steady_clock::time_point start_, last_;
  int last_decile_ = 0;
  bool live_open_ = false;
};

// "1h02m", "3m05s", "12.3s"
void format_duration(double seconds, char* buf, size_t n);

}  // namespace mfsd
