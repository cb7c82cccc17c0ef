#pragma once
/// @file masked_cg.hpp (private to src/fluid)
/// Conjugate gradients on the rows of a symmetric positive definite system that are not prescribed, for the
/// fractional step's consistent mass matrix (fractional_step.cpp).
#include <lagfsi/types.hpp>

#include <vector>

namespace lagfsi::fluid {

/// Solves (A + diag(k)) y = b in the rows i with prescribed[i] == 0; the prescribed entries of y are given and enter
/// the other rows' sums. Preconditioned by the diagonal (Jacobi); stops at a residual of 1e-13 |b| over the free rows
/// or after 500 iterations. For a P1 mass matrix the eigenvalues of diag(M)^-1 M lie in [1/2, 2], so the iterations
/// do not grow with the mesh.
void masked_jacobi_cg(const SparseMatrix& A, const Vec& k, const std::vector<char>& prescribed, const Vec& b, Vec& y);

}  // namespace lagfsi::fluid
