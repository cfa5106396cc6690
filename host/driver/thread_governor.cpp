#include "host/driver/thread_governor.hpp"

#include <algorithm>

namespace mfsd {

ThreadGovernor::ThreadGovernor(int start, std::function<void(int)> apply, Settings settings)
    : s_(settings), apply_(std::move(apply)), max_(std::max(1, start)), current_(max_), hold_(settings.first_hold) {
  changes_.push_back({0, current_});
}

void ThreadGovernor::set(int n) {
  if (n == current_) return;
  current_ = n;
  apply_(n);
  changes_.push_back({steps_, n});
  skip_ = true;
}

// Half the present count, or double it (at most the start's): up first, when
// it can, after a trial down, so that a run that went down comes back up
// once the cores are free again.
int ThreadGovernor::trial_count() {
  const int down = std::max(1, current_ / 2), up = std::min(max_, current_ * 2);
  if (up == current_) return down;
  if (down == current_) return up;
  try_up_ = !try_up_;
  return try_up_ ? up : down;
}

void ThreadGovernor::step_done(double seconds) {
  ++steps_;
  if (max_ == 1) return;
  if (skip_) {
    skip_ = false;
    return;
  }
  if (phase_ == Phase::hold) {
    held_ += seconds;
    if (held_ >= hold_) {
      phase_ = Phase::measure;
      sum_ = 0;
      count_ = 0;
    }
    return;
  }
  sum_ += seconds;
  ++count_;
  if (sum_ < s_.window_seconds || count_ < s_.window_steps) return;
  const double per_step = sum_ / double(count_);
  sum_ = 0;
  count_ = 0;
  if (phase_ == Phase::measure) {
    reference_ = per_step;
    const int previous = current_;
    candidate_ = trial_count();
    set(candidate_);
    candidate_ = previous;  // where to return to
    phase_ = Phase::trial;
    return;
  }
  // Trial: keep the tried count when faster by the margin, else go back.
  held_ = 0;
  phase_ = Phase::hold;
  if (per_step < (1.0 - s_.margin) * reference_) {
    hold_ = s_.hold;
  } else {
    set(candidate_);
    hold_ = std::min(s_.max_hold, std::max(s_.hold, 2 * hold_));
  }
}

}  // namespace mfsd
