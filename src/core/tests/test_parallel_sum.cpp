// Unit tests of the fixed-order sums of parallel loops (parallel_sum.hpp): on one thread the sums are the serial
// loop's, term for term; on two threads each thread sums its static share in iteration order and the shares are
// added in thread order, the same in every run.
#include <lagfsi/parallel_sum.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

using namespace lagfsi;

namespace {

constexpr Index kTerms = 5001;  // odd: the two threads' shares differ in length
constexpr Index kBins = 7;

/// Term i of the loop: added to bin i % kBins (values of very different sizes, so that the order shows).
double term(Index i) { return std::sin(0.37 * static_cast<double>(i)) * std::pow(10.0, static_cast<double>(i % 13)); }

struct Sums {
  Vec bins;
  double total = 0;
};

/// The loop over the terms with `threads` threads, through ThreadScatter and ThreadSums.
Sums parallel_sums(int threads) {
#ifdef _OPENMP
  omp_set_num_threads(threads);
#else
  (void)threads;
#endif
  Sums s;
  s.bins = Vec::Zero(kBins);
  ThreadScatter scatter({values_of(s.bins)});
  ThreadSums<> total;
#pragma omp parallel
  {
    double* const bins = scatter.arrays()[0];
    double sum = 0;
#pragma omp for schedule(static)
    for (Index i = 0; i < kTerms; ++i) {
      bins[i % kBins] += term(i);
      sum += term(i);
    }
    total.mine()[0] = sum;
  }
  scatter.merge();
  s.total = total.total();
  return s;
}

/// The serial loop over [begin, end).
Sums serial_sums(Index begin, Index end) {
  Sums s;
  s.bins = Vec::Zero(kBins);
  for (Index i = begin; i < end; ++i) {
    s.bins[i % kBins] += term(i);
    s.total += term(i);
  }
  return s;
}

TEST(ParallelSum, OneThreadGivesTheSerialLoopsSums) {
  const Sums p = parallel_sums(1), s = serial_sums(0, kTerms);
  EXPECT_EQ(p.total, s.total);
  for (Index b = 0; b < kBins; ++b) EXPECT_EQ(p.bins[b], s.bins[b]) << "bin " << b;
}

#ifdef _OPENMP
TEST(ParallelSum, TwoThreadsAddTheirStaticSharesInThreadOrder) {
  // schedule(static) gives thread 0 the first ceil(n / 2) iterations and thread 1 the rest.
  const Index half = (kTerms + 1) / 2;
  const Sums first = serial_sums(0, half), second = serial_sums(half, kTerms);
  for (int run = 0; run < 20; ++run) {
    const Sums p = parallel_sums(2);
    ASSERT_EQ(p.total, first.total + second.total) << "run " << run;
    for (Index b = 0; b < kBins; ++b) ASSERT_EQ(p.bins[b], first.bins[b] + second.bins[b]) << "bin " << b;
  }
}
#endif

}  // namespace
