// EFG body set-up from its input (efg_input.cpp): the shape functions at a point of a background cell (MLS,
// blended with the finite elements in coupled cells), the cached integration points and the matrix pattern.
// See src/efg/include/lagfsi/efg/efg_model.hpp.
#include <lagfsi/efg/efg_model.hpp>
#include <lagfsi/efg/integration.hpp>
#include <lagfsi/error.hpp>
#include <lagfsi/stopwatch.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <chrono>
#include <set>

namespace lagfsi::efg {

void EfgModel::shape_at(Index c, double xi, double eta, ShapeValues& out, bool derivatives) const {
  const auto& cell = mesh_.cells[c];
  double N[4], dxi[4], deta[4];
  q4_shape(xi, eta, N, dxi, deta);
  Vec2 x = Vec2::Zero();
  Mat2 J = Mat2::Zero();
  for (int a = 0; a < 4; ++a) {
    const Vec2& p = mesh_.nodes[cell[a]];
    x += N[a] * p;
    J.col(0) += dxi[a] * p;
    J.col(1) += deta[a] * p;
  }
  thread_local std::vector<Index> cand, sup;
  search_.within(x, rho_max_, cand);
  sup.clear();
  for (Index j : cand)
    if (mls_.domain().contains(x, mesh_.nodes[j], rho_[j]) &&
        (vis_.segments.empty() || vis_.visible(x, mesh_.nodes[j])))
      sup.push_back(j);
  // The coupling element of the cell: Q4 on a linear mesh, Q9 on a quadratic one; its active nodes' functions.
  FeCorrection fe;
  Index fe_node[9];
  const bool coupled = coupling_cell_[c];
  if (coupled) {
    const int npc = mesh_.nodes_per_cell();
    double Nf[9], fxi[9], feta[9];
    if (mesh_.quadratic())
      q9_shape(xi, eta, Nf, fxi, feta);
    else
      q4_shape(xi, eta, Nf, fxi, feta);
    const Mat2 Ji = J.inverse();  // dxi/dx = J^-T applied to (dxi, deta)
    for (int a = 0; a < npc; ++a) {
      const Index n = mesh_.cell_node(c, a);
      if (!active_[n]) continue;
      const Vec2 g = Ji.transpose() * Vec2(fxi[a], feta[a]);
      fe_node[fe.n] = n;
      fe.x[fe.n] = mesh_.nodes[n];
      fe.N[fe.n] = Nf[a];
      fe.Nx[fe.n] = g.x();
      fe.Ny[fe.n] = g.y();
      ++fe.n;
    }
  }
  mls_.compute(x, mesh_.nodes, rho_, sup, out, coupled ? &fe : nullptr, "cell " + std::to_string(c), derivatives);
  if (coupled) {  // add the FE functions of the active nodes
    for (int k = 0; k < fe.n; ++k) {
      {
        const Index n = fe_node[k];
        auto it = std::find(out.nodes.begin(), out.nodes.end(), n);
        size_t pos;
        if (it == out.nodes.end()) {
          out.nodes.push_back(n);
          out.N.push_back(0);
          out.Nx.push_back(0);
          out.Ny.push_back(0);
          pos = out.nodes.size() - 1;
        } else {
          pos = static_cast<size_t>(it - out.nodes.begin());
        }
        out.N[pos] += fe.N[k];
        out.Nx[pos] += fe.Nx[k];
        out.Ny[pos] += fe.Ny[k];
      }
    }
  }
}

void EfgModel::build_integration_points() {
  const auto t0 = SteadyClock::now();
  std::vector<double> gx, gw, ex, ew;
  gauss_legendre(gauss_, gx, gw);
  gauss_legendre(std::max(2, gauss_), ex, ew);  // the edge rule of the traction loads
  const Index nc = mesh_.num_cells();
  cell_nodes_.assign(nc, {});
  cell_gp_begin_.assign(nc + 1, 0);
  gps_.clear();
  long total_support = 0;
  static const double cxi[4] = {-1, 1, 1, -1}, ceta[4] = {-1, -1, 1, 1};
  std::vector<ShapeValues> sg, se;
  for (Index c = 0; c < nc; ++c) {
    cell_gp_begin_[c] = static_cast<Index>(gps_.size());
    std::vector<Vec2> xg, xe, wn;
    std::vector<double> wg;
    sg.assign(gauss_ * gauss_, {});
    std::set<Index> uni;
    for (int i = 0; i < gauss_; ++i)
      for (int j = 0; j < gauss_; ++j) {
        double N[4], dxi[4], deta[4];
        q4_shape(gx[i], gx[j], N, dxi, deta);
        Vec2 x = Vec2::Zero();
        Mat2 J = Mat2::Zero();
        for (int a = 0; a < 4; ++a) {
          const Vec2& p = mesh_.nodes[mesh_.cells[c][a]];
          x += N[a] * p;
          J.col(0) += dxi[a] * p;
          J.col(1) += deta[a] * p;
        }
        const double det = J.determinant();
        if (!(det > 0)) fail_input("domain", "background cell " + std::to_string(c) + " is inverted or degenerate");
        ShapeValues& sh = sg[i * gauss_ + j];
        shape_at(c, gx[i], gx[j], sh, true);
        min_rcond_ = std::min(min_rcond_, sh.rcond);
        xg.push_back(x);
        wg.push_back(gw[i] * gw[j] * det);
        uni.insert(sh.nodes.begin(), sh.nodes.end());
      }
    if (consistent_) {
      se.clear();
      for (int k = 0; k < 4; ++k) {
        const Vec2 pa = mesh_.nodes[mesh_.cells[c][k]], pb = mesh_.nodes[mesh_.cells[c][(k + 1) % 4]];
        const Vec2 nrm = Vec2((pb - pa).y(), -(pb - pa).x()).normalized();
        for (size_t q = 0; q < ex.size(); ++q) {
          const double s = 0.5 * (1 + ex[q]);
          se.emplace_back();
          shape_at(c, cxi[k] + s * (cxi[(k + 1) % 4] - cxi[k]), ceta[k] + s * (ceta[(k + 1) % 4] - ceta[k]), se.back(),
                   false);
          uni.insert(se.back().nodes.begin(), se.back().nodes.end());
          xe.push_back(pa + s * (pb - pa));
          wn.push_back(ew[q] * 0.5 * (pb - pa).norm() * nrm);
        }
      }
    }
    cell_nodes_[c].assign(uni.begin(), uni.end());
    const auto& cn = cell_nodes_[c];
    const int nu = static_cast<int>(cn.size()), ng = static_cast<int>(sg.size());
    auto col = [&](Index n) { return static_cast<int>(std::lower_bound(cn.begin(), cn.end(), n) - cn.begin()); };
    Eigen::MatrixXd N = Eigen::MatrixXd::Zero(ng, nu), Nx = N, Ny = N;
    for (int g = 0; g < ng; ++g)
      for (size_t k = 0; k < sg[g].nodes.size(); ++k) {
        const int j = col(sg[g].nodes[k]);
        N(g, j) = sg[g].N[k];
        Nx(g, j) = sg[g].Nx[k];
        Ny(g, j) = sg[g].Ny[k];
      }
    if (consistent_) {
      Eigen::MatrixXd Ne = Eigen::MatrixXd::Zero(static_cast<int>(se.size()), nu);
      for (size_t e = 0; e < se.size(); ++e)
        for (size_t k = 0; k < se[e].nodes.size(); ++k) Ne(static_cast<int>(e), col(se[e].nodes[k])) = se[e].N[k];
      correct_derivatives(mls_.basis().complete_degree(), xg, wg, N, xe, wn, Ne, Nx, Ny);
    }
    for (int g = 0; g < ng; ++g) {
      GaussPoint gp{xg[g], wg[g] * thickness_, c, static_cast<Index>(gnode_.size()), 0};
      for (int j = 0; j < nu; ++j) {
        if (N(g, j) == 0.0 && Nx(g, j) == 0.0 && Ny(g, j) == 0.0) continue;
        gnode_.push_back(cn[j]);
        gN_.push_back(N(g, j));
        gNx_.push_back(Nx(g, j));
        gNy_.push_back(Ny(g, j));
        gloc_.push_back(j);
        ++gp.n;
      }
      max_support_ = std::max(max_support_, static_cast<int>(gp.n));
      total_support += gp.n;
      gps_.push_back(gp);
    }
  }
  cell_gp_begin_[nc] = static_cast<Index>(gps_.size());
  mean_support_ = gps_.empty() ? 0 : static_cast<double>(total_support) / gps_.size();
  // Nodal evaluation U = f(V): the functions at each node, from a cell it is a corner of.
  const Index nn = mesh_.num_nodes();
  node_eval_.assign(nn, {});
  std::vector<char> done(nn, 0);
  ShapeValues sh;
  for (Index c = 0; c < nc; ++c)
    for (int a = 0; a < mesh_.nodes_per_cell(); ++a) {
      const Index n = mesh_.cell_node(c, a);
      if (done[n]) continue;
      done[n] = 1;
      double xi, eta;
      cell_node_natural(a, xi, eta);
      shape_at(c, xi, eta, sh, false);
      for (size_t k = 0; k < sh.nodes.size(); ++k)
        if (sh.N[k] != 0.0) node_eval_[n].emplace_back(sh.nodes[k], sh.N[k]);
    }
  t_shape_ = std::chrono::duration<double>(SteadyClock::now() - t0).count();
}

void EfgModel::fail_input(const std::string& key, const std::string& reason) const {
  throw InputError(file_, key.empty() ? path_ : path_ + "/" + key, reason);
}

void EfgModel::build_pattern() {
  const Index nn = mesh_.num_nodes();
  std::vector<std::vector<Index>> adj(nn);
  for (const auto& u : cell_nodes_)
    for (Index a : u) adj[a].insert(adj[a].end(), u.begin(), u.end());
  for (const auto& c : constraints_)
    for (Index a : c.sh.nodes) adj[a].insert(adj[a].end(), c.sh.nodes.begin(), c.sh.nodes.end());
  for (Index a = 0; a < nn; ++a) {
    adj[a].push_back(a);
    std::sort(adj[a].begin(), adj[a].end());
    adj[a].erase(std::unique(adj[a].begin(), adj[a].end()), adj[a].end());
  }
  // Multiplier columns / rows (Lagrange).
  std::vector<std::vector<Index>> extra_rows(ndof_);  // per dof column: multiplier rows
  std::vector<std::vector<Index>> mult_cols;
  if (essential_ == "lagrange")
    for (size_t k = 0; k < constraints_.size(); ++k) {
      std::vector<Index> rows;
      for (Index a : constraints_[k].sh.nodes) {
        const Index d = 2 * a + constraints_[k].comp;
        rows.push_back(d);
        extra_rows[d].push_back(ndof_ + static_cast<Index>(k));
      }
      std::sort(rows.begin(), rows.end());
      rows.push_back(ndof_ + static_cast<Index>(k));  // a structural zero diagonal
      mult_cols.push_back(rows);
    }
  K_.resize(nsys_, nsys_);
  std::vector<int> outer(nsys_ + 1, 0);
  std::vector<int> inner;
  for (Index col = 0; col < nsys_; ++col) {
    outer[col] = static_cast<int>(inner.size());
    if (col < ndof_) {
      for (Index a : adj[col / 2]) {
        inner.push_back(2 * a);
        inner.push_back(2 * a + 1);
      }
      for (Index r : extra_rows[col]) inner.push_back(r);
    } else {
      for (Index r : mult_cols[col - ndof_]) inner.push_back(r);
    }
  }
  outer[nsys_] = static_cast<int>(inner.size());
  std::vector<double> values(inner.size(), 0.0);
  K_ = Eigen::Map<const SparseMatrix>(nsys_, nsys_, static_cast<Index>(inner.size()), outer.data(), inner.data(),
                                      values.data());
  K_.makeCompressed();
  is_fixed_.assign(nsys_, 0);
  if (essential_ == "coupling")
    for (Index d : fixed_dofs_) is_fixed_[d] = 1;
}

}  // namespace lagfsi::efg
