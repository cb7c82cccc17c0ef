#pragma once
// Model linear systems the solver tests share (src/core/tests, tests/mpi): a shifted grid Laplacian, a
// saddle-point system with the PSPG Newton matrix's structure, and reproducible right-hand sides.
#include <lagfsi/types.hpp>

#include <random>
#include <vector>

namespace lagfsi::testing {

/// 5-point Laplacian on an n x n grid (Dirichlet boundary eliminated) plus `shift` on the diagonal.
/// Eigenvalues are in (shift, 8 + shift): SPD for shift > 0, indefinite for shift in (-8, 0).
inline SparseMatrix laplacian(int n, double shift) {
  std::vector<Triplet> t;
  auto id = [n](int i, int j) { return i * n + j; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      t.emplace_back(id(i, j), id(i, j), 4.0 + shift);
      if (i > 0) t.emplace_back(id(i, j), id(i - 1, j), -1.0);
      if (i < n - 1) t.emplace_back(id(i, j), id(i + 1, j), -1.0);
      if (j > 0) t.emplace_back(id(i, j), id(i, j - 1), -1.0);
      if (j < n - 1) t.emplace_back(id(i, j), id(i, j + 1), -1.0);
    }
  SparseMatrix A(n * n, n * n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

/// A stabilized Stokes-like system on an n x n grid with interleaved [u_x u_y p] per node:
///   [ m I + L (x) I2    G ] [u]   [f]
///   [ G^T          -eps L ] [p] = [g]
/// with L the grid Laplacian, G a centred-difference gradient: the structure of the PSPG Newton matrix.
inline SparseMatrix saddle_point(int n, double m, double eps) {
  const SparseMatrix L = laplacian(n, 0.0);
  std::vector<Triplet> t;
  for (int k = 0; k < L.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(L, k); it; ++it) {
      const Index r = it.row(), c = it.col();
      for (int d = 0; d < 2; ++d) t.emplace_back(3 * r + d, 3 * c + d, it.value() + (r == c ? m : 0.0));
      t.emplace_back(3 * r + 2, 3 * c + 2, -eps * it.value());
    }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int a = i * n + j;
      auto add = [&](int b, int d, double w) {
        t.emplace_back(3 * a + d, 3 * b + 2, w);  // G: velocity row, pressure column
        t.emplace_back(3 * b + 2, 3 * a + d, w);  // G^T
      };
      if (i + 1 < n) add(a + n, 0, 0.5);
      if (i > 0) add(a - n, 0, -0.5);
      if (j + 1 < n) add(a + 1, 1, 0.5);
      if (j > 0) add(a - 1, 1, -0.5);
    }
  SparseMatrix A(3 * n * n, 3 * n * n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

/// Uniform values in [-1, 1], the same for the same seed (on every process of an MPI test).
inline Vec random_vector(Index n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> dist(-1.0, 1.0);
  Vec v(n);
  for (Index i = 0; i < n; ++i) v[i] = dist(gen);
  return v;
}

}  // namespace lagfsi::testing
