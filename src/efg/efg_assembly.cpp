// EFG assembly (thesis Algorithms 2-4, Eqs. 4.15-4.16): per background cell, the Gauss points' B^T E B w and
// B^T sigma w on the union of the cell's supports, scattered into the fixed CSC pattern; the essential-condition
// terms (penalty, Lagrange rows); elimination of the dofs held directly (coupling) and the solves.
// See src/efg/include/lagfsi/efg/efg_model.hpp.
#include <lagfsi/efg/efg_model.hpp>
#include <lagfsi/error.hpp>
#include <lagfsi/parallel_sum.hpp>
#include <lagfsi/system_assembly.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <span>
#include <vector>

namespace lagfsi::efg {

void EfgModel::assemble(const Vec& x, Vec& fint, bool with_matrix) {
  fint = Vec::Zero(nsys_);
  if (with_matrix) std::fill(K_.valuePtr(), K_.valuePtr() + K_.nonZeros(), 0.0);
  const Index nc = mesh_.num_cells();
  hist1_.resize(gps_.size());
  const int* outer = K_.outerIndexPtr();
  const int* inner = K_.innerIndexPtr();
  // Cells in parallel, chunks of 4 dealt round-robin (cells differ in cost; a fixed deal keeps the sums the same
  // in every run with the same threads): each thread adds its cells into its own copy of fint and of K's values,
  // merged in thread order (parallel_sum.hpp; on one thread, the serial loop's sums).
  std::vector<std::span<double>> targets{values_of(fint)};
  if (with_matrix) targets.push_back(values_of(K_));
  ThreadScatter scatter(std::move(targets));
#pragma omp parallel
  {
    const std::span<double* const> out = scatter.arrays();
    double* const ft = out[0];
    double* const kt = with_matrix ? out[1] : nullptr;
    Eigen::MatrixXd Kc, B;
    Eigen::VectorXd fc, ue;
#pragma omp for schedule(static, 4) nowait
    for (Index c = 0; c < nc; ++c) {
      const auto& cn = cell_nodes_[c];
      const int m = 2 * static_cast<int>(cn.size());
      if (with_matrix) Kc.setZero(m, m);
      fc.setZero(m);
      const Material& mat = cell_material_[c] < 0 ? *material_ : *region_materials_[cell_material_[c]];
      for (Index g = cell_gp_begin_[c]; g < cell_gp_begin_[c + 1]; ++g) {
        const GaussPoint& gp = gps_[g];
        const int n = gp.n;
        B.setZero(3, 2 * n);
        Vec3 eps = Vec3::Zero();
        for (int k = 0; k < n; ++k) {
          const Index i = gp.begin + k;
          const double nx = gNx_[i], ny = gNy_[i];
          B(0, 2 * k) = nx;
          B(1, 2 * k + 1) = ny;
          B(2, 2 * k) = ny;
          B(2, 2 * k + 1) = nx;
          const double vx = x[2 * gnode_[i]], vy = x[2 * gnode_[i] + 1];
          eps[0] += nx * vx;
          eps[1] += ny * vy;
          eps[2] += ny * vx + nx * vy;
        }
        Vec3 sig;
        Mat3 E;
        mat.evaluate(eps, hist0_[g], hist1_[g], sig, E, operator_);
        const Eigen::VectorXd f = B.transpose() * sig * gp.w;
        Eigen::MatrixXd k;
        if (with_matrix) k = B.transpose() * (E * gp.w) * B;
        for (int a = 0; a < n; ++a) {
          const int la = gloc_[gp.begin + a];
          fc[2 * la] += f[2 * a];
          fc[2 * la + 1] += f[2 * a + 1];
          if (!with_matrix) continue;
          for (int bb = 0; bb < n; ++bb) {
            const int lb = gloc_[gp.begin + bb];
            Kc(2 * la, 2 * lb) += k(2 * a, 2 * bb);
            Kc(2 * la + 1, 2 * lb) += k(2 * a + 1, 2 * bb);
            Kc(2 * la, 2 * lb + 1) += k(2 * a, 2 * bb + 1);
            Kc(2 * la + 1, 2 * lb + 1) += k(2 * a + 1, 2 * bb + 1);
          }
        }
      }
      for (int a = 0; a < m; ++a) ft[2 * cn[a / 2] + a % 2] += fc[a];
      if (with_matrix)
        for (int b = 0; b < m; ++b) {
          const int col = 2 * cn[b / 2] + b % 2;
          // Rows of the column and the cell's dofs are both sorted: a merge walk.
          int p = outer[col];
          const int end = outer[col + 1];
          for (int a = 0; a < m; ++a) {
            const int row = 2 * cn[a / 2] + a % 2;
            while (p < end && inner[p] < row) ++p;
            kt[p] += Kc(a, b);
          }
        }
    }
  }
  scatter.merge();
  // Essential conditions by collocation: penalty beta N N^T, or Lagrange rows G (u^h(x_k) = lambda u_k).
  if (essential_ == "penalty") {
    for (const auto& c : constraints_) {
      double u = 0;
      for (size_t a = 0; a < c.sh.nodes.size(); ++a) u += c.sh.N[a] * x[2 * c.sh.nodes[a] + c.comp];
      for (size_t a = 0; a < c.sh.nodes.size(); ++a) {
        fint[2 * c.sh.nodes[a] + c.comp] += penalty_ * c.sh.N[a] * u;
        if (!with_matrix) continue;
        for (size_t b = 0; b < c.sh.nodes.size(); ++b)
          K_.coeffRef(2 * c.sh.nodes[a] + c.comp, 2 * c.sh.nodes[b] + c.comp) += penalty_ * c.sh.N[a] * c.sh.N[b];
      }
    }
  } else if (essential_ == "lagrange") {
    for (size_t k = 0; k < constraints_.size(); ++k) {
      const auto& c = constraints_[k];
      const Index r = ndof_ + static_cast<Index>(k);
      double u = 0;
      for (size_t a = 0; a < c.sh.nodes.size(); ++a) {
        const Index d = 2 * c.sh.nodes[a] + c.comp;
        u += c.sh.N[a] * x[d];
        fint[d] += c.sh.N[a] * x[r];
        if (with_matrix) {
          K_.coeffRef(r, d) += c.sh.N[a];
          K_.coeffRef(d, r) += c.sh.N[a];
        }
      }
      fint[r] = u;
    }
  }
}

void EfgModel::factorize() {
  // Eliminate the dofs held directly: remember K_:,fixed u_ref (the reference prescribed motion), then identity
  // rows and columns.
  Kfix_ref_ = Vec::Zero(nsys_);
  Vec uref = Vec::Zero(nsys_);
  for (size_t i = 0; i < fixed_dofs_.size(); ++i) uref[fixed_dofs_[i]] = fixed_ref_[i];
  if (essential_ == "coupling" && !fixed_dofs_.empty()) {
    for (int col = 0; col < K_.outerSize(); ++col) {
      if (!is_fixed_[col]) continue;
      for (SparseMatrix::InnerIterator it(K_, col); it; ++it)
        if (!is_fixed_[it.row()]) Kfix_ref_[it.row()] += it.value() * uref[col];
    }
    dirichlet_identity(K_, [&](Index i) { return is_fixed_[static_cast<size_t>(i)] != 0; });
  }
  if (!K_.valuePtr() || !Eigen::Map<const Vec>(K_.valuePtr(), K_.nonZeros()).allFinite())
    fail_solve("non-finite stiffness", true);
  try {
    solver_->setup(K_);
  } catch (const SolverError& e) {
    fail_solve(std::string("the stiffness cannot be factorized: ") + e.what(), true);
  }
}

Vec EfgModel::solve(const Vec& rhs, bool with_prescribed) {
  Vec r = rhs, out;
  if (essential_ == "coupling") {
    if (with_prescribed) r -= Kfix_ref_;
    for (size_t i = 0; i < fixed_dofs_.size(); ++i) r[fixed_dofs_[i]] = with_prescribed ? fixed_ref_[i] : 0.0;
  }
  solver_->solve(r, out);
  if (!out.allFinite()) fail_solve("non-finite solution (a singular system)", true);
  return out;
}

Vec EfgModel::to_control(const Vec& dx) const {
  if (!control_u_form_) return dx.head(ndof_);
  Vec u = Vec::Zero(ndof_);
  for (Index n = 0; n < mesh_.num_nodes(); ++n)
    for (const auto& [j, v] : node_eval_[n]) {
      u[2 * n] += v * dx[2 * j];
      u[2 * n + 1] += v * dx[2 * j + 1];
    }
  return u;
}

}  // namespace lagfsi::efg
