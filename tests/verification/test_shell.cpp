// Verification of the positional frame/shell element (shell.hpp):
//  - the Hessian equals central differences of the internal force, which equals central differences of the
//    strain energy; the Hessian is symmetric; a rigid motion (mid-line nodes moved by Q X + c, generalised
//    vectors rotated by Q) gives zero force and energy, and f(Q x + c) = Q f(x) on a deformed state;
//  - for orders 1-3, reduced and full shear integration, plane strain and plane stress, on a curved
//    reference mid-line (an arc), at a large deformation with thickness change and shear;
//  - the mass matrix carries the section's mass rho b t L (translation) and its rotary inertia
//    rho b t^3 L / 12 (a uniform rotation rate of the vectors);
//  - follower pressure: a closed loop of edges gets no net force, a face of length L gets p b L along its
//    inward normal, and the load turns with the structure (P (Q x + c) = Q P x);
//  - analytic solutions through the cases: Mattiasson's elastica within 0.5 % with 8 cubic elements, the
//    cantilever's static deflection within 0.3 % of Timoshenko's value with 6, convergence with the number
//    of elements, and the step response (peak 2 x static, energy balance).
#include <lagfsi/solid/shell.hpp>

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "case_runner.hpp"
#include "finite_difference.hpp"

using namespace lagfsi;
using namespace lagfsi::testing;

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Config {
  int order;
  bool reduced, plane_strain;
};

std::string name_of(const Config& c) {
  return "p" + std::to_string(c.order) + (c.reduced ? "_reduced" : "_full") + (c.plane_strain ? "_strain" : "_stress");
}

ShellSection section(const Config& c) {
  ShellSection s;
  s.thickness = 0.08;
  s.width = 0.5;
  s.young = 100.0;
  s.poisson = 0.3;
  s.density = 2.0;
  s.plane_strain = c.plane_strain;
  s.reduced_shear = c.reduced;
  return s;
}

/// An arc of radius 1 over 60 degrees with `ne` elements of order p (curved reference).
std::vector<Vec2> arc(int order, int ne) {
  std::vector<Vec2> pts;
  for (int i = 0; i <= order * ne; ++i) {
    const double a = (kPi / 3.0) * i / (order * ne);
    pts.emplace_back(std::cos(a), std::sin(a));
  }
  return pts;
}

/// A straight shell along x of length L with `ne` cubic elements.
ShellBody straight_shell(const ShellSection& s, double L, int ne) {
  std::vector<Vec2> line;
  for (int i = 0; i <= 3 * ne; ++i) line.emplace_back(L * i / (3.0 * ne), 0.0);
  return ShellBody(3, line, s);
}

/// The surface edges of the top face (eta = +1/2: surface points 0..n-1).
std::vector<std::vector<Index>> top_face(const ShellBody& body) {
  std::vector<std::vector<Index>> top;
  for (const auto& e : body.surface_edges()) {
    bool is_top = true;
    for (Index p : e) is_top = is_top && p < body.num_sections();
    if (is_top) top.push_back(e);
  }
  return top;
}

Mat2 rotation(double t) {
  Mat2 R;
  R << std::cos(t), -std::sin(t), std::sin(t), std::cos(t);
  return R;
}

/// Mid-line nodes moved by Q X + c, vectors by Q G.
Vec rigid(const ShellBody& b, const Vec& x, const Mat2& Q, const Vec2& c) {
  Vec y(x.size());
  const Index n = b.num_sections();
  for (Index i = 0; i < 2 * n; ++i) y.segment<2>(2 * i) = Q * x.segment<2>(2 * i) + (i < n ? c : Vec2::Zero());
  return y;
}

class ShellTangent : public ::testing::TestWithParam<Config> {};

TEST_P(ShellTangent, HessianGradientSymmetryObjectivity) {
  const Config cfg = GetParam();
  ShellBody body(cfg.order, arc(cfg.order, 3), section(cfg));
  const Index nd = body.num_dofs(), n = body.num_sections();
  const Vec& X = body.reference_positions();
  // A large deformation: the arc bent further, stretched 10 %, the vectors rotated off the normal (shear),
  // stretched (thickness change), plus a random perturbation.
  std::mt19937 gen(42 + cfg.order);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vec x(nd);
  for (Index i = 0; i < n; ++i) {
    const Vec2 P = X.segment<2>(2 * i);
    const double a = std::atan2(P.y(), P.x());
    x.segment<2>(2 * i) = 1.1 * Vec2(std::cos(1.4 * a), std::sin(1.4 * a)) + 0.01 * Vec2(u(gen), u(gen));
    x.segment<2>(2 * (n + i)) =
        1.15 * rotation(0.4 * a + 0.1) * X.segment<2>(2 * (n + i)) + 0.002 * Vec2(u(gen), u(gen));
  }
  SparseMatrix K = body.pattern();
  Vec f;
  const double W = body.internal_force(x, f, &K);
  const Eigen::MatrixXd Kd = Eigen::MatrixXd(K);
  ASSERT_GT(W, 0.0);
  ASSERT_GT(f.norm(), 0.1);

  {  // K = d f / dx
    const Eigen::MatrixXd Kfd =
        central_jacobian([&](const Vec& y, Vec& out) { body.internal_force(y, out, nullptr); }, x, 1e-6);
    const double rel = (Kd - Kfd).norm() / Kd.norm();
    std::printf("%-20s |K - K_fd|/|K| = %.2e", name_of(cfg).c_str(), rel);
    EXPECT_LT(rel, 1e-6) << name_of(cfg);
    EXPECT_LT((Kd - Kfd).cwiseAbs().maxCoeff() / Kd.cwiseAbs().maxCoeff(), 1e-6) << name_of(cfg);
  }
  {  // f = d W / dx
    Vec tmp;
    const Vec g = central_gradient([&](const Vec& y) { return body.internal_force(y, tmp, nullptr); }, x, 1e-6);
    const double rel = (f - g).norm() / f.norm();
    std::printf("  |f - dW/dx|/|f| = %.2e\n", rel);
    EXPECT_LT(rel, 1e-6) << name_of(cfg);
  }
  EXPECT_LT((Kd - Kd.transpose()).norm() / Kd.norm(), 1e-12) << name_of(cfg);
  ASSERT_EQ(K.nonZeros(), body.pattern().nonZeros());

  const Mat2 Q = rotation(1.1);
  const Vec2 c(3.0, -2.0);
  const double fscale = 100.0 * 0.08 * 0.5;  // E t b
  {
    Vec fr;
    const double Wr = body.internal_force(rigid(body, X, Q, c), fr, nullptr);
    EXPECT_LT(fr.cwiseAbs().maxCoeff(), 1e-10 * fscale) << name_of(cfg) << ": rigid motion gives f != 0";
    EXPECT_LT(std::abs(Wr), 1e-12 * fscale) << name_of(cfg);
  }
  {
    Vec fq;
    const double Wq = body.internal_force(rigid(body, x, Q, c), fq, nullptr);
    EXPECT_NEAR(Wq, W, 1e-11 * W) << name_of(cfg);
    EXPECT_LT((fq - rigid(body, f, Q, Vec2::Zero())).norm(), 1e-10 * f.norm()) << name_of(cfg);
  }
}

std::vector<Config> all_configs() {
  std::vector<Config> v;
  for (int p : {1, 2, 3})
    for (bool r : {true, false})
      for (bool ps : {true, false}) v.push_back({p, r, ps});
  return v;
}

INSTANTIATE_TEST_SUITE_P(AllOrders, ShellTangent, ::testing::ValuesIn(all_configs()),
                         [](const ::testing::TestParamInfo<Config>& i) { return name_of(i.param); });

TEST(ShellBody, MassTranslationAndRotaryInertia) {
  const Config cfg{3, true, true};
  const ShellSection s = section(cfg);
  const double L = 2.0;
  const ShellBody body = straight_shell(s, L, 4);
  const Index n = body.num_sections(), nd = body.num_dofs();
  // Translation: mid-line dofs x = 1, vectors 0: v^T M v = rho b t L.
  Vec tx = Vec::Zero(nd);
  for (Index i = 0; i < n; ++i) tx[2 * i] = 1.0;
  EXPECT_NEAR(tx.dot(body.mass() * tx), s.density * s.width * s.thickness * L, 1e-12);
  // Rotation rate 1 of every section about its mid-line point: the vector's velocity is e3 x G = (-Gy, Gx);
  // kinetic energy 2 T = rho b int eta^2 t^2 deta L t = rho b t^3 L / 12.
  Vec rot = Vec::Zero(nd);
  const Vec& X = body.reference_positions();
  for (Index i = 0; i < n; ++i) rot.segment<2>(2 * (n + i)) = Vec2(-X[2 * (n + i) + 1], X[2 * (n + i)]);
  EXPECT_NEAR(rot.dot(body.mass() * rot), s.density * s.width * std::pow(s.thickness, 3) * L / 12.0, 1e-14);
  // Gravity: the consistent forces sum to rho b t L g on the mid-line, zero on the vectors.
  const Vec fg = body.body_force(Vec2(0.0, -9.81 * s.density));
  double sum_mid = 0, sum_vec = 0;
  for (Index i = 0; i < n; ++i) {
    sum_mid += fg[2 * i + 1];
    sum_vec += std::abs(fg[2 * (n + i) + 1]);
  }
  EXPECT_NEAR(sum_mid, -9.81 * s.density * s.width * s.thickness * L, 1e-12);
  EXPECT_LT(sum_vec, 1e-14);
}

TEST(ShellBody, FollowerPressureOnFaces) {
  const Config cfg{3, true, true};
  const ShellSection s = section(cfg);
  const double L = 2.0;
  const ShellBody body = straight_shell(s, L, 4);
  const Index n = body.num_sections();
  // The edges of the top face (eta = +1/2, normal +y).
  const auto top = top_face(body), all = body.surface_edges();
  ASSERT_EQ(top.size(), 4u);
  const SparseMatrix P = follower_pressure_matrix(body, top);
  const Vec& X = body.reference_positions();
  const Vec f = P * X;
  Vec2 R = Vec2::Zero();
  for (Index i = 0; i < n; ++i) R += f.segment<2>(2 * i);  // resultant: the mid-line (translation) dofs
  EXPECT_NEAR(R.x(), 0.0, 1e-12);
  EXPECT_NEAR(R.y(), -s.width * L, 1e-12);  // unit pressure pushes the top face down
  // Closed boundary: no net force (uniform pressure all around).
  const Vec fa = follower_pressure_matrix(body, all) * X;
  Vec2 Ra = Vec2::Zero();
  for (Index i = 0; i < n; ++i) Ra += fa.segment<2>(2 * i);
  EXPECT_LT(Ra.norm(), 1e-12);
  // It follows the structure: P (Q x + c) = Q P x.
  const Mat2 Q = rotation(0.7);
  const Vec fq = P * rigid(body, X, Q, Vec2(1.0, 2.0));
  EXPECT_LT((fq - rigid(body, f, Q, Vec2::Zero())).norm(), 1e-12 * f.norm());
}

TEST(ShellBody, SimplySupportedBeamUnderPressure) {
  // Linear response (one Newton step from the reference) of a pinned-pinned beam under a uniform pressure q
  // on its top face: midspan deflection 5 q L^4 / (384 EI) + q L^2 / (8 kappa G A) (Timoshenko) and bending
  // moment q L^2 / 8, with 4 cubic elements; the pressure's consistent forces come from
  // follower_pressure_matrix at the reference (a dead load at this size).
  ShellSection s;
  s.thickness = 0.02;
  s.width = 1.0;
  s.young = 1e7;
  s.poisson = 0.0;
  s.density = 1000.0;
  s.plane_strain = false;
  const double L = 1.0, q = 1.0;
  const ShellBody body = straight_shell(s, L, 4);
  const Index n = body.num_sections();
  const auto top = top_face(body);
  const Vec& X = body.reference_positions();
  const Vec f = q * (follower_pressure_matrix(body, top) * X);
  SparseMatrix K = body.pattern();
  Vec fint;
  body.internal_force(X, fint, &K);
  Eigen::MatrixXd Kd = Eigen::MatrixXd(K);
  Vec r = f;
  // Pinned ends: the mid-line nodes 0 and n-1 held (both components); the vectors free to rotate.
  for (Index node : {Index(0), n - 1})
    for (int c = 0; c < 2; ++c) {
      const Index d = 2 * node + c;
      Kd.row(d).setZero();
      Kd.col(d).setZero();
      Kd(d, d) = 1.0;
      r[d] = 0.0;
    }
  const Vec u = Kd.lu().solve(r);
  const double EI = s.young * std::pow(s.thickness, 3) / 12.0;
  const double w_ref =
      5.0 * q * std::pow(L, 4) / (384.0 * EI) + q * L * L / (8.0 * (5.0 / 6.0) * 0.5 * s.young * s.thickness);
  const Index mid = (n - 1) / 2;
  const double w = -u[2 * mid + 1];
  const ShellBody::Resultants res = body.resultants(X + u);
  std::printf("midspan deflection %.6e (Timoshenko %.6e), moment %.5f (q L^2/8 = %.5f)\n", w, w_ref, res.moment[mid],
              q * L * L / 8.0);
  EXPECT_NEAR(w, w_ref, 1e-3 * w_ref);
  // Sagging stretches the bottom face: negative moment in the shell's convention; the resultant at a node
  // is the average of the neighbouring elements' values there (second derivative of a cubic: 2 % allowed).
  EXPECT_NEAR(-res.moment[mid], q * L * L / 8.0, 0.02 * q * L * L / 8.0);
  EXPECT_LT(std::abs(res.moment[0]), 0.02 * q * L * L / 8.0);  // pinned: no moment at the supports
}

// ---------------------------------------------------------------- analytic solutions through the cases

TEST(ElasticaShell, EightCubicElementsWithinHalfPercentOfMattiasson) {
  expect_tip_matches_mattiasson(probes_of(run_case_file("cases/elastica_shell/case.json", "elastica_shell")),
                                "cases/elastica_shell", 0.005);
}

TEST(ElasticaShell, ErrorFallsWithTheNumberOfElements) {
  // Tip deflection at lambda = 10 with 1, 2, 4 cubic elements: the error must fall (it is dominated by
  // the interpolation of the large rotation).
  const double ref = 0.81061;
  double prev = 1e9;
  for (int ne : {1, 2, 4}) {
    const Csv c = probes_of(run_case_file("cases/elastica_shell/case.json", "elastica_shell_ne" + std::to_string(ne),
                                          {"bodies.0.mesh.elements=" + std::to_string(ne)}));
    const double err = std::abs(at_time(c, "tip_uy", 1.0) / ref - 1.0);
    std::printf("%d elements: |w/L - ref| / ref = %.2e\n", ne, err);
    EXPECT_LT(err, prev) << ne << " elements";
    prev = err;
  }
}

/// The Timoshenko static deflection shipped with the case (reference/analytic.csv, negative: downwards).
double cantilever_timoshenko() {
  const Csv ref = read_csv(fs::path(LAGFSI_SOURCE_DIR) / "cases/cantilever_step_load_shell/reference/analytic.csv");
  for (size_t i = 0; i < ref.rows(); ++i)
    if (ref.text.at("quantity")[i] == "tip_uy_static_timoshenko") return -ref["value"][i];
  ADD_FAILURE() << "no tip_uy_static_timoshenko in analytic.csv";
  return std::nan("");
}

TEST(CantileverStepLoadShell, StaticWithinPointThreePercentOfTimoshenko) {
  const Csv c = probes_of(run_case_file("cases/cantilever_step_load_shell/case.json", "cantilever_shell_static",
                                        {"analysis.type=static", "analysis.load_steps=1"}));
  const double d = -c["tip_uy_axis"].back();
  std::printf("static %.6f m, Timoshenko %.6f m\n", d, cantilever_timoshenko());
  EXPECT_LT(std::abs(d / cantilever_timoshenko() - 1.0), 0.003);
  EXPECT_NEAR(c["reaction_y"].back(), 5e6, 1e-6 * 5e6);
}

TEST(CantileverStepLoadShell, StepResponsePeakAndEnergyBalance) {
  const Csv c = probes_of(run_case_file("cases/cantilever_step_load_shell/case.json", "cantilever_shell_dynamic"));
  double peak = 0, worst = 0, emax = 0;
  for (size_t i = 0; i < c.rows(); ++i) {
    peak = std::min(peak, c["tip_uy_axis"][i]);
    worst = std::max(worst, std::abs(c["energy_balance"][i]));
    emax = std::max(emax, std::abs(c["energy_total"][i]));
  }
  std::printf("peak %.6f m = %.4f x static; |balance| / E = %.2e\n", peak, -peak / cantilever_timoshenko(),
              worst / emax);
  EXPECT_LT(std::abs(-peak / (2.0 * cantilever_timoshenko()) - 1.0), 0.01);
  EXPECT_LT(worst, 1e-4 * emax);
}

}  // namespace

namespace {

/// A shell case written by the test (static, unit width): a beam L = 1 m, t = 0.02 m, E = 1e7 Pa, nu = 0 with
/// the given boundary conditions and loads; returns the probes.
Csv run_beam(const std::string& tag, const nlohmann::json& bcs, const nlohmann::json& loads,
             const nlohmann::json& probes, int load_steps = 1) {
  const fs::path dir = fresh_dir(tag);
  nlohmann::json j = {
      {"name", tag},
      {"analysis", {{"type", "static"}, {"load_steps", load_steps}, {"linear_solver", {{"type", "umfpack"}}}}},
      {"bodies",
       {{{"name", "beam"},
         {"type", "shell"},
         {"material",
          {{"type", "svk"}, {"young", 1e7}, {"poisson", 0.0}, {"density", 1000.0}, {"hypothesis", "plane_stress"}}},
         {"thickness", 0.02},
         {"geometry", {{"type", "line"}, {"from", {0, 0}}, {"to", {1, 0}}}},
         {"mesh", {{"elements", 4}, {"order", 3}}},
         {"boundary_conditions", bcs},
         {"loads", loads}}}},
      {"probes", probes},
      {"output", {{"vtk", false}}}};
  return probes_of(run_case_text(dir, j.dump(2)));
}

nlohmann::json point(double x, double y) { return {{"type", "point"}, {"at", {x, y}}}; }

}  // namespace

TEST(ShellCase, PinnedBeamUnderDeadAndFollowerPressure) {
  // Through the case file: "pinned" ends (the right one free to slide: components y), a pressure of 1 Pa on
  // the top face. Small load: midspan deflection 5 q L^4 / (384 EI) + q L^2 / (8 kappa G A) for both the dead
  // and the follower pressure (they differ by O(w'^2)).
  const double EI = 1e7 * 8e-6 / 12.0, w_ref = 5.0 / (384.0 * EI) + 1.0 / (8.0 * (5.0 / 6.0) * 0.5e7 * 0.02);
  const nlohmann::json bcs = {{{"type", "pinned"}, {"select", point(0, 0)}},
                              {{"type", "pinned"}, {"select", point(1, 0)}, {"components", "y"}}};
  const nlohmann::json probes = {
      {{"name", "mid"}, {"type", "displacement"}, {"body", "beam"}, {"at", {0.5, 0.0}}, {"component", "y"}},
      {{"name", "end_x"}, {"type", "displacement"}, {"body", "beam"}, {"at", {1.0, 0.0}}, {"component", "x"}}};
  for (bool follower : {false, true}) {
    const nlohmann::json loads = {{{"type", "pressure"},
                                   {"select", {{"type", "segment"}, {"from", {0, 0.01}}, {"to", {1, 0.01}}}},
                                   {"value", 1.0},
                                   {"follower", follower}}};
    const Csv c = run_beam(std::string("shell_pinned_") + (follower ? "follower" : "dead"), bcs, loads, probes);
    std::printf("pinned beam, %s pressure: midspan %.6e m (Timoshenko %.6e)\n", follower ? "follower" : "dead",
                -c["mid"].back(), w_ref);
    EXPECT_NEAR(-c["mid"].back(), w_ref, 2e-3 * w_ref) << (follower ? "follower" : "dead");
  }
}

TEST(ShellCase, PrescribedEndMotionStretchesTheShellUniformly) {
  // The left end clamped, the right end prescribed to move by 0.05 m along the axis (rotation held): a uniform
  // stretch, so the displacement grows linearly along the shell (exact for any order: the Green strain is
  // uniform), and the shell stays straight.
  const nlohmann::json bcs = {{{"type", "fixed"}, {"select", point(0, 0)}},
                              {{"type", "prescribed_displacement"}, {"select", point(1, 0)}, {"value", {0.05, 0.0}}}};
  const nlohmann::json probes = {
      {{"name", "q_x"}, {"type", "displacement"}, {"body", "beam"}, {"at", {0.3, 0.01}}, {"component", "x"}},
      {{"name", "q_y"}, {"type", "displacement"}, {"body", "beam"}, {"at", {0.3, -0.01}}, {"component", "y"}}};
  const Csv c = run_beam("shell_prescribed", bcs, nlohmann::json::array(), probes, 2);
  EXPECT_NEAR(c["q_x"].back(), 0.3 * 0.05, 1e-9);
  EXPECT_LT(std::abs(c["q_y"].back()), 2e-4);  // the faces move in by the thickness change only
}
