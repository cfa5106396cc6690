#include "host/driver/progress.hpp"

#include <unistd.h>

#include <cmath>

namespace mfsd {

void format_duration(double s, char* buf, size_t n) {
  if (!std::isfinite(s) || s < 0) {
    std::snprintf(buf, n, "--");
  } else if (s < 60) {
    std::snprintf(buf, n, "%.1fs", s);
  } else if (s < 3600) {
    std::snprintf(buf, n, "%dm%02ds", int(s / 60), int(s) % 60);
  } else {
    std::snprintf(buf, n, "%dh%02dm", int(s / 3600), (int(s) % 3600) / 60);
  }
}

Progress::Progress(double end_time, bool enabled, double start_time, long start_steps)
    : end_time_(end_time),
      start_time_(start_time),
      start_steps_(start_steps),
      enabled_(enabled),
      tty_(isatty(STDERR_FILENO) != 0) {
  start_ = last_ = std::chrono::steady_clock::now();
  last_decile_ = end_time > 0 ? int(10.0 * start_time / end_time + 1e-9) : 0;
}

void Progress::print(double time, long steps, bool live) {
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double frac = end_time_ > 0 ? std::min(1.0, time / end_time_) : 0.0;
  const double rate = wall > 0 ? double(steps - start_steps_) / wall : 0.0;
  const double done = end_time_ > start_time_ ? (time - start_time_) / (end_time_ - start_time_) : 0.0;
  const double eta = done > 0 ? wall * (1.0 - done) / done : NAN;
  char eta_text[32], wall_text[32];
  format_duration(eta, eta_text, sizeof eta_text);
  format_duration(wall, wall_text, sizeof wall_text);
  if (live) {
    std::fprintf(stderr, "\r  t = %.6g / %.6g s  %5.1f %%  %ld steps  %.0f steps/s  elapsed %s  ETA %s   ", time,
                 end_time_, 100.0 * frac, steps, rate, wall_text, eta_text);
    live_open_ = true;
  } else {
    std::fprintf(stderr, "  t = %.6g / %.6g s  %5.1f %%  %ld steps  %.0f steps/s  elapsed %s  ETA %s\n", time,
                 end_time_, 100.0 * frac, steps, rate, wall_text, eta_text);
  }
  std::fflush(stderr);
}

void Progress::update(double time, long steps) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  const double since = std::chrono::duration<double>(now - last_).count();
  if (tty_) {
    if (since < 0.25) return;
    last_ = now;
    print(time, steps, true);
    return;
  }
  const int decile = end_time_ > 0 ? int(10.0 * time / end_time_ + 1e-9) : 0;
  if (decile > last_decile_ || since >= 60.0) {
    last_decile_ = std::max(decile, last_decile_);
    last_ = now;
    print(time, steps, false);
  }
}

void Progress::finish() {
  if (enabled_ && live_open_) std::fprintf(stderr, "\n");
  live_open_ = false;
}

}  // namespace mfsd
