#pragma once
/// @file parallel_sum.hpp
/// Sums of parallel loops that are the same from run to run for a given number of threads.
///
/// Floating-point addition is not associative: a sum depends on the order of its terms. An OpenMP
/// `reduction(+ : ...)` adds the threads' partial sums in the order the threads happen to finish, and `atomic`
/// additions into a shared array land in the order the threads happen to reach them, so both give results that
/// differ in the last digits from one run to the next, which an unstable flow (a splash) amplifies. The rule
/// used instead: every loop that sums has schedule(static) (a thread's share of the iterations depends only on
/// the number of threads), each thread sums its share on its own, in iteration order, and the threads' partials
/// are combined in thread order (0, 1, 2, ...). With one thread each sum is that of the serial loop, term for
/// term.
///  - ThreadSums: scalar reductions (an energy, a norm);
///  - ThreadScatter: additions of a loop over elements (or particles, cells) into shared arrays (nodal vectors,
///    a sparse matrix's values): thread 0 adds into the arrays themselves, every other thread into zeroed
///    copies of its own, which merge() adds to the arrays in thread order.
#include <lagfsi/types.hpp>

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace lagfsi {

/// Threads a parallel region may have (1 without OpenMP).
inline int max_parallel_threads() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

/// The calling thread's number in its team (0 outside a parallel region and without OpenMP).
inline int parallel_thread_index() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

/// The values of a vector or of a sparse matrix (on its fixed pattern), as a ThreadScatter target.
inline std::span<double> values_of(Vec& v) { return {v.data(), static_cast<size_t>(v.size())}; }
inline std::span<double> values_of(SparseMatrix& A) { return {A.valuePtr(), static_cast<size_t>(A.nonZeros())}; }

/// N sums over a parallel region: each thread accumulates its share into local variables and stores them with
/// mine() at the end of the region; total(k) adds the threads' partials in thread order.
template <int N = 1>
class ThreadSums {
 public:
  ThreadSums() : slots_(static_cast<size_t>(max_parallel_threads())) {}
  /// The calling thread's partials (zero until it stores them).
  std::array<double, N>& mine() { return slots_[static_cast<size_t>(parallel_thread_index())].v; }
  double total(int k = 0) const {
    double s = 0.0;
    for (const Slot& slot : slots_) s += slot.v[static_cast<size_t>(k)];
    return s;
  }

 private:
  struct alignas(64) Slot {  // one cache line per thread
    std::array<double, N> v{};
  };
  std::vector<Slot> slots_;
};

/// Additions of a parallel loop into shared arrays, in an order that depends only on the number of threads.
/// Usage:
///   ThreadScatter scatter({values_of(R), values_of(K)});  // the arrays the loop adds into
///   #pragma omp parallel if (...)
///   {
///     const auto out = scatter.arrays();                  // this thread's arrays, in the order given
///   #pragma omp for schedule(static) nowait                // the region's end is the one barrier
///     for (...) out[0][i] += ...;
///   }
///   scatter.merge();
/// A ThreadScatter kept between calls reuses its copies (set the arrays again with targets()). A loop followed by
/// nothing but the end of its region takes `nowait`: on a loaded machine each barrier of spinning threads (the
/// loop's, then the region's) can cost a time slice.
class ThreadScatter {
 public:
  ThreadScatter() = default;
  explicit ThreadScatter(std::vector<std::span<double>> targets) { this->targets(std::move(targets)); }

  /// The arrays the next loop adds into.
  void targets(std::vector<std::span<double>> targets) {
    targets_ = std::move(targets);
    const size_t nt = static_cast<size_t>(max_parallel_threads());
    if (copies_.size() < nt) copies_.resize(nt);
    pointers_.assign(nt, std::vector<double*>(targets_.size(), nullptr));
    used_.assign(nt, 0);
  }

  /// Called once by each thread of the region before its loop: the arrays it adds into (the targets themselves
  /// for thread 0, zeroed copies for the others).
  std::span<double* const> arrays() {
    const size_t t = static_cast<size_t>(parallel_thread_index());
    std::vector<double*>& p = pointers_[t];
    if (t == 0) {
      for (size_t k = 0; k < targets_.size(); ++k) p[k] = targets_[k].data();
    } else {
      std::vector<std::vector<double>>& mine = copies_[t];
      if (mine.size() < targets_.size()) mine.resize(targets_.size());
      for (size_t k = 0; k < targets_.size(); ++k) {
        mine[k].assign(targets_[k].size(), 0.0);
        p[k] = mine[k].data();
      }
      used_[t] = 1;
    }
    return p;
  }

  /// After the region: adds the copies of threads 1, 2, ... into the targets, in that order, entry by entry
  /// (serially but for very long arrays: a merge inside the region would cost a second barrier, and on a loaded
  /// machine a barrier can cost a time slice).
  void merge() {
    for (size_t k = 0; k < targets_.size(); ++k) {
      double* out = targets_[k].data();
      const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(targets_[k].size());
      std::vector<const double*> from;
      for (size_t t = 1; t < used_.size(); ++t)
        if (used_[t]) from.push_back(copies_[t][k].data());
      if (from.empty()) continue;
#pragma omp parallel for schedule(static) if (n >= (1 << 20))
      for (std::ptrdiff_t i = 0; i < n; ++i)
        for (const double* c : from) out[i] += c[i];
    }
    used_.assign(used_.size(), 0);
  }

 private:
  std::vector<std::span<double>> targets_;
  std::vector<std::vector<std::vector<double>>> copies_;  // [thread][target]
  std::vector<std::vector<double*>> pointers_;            // [thread][target]
  std::vector<char> used_;                                // the thread wrote copies in this loop
};

}  // namespace lagfsi
