// The CPU backend's algorithms against std:: references, with 1 and 2 threads.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "host/backend/algorithms.hpp"
#include "host/backend/cpu.hpp"

using namespace mfsd;

namespace {
struct Square {
  const double* x;
  double operator()(Index i) const { return x[i] * x[i]; }
};
struct Max {
  double operator()(double a, double b) const { return std::max(a, b); }
};
struct Plus {
  double operator()(double a, double b) const { return a + b; }
};
struct Write {
  Index* out;
  void operator()(Index i) const { out[i] = 3 * i; }
};
}  // namespace

class CpuBackend : public ::testing::TestWithParam<int> {
 protected:
  void SetUp() override { omp_set_num_threads(GetParam()); }
};

TEST_P(CpuBackend, ParallelForVisitsEveryIndexOnce) {
  DeviceVector<Cpu, Index> v(1000, -1);
  parallel_for<Cpu>(Index(10), Index(1000), Write{raw(v)});
  const auto h = to_host<Cpu>(v);
  for (Index i = 0; i < 1000; ++i) EXPECT_EQ(h[size_t(i)], i < 10 ? -1 : 3 * i);
}

TEST_P(CpuBackend, ReductionsMatchStd) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double> x(10007);
  for (auto& e : x) e = u(rng);
  DeviceVector<Cpu, double> d;
  from_host<Cpu>(x, d);
  double ref_sum = 0, ref_max = 0;
  for (double e : x) ref_sum += e * e, ref_max = std::max(ref_max, e * e);
  EXPECT_NEAR(transform_reduce<Cpu>(0, Index(x.size()), Square{raw(d)}, 0.0, Plus{}), ref_sum, 1e-9);
  EXPECT_EQ(transform_reduce<Cpu>(0, Index(x.size()), Square{raw(d)}, 0.0, Max{}), ref_max);
  EXPECT_EQ(transform_reduce<Cpu>(5, Index(5), Square{raw(d)}, 7.0, Max{}), 7.0);  // empty range
}

TEST_P(CpuBackend, SortGatherAndScan) {
  std::vector<std::int64_t> keys(5000);
  std::mt19937 rng(9);
  for (auto& k : keys) k = std::int64_t(rng() % 300);
  DeviceVector<Cpu, std::int64_t> dk;
  from_host<Cpu>(keys, dk);
  DeviceVector<Cpu, Index> perm(keys.size());
  sequence<Cpu, Index>(perm);
  sort_by_key<Cpu, std::int64_t, Index>(dk, perm);
  const auto sk = to_host<Cpu>(dk);
  const auto p = to_host<Cpu>(perm);
  EXPECT_TRUE(std::is_sorted(sk.begin(), sk.end()));
  for (size_t i = 0; i < keys.size(); ++i) EXPECT_EQ(sk[i], keys[size_t(p[i])]);
  // gather puts the original keys in sorted order.
  DeviceVector<Cpu, std::int64_t> original, gathered(keys.size());
  from_host<Cpu>(keys, original);
  gather<Cpu, std::int64_t>(perm, original, gathered);
  EXPECT_EQ(to_host<Cpu>(gathered), sk);
  // exclusive scan with a wider output type, and its total.
  std::vector<Index> counts(keys.size());
  for (size_t i = 0; i < counts.size(); ++i) counts[i] = Index(keys[i]);
  DeviceVector<Cpu, Index> dc;
  from_host<Cpu>(counts, dc);
  DeviceVector<Cpu, PairIndex> offsets(counts.size() + 1);
  const PairIndex total = exclusive_scan<Cpu, Index, PairIndex>(dc, offsets);
  const auto o = to_host<Cpu>(offsets);
  PairIndex run = 0;
  for (size_t i = 0; i < counts.size(); ++i) {
    EXPECT_EQ(o[i], run);
    run += counts[i];
  }
  EXPECT_EQ(total, run);
}

// The half-pair loop against the full gather on a 1-D chain of n points,
// pairs |i - j| <= w, pair value (j - i) * (i + j + 1), antisymmetric in a
// shared factor: a_i = sum_j s_ij c_ij with c_ij = (i + j + 1), s_ij = j - i.
// w from 1 (neighbours in the same block) to n (every block's buffer reaches
// every later block); every element gets exactly its own sum.
struct ChainRow {
  Index n, w;
  void operator()(Index i, const HalfPairSink<double>& sink) const {
    double own = 0;
    for (Index j = i + 1; j <= std::min(n - 1, i + w); ++j) {
      const double c = double(i + j + 1), s = double(j - i);
      own += s * c;         // to i
      sink.add(j, -s * c);  // to j: s_ji = -s_ij
    }
    sink.add(i, own);
  }
};

TEST_P(CpuBackend, HalfPairLoopMatchesTheFullGather) {
  const Index n = 101;
  for (int threads : {GetParam(), 5})
    for (Index w : {1, 3, 20, 60, 100}) {
      omp_set_num_threads(threads);
      DeviceVector<Cpu, double> acc(size_t(n), -99.0), out(size_t(n), -99.0);
      std::vector<double> workspace;
      double* o = raw(out);
      half_pair_for(Cpu{}, Index(0), n, w, 0.0, raw(acc), workspace, ChainRow{n, w},
                    [o](Index i, double total) { o[i] = total; });
      const auto h = to_host<Cpu>(out);
      for (Index i = 0; i < n; ++i) {
        double expected = 0;
        for (Index j = std::max(Index(0), i - w); j <= std::min(n - 1, i + w); ++j)
          if (j != i) expected += double(j - i) * double(i + j + 1);
        EXPECT_EQ(h[size_t(i)], expected) << threads << " threads, w " << w << ", i " << i;  // integers: exact
      }
    }
  // A sub-range leaves the rest alone.
  DeviceVector<Cpu, double> acc(20, -1.0), out(20, -1.0);
  std::vector<double> workspace;
  double* o = raw(out);
  half_pair_for(Cpu{}, Index(5), Index(15), Index(0), 0.0, raw(acc), workspace, ChainRow{0, 0},
                [o](Index i, double total) { o[i] = total; });
  const auto h = to_host<Cpu>(out);
  for (Index i = 0; i < 20; ++i) EXPECT_EQ(h[size_t(i)], i >= 5 && i < 15 ? 0.0 : -1.0);
}

INSTANTIATE_TEST_SUITE_P(Threads, CpuBackend, ::testing::Values(1, 2));

namespace {
// Counts its calls per element (a side effect a pure transform_reduce may not have).
struct CountingSquare {
  Index* calls;
  double operator()(Index i) const {
    ++calls[i];
    return double(i) * double(i);
  }
};
}  // namespace

TEST_P(CpuBackend, ParallelReduceCallsEachIndexExactlyOnce) {
  const Index n = 10007;
  DeviceVector<Cpu, Index> calls(size_t(n), 0);
  DeviceVector<Cpu, double> out(1, -1.0);
  parallel_reduce<Cpu>(Index(3), n, CountingSquare{raw(calls)}, 0.0, Plus{}, raw(out));
  const auto c = to_host<Cpu>(calls);
  for (Index i = 0; i < n; ++i) ASSERT_EQ(c[size_t(i)], i < 3 ? 0 : 1) << "element " << i;
  double expected = 0;
  for (Index i = 3; i < n; ++i) expected += double(i) * double(i);
  EXPECT_NEAR(to_host<Cpu>(out)[0], expected, 1e-12 * expected);
  // The same result with the same thread count, run after run.
  DeviceVector<Cpu, double> again(1, -1.0);
  parallel_reduce<Cpu>(Index(3), n, CountingSquare{raw(calls)}, 0.0, Plus{}, raw(again));
  EXPECT_EQ(to_host<Cpu>(again)[0], to_host<Cpu>(out)[0]);
}

TEST_P(CpuBackend, ParallelReduceOfAnEmptyRangeIsInit) {
  DeviceVector<Cpu, Index> calls(4, 0);
  DeviceVector<Cpu, double> out(1, -1.0);
  parallel_reduce<Cpu>(Index(2), Index(2), CountingSquare{raw(calls)}, -7.5, Max{}, raw(out));
  EXPECT_EQ(to_host<Cpu>(out)[0], -7.5);
}
