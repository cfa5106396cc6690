// Compute roof of one core for the roofline suite: the throughput of
// independent 4-wide double fused multiply-adds (ten chains, enough to fill
// two FMA pipes of latency 4-5), and the rate of one dependent chain, which
// gives the core clock when the FMA latency is known (4 cycles on AMD Zen 3/4
// and Intel since Skylake).
// Usage: mfsd_fma_peak [--iterations N] [--latency L]; prints JSON.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>

typedef double V4 __attribute__((vector_size(32)));

namespace {

// The empty asm keeps every chain in a register and stops the compiler from
// folding or reordering the multiply-adds across iterations.
#define MFSD_FMA_STEP(x) x = x * m + c;

double independent_rate(long n) {
  V4 a0 = {1, 1, 1, 1}, a1 = a0 * 2, a2 = a0 * 3, a3 = a0 * 4, a4 = a0 * 5, a5 = a0 * 6, a6 = a0 * 7, a7 = a0 * 8,
     a8 = a0 * 9, a9 = a0 * 10;
  const V4 m = {1.0000000001, 1, 1, 1}, c = {1e-10, 0, 0, 0};
  const auto t0 = std::chrono::steady_clock::now();
  for (long i = 0; i < n; ++i) {
    MFSD_FMA_STEP(a0)
    MFSD_FMA_STEP(a1)
    MFSD_FMA_STEP(a2)
    MFSD_FMA_STEP(a3)
    MFSD_FMA_STEP(a4)
    MFSD_FMA_STEP(a5)
    MFSD_FMA_STEP(a6)
    MFSD_FMA_STEP(a7)
    MFSD_FMA_STEP(a8)
    MFSD_FMA_STEP(a9)
    asm volatile(""
                 : "+v"(a0), "+v"(a1), "+v"(a2), "+v"(a3), "+v"(a4), "+v"(a5), "+v"(a6), "+v"(a7), "+v"(a8), "+v"(a9));
  }
  const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const V4 sum = a0 + a1 + a2 + a3 + a4 + a5 + a6 + a7 + a8 + a9;
  if (!(sum[0] > 0)) std::abort();
  return 10.0 * double(n) / sec;
}

double dependent_rate(long n) {
  V4 a0 = {1, 1, 1, 1};
  const V4 m = {1.0000000001, 1, 1, 1}, c = {1e-10, 0, 0, 0};
  const auto t0 = std::chrono::steady_clock::now();
  for (long i = 0; i < n; ++i) {
    MFSD_FMA_STEP(a0)
    asm volatile("" : "+v"(a0));
  }
  const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!(a0[0] > 0)) std::abort();
  return double(n) / sec;
}

}  // namespace

int main(int argc, char** argv) {
  long iterations = 100'000'000;
  int latency = 4;
  for (int k = 1; k + 1 < argc; k += 2) {
    if (!std::strcmp(argv[k], "--iterations"))
      iterations = std::atol(argv[k + 1]);
    else if (!std::strcmp(argv[k], "--latency"))
      latency = std::atoi(argv[k + 1]);
    else {
      std::fprintf(stderr, "mfsd_fma_peak: unknown option %s\n", argv[k]);
      return 2;
    }
  }
  if (iterations < 1000 || latency < 1) {
    std::fprintf(stderr, "mfsd_fma_peak: expected iterations >= 1000, latency >= 1\n");
    return 2;
  }
  double best_independent = 0, best_dependent = 0;  // best of three: the VM steals time
  for (int r = 0; r < 3; ++r) {
    best_independent = std::max(best_independent, independent_rate(iterations));
    best_dependent = std::max(best_dependent, dependent_rate(iterations));
  }
  const double clock = best_dependent * latency;
  std::printf(
      "{\"fma4_per_second\": %.4g, \"dependent_fma_per_second\": %.4g, \"assumed_fma_latency\": %d, "
      "\"clock_ghz\": %.3f, \"fma4_per_cycle\": %.3f}\n",
      best_independent, best_dependent, latency, clock * 1e-9, best_independent / clock);
  return 0;
}
