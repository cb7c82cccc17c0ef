// The repeated pieces around a linear solve (src/core/include/lagfsi/system_assembly.hpp).
#include <lagfsi/system_assembly.hpp>

#include <stdexcept>

namespace lagfsi {

void dirichlet_identity(SparseMatrix& A, Vec& r, const std::vector<char>& fixed) {
  dirichlet_identity(A, [&](Index i) { return fixed[i] != 0; });
  for (Index i = 0; i < r.size(); ++i)
    if (fixed[i]) r[i] = 0.0;
}

void combine_tangent(SparseMatrix& K, double c_k, double c_m, const SparseMatrix& M, double c_c,
                     const SparseMatrix* C) {
  if (M.nonZeros() != K.nonZeros() || (C && C->nonZeros() != K.nonZeros()))
    throw std::invalid_argument("combine_tangent: K, M and C must share one sparsity pattern");
  double* h = K.valuePtr();
  const double* m = M.valuePtr();
  const double* c = C ? C->valuePtr() : nullptr;
  for (Index i = 0; i < K.nonZeros(); ++i) {
    h[i] = c_k * h[i] + c_m * m[i];
    if (c) h[i] += c_c * c[i];
  }
}

void combine_tangent_lumped(SparseMatrix& K, double c_k, double c_m, const Vec& node_mass) {
  K *= c_k;
  for (Index I = 0; I < node_mass.size(); ++I)
    for (int c = 0; c < 2; ++c) {
      const Index d = 2 * I + c;
      K.coeffRef(d, d) += c_m * node_mass[I];
    }
}

}  // namespace lagfsi
