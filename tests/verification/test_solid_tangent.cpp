// Verification of SolidBody::internal_force (solid.hpp), the positional formulation of Coda (2003) /
// Coda & Paccola (2008):
//  - the Hessian K equals central finite differences of f_int (K is the exact tangent);
//  - f_int equals central finite differences of strain_energy (f_int is the exact gradient);
//  - K is symmetric (it is the Hessian of a potential);
//  - objectivity: a rigid translation plus a finite rotation of the reference configuration gives zero
//    internal force and zero energy, and superposing a rigid motion on a deformed state rotates f_int
//    and K (f(Q x + c) = Q f(x), K(Q x + c) = Q K(x) Q^T with Q acting node by node).
// For T3, T6, T10, both laws (svk, neo_hookean) and both hypotheses (plane strain, plane stress), at a
// random, moderately large deformation (stretches of about +-30 %, shear about 0.3, plus a random
// nodal perturbation) of a mesh whose reference nodes are also randomly perturbed (curved T6/T10
// elements, so that the general isoparametric path is exercised).
#include <lagfsi/material.hpp>
#include <lagfsi/meshing/primitives.hpp>
#include <lagfsi/solid/solid.hpp>

#include <gtest/gtest.h>

#include "finite_difference.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>

using namespace lagfsi;

namespace {

struct Config {
  int order;
  std::string law;
  PlaneHypothesis hyp;
};

std::string name_of(const Config& c) {
  return "T" + std::to_string(TriMesh::nodes_per_element(c.order)) + "_" + c.law + "_" +
         (c.hyp == PlaneHypothesis::PlaneStrain ? "plane_strain" : "plane_stress");
}

constexpr double kE = 100.0, kNu = 0.3, kRho = 2.0, kThickness = 0.4;

/// A 3 x 2 crossed mesh of [0, 1] x [0, 0.7], elevated, with every node moved randomly by up to
/// 4 % of the cell size (edges become curved for T6 / T10; Jacobians stay positive).
TriMesh make_mesh(int order, std::mt19937& gen) {
  TriMesh m = meshing::elevate(meshing::mesh_rectangle_structured(0.0, 0.0, 1.0, 0.7, 3, 2, "crossed"), order);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double amp = 0.04 * 0.33;
  for (auto& p : m.nodes) p += amp * Vec2(u(gen), u(gen));
  return m;
}

/// A moderately large smooth deformation plus a small random nodal perturbation.
Vec deformed(const Vec& X, std::mt19937& gen) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vec x(X.size());
  for (Index i = 0; i < X.size() / 2; ++i) {
    const double a = X[2 * i], b = X[2 * i + 1];
    x[2 * i] = 1.25 * a + 0.3 * b + 0.15 * a * b + 0.05 * std::sin(2.0 * b) + 0.01 * u(gen);
    x[2 * i + 1] = -0.1 * a + 0.8 * b + 0.1 * a * a + 0.01 * u(gen);
  }
  return x;
}

Mat2 rotation(double t) {
  Mat2 R;
  R << std::cos(t), -std::sin(t), std::sin(t), std::cos(t);
  return R;
}

Vec rigid(const Vec& x, const Mat2& Q, const Vec2& c) {
  Vec y(x.size());
  for (Index i = 0; i < x.size() / 2; ++i) y.segment<2>(2 * i) = Q * x.segment<2>(2 * i) + c;
  return y;
}

class SolidTangent : public ::testing::TestWithParam<Config> {};

TEST_P(SolidTangent, HessianGradientSymmetryObjectivity) {
  const Config cfg = GetParam();
  std::mt19937 gen(1234 + 17 * cfg.order);
  auto mat = std::shared_ptr<const SolidMaterial>(make_solid_material(cfg.law, kE, kNu, kRho, cfg.hyp));
  SolidBody body(make_mesh(cfg.order, gen), mat, kThickness);
  const Index nd = body.num_dofs();
  const Vec& X = body.reference_positions();
  const Vec x = deformed(X, gen);

  SparseMatrix K = body.pattern();
  Vec f;
  const double W = body.internal_force(x, f, &K);
  const Eigen::MatrixXd Kd = Eigen::MatrixXd(K);
  ASSERT_GT(f.norm(), 1.0);  // a genuinely loaded state (force scale E t L ~ 40)
  ASSERT_GT(W, 0.0);
  EXPECT_NEAR(W, body.strain_energy(x), 1e-13 * W);

  // 1. K against central differences of f_int, column by column. Step h = 1e-6 (lengths are O(1)):
  //    truncation O(h^2 f''') ~ 1e-12 relative, round-off O(eps |f| / h) ~ 1e-10 relative, so 1e-6
  //    leaves a wide margin while any missing or wrong term (geometric stiffness, plane-stress
  //    condensation, a wrong D) gives an O(1e-2..1) relative error.
  {
    const Eigen::MatrixXd Kfd = lagfsi::testing::central_jacobian(
        [&](const Vec& y, Vec& out) { body.internal_force(y, out, nullptr); }, x, 1e-6);
    const double rel = (Kd - Kfd).norm() / Kd.norm();
    std::printf("%-28s |K - K_fd|/|K| = %.2e", name_of(cfg).c_str(), rel);
    EXPECT_LT(rel, 1e-6) << name_of(cfg) << ": |K - K_fd| / |K| = " << rel;
    // Entry-wise too, so that a small block cannot hide in the norm of a large matrix.
    const double worst = (Kd - Kfd).cwiseAbs().maxCoeff() / Kd.cwiseAbs().maxCoeff();
    EXPECT_LT(worst, 1e-6) << name_of(cfg) << ": max entry error / max |K| = " << worst;
  }

  // 2. f_int against central differences of the energy (h = 1e-5: round-off eps W / h ~ 1e-11 of |f|,
  //    truncation h^2 ~ 1e-10).
  {
    const Vec g = lagfsi::testing::central_gradient([&](const Vec& y) { return body.strain_energy(y); }, x, 1e-5);
    const double rel = (f - g).norm() / f.norm();
    std::printf("  |f - dW/dx|/|f| = %.2e\n", rel);
    EXPECT_LT(rel, 1e-6) << name_of(cfg) << ": |f - dW/dx| / |f| = " << rel;
  }

  // 3. Symmetry (exact up to round-off of the assembly: 1e-12 relative).
  {
    const double asym = (Kd - Kd.transpose()).norm() / Kd.norm();
    EXPECT_LT(asym, 1e-12) << name_of(cfg);
    // The pattern must be the one the body announces: K's structure equals pattern()'s.
    ASSERT_EQ(K.nonZeros(), body.pattern().nonZeros());
  }

  // 4. Objectivity. Force scale for "zero to round-off": E t L = 40; round-off of a sum of O(1)
  //    terms is ~1e-14 of that; 1e-10 allows for the cancellation in F^T F - I.
  const double fscale = kE * kThickness * 1.0;
  const Mat2 Q = rotation(1.1);  // a finite rotation (63 degrees)
  const Vec2 c(3.0, -2.0);
  {
    Vec fr;
    SparseMatrix Kr = body.pattern();
    const double Wr = body.internal_force(rigid(X, Q, c), fr, &Kr);
    EXPECT_LT(fr.cwiseAbs().maxCoeff(), 1e-10 * fscale) << name_of(cfg) << ": rigid motion gives f_int != 0";
    EXPECT_LT(std::abs(Wr), 1e-12 * fscale) << name_of(cfg) << ": rigid motion gives W != 0";
    // At a rigid position the tangent is the small-strain stiffness rotated: it has the 3 rigid modes
    // of the rotated body in its kernel (to round-off): translations and the infinitesimal rotation.
    const Eigen::MatrixXd Krd = Eigen::MatrixXd(Kr);
    const Vec xr = rigid(X, Q, c);
    Vec tx(nd), ty(nd), rot(nd);
    for (Index i = 0; i < nd / 2; ++i) {
      tx.segment<2>(2 * i) = Vec2(1, 0);
      ty.segment<2>(2 * i) = Vec2(0, 1);
      rot.segment<2>(2 * i) = Vec2(-(xr[2 * i + 1] - c.y()), xr[2 * i] - c.x());
    }
    for (const Vec* mode : {&tx, &ty, &rot})
      EXPECT_LT((Krd * *mode).norm(), 1e-10 * Krd.norm() * mode->norm()) << name_of(cfg) << ": rigid mode not in ker K";
  }
  {
    Vec fq;
    SparseMatrix Kq = body.pattern();
    const double Wq = body.internal_force(rigid(x, Q, c), fq, &Kq);
    EXPECT_NEAR(Wq, W, 1e-12 * W) << name_of(cfg);
    Vec fexp = rigid(f, Q, Vec2::Zero());
    EXPECT_LT((fq - fexp).norm(), 1e-11 * f.norm()) << name_of(cfg) << ": f(Qx + c) != Q f(x)";
    // Block-diagonal Q for all nodes.
    Eigen::MatrixXd Qb = Eigen::MatrixXd::Zero(nd, nd);
    for (Index i = 0; i < nd / 2; ++i) Qb.block<2, 2>(2 * i, 2 * i) = Q;
    const Eigen::MatrixXd Kexp = Qb * Kd * Qb.transpose();
    EXPECT_LT((Eigen::MatrixXd(Kq) - Kexp).norm(), 1e-11 * Kd.norm()) << name_of(cfg) << ": K(Qx + c) != Q K Q^T";
  }
  // Equilibrium of the internal forces (a consequence of objectivity): zero resultant and moment.
  {
    Vec2 R = Vec2::Zero();
    double Mz = 0.0;
    for (Index i = 0; i < nd / 2; ++i) {
      R += f.segment<2>(2 * i);
      Mz += x[2 * i] * f[2 * i + 1] - x[2 * i + 1] * f[2 * i];
    }
    EXPECT_LT(R.norm(), 1e-11 * f.norm()) << name_of(cfg);
    EXPECT_LT(std::abs(Mz), 1e-11 * f.norm()) << name_of(cfg);
  }
}

std::vector<Config> all_configs() {
  std::vector<Config> v;
  for (int p : {1, 2, 3})
    for (const char* law : {"svk", "neo_hookean"})
      for (PlaneHypothesis h : {PlaneHypothesis::PlaneStrain, PlaneHypothesis::PlaneStress}) v.push_back({p, law, h});
  return v;
}

INSTANTIATE_TEST_SUITE_P(AllElementsLawsHypotheses, SolidTangent, ::testing::ValuesIn(all_configs()),
                         [](const ::testing::TestParamInfo<Config>& i) { return name_of(i.param); });

}  // namespace
