#pragma once
/// @file element_loop.hpp (private to src/fluid)
/// The fractional step's element sums over threads (fractional_step.cpp).
#include <lagfsi/parallel_sum.hpp>
#include <lagfsi/types.hpp>

#include <span>
#include <utility>
#include <vector>

namespace lagfsi::fluid {

/// The number of elements from which the element loops run on several threads.
inline constexpr Index kParallelElements = 2000;

/// Runs body(e, out) for every element, in parallel above a size where threads pay: the body adds into
/// out[k], the calling thread's array for targets[k] (ThreadScatter: the sums are the same in every run with the
/// same number of threads, and on one thread those of the serial loop).
template <class Body>
void element_loop(Index ne, ThreadScatter& scatter, std::vector<std::span<double>> targets, const Body& body) {
  scatter.targets(std::move(targets));
#pragma omp parallel if (ne >= kParallelElements)
  {
    const std::span<double* const> out = scatter.arrays();
#pragma omp for schedule(static) nowait
    for (Index e = 0; e < ne; ++e) body(e, out);
  }
  scatter.merge();
}

}  // namespace lagfsi::fluid
