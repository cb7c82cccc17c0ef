#include <lagfsi/element.hpp>
#include <lagfsi/error.hpp>
#include <lagfsi/parallel_sum.hpp>
#include <lagfsi/solid/solid.hpp>
#include <lagfsi/vtk_output.hpp>

#include "positional_kernel.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace lagfsi {

namespace {

/// Parent-space data for all quadrature points of an order (shared by all elements).
struct ParentRule {
  std::vector<Eigen::VectorXd> N;
  std::vector<Eigen::MatrixX2d> dN;
  std::vector<double> w;
};

ParentRule parent_rule(int order, int degree) {
  ParentRule r;
  for (const auto& q : triangle_quadrature(degree)) {
    Eigen::VectorXd N;
    Eigen::MatrixX2d dN;
    triangle_shape(order, q.xi1, q.xi2, N, dN);
    r.N.push_back(N);
    r.dN.push_back(dN);
    r.w.push_back(q.weight);
  }
  return r;
}

}  // namespace

SolidBody::SolidBody(TriMesh reference, std::shared_ptr<const SolidMaterial> material, double thickness)
    : mesh_(std::move(reference)), material_(std::move(material)), thickness_(thickness) {
  if (mesh_.order < 1 || mesh_.order > 3) throw std::invalid_argument("solid elements must be of order 1, 2 or 3");
  if (mesh_.num_elements() == 0) throw std::invalid_argument("solid mesh has no elements");
  if (!(thickness_ > 0.0)) throw std::invalid_argument("thickness must be positive");
  const ParentRule rule = parent_rule(mesh_.order, 2 * mesh_.order);
  qdN_ = rule.dN;
  qw_ = rule.w;
  X_.resize(num_dofs());
  for (Index i = 0; i < num_nodes(); ++i) X_.segment<2>(2 * i) = mesh_.nodes[i];
  surface_points_.resize(num_nodes());
  for (Index i = 0; i < num_nodes(); ++i) surface_points_[i].node = i;
  for (const auto& e : boundary_edges(mesh_)) surface_edges_.push_back(e.nodes);
  build_pattern();
  build_mass();
}

void SolidBody::build_pattern() {
  assembly_ = ElementPattern(mesh_.conn, mesh_.nodes_per_element(), num_nodes(), 2);
  pattern_ = assembly_.pattern();
}

void SolidBody::build_mass() {
  const int npe = mesh_.nodes_per_element();
  const ParentRule rule = parent_rule(mesh_.order, 2 * mesh_.order);
  mass_ = pattern_;
  double* val = mass_.valuePtr();
  std::fill(val, val + mass_.nonZeros(), 0.0);
  const double rho = material_->density();
  Eigen::MatrixX2d Xe(npe, 2);
  for (Index e = 0; e < mesh_.num_elements(); ++e) {
    const Index* c = mesh_.element(e);
    for (int a = 0; a < npe; ++a) Xe.row(a) = mesh_.nodes[c[a]].transpose();
    Eigen::MatrixXd Me = Eigen::MatrixXd::Zero(npe, npe);
    for (size_t q = 0; q < rule.w.size(); ++q) {
      const Mat2 A0 = Xe.transpose() * rule.dN[q];
      const double detA0 = A0.determinant();
      if (!(detA0 > 0.0))
        throw std::invalid_argument("element " + std::to_string(e) + " has non-positive area or is clockwise");
      Me += rule.N[q] * rule.N[q].transpose() * (rho * rule.w[q] * detA0 * thickness_);
    }
    assembly_.add_per_component(e, Me, val);
  }
}

Vec SolidBody::lumped_mass() const {
  Vec ml = Vec::Zero(num_dofs());
  for (int k = 0; k < mass_.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(mass_, k); it; ++it) ml[it.row()] += it.value();
  return ml;
}

template <int NPE>
double SolidBody::assemble(const Vec& x, Vec& f, SparseMatrix* K, bool need_force) const {
  constexpr int M = 2 * NPE;
  using MatN2 = Eigen::Matrix<double, NPE, 2>;
  using MatM = Eigen::Matrix<double, M, M>;
  const size_t nq = qw_.size();

  if (need_force) f.setZero(num_dofs());
  double* kval = K ? K->valuePtr() : nullptr;
  if (K) std::fill(kval, kval + K->nonZeros(), 0.0);
  ThreadSums<> energy_sum;
  const Index ne = mesh_.num_elements();
  std::atomic<Index> failed{ne};  // the lowest element that failed (the one reported, whatever the timing)
  std::string failure;

  // One parallel region for all colours (a barrier between colours); small meshes run serially, where
  // forking threads costs more than the work. The elements of a colour share no node, so their additions
  // into f and K do not race and each entry gets its terms in colour order; the strain energy is summed per
  // thread and added in thread order (parallel_sum.hpp): the same in every run with the same threads.
#pragma omp parallel if (ne >= 256)
  {
    double energy = 0.0;
    for (const auto& elems : assembly_.colors()) {
      const Index nce = static_cast<Index>(elems.size());
#pragma omp for schedule(static)
      for (Index ie = 0; ie < nce; ++ie) {
        const Index e = elems[ie];
        if (failed.load(std::memory_order_relaxed) < e) continue;
        const Index* c = mesh_.element(e);
        MatN2 Xe, xe;
        for (int a = 0; a < NPE; ++a) {
          Xe.row(a) = mesh_.nodes[c[a]].transpose();
          xe.row(a) = x.segment<2>(2 * c[a]).transpose();
        }
        Eigen::Matrix<double, M, 1> fe = Eigen::Matrix<double, M, 1>::Zero();
        MatM Ke = MatM::Zero();
        try {
          for (size_t q = 0; q < nq; ++q) {
            const MatN2 dN = qdN_[q];
            const Mat2 A0 = Xe.transpose() * dN;
            const double detA0 = A0.determinant();
            const MatN2 G = dN * A0.inverse();
            const double dV = qw_[q] * detA0 * thickness_;
            const Mat2 F = xe.transpose() * G;
            const MaterialResponse r = material_->evaluate(F);
            energy += r.psi * dV;
            detail::add_positional_point<NPE>(G, F, r.S, r.D, dV, need_force ? &fe : nullptr, K ? &Ke : nullptr);
          }
        } catch (const std::exception& ex) {
#pragma omp critical(lagfsi_solid_failure)
          if (e < failed) {
            failed = e;
            failure = "element " + std::to_string(e) + ": " + ex.what();
          }
          continue;
        }
        if (need_force)
          for (int a = 0; a < NPE; ++a) f.segment<2>(2 * c[a]) += fe.template segment<2>(2 * a);
        if (K) assembly_.add(e, Ke, kval);
      }
    }
    energy_sum.mine()[0] = energy;
  }
  if (failed < ne) throw SolverError(failure);
  const double energy = energy_sum.total();
  if (!std::isfinite(energy)) throw SolverError("non-finite strain energy");
  return energy;
}

double SolidBody::internal_force(const Vec& x, Vec& f, SparseMatrix* K) const {
  if (x.size() != num_dofs()) throw std::invalid_argument("position vector has the wrong size");
  switch (mesh_.order) {
    case 1:
      return assemble<3>(x, f, K, true);
    case 2:
      return assemble<6>(x, f, K, true);
    default:
      return assemble<10>(x, f, K, true);
  }
}

double SolidBody::strain_energy(const Vec& x) const {
  Vec dummy;
  switch (mesh_.order) {
    case 1:
      return assemble<3>(x, dummy, nullptr, false);
    case 2:
      return assemble<6>(x, dummy, nullptr, false);
    default:
      return assemble<10>(x, dummy, nullptr, false);
  }
}

Vec SolidBody::body_force(const Vec2& b) const {
  Vec g(num_dofs());
  const double rho = material_->density();
  for (Index i = 0; i < num_nodes(); ++i) g.segment<2>(2 * i) = b / rho;
  return mass_ * g;
}

Vec SolidBody::edge_traction(const std::vector<std::vector<Index>>& edges, const Vec2& t) const {
  return surface_traction(*this, edges, t);  // the surface points of a continuum are its nodes
}

bool SolidBody::locate(const Vec2& P, Index& element, double& xi1, double& xi2) const {
  double best = -1e300;
  for (Index e = 0; e < mesh_.num_elements(); ++e) {
    const Index* c = mesh_.element(e);
    const Vec2 &v0 = mesh_.nodes[c[0]], &v1 = mesh_.nodes[c[1]], &v2 = mesh_.nodes[c[2]];
    // P = v2 + L1 (v0 - v2) + L2 (v1 - v2)
    Mat2 A;
    A.col(0) = v0 - v2;
    A.col(1) = v1 - v2;
    const Vec2 L = A.inverse() * (P - v2);
    const double m = std::min({L[0], L[1], 1.0 - L[0] - L[1]});
    if (m > best) {
      best = m;
      element = e;
      xi1 = L[0];
      xi2 = L[1];
    }
  }
  return best > -1e-9;
}

bool SolidBody::locate(const Vec2& P, std::vector<std::pair<Index, double>>& weights) const {
  Index e;
  double xi1, xi2;
  if (!locate(P, e, xi1, xi2)) return false;
  Eigen::VectorXd N;
  Eigen::MatrixX2d dN;
  triangle_shape(mesh_.order, xi1, xi2, N, dN);
  const Index* c = mesh_.element(e);
  weights.clear();
  for (int a = 0; a < mesh_.nodes_per_element(); ++a) weights.emplace_back(c[a], N[a]);
  return true;
}

void SolidBody::write_output(PvdSeries& series, double t, const KinematicState& st) const {
  const Index nn = num_nodes();
  VtuData d;
  d.mesh = &mesh_;
  d.points.resize(nn);
  Field u{"displacement", 2, {}}, v{"velocity", 2, {}}, a{"acceleration", 2, {}};
  for (Index n = 0; n < nn; ++n) {
    d.points[n] = st.x.segment<2>(2 * n);
    for (int c = 0; c < 2; ++c) {
      u.values.push_back(st.x[2 * n + c] - X_[2 * n + c]);
      v.values.push_back(st.v[2 * n + c]);
      a.values.push_back(st.a[2 * n + c]);
    }
  }
  auto s = nodal_stress(st.x);
  d.point_fields = {
      u, v, a, {"cauchy_stress", 4, s.cauchy}, {"von_mises", 1, s.von_mises}, {"green_strain", 3, s.green}};
  series.write(t, d);
}

SolidBody::NodalStress SolidBody::nodal_stress(const Vec& x) const {
  const int npe = mesh_.nodes_per_element();
  NodalStress out;
  out.cauchy.assign(4 * num_nodes(), 0.0);
  out.von_mises.assign(num_nodes(), 0.0);
  out.green.assign(3 * num_nodes(), 0.0);
  std::vector<int> count(num_nodes(), 0);
  const auto coords = triangle_node_coordinates(mesh_.order);
  Eigen::MatrixX2d Xe(npe, 2), xe(npe, 2);
  Eigen::VectorXd N;
  Eigen::MatrixX2d dN;
  for (Index e = 0; e < mesh_.num_elements(); ++e) {
    const Index* c = mesh_.element(e);
    for (int a = 0; a < npe; ++a) {
      Xe.row(a) = mesh_.nodes[c[a]].transpose();
      xe.row(a) = x.segment<2>(2 * c[a]).transpose();
    }
    for (int k = 0; k < npe; ++k) {
      triangle_shape(mesh_.order, coords[k].first, coords[k].second, N, dN);
      const Mat2 A0 = Xe.transpose() * dN;
      const Mat2 F = xe.transpose() * dN * A0.inverse();
      const Mat2 E = 0.5 * (F.transpose() * F - Mat2::Identity());
      MaterialResponse r;
      try {
        r = material_->evaluate(F);
      } catch (const std::exception&) {
        continue;  // inverted element: leave its contribution out of the average
      }
      const double J = F.determinant() * r.F33;
      const Mat2 sigma = F * r.S * F.transpose() / J;
      const double szz = r.S33 * r.F33 * r.F33 / J;
      const Index n = c[k];
      out.cauchy[4 * n] += sigma(0, 0);
      out.cauchy[4 * n + 1] += sigma(1, 1);
      out.cauchy[4 * n + 2] += sigma(0, 1);
      out.cauchy[4 * n + 3] += szz;
      out.green[3 * n] += E(0, 0);
      out.green[3 * n + 1] += E(1, 1);
      out.green[3 * n + 2] += E(0, 1);
      ++count[n];
    }
  }
  for (Index n = 0; n < num_nodes(); ++n) {
    if (count[n] == 0) continue;
    for (int i = 0; i < 4; ++i) out.cauchy[4 * n + i] /= count[n];
    for (int i = 0; i < 3; ++i) out.green[3 * n + i] /= count[n];
    const double sx = out.cauchy[4 * n], sy = out.cauchy[4 * n + 1], sxy = out.cauchy[4 * n + 2],
                 sz = out.cauchy[4 * n + 3];
    out.von_mises[n] =
        std::sqrt(0.5 * ((sx - sy) * (sx - sy) + (sy - sz) * (sy - sz) + (sz - sx) * (sz - sx)) + 3 * sxy * sxy);
  }
  return out;
}

}  // namespace lagfsi
