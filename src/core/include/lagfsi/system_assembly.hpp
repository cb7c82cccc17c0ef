#pragma once
/// @file system_assembly.hpp
/// The small pieces every implicit model repeats around its linear solve (the "builder" half of Kratos's
/// builder-and-solver split; the solver half is linear_solver.hpp):
///  - dirichlet_identity(): the rows and columns of prescribed dofs become those of the identity, so that the
///    correction of a prescribed dof is zero and the matrix keeps its symmetry (the residual's entries of
///    those dofs are zeroed by the caller or by the overload that takes it);
///  - combine_tangent(): the tangent of an implicit time step, H = c_k K + c_m M + c_c C, formed in place of
///    K's values when K, M and C share one sparsity pattern (a consistent mass), or with a lumped (diagonal)
///    mass; c_m, c_c, c_k are the integrator's coefficients (time_integrator.hpp).
/// Each is written once here; the solid, the fluid's two schemes, the implicit MPM and the EFG body use them.
#include <lagfsi/types.hpp>

#include <vector>

namespace lagfsi {

/// Rows and columns of the dofs with fixed(i) true become those of the identity (1 on the diagonal, 0
/// elsewhere); every other stored entry is handed to other(row, col, value) to change it if it wants (scale a
/// block, add to the diagonal). Entries outside A's pattern are not created: a prescribed dof needs its
/// diagonal in the pattern.
template <class Fixed, class Other>
void dirichlet_identity(SparseMatrix& A, const Fixed& fixed, const Other& other) {
  for (int col = 0; col < A.outerSize(); ++col)
    for (SparseMatrix::InnerIterator it(A, col); it; ++it) {
      if (fixed(it.row()) || fixed(it.col()))
        it.valueRef() = it.row() == it.col() ? 1.0 : 0.0;
      else
        other(it.row(), it.col(), it.valueRef());
    }
}

/// The same, the other entries left as they are.
template <class Fixed>
void dirichlet_identity(SparseMatrix& A, const Fixed& fixed) {
  dirichlet_identity(A, fixed, [](Index, Index, double&) {});
}

/// A mask of the prescribed dofs (fixed[i] != 0): identity rows and columns in A, and r[i] = 0.
void dirichlet_identity(SparseMatrix& A, Vec& r, const std::vector<char>& fixed);

/// H = c_k K + c_m M (+ c_c C) written over K's values (K, M and, when given, C on the same pattern, entry by
/// entry: h = c_k k + c_m m, then h += c_c c).
void combine_tangent(SparseMatrix& K, double c_k, double c_m, const SparseMatrix& M, double c_c = 0.0,
                     const SparseMatrix* C = nullptr);

/// H = c_k K + c_m diag(m_I, m_I) for a lumped mass of one value per node and two dofs per node (2 I, 2 I + 1),
/// written over K (a diagonal entry missing from K's pattern is inserted).
void combine_tangent_lumped(SparseMatrix& K, double c_k, double c_m, const Vec& node_mass);

}  // namespace lagfsi
