// The CPU thread count of a run chosen by measuring, while it runs, when the
// user fixed none (--threads, OMP_NUM_THREADS). OpenMP's waiting threads spin
// at every barrier of a step; where another program keeps the cores busy (two
// runs of a parameter study side by side) the spinning threads take the
// cores from the working ones and a step costs several times more than with
// fewer threads (docs/performance.md, "Shared cores"). The governor times the
// steps at the present count, then a window at a neighbouring count (half, or
// double up to the start's), and keeps whichever is faster by a margin; it
// tries again after a hold that doubles while nothing changes. On an idle
// machine it costs the trial windows at the lower count.
//
// Results depend on the thread count at round-off only (the reductions'
// partial sums), so a governed run is not bit for bit repeatable: give
// --threads for that.
#pragma once
#include <functional>
#include <vector>

namespace mfsd {

class ThreadGovernor {
 public:
  struct Settings {
    double window_seconds = 0.05;  // of step time, per measurement
    long window_steps = 5;        // and at least this many steps
    double first_hold = 0.05;     // step seconds before the first trial
    double hold = 2.0;            // after a change; doubles while nothing changes
    double max_hold = 32.0;
    double margin = 0.25;  // a trial count is kept when its step is this much faster
  };
  struct Change {
    long step;  // the governor's step count when the count changed
    int threads;
  };

  // `start`: the count to begin with and never exceed; `apply` sets a count.
  ThreadGovernor(int start, std::function<void(int)> apply) : ThreadGovernor(start, std::move(apply), Settings{}) {}
  ThreadGovernor(int start, std::function<void(int)> apply, Settings settings);

  // After each step, with its wall seconds (the step's own, not the outputs').
  void step_done(double seconds);
  int threads() const { return current_; }
  // Every count it ran with, from the start's (trials that were not kept included).
  const std::vector<Change>& changes() const { return changes_; }

 private:
  enum class Phase { hold, measure, trial };
  void set(int n);
  int trial_count();

  Settings s_;
  std::function<void(int)> apply_;
  int max_, current_, candidate_ = 0;
  bool try_up_ = true;
  Phase phase_ = Phase::hold;
  double hold_, held_ = 0;
  double sum_ = 0, reference_ = 0;
  long count_ = 0, steps_ = 0;
  bool skip_ = false;  // the first step after a change (the team's start)
  std::vector<Change> changes_;
};

}  // namespace mfsd
