// Benchmark (not a test): the memory bandwidth one process streams, the STREAM "triad" a[i] = b[i] + s c[i]
// (McCalpin 1995, https://www.cs.virginia.edu/stream/) over three arrays far larger than the caches;
// the median of `repeats` passes (copies started together overlap over most of them), in GB/s counting 24 bytes per i.
// Run one copy alone and P copies at once (tests/bench/bench_mpi.py does both) to see whether P processes share the
// bandwidth (each copy slower) or each has its own.
//
// usage: bench_bandwidth [doubles=40000000] [repeats=30]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

int main(int argc, char** argv) {
  const long n = argc > 1 ? std::atol(argv[1]) : 40000000L;
  const int repeats = argc > 2 ? std::atoi(argv[2]) : 30;
  if (n < 1 || repeats < 1) {
    std::fprintf(stderr, "usage: bench_bandwidth [doubles=40000000] [repeats=30]\n");
    return 2;
  }
  std::vector<double> a(static_cast<size_t>(n), 0.0), b(static_cast<size_t>(n), 1.0), c(static_cast<size_t>(n), 2.0);
  std::vector<double> seconds;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    for (long i = 0; i < n; ++i)
      a[static_cast<size_t>(i)] = b[static_cast<size_t>(i)] + 3.0 * c[static_cast<size_t>(i)];
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    seconds.push_back(s);
  }
  std::nth_element(seconds.begin(), seconds.begin() + repeats / 2, seconds.end());
  const double median = seconds[static_cast<size_t>(repeats / 2)];
  // a[n / 2] printed so that the loop is not optimized away.
  std::printf("%.2f GB/s (check %g)\n", 24.0 * static_cast<double>(n) / median / 1e9, a[static_cast<size_t>(n / 2)]);
  return 0;
}
