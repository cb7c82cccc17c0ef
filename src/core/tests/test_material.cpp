// Hyperelastic laws of material.hpp: stresses and tangents against finite differences of the energy,
// the linear-elastic limit built from (E, nu), plane-stress conditions, objectivity, inversion.
#include <lagfsi/error.hpp>
#include <lagfsi/material.hpp>

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

using namespace lagfsi;

namespace {

struct Params {
  double E, nu;
};
const std::vector<Params> kParams = {{210.0, 0.3}, {1.0, 0.45}, {3.0, 0.0}, {50.0, -0.2}};
const char* const kLaws[] = {"svk", "neo_hookean"};
const PlaneHypothesis kHyps[] = {PlaneHypothesis::PlaneStrain, PlaneHypothesis::PlaneStress};

std::string label(const std::string& law, PlaneHypothesis h, const Params& p) {
  return law + (h == PlaneHypothesis::PlaneStrain ? " plane strain" : " plane stress") + " E=" + std::to_string(p.E) +
         " nu=" + std::to_string(p.nu);
}

// Linear-elastic Voigt matrix (engineering shear), from E and nu only.
Eigen::Matrix3d linear_elastic(double E, double nu, PlaneHypothesis h) {
  Eigen::Matrix3d D;
  if (h == PlaneHypothesis::PlaneStrain) {
    const double f = E / ((1 + nu) * (1 - 2 * nu));
    D << 1 - nu, nu, 0, nu, 1 - nu, 0, 0, 0, (1 - 2 * nu) / 2;
    D *= f;
  } else {
    const double f = E / (1 - nu * nu);
    D << 1, nu, 0, nu, 1, 0, 0, 0, (1 - nu) / 2;
    D *= f;
  }
  return D;
}

Mat2 rotation(double t) {
  Mat2 R;
  R << std::cos(t), -std::sin(t), std::sin(t), std::cos(t);
  return R;
}

// Green-Lagrange strain from the engineering vector e = (E11, E22, 2 E12).
Mat2 strain(const Eigen::Vector3d& e) {
  Mat2 E;
  E << e(0), 0.5 * e(2), 0.5 * e(2), e(1);
  return E;
}

// Symmetric stretch U = sqrt(C) with C = I + 2E, so that U^T U = C.
Mat2 stretch_from_strain(const Mat2& E) {
  const Mat2 C = Mat2::Identity() + 2.0 * E;
  Eigen::SelfAdjointEigenSolver<Mat2> es(C);
  return es.operatorSqrt();
}

Eigen::Vector3d voigt(const Mat2& S) { return Eigen::Vector3d(S(0, 0), S(1, 1), S(0, 1)); }

Eigen::Vector3d engineering(const Mat2& F) {
  const Mat2 E = 0.5 * (F.transpose() * F - Mat2::Identity());
  return Eigen::Vector3d(E(0, 0), E(1, 1), 2.0 * E(0, 1));
}

MaterialResponse at_strain(const SolidMaterial& m, const Eigen::Vector3d& e) {
  return m.evaluate(stretch_from_strain(strain(e)));
}

// Deformation gradients with det F > 0: near identity, and far from it (stretches up to smax).
std::vector<Mat2> sample_F(unsigned seed, double smin, double smax) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), s(smin, smax), ang(-3.0, 3.0);
  std::vector<Mat2> out;
  for (int i = 0; i < 4; ++i) {
    Mat2 G;
    G << u(gen), u(gen), u(gen), u(gen);
    out.push_back(Mat2::Identity() + 0.02 * G);
  }
  for (int i = 0; i < 6; ++i) {
    const Mat2 Sd = Eigen::Vector2d(s(gen), s(gen)).asDiagonal();
    out.push_back(rotation(ang(gen)) * Sd * rotation(ang(gen)).transpose());
  }
  Mat2 shear;
  shear << 1.0, 0.4, 0.0, 1.0;
  out.push_back(shear);
  return out;
}

// Stretch range admissible for both laws (SVK plane stress needs 1 + 2 E33 > 0).
std::vector<Mat2> sample_for(const std::string& law, PlaneHypothesis h, unsigned seed) {
  if (law == "svk" && h == PlaneHypothesis::PlaneStress) return sample_F(seed, 0.75, 1.25);
  return sample_F(seed, 0.55, 1.6);
}

}  // namespace

static_assert(std::is_base_of_v<MaterialLaw, SolidMaterial>, "the solids' laws are material laws");

TEST(Material, FactoryAndAccessors) {
  auto m = make_solid_material("svk", 100.0, 0.25, 7.8, PlaneHypothesis::PlaneStress);
  EXPECT_EQ(m->type(), "svk");
  EXPECT_DOUBLE_EQ(m->young(), 100.0);
  EXPECT_DOUBLE_EQ(m->poisson(), 0.25);
  EXPECT_DOUBLE_EQ(m->density(), 7.8);
  EXPECT_EQ(m->hypothesis(), PlaneHypothesis::PlaneStress);
  EXPECT_EQ(make_solid_material("neo_hookean", 1.0, 0.3, 1.0, PlaneHypothesis::PlaneStrain)->type(), "neo_hookean");
  try {
    make_solid_material("mooney", 1.0, 0.3, 1.0, PlaneHypothesis::PlaneStrain);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "unknown material 'mooney' (valid: svk, neo_hookean)");
  }
  EXPECT_THROW(make_solid_material("svk", -1.0, 0.3, 1.0, PlaneHypothesis::PlaneStrain), std::invalid_argument);
  EXPECT_THROW(make_solid_material("svk", 1.0, 0.5, 1.0, PlaneHypothesis::PlaneStrain), std::invalid_argument);
}

TEST(Material, IdentityGivesZeroStressAndLinearElasticTangent) {
  for (const auto& p : kParams)
    for (const char* law : kLaws)
      for (auto h : kHyps) {
        auto m = make_solid_material(law, p.E, p.nu, 1.0, h);
        const auto r = m->evaluate(Mat2::Identity());
        const std::string what = label(law, h, p);
        EXPECT_NEAR(r.psi, 0.0, 1e-14 * p.E) << what;
        EXPECT_LT(r.S.norm(), 1e-14 * p.E) << what;
        EXPECT_NEAR(r.S33, 0.0, 1e-14 * p.E) << what;
        EXPECT_NEAR(r.F33, 1.0, 1e-14) << what;
        const Eigen::Matrix3d D0 = linear_elastic(p.E, p.nu, h);
        EXPECT_LT((r.D - D0).norm(), 1e-12 * D0.norm()) << what << "\nD =\n" << r.D << "\nexpected\n" << D0;
      }
}

TEST(Material, StressIsEnergyDerivative) {
  // S_v(a) = d psi / d e_a with e = (E11, E22, 2 E12), by central differences on E (F = sqrt(I + 2E)).
  const double h = 1e-5;
  unsigned seed = 1;
  for (const auto& p : kParams)
    for (const char* law : kLaws)
      for (auto hyp : kHyps) {
        auto m = make_solid_material(law, p.E, p.nu, 1.0, hyp);
        for (const Mat2& F : sample_for(law, hyp, seed++)) {
          const Eigen::Vector3d e = engineering(F);
          const auto r = at_strain(*m, e);
          const double scale = r.D.norm();
          for (int a = 0; a < 3; ++a) {
            Eigen::Vector3d ep = e, em = e;
            ep(a) += h;
            em(a) -= h;
            const double fd = (at_strain(*m, ep).psi - at_strain(*m, em).psi) / (2 * h);
            EXPECT_NEAR(voigt(r.S)(a), fd, 1e-7 * scale) << label(law, hyp, p) << " component " << a << "\nF =\n" << F;
          }
        }
      }
}

TEST(Material, FirstPiolaIsEnergyDerivativeWrtF) {
  // P = F S = d psi / dF, by central differences on the (non-symmetric) entries of F.
  const double h = 1e-6;
  unsigned seed = 100;
  for (const auto& p : kParams)
    for (const char* law : kLaws)
      for (auto hyp : kHyps) {
        auto m = make_solid_material(law, p.E, p.nu, 1.0, hyp);
        for (const Mat2& F : sample_for(law, hyp, seed++)) {
          const auto r = m->evaluate(F);
          const Mat2 P = F * r.S;
          const double scale = r.D.norm();
          for (int i = 0; i < 2; ++i)
            for (int j = 0; j < 2; ++j) {
              Mat2 Fp = F, Fm = F;
              Fp(i, j) += h;
              Fm(i, j) -= h;
              const double fd = (m->evaluate(Fp).psi - m->evaluate(Fm).psi) / (2 * h);
              EXPECT_NEAR(P(i, j), fd, 1e-6 * scale) << label(law, hyp, p) << " P" << i << j;
            }
        }
      }
}

TEST(Material, TangentIsStressDerivativeAndSymmetric) {
  // Column b of D = d S_v / d e_b; column 3 perturbs E12 and E21 each by h/2.
  const double h = 1e-5;
  unsigned seed = 200;
  for (const auto& p : kParams)
    for (const char* law : kLaws)
      for (auto hyp : kHyps) {
        auto m = make_solid_material(law, p.E, p.nu, 1.0, hyp);
        for (const Mat2& F : sample_for(law, hyp, seed++)) {
          const Eigen::Vector3d e = engineering(F);
          const auto r = at_strain(*m, e);
          const double scale = r.D.norm();
          EXPECT_LT((r.D - r.D.transpose()).norm(), 1e-12 * scale) << label(law, hyp, p);
          for (int b = 0; b < 3; ++b) {
            Eigen::Vector3d ep = e, em = e;
            ep(b) += h;
            em(b) -= h;
            const Eigen::Vector3d fd = (voigt(at_strain(*m, ep).S) - voigt(at_strain(*m, em).S)) / (2 * h);
            for (int a = 0; a < 3; ++a)
              EXPECT_NEAR(r.D(a, b), fd(a), 1e-7 * scale) << label(law, hyp, p) << " D(" << a << "," << b << ")\nF =\n"
                                                          << F;
          }
        }
      }
}

TEST(Material, PlaneStressOutOfPlaneConditions) {
  unsigned seed = 300;
  for (const auto& p : kParams) {
    const double lam = p.E * p.nu / ((1 + p.nu) * (1 - 2 * p.nu)), mu = p.E / (2 * (1 + p.nu));
    // Neo-Hookean: the 3D S33 = mu (1 - 1/C33) + lam ln J / C33 with J = det F * F33 vanishes.
    auto nh = make_solid_material("neo_hookean", p.E, p.nu, 1.0, PlaneHypothesis::PlaneStress);
    for (const Mat2& F : sample_F(seed++, 0.55, 1.6)) {
      const auto r = nh->evaluate(F);
      const double c33 = r.F33 * r.F33;
      const double S33 = mu * (1 - 1 / c33) + lam * std::log(F.determinant() * r.F33) / c33;
      EXPECT_NEAR(S33, 0.0, 1e-12 * p.E) << "nu " << p.nu;
      EXPECT_EQ(r.S33, 0.0);
      // The energy includes the out-of-plane stretch: 3D formula with C33 = F33^2.
      const double lnJ = std::log(F.determinant() * r.F33);
      const double psi = 0.5 * mu * ((F.transpose() * F).trace() + c33 - 3) - mu * lnJ + 0.5 * lam * lnJ * lnJ;
      EXPECT_NEAR(r.psi, psi, 1e-12 * p.E);
    }
    // SVK: E33 = (F33^2 - 1)/2 = -nu/(1 - nu) (E11 + E22) makes the 3D S33 vanish.
    auto svk = make_solid_material("svk", p.E, p.nu, 1.0, PlaneHypothesis::PlaneStress);
    for (const Mat2& F : sample_F(seed++, 0.75, 1.25)) {
      const auto r = svk->evaluate(F);
      const Eigen::Vector3d e = engineering(F);
      EXPECT_NEAR(0.5 * (r.F33 * r.F33 - 1), -p.nu / (1 - p.nu) * (e(0) + e(1)), 1e-13);
      EXPECT_EQ(r.S33, 0.0);
    }
  }
}

TEST(Material, PlaneStressNeoHookeanExtremeCompressionConverges) {
  // Strong compression of a nearly incompressible material: the S33 = 0 iteration must still converge.
  auto m = make_solid_material("neo_hookean", 1.0, 0.49, 1.0, PlaneHypothesis::PlaneStress);
  const double lam = 0.49 / (1.49 * 0.02), mu = 1.0 / 2.98;
  for (double s : {0.05, 0.2, 3.0, 10.0}) {
    const Mat2 F = Eigen::Vector2d(s, 0.9 * s).asDiagonal();
    const auto r = m->evaluate(F);
    const double c33 = r.F33 * r.F33, lnJ = std::log(F.determinant() * r.F33);
    // Relative to the size of the two terms (each ~ mu / C33, large in strong stretching).
    const double terms = mu * std::abs(1 - 1 / c33) + lam * std::abs(lnJ) / c33;
    EXPECT_NEAR(mu * (1 - 1 / c33) + lam * lnJ / c33, 0.0, 1e-13 * terms) << "s " << s;
    EXPECT_GT(terms, 0.1) << "s " << s;  // a real out-of-plane adjustment took place
    EXPECT_TRUE(r.D.allFinite());
  }
}

TEST(Material, PlaneStrainOutOfPlaneStress) {
  // Small strains: S33 = nu (S11 + S22) as in linear elasticity (exact for SVK, to O(eps^2) for Neo-Hookean).
  std::mt19937 gen(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const auto& p : kParams)
    for (const char* law : kLaws) {
      auto m = make_solid_material(law, p.E, p.nu, 1.0, PlaneHypothesis::PlaneStrain);
      Mat2 G;
      G << u(gen), u(gen), u(gen), u(gen);
      const double eps = 1e-4;
      const auto r = m->evaluate(Mat2::Identity() + eps * G);
      EXPECT_EQ(r.F33, 1.0);
      const double tol = std::string(law) == "svk" ? 1e-13 * p.E : 10 * p.E * eps * eps;
      EXPECT_NEAR(r.S33, p.nu * r.S.trace(), tol) << law << " nu " << p.nu;
    }
}

TEST(Material, SvkAndNeoHookeanAgreeToFirstOrder) {
  std::mt19937 gen(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const auto& p : kParams)
    for (auto hyp : kHyps) {
      auto svk = make_solid_material("svk", p.E, p.nu, 1.0, hyp);
      auto nh = make_solid_material("neo_hookean", p.E, p.nu, 1.0, hyp);
      for (int trial = 0; trial < 3; ++trial) {
        Mat2 G;
        G << u(gen), u(gen), u(gen), u(gen);
        auto diff = [&](double eps) {
          const Mat2 F = Mat2::Identity() + eps * G;
          return (svk->evaluate(F).S - nh->evaluate(F).S).norm();
        };
        const double d1 = diff(1e-3), d2 = diff(5e-4);
        const double S1 = svk->evaluate(Mat2::Identity() + 1e-3 * G).S.norm();
        EXPECT_LT(d1, 1e-2 * S1) << label("both", hyp, p);        // much smaller than the stress itself
        EXPECT_NEAR(d1 / d2, 4.0, 0.2) << label("both", hyp, p);  // quadratic in the strain
      }
    }
}

TEST(Material, Objectivity) {
  std::mt19937 gen(21);
  std::uniform_real_distribution<double> ang(-3.0, 3.0);
  for (const auto& p : kParams)
    for (const char* law : kLaws)
      for (auto hyp : kHyps) {
        auto m = make_solid_material(law, p.E, p.nu, 1.0, hyp);
        const std::string what = label(law, hyp, p);
        for (int k = 0; k < 3; ++k) {
          const Mat2 R = rotation(ang(gen));
          const auto r = m->evaluate(R);
          EXPECT_LT(r.S.norm(), 1e-12 * p.E) << what;
          EXPECT_NEAR(r.psi, 0.0, 1e-12 * p.E) << what;
          EXPECT_NEAR(r.F33, 1.0, 1e-12) << what;
        }
        for (const Mat2& F : sample_for(law, hyp, 400u + static_cast<unsigned>(p.E))) {
          const Mat2 U = stretch_from_strain(0.5 * (F.transpose() * F - Mat2::Identity()));
          const Mat2 R = rotation(ang(gen));
          const auto ru = m->evaluate(U), rr = m->evaluate(R * U);
          EXPECT_LT((ru.S - rr.S).norm(), 1e-12 * ru.D.norm()) << what;
          EXPECT_LT((ru.D - rr.D).norm(), 1e-12 * ru.D.norm()) << what;
          EXPECT_NEAR(ru.psi, rr.psi, 1e-12 * ru.D.norm()) << what;
          EXPECT_NEAR(ru.F33, rr.F33, 1e-12) << what;
          // F and its polar stretch give the same response too.
          EXPECT_LT((m->evaluate(F).S - ru.S).norm(), 1e-10 * ru.D.norm()) << what;
        }
      }
}

TEST(Material, InvertedOrNonFiniteFThrows) {
  Mat2 zero_det, neg_det, reflect, nan_F;
  zero_det << 1.0, 2.0, 0.5, 1.0;
  neg_det << 1.0, 2.0, 2.0, 1.0;
  reflect << 1.0, 0.0, 0.0, -1.0;
  nan_F << 1.0, std::nan(""), 0.0, 1.0;
  for (const char* law : kLaws)
    for (auto hyp : kHyps) {
      auto m = make_solid_material(law, 1.0, 0.3, 1.0, hyp);
      for (const Mat2& F : {zero_det, neg_det, reflect, nan_F}) {
        try {
          m->evaluate(F);
          ADD_FAILURE() << law << ": no exception for F =\n" << F;
        } catch (const SolverError& e) {
          EXPECT_NE(std::string(e.what()).find("inverted element (det F = "), std::string::npos) << e.what();
        }
      }
    }
  // SVK plane stress has no real thickness stretch when tr E is too large.
  auto svk = make_solid_material("svk", 1.0, 0.3, 1.0, PlaneHypothesis::PlaneStress);
  EXPECT_THROW(svk->evaluate(2.0 * Mat2::Identity()), SolverError);
}
