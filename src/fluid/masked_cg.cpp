// Jacobi-preconditioned conjugate gradients (Hestenes & Stiefel 1952) restricted to the free rows of a system.
#include "masked_cg.hpp"

#include <algorithm>
#include <cmath>

namespace lagfsi::fluid {

void masked_jacobi_cg(const SparseMatrix& A, const Vec& k, const std::vector<char>& prescribed, const Vec& b, Vec& y) {
  const Index n = A.rows();
  const auto free_rows = [&](Vec r) {  // r with its prescribed rows zeroed
    for (Index i = 0; i < n; ++i)
      if (prescribed[static_cast<size_t>(i)]) r[i] = 0.0;
    return r;
  };
  const auto apply = [&](const Vec& z) { return free_rows(A * z + k.cwiseProduct(z)); };
  Vec diag = A.diagonal() + k;
  for (Index i = 0; i < n; ++i)
    if (!(diag[i] > 0)) diag[i] = 1.0;  // an empty row (a particle in no element: prescribed)
  double b2 = 0;
  for (Index i = 0; i < n; ++i)
    if (!prescribed[static_cast<size_t>(i)]) b2 += b[i] * b[i];
  const double b_norm = std::sqrt(b2);
  Vec r = free_rows(b - apply(y));
  Vec z = r.cwiseQuotient(diag), p = z;
  double rz = r.dot(z);
  for (int it = 0; it < 500 && r.norm() > 1e-13 * std::max(b_norm, 1e-300); ++it) {
    const Vec q = apply(p);
    const double alpha = rz / p.dot(q);
    y += alpha * p;
    r -= alpha * q;
    z = r.cwiseQuotient(diag);
    const double rz_new = r.dot(z);
    p = z + (rz_new / rz) * p;
    rz = rz_new;
  }
}

}  // namespace lagfsi::fluid
