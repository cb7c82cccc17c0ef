// Spatial convergence of the positional solid (SolidBody) for T3, T6, T10 by the method of manufactured
// solutions (Roache 2002; Salari & Knupp 2000) in the geometrically nonlinear regime.
//
// Manufactured displacement on the unit square (smooth, strains up to about 0.2, so the SVK law is
// exercised well beyond the linear regime):
//     u1 = 0.10 sin(2 X + Y + 0.3),   u2 = 0.08 sin(X - 1.5 Y + 1.1).
// The body force that makes it an equilibrium, b = -Div P with P = F S(E), S = lambda tr(E) I + 2 mu E
// (SVK, plane strain), is computed here analytically from the second derivatives of u, with its own
// SVK implementation (independent of material.cpp); the analytic divergence is itself checked against
// finite differences of P. The consistent nodal load int N_a b dV is integrated with the degree-8 rule
// (b is not polynomial; its quadrature error is far below the discretisation errors measured). Dirichlet
// conditions x = X + u(X) on every boundary node; the static problem is solved by Newton with the
// SolidBody tangent.
//
// Errors (degree-8 quadrature on every element): e_L2 = ||x_h - X - u||, e_H1 = ||grad x_h - F||.
// A-priori estimates for smooth solutions (Ciarlet; for the nonlinear elastic case, the same rates hold
// near a stable smooth solution): e_L2 = O(h^{p+1}), e_H1 = O(h^p). Observed order between the two finest
// of four structured "crossed" meshes; asserted: L2 order >= p + 1 - 0.3, H1 order >= p - 0.3 (the margin
// 0.3 covers pre-asymptotic effects; a wrong element, quadrature or load gives order <= p or stagnation).
#include <lagfsi/element.hpp>
#include <lagfsi/linear_solver.hpp>
#include <lagfsi/material.hpp>
#include <lagfsi/mesh.hpp>
#include <lagfsi/meshing/primitives.hpp>
#include <lagfsi/solid/solid.hpp>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <set>
#include <vector>

using namespace lagfsi;

namespace {

constexpr double kE = 1.0, kNu = 0.3;
const double kLam = kE * kNu / ((1 + kNu) * (1 - 2 * kNu));
const double kMu = kE / (2 * (1 + kNu));

// u_i = a_i sin(k_i . X + phi_i)
const std::array<double, 2> kA = {0.10, 0.08};
const std::array<Vec2, 2> kK = {Vec2(2.0, 1.0), Vec2(1.0, -1.5)};
const std::array<double, 2> kPhi = {0.3, 1.1};

Vec2 u_exact(const Vec2& X) {
  return Vec2(kA[0] * std::sin(kK[0].dot(X) + kPhi[0]), kA[1] * std::sin(kK[1].dot(X) + kPhi[1]));
}

Mat2 F_exact(const Vec2& X) {
  Mat2 F = Mat2::Identity();
  for (int i = 0; i < 2; ++i) F.row(i) += kA[i] * std::cos(kK[i].dot(X) + kPhi[i]) * kK[i].transpose();
  return F;
}

/// dF/dX_K.
Mat2 dF_exact(const Vec2& X, int K) {
  Mat2 d = Mat2::Zero();
  for (int i = 0; i < 2; ++i) d.row(i) = -kA[i] * std::sin(kK[i].dot(X) + kPhi[i]) * kK[i][K] * kK[i].transpose();
  return d;
}

/// First Piola stress of SVK (plane strain), independent of material.cpp.
Mat2 piola(const Mat2& F) {
  const Mat2 E = 0.5 * (F.transpose() * F - Mat2::Identity());
  const Mat2 S = kLam * E.trace() * Mat2::Identity() + 2 * kMu * E;
  return F * S;
}

/// b = -Div P, analytic: dP/dX_K = dF_K S + F dS_K, dS_K = lambda tr(dE_K) I + 2 mu dE_K,
/// dE_K = sym(F^T dF_K).
Vec2 body_force(const Vec2& X) {
  const Mat2 F = F_exact(X);
  const Mat2 E = 0.5 * (F.transpose() * F - Mat2::Identity());
  const Mat2 S = kLam * E.trace() * Mat2::Identity() + 2 * kMu * E;
  Vec2 div = Vec2::Zero();
  for (int K = 0; K < 2; ++K) {
    const Mat2 dF = dF_exact(X, K);
    const Mat2 FtdF = F.transpose() * dF;
    const Mat2 dE = 0.5 * (FtdF + FtdF.transpose());
    const Mat2 dS = kLam * dE.trace() * Mat2::Identity() + 2 * kMu * dE;
    const Mat2 dP = dF * S + F * dS;
    div += dP.col(K);
  }
  return -div;
}

struct Errors {
  double h, l2, h1;
  int newton;
  Index dofs;
};

Errors solve_and_measure(int order, int n) {
  auto mat =
      std::shared_ptr<const SolidMaterial>(make_solid_material("svk", kE, kNu, 1.0, PlaneHypothesis::PlaneStrain));
  SolidBody body(meshing::elevate(meshing::mesh_rectangle_structured(0, 0, 1, 1, n, n, "crossed"), order), mat, 1.0);
  const TriMesh& m = body.mesh();
  const Index nd = body.num_dofs();
  const int npe = m.nodes_per_element();
  const Vec& X = body.reference_positions();

  // Consistent load of the manufactured body force (degree-8 rule, straight-sided elements).
  Vec fext = Vec::Zero(nd);
  const auto& rule = triangle_quadrature(8);
  Eigen::VectorXd N;
  Eigen::MatrixX2d dN;
  Eigen::MatrixX2d Xe(npe, 2), xe(npe, 2);
  for (Index e = 0; e < m.num_elements(); ++e) {
    const Index* c = m.element(e);
    for (int a = 0; a < npe; ++a) Xe.row(a) = m.nodes[c[a]].transpose();
    for (const auto& q : rule) {
      triangle_shape(order, q.xi1, q.xi2, N, dN);
      const Mat2 A0 = Xe.transpose() * dN;
      const Vec2 Xq = Xe.transpose() * N;
      const Vec2 b = body_force(Xq);
      const double dV = q.weight * A0.determinant();
      for (int a = 0; a < npe; ++a) fext.segment<2>(2 * c[a]) += N[a] * dV * b;
    }
  }

  // Dirichlet: all boundary nodes at X + u(X).
  std::vector<char> fixed(nd, 0);
  for (const auto& be : boundary_edges(m))
    for (Index v : be.nodes) fixed[2 * v] = fixed[2 * v + 1] = 1;
  Vec x = X, target = X;
  for (Index v = 0; v < m.num_nodes(); ++v)
    if (fixed[2 * v]) target.segment<2>(2 * v) = m.nodes[v] + u_exact(m.nodes[v]);

  // Newton from the reference configuration; the Dirichlet values enter through the first correction
  // (rows and columns of the fixed dofs eliminated, their prescribed increments g moved to the right).
  auto solver = make_linear_solver("umfpack");
  SparseMatrix K = body.pattern();
  Vec f, dx;
  int its = 0;
  double last_dx = 1e300;
  for (its = 0; its < 30; ++its) {
    if (last_dx < 1e-12 * x.norm()) break;  // quadratic convergence: the next correction is ~1e-24
    body.internal_force(x, f, &K);
    Vec r = f - fext, g = Vec::Zero(nd);
    for (Index i = 0; i < nd; ++i)
      if (fixed[i]) {
        g[i] = target[i] - x[i];
        r[i] = 0.0;
      }
    Vec rhs = -r - K * g;
    for (int k = 0; k < K.outerSize(); ++k)
      for (SparseMatrix::InnerIterator it(K, k); it; ++it)
        if (fixed[it.row()] || fixed[it.col()]) it.valueRef() = it.row() == it.col() ? 1.0 : 0.0;
    for (Index i = 0; i < nd; ++i)
      if (fixed[i]) rhs[i] = g[i];
    solver->setup(K);
    solver->solve(rhs, dx);
    x += dx;
    last_dx = dx.norm();
  }
  EXPECT_LT(its, 30) << "Newton did not converge (order " << order << ", n " << n << ")";

  // Errors.
  double l2 = 0.0, h1 = 0.0;
  for (Index e = 0; e < m.num_elements(); ++e) {
    const Index* c = m.element(e);
    for (int a = 0; a < npe; ++a) {
      Xe.row(a) = m.nodes[c[a]].transpose();
      xe.row(a) = x.segment<2>(2 * c[a]).transpose();
    }
    for (const auto& q : rule) {
      triangle_shape(order, q.xi1, q.xi2, N, dN);
      const Mat2 A0 = Xe.transpose() * dN;
      const double dV = q.weight * A0.determinant();
      const Vec2 Xq = Xe.transpose() * N;
      const Vec2 xq = xe.transpose() * N;
      const Mat2 Fh = xe.transpose() * dN * A0.inverse();
      l2 += (xq - Xq - u_exact(Xq)).squaredNorm() * dV;
      h1 += (Fh - F_exact(Xq)).squaredNorm() * dV;
    }
  }
  return {1.0 / n, std::sqrt(l2), std::sqrt(h1), its, nd};
}

TEST(ManufacturedSolution, BodyForceIsMinusDivergenceOfP) {
  // Guard of the test's own analytic derivative: central differences of P (h = 1e-5; truncation
  // ~1e-10, round-off ~1e-11 relative to |b| ~ 0.1).
  const double h = 1e-5;
  for (const Vec2& X : {Vec2(0.1, 0.2), Vec2(0.7, 0.4), Vec2(0.5, 0.9)}) {
    Vec2 div = Vec2::Zero();
    for (int K = 0; K < 2; ++K) {
      Vec2 dX = Vec2::Zero();
      dX[K] = h;
      div += (piola(F_exact(X + dX)) - piola(F_exact(X - dX))).col(K) / (2 * h);
    }
    EXPECT_LT((body_force(X) + div).norm(), 1e-8 * div.norm());
    // and F_exact is the gradient of u_exact
    for (int K = 0; K < 2; ++K) {
      Vec2 dX = Vec2::Zero();
      dX[K] = h;
      const Vec2 col = (u_exact(X + dX) - u_exact(X - dX)) / (2 * h);
      EXPECT_LT((F_exact(X).col(K) - Mat2::Identity().col(K) - col).norm(), 1e-9);
    }
  }
}

class SpatialConvergence : public ::testing::TestWithParam<int> {};

TEST_P(SpatialConvergence, OptimalOrdersL2AndH1) {
  const int p = GetParam();
  // Mesh sequences chosen so that the finest error is far above round-off (the T10 H1 error is about
  // 2e-6 at n = 16) and each order runs in under a second.
  const std::vector<int> ns = p == 1   ? std::vector<int>{8, 16, 32, 64}
                              : p == 2 ? std::vector<int>{4, 8, 16, 32}
                                       : std::vector<int>{2, 4, 8, 16};
  std::vector<Errors> errs;
  for (int n : ns) errs.push_back(solve_and_measure(p, n));
  for (size_t i = 0; i < errs.size(); ++i) {
    std::printf("T%-2d n=%3d dofs=%6d newton=%d  e_L2=%.3e  e_H1=%.3e", TriMesh::nodes_per_element(p), ns[i],
                errs[i].dofs, errs[i].newton, errs[i].l2, errs[i].h1);
    if (i > 0)
      std::printf("  order L2 %.3f  H1 %.3f", std::log(errs[i - 1].l2 / errs[i].l2) / std::log(2.0),
                  std::log(errs[i - 1].h1 / errs[i].h1) / std::log(2.0));
    std::printf("\n");
  }
  const auto& a = errs[errs.size() - 2];
  const auto& b = errs.back();
  const double order_l2 = std::log(a.l2 / b.l2) / std::log(a.h / b.h);
  const double order_h1 = std::log(a.h1 / b.h1) / std::log(a.h / b.h);
  EXPECT_GE(order_l2, p + 1 - 0.3) << "T" << TriMesh::nodes_per_element(p);
  EXPECT_GE(order_h1, p - 0.3) << "T" << TriMesh::nodes_per_element(p);
  // The error must also be small in absolute terms on the finest mesh (|u| ~ 0.1; measured 1e-8..1e-5).
  EXPECT_LT(b.l2, 1e-3 * 0.1);
}

INSTANTIATE_TEST_SUITE_P(Orders, SpatialConvergence, ::testing::Values(1, 2, 3),
                         [](const ::testing::TestParamInfo<int>& i) {
                           return "T" + std::to_string(TriMesh::nodes_per_element(i.param));
                         });

}  // namespace
