// Positional frame/shell elements (shell.hpp).
#include <lagfsi/element.hpp>
#include <lagfsi/error.hpp>
#include <lagfsi/solid/shell.hpp>
#include <lagfsi/vtk_output.hpp>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "positional_kernel.hpp"

namespace lagfsi {

namespace {

/// Thickness rule: 3 Gauss points mapped to eta in [-1/2, 1/2].
const std::vector<std::pair<double, double>>& thickness_rule() {
  static const std::vector<std::pair<double, double>> r = [] {
    std::vector<std::pair<double, double>> out;
    for (const auto& [s, w] : line_quadrature(3)) out.emplace_back(s - 0.5, w);
    return out;
  }();
  return r;
}

Vec2 perp(const Vec2& t) { return Vec2(-t.y(), t.x()); }

}  // namespace

ShellBody::ShellBody(int order, std::vector<Vec2> midline, const ShellSection& section)
    : order_(order), sec_(section), mid_(std::move(midline)) {
  if (order_ < 1 || order_ > 3) throw std::invalid_argument("shell elements must be of order 1, 2 or 3");
  const Index n = static_cast<Index>(mid_.size());
  if (n < order_ + 1 || (n - 1) % order_ != 0)
    throw std::invalid_argument("a shell of order " + std::to_string(order_) +
                                " needs order * elements + 1 nodes, got " + std::to_string(n));
  if (!(sec_.thickness > 0.0)) throw std::invalid_argument("shell thickness must be positive");
  if (!(sec_.width > 0.0)) throw std::invalid_argument("shell width must be positive");
  if (!(sec_.young > 0.0) || !(sec_.density > 0.0)) throw std::invalid_argument("young and density must be positive");
  if (!(sec_.poisson > -1.0 && sec_.poisson < 0.5)) throw std::invalid_argument("poisson must lie in (-1, 0.5)");
  if (!(sec_.shear_correction > 0.0)) throw std::invalid_argument("shear_correction must be positive");
  Eb_ = sec_.plane_strain ? sec_.young / (1.0 - sec_.poisson * sec_.poisson) : sec_.young;
  Gs_ = sec_.shear_correction * sec_.young / (2.0 * (1.0 + sec_.poisson));

  // Reference normals: the average of the unit tangents of the elements at a node.
  const Index ne = num_elements();
  std::vector<Vec2> tangent(n, Vec2::Zero());
  Eigen::VectorXd N, dN;
  for (Index e = 0; e < ne; ++e)
    for (int k = 0; k <= order_; ++k) {
      line_shape(order_, static_cast<double>(k) / order_, N, dN);
      Vec2 t = Vec2::Zero();
      for (int a = 0; a <= order_; ++a) t += dN[a] * mid_[e * order_ + a];
      if (!(t.norm() > 1e-12 * (mid_[e * order_ + order_] - mid_[e * order_]).norm()) || !(t.norm() > 0.0))
        throw std::invalid_argument("shell element " + std::to_string(e) + " has coincident nodes");
      tangent[e * order_ + k] += t.normalized();
    }
  normal_.resize(n);
  for (Index a = 0; a < n; ++a) {
    if (!(tangent[a].norm() > 1e-6))
      throw std::invalid_argument("shell folds back on itself at node " + std::to_string(a));
    normal_[a] = perp(tangent[a].normalized());
  }
  X_.resize(2 * num_nodes());
  for (Index a = 0; a < n; ++a) {
    X_.segment<2>(2 * a) = mid_[a];
    X_.segment<2>(2 * (n + a)) = sec_.thickness * normal_[a];
  }

  // Element connectivity over dof nodes: the element's mid-line nodes, then their vectors.
  const int npe = 2 * (order_ + 1);
  std::vector<Index> conn;
  conn.reserve(static_cast<size_t>(ne) * npe);
  for (Index e = 0; e < ne; ++e) {
    for (int a = 0; a <= order_; ++a) conn.push_back(e * order_ + a);
    for (int a = 0; a <= order_; ++a) conn.push_back(n + e * order_ + a);
  }
  assembly_ = ElementPattern(conn, npe, num_nodes(), 2);

  build_points();

  // Consistent mass (with rotary inertia): the points of the full rule (p + 1 along xi, 3 through the
  // thickness), which integrate it exactly on a straight element.
  mass_ = assembly_.pattern();
  double* val = mass_.valuePtr();
  std::fill(val, val + mass_.nonZeros(), 0.0);
  for (Index e = 0; e < ne; ++e) {
    Eigen::MatrixXd Me = Eigen::MatrixXd::Zero(npe, npe);
    for (const QuadPoint& q : points_[e])
      if (!q.shear_only) Me += q.Phi * q.Phi.transpose() * (sec_.density * q.dV);
    assembly_.add_per_component(e, Me, val);
  }

  // Surface: faces (top ids 0..n-1 at eta = +1/2, bottom ids n..2n-1 at eta = -1/2) and the interior points
  // of the end edges; edges counter-clockwise around the section (outward normal on the right).
  for (Index a = 0; a < n; ++a) surface_points_.push_back({a, n + a, 0.5});
  for (Index a = 0; a < n; ++a) surface_points_.push_back({a, n + a, -0.5});
  const Index start0 = 2 * n, end0 = 2 * n + (order_ - 1);
  for (int k = 1; k < order_; ++k) surface_points_.push_back({0, n, 0.5 - static_cast<double>(k) / order_});
  for (int k = 1; k < order_; ++k)
    surface_points_.push_back({n - 1, 2 * n - 1, -0.5 + static_cast<double>(k) / order_});
  for (Index e = 0; e < ne; ++e) {  // bottom face, along the mid-line
    std::vector<Index> edge;
    for (int a = 0; a <= order_; ++a) edge.push_back(n + e * order_ + a);
    surface_edges_.push_back(edge);
  }
  {  // end edge, bottom to top
    std::vector<Index> edge{2 * n - 1};
    for (int k = 1; k < order_; ++k) edge.push_back(end0 + k - 1);
    edge.push_back(n - 1);
    surface_edges_.push_back(edge);
  }
  for (Index e = ne - 1; e >= 0; --e) {  // top face, backwards
    std::vector<Index> edge;
    for (int a = order_; a >= 0; --a) edge.push_back(e * order_ + a);
    surface_edges_.push_back(edge);
  }
  {  // start edge, top to bottom
    std::vector<Index> edge{0};
    for (int k = 1; k < order_; ++k) edge.push_back(start0 + k - 1);
    edge.push_back(n);
    surface_edges_.push_back(edge);
  }
}

void ShellBody::build_points() {
  // Reference data of every quadrature point (G = dPhi/dX in the section's frame, dV, which law part),
  // computed once: assembly then only forms F = x_e^T G.
  const Index n = num_sections(), ne = num_elements();
  const int npe = 2 * (order_ + 1);
  Dfull_ = Eigen::Vector3d(Eb_, sec_.young, sec_.reduced_shear ? 0.0 : Gs_).asDiagonal();
  Dshear_ = Eigen::Vector3d(0.0, 0.0, Gs_).asDiagonal();
  struct Rule {
    int points;
    bool shear_only;
  };
  std::vector<Rule> rules{{order_ + 1, false}};
  if (sec_.reduced_shear) rules.push_back({order_, true});
  Eigen::VectorXd N, dN;
  Eigen::MatrixXd Xe(npe, 2);
  points_.assign(ne, {});
  for (Index e = 0; e < ne; ++e) {
    for (int a = 0; a <= order_; ++a) {
      Xe.row(a) = X_.segment<2>(2 * (e * order_ + a)).transpose();
      Xe.row(order_ + 1 + a) = X_.segment<2>(2 * (n + e * order_ + a)).transpose();
    }
    for (const Rule& rule : rules)
      for (const auto& [s, ws] : line_quadrature(rule.points)) {
        line_shape(order_, s, N, dN);
        Vec2 tm = Vec2::Zero();
        for (int a = 0; a <= order_; ++a) tm += dN[a] * mid_[e * order_ + a];
        Mat2 R;
        R.col(0) = tm.normalized();
        R.col(1) = perp(R.col(0));
        for (const auto& [eta, we] : thickness_rule()) {
          Eigen::MatrixX2d dPhi(npe, 2);
          dPhi.col(0) << dN, eta * dN;
          dPhi.col(1) << Eigen::VectorXd::Zero(order_ + 1), N;
          const Mat2 A0loc = R.transpose() * (Xe.transpose() * dPhi);
          const double det = A0loc.determinant();
          if (!(det > 0.0))
            throw std::invalid_argument("shell element " + std::to_string(e) + " is too curved for its thickness");
          Eigen::VectorXd Phi(npe);
          Phi << N, eta * N;
          points_[e].push_back({dPhi * A0loc.inverse(), Phi, ws * we * det * sec_.width, rule.shear_only});
        }
      }
  }
}

template <int NPE>
double ShellBody::assemble(const Vec& x, Vec* f, SparseMatrix* K) const {
  using MatN2 = Eigen::Matrix<double, NPE, 2>;
  using VecM = Eigen::Matrix<double, 2 * NPE, 1>;
  using MatM = Eigen::Matrix<double, 2 * NPE, 2 * NPE>;
  const Index n = num_sections(), ne = num_elements();
  const int p = order_;
  if (f) f->setZero(num_dofs());
  double* kval = K ? K->valuePtr() : nullptr;
  if (K) std::fill(kval, kval + K->nonZeros(), 0.0);
  double energy = 0.0;
  Index nodes[NPE];
  MatN2 xe;
  for (Index e = 0; e < ne; ++e) {
    for (int a = 0; a <= p; ++a) {
      nodes[a] = e * p + a;
      nodes[p + 1 + a] = n + e * p + a;
    }
    for (int a = 0; a < NPE; ++a) xe.row(a) = x.segment<2>(2 * nodes[a]).transpose();
    VecM fe = VecM::Zero();
    MatM Ke = MatM::Zero();
    for (const QuadPoint& q : points_[e]) {
      const MatN2 G = q.G;
      const Mat2 F = xe.transpose() * G;
      if (!(F.determinant() > 0.0))
        throw SolverError("shell element " + std::to_string(e) + ": inverted section (det F <= 0)");
      const Mat2 E = 0.5 * (F.transpose() * F - Mat2::Identity());
      const Eigen::Matrix3d& D = q.shear_only ? Dshear_ : Dfull_;
      const Eigen::Vector3d Ev(E(0, 0), E(1, 1), 2.0 * E(0, 1));
      const Eigen::Vector3d Sv = D * Ev;
      Mat2 S;
      S << Sv[0], Sv[2], Sv[2], Sv[1];
      energy += 0.5 * Ev.dot(Sv) * q.dV;
      if (f || K) detail::add_positional_point<NPE>(G, F, S, D, q.dV, &fe, K ? &Ke : nullptr);
    }
    if (f)
      for (int a = 0; a < NPE; ++a) f->segment<2>(2 * nodes[a]) += fe.template segment<2>(2 * a);
    if (K) assembly_.add(e, Ke, kval);
  }
  if (!std::isfinite(energy)) throw SolverError("non-finite strain energy");
  return energy;
}

double ShellBody::internal_force(const Vec& x, Vec& f, SparseMatrix* K) const {
  if (x.size() != num_dofs()) throw std::invalid_argument("position vector has the wrong size");
  switch (order_) {
    case 1:
      return assemble<4>(x, &f, K);
    case 2:
      return assemble<6>(x, &f, K);
    default:
      return assemble<8>(x, &f, K);
  }
}

Vec ShellBody::body_force(const Vec2& b) const {
  // M times the uniform field b / rho on the mid-line nodes (zero on the vectors): int Phi_A b dV, since the
  // N_a sum to one.
  Vec g = Vec::Zero(num_dofs());
  for (Index a = 0; a < num_sections(); ++a) g.segment<2>(2 * a) = b / sec_.density;
  return mass_ * g;
}

bool ShellBody::locate(const Vec2& P, std::vector<std::pair<Index, double>>& weights) const {
  const Index n = num_sections();
  double best = std::numeric_limits<double>::infinity();
  Index best_e = -1;
  double best_s = 0, best_eta = 0;
  Eigen::VectorXd N, dN;
  for (Index e = 0; e < num_elements(); ++e) {
    // Closest point of the mid-line: sampling, then Newton on (X(s) - P) . X'(s) = 0 (straight or gently
    // curved elements).
    double s = 0.0, dmin = std::numeric_limits<double>::infinity();
    for (int k = 0; k <= 20; ++k) {
      const double sk = k / 20.0;
      line_shape(order_, sk, N, dN);
      Vec2 X = Vec2::Zero();
      for (int a = 0; a <= order_; ++a) X += N[a] * mid_[e * order_ + a];
      if ((X - P).norm() < dmin) {
        dmin = (X - P).norm();
        s = sk;
      }
    }
    for (int it = 0; it < 20; ++it) {
      line_shape(order_, s, N, dN);
      Vec2 X = Vec2::Zero(), dX = Vec2::Zero();
      for (int a = 0; a <= order_; ++a) {
        X += N[a] * mid_[e * order_ + a];
        dX += dN[a] * mid_[e * order_ + a];
      }
      const double ds = -(X - P).dot(dX) / dX.squaredNorm();
      s = std::clamp(s + ds, 0.0, 1.0);
      if (std::abs(ds) < 1e-14) break;
    }
    line_shape(order_, s, N, dN);
    Vec2 X = Vec2::Zero(), Gs = Vec2::Zero();
    for (int a = 0; a <= order_; ++a) {
      X += N[a] * mid_[e * order_ + a];
      Gs += N[a] * X_.segment<2>(2 * (n + e * order_ + a));
    }
    const double eta = (P - X).dot(Gs) / Gs.squaredNorm();
    const Vec2 rest = P - X - eta * Gs;  // off the section line
    const double miss = rest.norm() + std::max(0.0, std::abs(eta) - 0.5) * Gs.norm();
    if (miss < best) {
      best = miss;
      best_e = e;
      best_s = s;
      best_eta = eta;
    }
  }
  if (best_e < 0 || best > 1e-6 * sec_.thickness + 1e-12) return false;
  line_shape(order_, best_s, N, dN);
  weights.clear();
  for (int a = 0; a <= order_; ++a) {
    weights.emplace_back(best_e * order_ + a, N[a]);
    weights.emplace_back(n + best_e * order_ + a, best_eta * N[a]);
  }
  return true;
}

ShellBody::Resultants ShellBody::resultants(const Vec& x) const {
  const Index n = num_sections();
  Resultants r;
  r.axial.assign(n, 0.0);
  r.shear.assign(n, 0.0);
  r.moment.assign(n, 0.0);
  std::vector<int> count(n, 0);
  const int npe = 2 * (order_ + 1);
  Eigen::VectorXd N, dN;
  Eigen::MatrixXd Xe(npe, 2), xe(npe, 2);
  for (Index e = 0; e < num_elements(); ++e) {
    for (int a = 0; a <= order_; ++a)
      for (int half = 0; half < 2; ++half) {
        const Index node = half * n + e * order_ + a;
        Xe.row(half * (order_ + 1) + a) = X_.segment<2>(2 * node).transpose();
        xe.row(half * (order_ + 1) + a) = x.segment<2>(2 * node).transpose();
      }
    for (int k = 0; k <= order_; ++k) {
      line_shape(order_, static_cast<double>(k) / order_, N, dN);
      Vec2 tm = Vec2::Zero();
      for (int a = 0; a <= order_; ++a) tm += dN[a] * mid_[e * order_ + a];
      Mat2 R;
      R.col(0) = tm.normalized();
      R.col(1) = perp(R.col(0));
      double Nk = 0, Qk = 0, Mk = 0;
      for (const auto& [eta, we] : thickness_rule()) {
        Eigen::MatrixX2d dPhi(npe, 2);
        dPhi.col(0) << dN, eta * dN;
        dPhi.col(1) << Eigen::VectorXd::Zero(order_ + 1), N;
        const Mat2 A0loc = R.transpose() * (Xe.transpose() * dPhi);
        const Mat2 F = xe.transpose() * dPhi * A0loc.inverse();
        const Mat2 E = 0.5 * (F.transpose() * F - Mat2::Identity());
        Nk += we * Eb_ * E(0, 0);
        Qk += we * Gs_ * 2.0 * E(0, 1);
        Mk += we * Eb_ * E(0, 0) * eta;
      }
      const double bt = sec_.width * sec_.thickness;
      const Index node = e * order_ + k;
      r.axial[node] += bt * Nk;
      r.shear[node] += bt * Qk;
      r.moment[node] += bt * sec_.thickness * Mk;
      ++count[node];
    }
  }
  for (Index a = 0; a < n; ++a) {
    r.axial[a] /= count[a];
    r.shear[a] /= count[a];
    r.moment[a] /= count[a];
  }
  return r;
}

void ShellBody::write_output(PvdSeries& series, double t, const KinematicState& st) const {
  const Index n = num_sections();
  VtpData d;
  d.points.resize(n);
  std::vector<Index> line(n);
  Field u{"displacement", 2, {}}, v{"velocity", 2, {}}, g{"generalised_vector", 2, {}}, th{"thickness", 1, {}},
      rot{"rotation", 1, {}};
  for (Index a = 0; a < n; ++a) {
    d.points[a] = st.x.segment<2>(2 * a);
    line[a] = a;
    const Vec2 ga = st.x.segment<2>(2 * (n + a)), Ga = X_.segment<2>(2 * (n + a));
    for (int c = 0; c < 2; ++c) {
      u.values.push_back(st.x[2 * a + c] - X_[2 * a + c]);
      v.values.push_back(st.v[2 * a + c]);
      g.values.push_back(ga[c]);
    }
    th.values.push_back(ga.norm());
    rot.values.push_back(std::atan2(Ga.x() * ga.y() - Ga.y() * ga.x(), Ga.dot(ga)));
  }
  d.lines.push_back(line);
  const Resultants r = resultants(st.x);
  d.point_fields = {
      u, v, g, th, rot, {"axial_force", 1, r.axial}, {"shear_force", 1, r.shear}, {"bending_moment", 1, r.moment}};
  series.write(t, d);
}

}  // namespace lagfsi
