// The thread governor (host/driver/thread_governor.hpp) on model step times:
// an idle machine (t = t1 / n) keeps the start's count and spends little time
// in trials; shared cores where spinning makes two threads slower than one
// (the parameter study of two runs side by side: 2 threads 6x slower than
// one, measured in docs/performance.md) go down to one thread within the
// first second; when the other run ends the count comes back up.
#include <gtest/gtest.h>

#include <functional>

#include "host/driver/thread_governor.hpp"

using namespace mfsd;

namespace {

// Runs `steps` steps whose time is model(threads); returns the steps spent
// at each count (index = threads).
std::vector<long> run(ThreadGovernor& g, const std::function<double(int)>& model, long steps, int max) {
  std::vector<long> at(size_t(max) + 1, 0);
  for (long k = 0; k < steps; ++k) {
    const int n = g.threads();
    ++at[size_t(n)];
    g.step_done(model(n));
  }
  return at;
}

}  // namespace

TEST(ThreadGovernor, IdleMachineKeepsTheStartCount) {
  int applied = 2;
  ThreadGovernor g(2, [&](int n) { applied = n; });
  const auto idle = [](int n) { return 100e-6 / n; };
  const auto at = run(g, idle, 200000, 2);  // 10 s of steps at 2 threads
  EXPECT_EQ(g.threads(), 2);
  EXPECT_EQ(applied, 2);
  // Trials at one thread: a window of 0.05 s after 0.05, 2, 4, 8 s ...
  EXPECT_LT(double(at[1]) / double(at[1] + at[2]), 0.04);
}

TEST(ThreadGovernor, SharedCoresGoDownAndComeBack) {
  int applied = 2;
  ThreadGovernor g(2, [&](int n) { applied = n; });
  const auto loaded = [](int n) { return n == 2 ? 600e-6 : 170e-6; };
  long steps = 0;
  double seconds = 0;
  while (g.threads() == 2 && steps < 100000) {
    seconds += loaded(g.threads());
    g.step_done(loaded(g.threads()));
    ++steps;
  }
  EXPECT_EQ(g.threads(), 1);
  EXPECT_EQ(applied, 1);
  EXPECT_LT(seconds, 0.2);  // hold 0.05 s, a window at 2 threads, the trial's window
  // It stays down while the cores are shared ...
  run(g, loaded, 20000, 2);
  EXPECT_EQ(g.threads(), 1);
  // ... and goes back up once they are free (a trial up after at most the hold).
  const auto idle = [](int n) { return 100e-6 / n; };
  run(g, idle, 200000, 2);
  EXPECT_EQ(g.threads(), 2);
  EXPECT_GE(g.changes().size(), 3u);
}

TEST(ThreadGovernor, FindsTheBestOfManyCounts) {
  // 16 threads, best at 4 (another program holds 12 cores): halves until slower.
  ThreadGovernor g(16, [](int) {});
  const auto model = [](int n) { return n <= 4 ? 400e-6 / n : 100e-6 * n; };
  run(g, model, 100000, 16);
  EXPECT_EQ(g.threads(), 4);
}

TEST(ThreadGovernor, OneThreadNeverChanges) {
  int calls = 0;
  ThreadGovernor g(1, [&](int) { ++calls; });
  run(g, [](int) { return 1e-3; }, 10000, 1);
  EXPECT_EQ(calls, 0);
  EXPECT_EQ(g.changes().size(), 1u);
}
