// MPM materials and transfers, directly (src/mpm/include/lagfsi/mpm): the Mohr-Coulomb return mapping (an admissible
// trial unchanged, the tension cut-off, the apex, both edges, objectivity, and two stress paths with a closed
// form: isochoric pure shear and a drained plane-strain biaxial test), the linear elastic law, the factory, the
// shape functions, and the particle-grid transfers (P2G conserves mass and momentum; G2P reproduces a linear
// grid velocity field).
#include <lagfsi/error.hpp>
#include <lagfsi/mpm/mpm_material.hpp>
#include <lagfsi/mpm/mpm_state.hpp>
#include <lagfsi/mpm/mpm_transfer.hpp>

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

using namespace lagfsi;
using namespace lagfsi::mpm;

namespace {

// A soil: E = 10 MPa, nu = 0.3, c = 10 kPa, phi = 30 deg (c cot(phi) = 17.32 kPa, c cos(phi) = 8.66 kPa).
constexpr double kE = 1e7, kNu = 0.3, kRho = 2000, kC = 1e4, kPhi = 30;
const double kMu = kE / (2 * (1 + kNu));
const double kSin = std::sin(kPhi * M_PI / 180), kCos = std::cos(kPhi * M_PI / 180);

/// Principal stresses s1 >= s2 >= s3 of (xx, yy, xy, zz).
std::array<double, 3> principal(const Stress& s) {
  const double c = 0.5 * (s[0] + s[1]), r = std::hypot(0.5 * (s[0] - s[1]), s[2]);
  std::array<double, 3> p = {c + r, c - r, s[3]};
  std::sort(p.begin(), p.end(), [](double a, double b) { return a > b; });
  return p;
}

/// Mohr-Coulomb yield function of the planes through (si, sj), si >= sj.
double f_plane(double si, double sj) { return (si - sj) + (si + sj) * kSin - 2 * kC * kCos; }

/// Isotropic elastic D n in principal space.
Eigen::Vector3d D(const Eigen::Vector3d& n) {
  const double lambda = kE * kNu / ((1 + kNu) * (1 - 2 * kNu));
  return Eigen::Vector3d::Constant(lambda * n.sum()) + 2 * kMu * n;
}

}  // namespace

// ---------------------------------------------------------------- Mohr-Coulomb return mapping

static_assert(std::is_base_of_v<MaterialLaw, MpmMaterial>, "the MPM laws are material laws");

TEST(MpmMaterial, MohrCoulombDeclaresItsPlasticMultiplierAndTheElasticLawNothing) {
  const MohrCoulomb mc(kE, kNu, kRho, kC, kPhi, 0.0);
  EXPECT_EQ(mc.state_variables(), (std::vector<std::string>{"plastic_multiplier"}));
  EXPECT_TRUE(LinearElastic(kE, kNu, kRho).state_variables().empty());
  EXPECT_DOUBLE_EQ(mc.shear_modulus(), kMu);  // the constants of MaterialLaw
  EXPECT_DOUBLE_EQ(mc.density(), kRho);
}

TEST(MpmMohrCoulomb, AdmissibleTrialIsUnchanged) {
  const MohrCoulomb mc(kE, kNu, kRho, kC, kPhi, 0.0);
  for (const Stress& trial : {Stress{-100e3, -120e3, 5e3, -110e3}, Stress{0, 0, 0, 0}, Stress{1e3, -2e3, 1e3, 0.0},
                              Stress{-300e3, -200e3, -40e3, -250e3}}) {
    Stress s = trial;
    EXPECT_EQ(mc.return_mapping(s), 0.0);
    for (int k = 0; k < 4; ++k) EXPECT_EQ(s[k], trial[k]) << k;
  }
}

TEST(MpmMohrCoulomb, TensionCutOffCapsTheLargestPrincipalStress) {
  // Inside the Mohr-Coulomb surface (f = -3.3 kPa) but s1 = 6 kPa above a cut-off of 5 kPa: only s1 is cut,
  // with the multiplier (s1 - cut-off) / 2 mu.
  const MohrCoulomb mc(kE, kNu, kRho, kC, kPhi, 0.0, 5e3);
  ASSERT_LT(f_plane(6e3, -10e3), 0.0);
  Stress s = {6e3, -10e3, 0.0, -5e3};
  const double dg = mc.return_mapping(s);
  EXPECT_DOUBLE_EQ(s[0], 5e3);
  EXPECT_EQ(s[1], -10e3);
  EXPECT_EQ(s[2], 0.0);
  EXPECT_EQ(s[3], -5e3);
  EXPECT_NEAR(dg, 1e3 / (2 * kMu), 1e-15);
}

TEST(MpmMohrCoulomb, TrialBeyondTheApexReturnsToTheApex) {
  // Hydrostatic tension of 1 MPa, far beyond c cot(phi): back to the apex, all principal stresses c cot(phi).
  const MohrCoulomb mc(kE, kNu, kRho, kC, kPhi, 0.0);
  const double apex = kC * kCos / kSin;
  EXPECT_NEAR(mc.apex(), apex, 1e-9 * apex);
  EXPECT_NEAR(mc.tension_cutoff(), apex, 1e-9 * apex);  // default cut-off: at the apex
  for (const Stress& trial : {Stress{1e6, 1e6, 0.0, 1e6}, Stress{3e5, 1e5, 5e4, 2e5}, Stress{5e4, 4e4, 0.0, -1e4}}) {
    Stress s = trial;
    const double dg = mc.return_mapping(s);
    EXPECT_GT(dg, 0.0);
    EXPECT_NEAR(s[0], apex, 1e-9 * apex);
    EXPECT_NEAR(s[1], apex, 1e-9 * apex);
    EXPECT_NEAR(s[2], 0.0, 1e-9 * apex);
    EXPECT_NEAR(s[3], apex, 1e-9 * apex);
  }
  // With a cut-off below the apex, the apex is cut down to it.
  const MohrCoulomb capped(kE, kNu, kRho, kC, kPhi, 0.0, 5e3);
  Stress s = {1e6, 1e6, 0.0, 1e6};
  EXPECT_GT(capped.return_mapping(s), 0.0);
  for (int k : {0, 1, 3}) EXPECT_NEAR(s[k], 5e3, 1e-9 * 5e3) << k;
  EXPECT_NEAR(s[2], 0.0, 1e-6);
}

namespace {

/// Checks a return onto an edge: the two principal stresses of the edge equal, both planes' yield functions zero
/// (to round-off), and trial - result = g1 D n1 + g2 D n2 with g1, g2 >= 0 summing to the returned multiplier.
void expect_edge_return(const Stress& trial, bool upper_edge, double psi) {
  const MohrCoulomb mc(kE, kNu, kRho, kC, kPhi, psi);
  Stress s = trial;
  const double dg = mc.return_mapping(s);
  const auto t = principal(trial), r = principal(s);
  const double scale = std::abs(t[2]);
  if (upper_edge)
    EXPECT_NEAR(r[0], r[1], 1e-12 * scale);  // s1 = s2
  else
    EXPECT_NEAR(r[1], r[2], 1e-12 * scale);  // s2 = s3
  EXPECT_NEAR(f_plane(r[0], r[2]), 0.0, 1e-10 * scale);
  EXPECT_NEAR(upper_edge ? f_plane(r[1], r[2]) : f_plane(r[0], r[1]), 0.0, 1e-10 * scale);
  // The flow directions of the two active planes, in the sorted principal frame.
  const double sp = std::sin(psi * M_PI / 180);
  Eigen::Vector3d n1(1 + sp, 0, -(1 - sp)),
      n2 = upper_edge ? Eigen::Vector3d(0, 1 + sp, -(1 - sp)) : Eigen::Vector3d(1 + sp, -(1 - sp), 0);
  Eigen::Matrix<double, 3, 2> A;
  A << D(n1), D(n2);
  const Eigen::Vector3d delta(t[0] - r[0], t[1] - r[1], t[2] - r[2]);
  const Eigen::Vector2d g = A.colPivHouseholderQr().solve(delta);
  EXPECT_NEAR((A * g - delta).norm(), 0.0, 1e-10 * scale);
  EXPECT_GT(g[0], 0.0);
  EXPECT_GT(g[1], 0.0);
  EXPECT_NEAR(dg, g[0] + g[1], 1e-9 * dg);
}

}  // namespace

TEST(MpmMohrCoulomb, ReturnToTheEdges) {
  // s1 = s2 > s3 (triaxial extension of the compression side): the main-plane return would put s1 below s2.
  expect_edge_return({-50e3, -300e3, 0.0, -50e3}, true, 0.0);
  // s1 > s2 = s3: the main-plane return would put s3 above s2.
  expect_edge_return({-50e3, -300e3, 0.0, -300e3}, false, 0.0);
  // The same with dilatancy (psi = 10 deg), and with the out-of-plane stress not quite on the edge.
  expect_edge_return({-50e3, -300e3, 0.0, -55e3}, true, 10.0);
  expect_edge_return({-50e3, -300e3, 0.0, -290e3}, false, 10.0);
}

TEST(MpmMohrCoulomb, MainPlaneReturnKeepsThePrincipalDirections) {
  // A trial on the main plane's side (s2 well between s1 and s3), given in axes turned by 25 degrees: the
  // result is the unturned result turned, and it lies on the yield surface.
  const MohrCoulomb mc(kE, kNu, kRho, kC, kPhi, 5.0);
  Stress a = {-20e3, -400e3, 0.0, -200e3};
  const double dga = mc.return_mapping(a);
  ASSERT_GT(dga, 0.0);
  const auto ra = principal(a);
  EXPECT_NEAR(f_plane(ra[0], ra[2]), 0.0, 1e-10 * 400e3);
  EXPECT_EQ(a[2], 0.0);
  const double th = 25 * M_PI / 180, c = std::cos(th), s = std::sin(th);
  auto turn = [&](const Stress& x) {
    Mat2 S;
    S << x[0], x[2], x[2], x[1];
    Mat2 R;
    R << c, -s, s, c;
    const Mat2 T = R * S * R.transpose();
    return Stress{T(0, 0), T(1, 1), T(0, 1), x[3]};
  };
  Stress b = turn({-20e3, -400e3, 0.0, -200e3});
  EXPECT_NEAR(mc.return_mapping(b), dga, 1e-12 * dga);
  const Stress expected = turn(a);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(b[k], expected[k], 1e-9 * 400e3) << k;
}

TEST(MpmMohrCoulomb, IsochoricPureShearReachesTheClosedFormStrength) {
  // From an isotropic compression p0, pure shear strain increments (dxx = -dyy = e / n, no volume change) with
  // psi = 0: the mean stress and sigma_zz stay -p0, and the shear stress (s1 - s3) / 2 rises as 2 mu e up to
  // the yield stress c cos(phi) + p0 sin(phi), where it stays; the plastic multiplier is e - e_y.
  const MohrCoulomb mc(kE, kNu, kRho, kC, kPhi, 0.0);
  const double p0 = 100e3, tau_y = kC * kCos + p0 * kSin, e_y = tau_y / (2 * kMu);
  Stress s = {-p0, -p0, 0.0, -p0};
  const int n = 400;
  const double e_end = 4 * e_y, de = e_end / n;
  double plastic = 0, e = 0;
  for (int k = 0; k < n; ++k) {
    plastic += mc.update_stress(s, {de, -de, 0.0, 0.0});
    e += de;
    const double tau = 0.5 * (s[0] - s[1]);
    EXPECT_NEAR(tau, std::min(2 * kMu * e, tau_y), 1e-9 * tau_y) << "e = " << e;
    EXPECT_NEAR(0.5 * (s[0] + s[1]), -p0, 1e-9 * p0);
    EXPECT_NEAR(s[3], -p0, 1e-9 * p0);
  }
  EXPECT_NEAR(plastic, e_end - e_y, 1e-9 * e_end);
  const auto r = principal(s);
  EXPECT_NEAR(f_plane(r[0], r[2]), 0.0, 1e-9 * p0);
  // The same path in axes turned by 45 degrees (a shear strain): sigma_xy reaches tau_y, sigma_xx = sigma_yy.
  Stress t = {-p0, -p0, 0.0, -p0};
  for (int k = 0; k < n; ++k) mc.update_stress(t, {0.0, 0.0, de, 0.0});
  EXPECT_NEAR(t[2], tau_y, 1e-9 * tau_y);
  EXPECT_NEAR(t[0], -p0, 1e-9 * p0);
  EXPECT_NEAR(t[1], -p0, 1e-9 * p0);
}

TEST(MpmMohrCoulomb, DrainedPlaneStrainBiaxialTestFailsAtTheClosedFormStress) {
  // Plane strain compression along y at a constant confining stress sigma_c on x (mixed control: each axial
  // strain increment's lateral strain found by secant iterations). Non-associated (psi = 0): perfectly plastic,
  // the axial stress reaches and keeps sigma_a = sigma_c Kp + 2 c sqrt(Kp), Kp = (1 + sin phi) / (1 - sin phi).
  const MohrCoulomb mc(kE, kNu, kRho, kC, kPhi, 0.0);
  const double sc = 100e3, Kp = (1 + kSin) / (1 - kSin), sa = sc * Kp + 2 * kC * std::sqrt(Kp);
  const double s0v = -sc;
  Stress s = {s0v, s0v, 0.0, s0v};
  const double dey = -2e-4;  // 300 steps to 6 %; failure at about 2.1 %
  double peak = 0;
  for (int k = 0; k < 300; ++k) {
    auto trial = [&](double dex, Stress& out) {
      out = s;
      mc.update_stress(out, {dex, dey, 0.0, 0.0});
      return out[0] - s0v;  // lateral stress error
    };
    Stress out;
    double x0 = 0, x1 = -kNu / (1 - kNu) * dey, r0 = trial(x0, out), r1 = trial(x1, out);
    for (int it = 0; it < 50 && std::abs(r1) > 1e-9 * sc; ++it) {
      const double x2 = x1 - r1 * (x1 - x0) / (r1 - r0);
      x0 = x1;
      r0 = r1;
      x1 = x2;
      r1 = trial(x1, out);
    }
    ASSERT_LT(std::abs(r1), 1e-6 * sc) << "step " << k;
    s = out;
    peak = std::max(peak, -s[1]);
  }
  EXPECT_NEAR(-s[1], sa, 1e-6 * sa);  // at failure at the end of the path
  EXPECT_NEAR(peak, sa, 1e-6 * sa);   // and never above it
  EXPECT_NEAR(s[0], -sc, 1e-6 * sc);
  const auto r = principal(s);
  EXPECT_NEAR(f_plane(r[0], r[2]), 0.0, 1e-6 * sa);
  EXPECT_LE(r[2], s[3]);  // sigma_zz stayed the intermediate principal stress
  EXPECT_GE(r[0], s[3]);
}

// ---------------------------------------------------------------- linear elastic law and factory

TEST(MpmLinearElastic, JaumannTrialAndNoReturn) {
  const LinearElastic le(kE, kNu, kRho);
  const double lambda = kE * kNu / ((1 + kNu) * (1 - 2 * kNu));
  Stress s = {1e3, -2e3, 5e2, 0.0};
  const double w = 1e-3;
  EXPECT_EQ(le.update_stress(s, {1e-4, 2e-4, 3e-5, w}), 0.0);
  EXPECT_NEAR(s[0], 1e3 + lambda * 3e-4 + 2 * kMu * 1e-4 + 2 * w * 5e2, 1e-9);
  EXPECT_NEAR(s[1], -2e3 + lambda * 3e-4 + 2 * kMu * 2e-4 - 2 * w * 5e2, 1e-9);
  EXPECT_NEAR(s[2], 5e2 + 2 * kMu * 3e-5 + w * (-2e3 - 1e3), 1e-9);
  EXPECT_NEAR(s[3], lambda * 3e-4, 1e-9);
  EXPECT_NEAR(le.p_wave_speed(), std::sqrt((lambda + 2 * kMu) / kRho), 1e-12);
  EXPECT_NEAR(le.s_wave_speed(), std::sqrt(kMu / kRho), 1e-12);
}

TEST(MpmMaterialFactory, ReadsBothLawsAndRejectsBadOnes) {
  auto mat =
      make_mpm_material(Params(Json{{"type", "linear_elastic"}, {"young", 1e6}, {"density", 1800.0}}, "t.json", "/m"));
  EXPECT_EQ(mat->type(), "linear_elastic");
  EXPECT_FALSE(mat->plastic());
  EXPECT_EQ(mat->poisson(), 0.0);
  auto mc = make_mpm_material(Params(Json{{"type", "mohr_coulomb"},
                                          {"young", 1e6},
                                          {"density", 1800.0},
                                          {"cohesion", 1e3},
                                          {"friction_angle", 30.0},
                                          {"tension_cutoff", 500.0}},
                                     "t.json", "/m"));
  EXPECT_EQ(mc->type(), "mohr_coulomb");
  EXPECT_TRUE(mc->plastic());
  EXPECT_EQ(dynamic_cast<const MohrCoulomb&>(*mc).tension_cutoff(), 500.0);
  EXPECT_THROW(make_mpm_material(Params(Json{{"type", "mohr_coulomb"},
                                             {"young", 1e6},
                                             {"density", 1800.0},
                                             {"cohesion", 1e3},
                                             {"friction_angle", 30.0},
                                             {"tension_cutoff", 5000.0}},
                                        "t.json", "/m")),
               InputError);  // above c cot(phi) = 1732 Pa
  EXPECT_THROW(make_mpm_material(
                   Params(Json{{"type", "mohr_coulomb"}, {"young", 1e6}, {"density", 1800.0}, {"friction_angle", 95.0}},
                          "t.json", "/m")),
               InputError);
  EXPECT_THROW(
      make_mpm_material(Params(Json{{"type", "linear_elastic"}, {"young", 1e6}, {"density", 1800.0}, {"poisson", 0.5}},
                               "t.json", "/m")),
      InputError);
}

// ---------------------------------------------------------------- shape functions and transfers

namespace {

Grid make_grid() {
  Grid g;
  g.origin = Vec2(-1.0, 0.5);
  g.h = 0.5;
  g.nx = 6;
  g.ny = 5;
  g.allocate();
  return g;
}

/// Particles at the centres of 2 x 2 sub-cells of the cells [1, 5) x [1, 4), with uneven masses.
Particles make_particles(const Grid& g, const Vec2& v0) {
  Particles P;
  const double hp = g.h / 2;
  for (int j = 2; j < 8; ++j)
    for (int i = 2; i < 10; ++i) {
      P.add(g.origin + Vec2((i + 0.5) * hp, (j + 0.5) * hp), 1.0 + 0.1 * ((i * 7 + j * 3) % 5), hp * hp);
      P.v.back() = v0;
    }
  return P;
}

}  // namespace

TEST(MpmShapeFunctions, PartitionOfUnityAndZeroGradientSum) {
  const Grid g = make_grid();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> ux(-0.85, 1.85), uy(0.65, 2.85);  // GIMP domains (h / 4) inside the grid
  for (bool gimp : {false, true}) {
    const ShapeFunctions shape{gimp, 2};
    for (int k = 0; k < 200; ++k) {
      const Vec2 x(ux(rng), uy(rng));
      Support s;
      shape.evaluate(g, x, s);
      double sum = 0;
      Vec2 dsum = Vec2::Zero(), xsum = Vec2::Zero();
      for (int a = 0; a < s.n; ++a) {
        sum += s.N[a];
        dsum += s.dN[a];
        const Index I = s.node[a];
        xsum += s.N[a] * g.node_position(I % (g.nx + 1), I / (g.nx + 1));
      }
      EXPECT_NEAR(sum, 1.0, 1e-14) << gimp;
      EXPECT_NEAR(dsum.norm(), 0.0, 1e-12) << gimp;
      EXPECT_NEAR((xsum - x).norm(), 0.0, 1e-13) << gimp;  // linear reproduction
    }
  }
}

TEST(MpmTransfer, ParticlesToGridConservesMassAndMomentum) {
  const Vec2 v0(0.3, -1.7), gravity(0.0, -9.81);
  for (bool gimp : {false, true}) {
    Grid g = make_grid();
    Particles P = make_particles(g, v0);
    for (auto& s : P.stress) s = {-2e3, -5e3, 7e2, -1e3};  // uniform: no net internal force
    const ShapeFunctions shape{gimp, 2};
    std::vector<Support> support;
    ASSERT_EQ(locate_particles(g, shape, P, support), -1);
    ScatterBuffers buffers;
    particles_to_grid(P, support, true, true, gravity, {}, g, buffers);
    double M = 0, m = 0;
    Vec2 Mv = Vec2::Zero(), mv = Vec2::Zero(), f = Vec2::Zero();
    for (size_t p = 0; p < P.size(); ++p) {
      M += P.mass[p];
      Mv += P.mass[p] * P.v[p];
    }
    for (size_t I = 0; I < g.num_nodes(); ++I) {
      m += g.mass[I];
      mv += g.momentum[I];
      f += g.force[I];
    }
    EXPECT_NEAR(m, M, 1e-13 * M) << gimp;
    EXPECT_NEAR((mv - Mv).norm(), 0.0, 1e-13 * Mv.norm()) << gimp;
    EXPECT_NEAR((f - M * gravity).norm(), 0.0, 1e-10 * M * gravity.norm()) << gimp;
    // A uniform velocity is the velocity of every node that carries mass.
    velocities_from_momentum(g);
    for (size_t I = 0; I < g.num_nodes(); ++I) {
      if (g.mass[I] > 0)
        EXPECT_NEAR((g.velocity[I] - v0).norm(), 0.0, 1e-13) << I;
      else
        EXPECT_EQ(g.velocity[I], Vec2::Zero());
    }
  }
}

TEST(MpmTransfer, GridToParticlesReproducesALinearVelocityField) {
  // v(x) = a + B x at the nodes; PIC (flip = 0) gives v(x_p) at each particle, x_p moves by dt v(x_p), and the
  // velocity gradient is B. With FLIP (flip = 1) and nodal forces m_I a0, each particle gains dt a0.
  const Vec2 a(0.2, -0.1);
  Mat2 B;
  B << 0.3, -0.4, 0.25, 0.1;
  const double dt = 1e-2;
  for (bool gimp : {false, true}) {
    Grid g = make_grid();
    for (int j = 0; j <= g.ny; ++j)
      for (int i = 0; i <= g.nx; ++i) {
        const size_t I = static_cast<size_t>(j) * (g.nx + 1) + i;
        g.mass[I] = 1.0 + 0.1 * i;
        g.velocity[I] = a + B * g.node_position(i, j);
        g.force[I] = Vec2::Zero();
      }
    Particles P = make_particles(g, Vec2(5.0, 5.0));
    const std::vector<Vec2> x0 = P.x;
    const ShapeFunctions shape{gimp, 2};
    std::vector<Support> support;
    ASSERT_EQ(locate_particles(g, shape, P, support), -1);
    for (size_t p = 0; p < P.size(); ++p)
      EXPECT_NEAR((velocity_gradient(g.velocity, support[p]) - B).norm(), 0.0, 1e-12) << gimp;
    const double work = grid_to_particles(g, support, dt, 0.0, Vec2(0, -10.0), P);
    double expected_work = 0;
    for (size_t p = 0; p < P.size(); ++p) {
      const Vec2 v = a + B * x0[p];
      EXPECT_NEAR((P.v[p] - v).norm(), 0.0, 1e-13) << gimp << " particle " << p;
      EXPECT_NEAR((P.x[p] - (x0[p] + dt * v)).norm(), 0.0, 1e-15) << gimp;
      expected_work += P.mass[p] * -10.0 * dt * v.y();
    }
    EXPECT_NEAR(work, expected_work, 1e-12);
    // FLIP: a uniform acceleration a0 (nodal forces m_I a0) is added to the particles' own velocities.
    const Vec2 a0(1.0, -2.0);
    for (size_t I = 0; I < g.num_nodes(); ++I) g.force[I] = g.mass[I] * a0;
    const std::vector<Vec2> v_before = P.v;
    grid_to_particles(g, support, dt, 1.0, Vec2::Zero(), P);
    for (size_t p = 0; p < P.size(); ++p) {
      EXPECT_NEAR((P.v[p] - (v_before[p] + dt * a0)).norm(), 0.0, 1e-13) << gimp;
      EXPECT_NEAR((P.acceleration[p] - a0).norm(), 0.0, 1e-13) << gimp;
    }
  }
}

TEST(MpmTransfer, ParticleOutsideTheGridIsReported) {
  const Grid g = make_grid();
  Particles P = make_particles(g, Vec2::Zero());
  P.x[7] = Vec2(10.0, 1.0);
  std::vector<Support> support;
  EXPECT_EQ(locate_particles(g, ShapeFunctions{}, P, support), 7);
}
