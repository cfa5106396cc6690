// Device errors name their stage (host/solver/stage_run.hpp), and a step's
// results come to the host in one copy (host/backend/device_results.hpp).
#include <gtest/gtest.h>
#include <thrust/system_error.h>

#include <string>
#include <system_error>

#include "host/backend/algorithms.hpp"
#include "host/backend/cpu.hpp"
#include "host/backend/device_results.hpp"
#include "host/backend/round_trips.hpp"
#include "host/solver/stage_run.hpp"

using namespace mfsd;

namespace {

std::string message_of(void (*f)()) {
  try {
    run_stage<Cpu>("contact", "stress, contact, time_step", f);
  } catch (const BackendError& e) {
    return std::string(e.deferred() ? "deferred: " : "now: ") + e.what();
  }
  return "no error";
}

struct Index2 {
  double operator()(Index i) const { return 2.0 * double(i); }
};
struct Plus {
  double operator()(double a, double b) const { return a + b; }
};
struct MaxPair {
  struct Pair {
    double a;
    long b;
  };
  Pair operator()(Pair x, Pair y) const { return {x.a > y.a ? x.a : y.a, x.b + y.b}; }
};
struct MakePair {
  MaxPair::Pair operator()(Index i) const { return {double(i % 17), 1}; }
};

}  // namespace

TEST(StageRun, AFaultInTheStageNamesIt) {
  const std::string m = message_of([] { throw BackendError("device error: an illegal memory access"); });
  EXPECT_EQ(m, "now: in stage 'contact': device error: an illegal memory access");
}

TEST(StageRun, AThrustErrorBecomesABackendErrorNamingTheStage) {
  const std::string m =
      message_of([] { throw thrust::system_error(int(std::errc::not_enough_memory), thrust::system_category()); });
  EXPECT_EQ(m.rfind("now: in stage 'contact': ", 0), 0u) << m;
}

TEST(StageRun, ADeferredFaultListsTheStepsStagesAndTheCheckedMode) {
  const std::string m = message_of([] { throw BackendError("device error: misaligned address", true); });
  EXPECT_EQ(m.rfind("deferred: device error: misaligned address; found at the step's synchronisation", 0), 0u) << m;
  EXPECT_NE(m.find("(stress, contact, time_step)"), std::string::npos) << m;
  EXPECT_NE(m.find("MFSD_CUDA_SYNC_CHECK=1"), std::string::npos) << m;
}

TEST(StageRun, OtherErrorsPassThrough) {
  EXPECT_THROW(run_stage<Cpu>("stress", "stress", [] { throw std::invalid_argument("x"); }), std::invalid_argument);
  EXPECT_NO_THROW(run_stage<Cpu>("stress", "stress", [] {}));
}

TEST(DeviceResults, AStepsReductionsComeBackInOneRoundTrip) {
  DeviceResults<Cpu> results;
  for (int step = 0; step < 3; ++step) {  // slots are reused step after step
    results.clear();
    const auto sum = results.reduce(Index(0), Index(1000), Index2{}, 0.0, Plus{});
    const auto pair = results.reduce(Index(0), Index(500 + step), MakePair{}, MaxPair::Pair{-1.0, 0}, MaxPair{});
    const auto empty = results.reduce(Index(4), Index(4), Index2{}, 3.25, Plus{});
    const long before = round_trips();
    results.fetch();
    EXPECT_EQ(round_trips() - before, 1);
    EXPECT_EQ(results.get(sum), 999.0 * 1000.0);
    EXPECT_EQ(results.get(pair).a, 16.0);
    EXPECT_EQ(results.get(pair).b, 500 + step);
    EXPECT_EQ(results.get(empty), 3.25);
  }
}

TEST(DeviceResults, ManySlotsGrowTheBufferWithoutLosingEarlierOnes) {
  DeviceResults<Cpu> results;
  std::vector<ResultSlot<double>> slots;
  for (Index k = 0; k < 2000; ++k) slots.push_back(results.reduce(Index(0), k, Index2{}, 0.0, Plus{}));
  results.fetch();
  for (Index k = 0; k < 2000; ++k) ASSERT_EQ(results.get(slots[size_t(k)]), double(k) * double(k - 1)) << k;
}
