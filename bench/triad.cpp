// STREAM-like triad a[i] = b[i] + s c[i] on OpenMP threads: the sustainable
// memory bandwidth the roofline suite compares the TLSPH stages against.
// Counts 24 bytes per element (two reads, one write), as STREAM does.
// Usage: mfsd_triad [--threads N] [--elements N] [--repeats N]; prints JSON.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

int main(int argc, char** argv) {
  long elements = 20'000'000;  // 3 x 160 MB, far beyond the last-level cache
  int repeats = 20;
  int threads = omp_get_max_threads();
  for (int k = 1; k + 1 < argc; k += 2) {
    if (!std::strcmp(argv[k], "--threads"))
      threads = std::atoi(argv[k + 1]);
    else if (!std::strcmp(argv[k], "--elements"))
      elements = std::atol(argv[k + 1]);
    else if (!std::strcmp(argv[k], "--repeats"))
      repeats = std::atoi(argv[k + 1]);
    else {
      std::fprintf(stderr, "mfsd_triad: unknown option %s\n", argv[k]);
      return 2;
    }
  }
  if (threads < 1 || elements < 1000 || repeats < 1) {
    std::fprintf(stderr, "mfsd_triad: expected threads >= 1, elements >= 1000, repeats >= 1\n");
    return 2;
  }
  omp_set_num_threads(threads);
  std::unique_ptr<double[]> a(new double[size_t(elements)]), b(new double[size_t(elements)]),
      c(new double[size_t(elements)]);
  // First touch by the threads that use the data.
#pragma omp parallel for schedule(static)
  for (long i = 0; i < elements; ++i) a[i] = 0.0, b[i] = 1.0, c[i] = 2.0;
  const double s = 3.0;
  std::vector<double> gbs;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
#pragma omp parallel for schedule(static)
    for (long i = 0; i < elements; ++i) a[i] = b[i] + s * c[i];
    const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    gbs.push_back(24.0 * double(elements) / sec * 1e-9);
  }
  if (a[elements / 2] != 7.0) {
    std::fprintf(stderr, "mfsd_triad: wrong result\n");
    return 1;
  }
  std::vector<double> sorted = gbs;
  std::sort(sorted.begin(), sorted.end());
  std::printf(
      "{\"threads\": %d, \"elements\": %ld, \"bytes_per_element\": 24, \"repeats\": %d, "
      "\"best_gb_per_s\": %.3f, \"median_gb_per_s\": %.3f}\n",
      threads, elements, repeats, sorted.back(), sorted[sorted.size() / 2]);
  return 0;
}
