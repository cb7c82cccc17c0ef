// Regression runs of the EFG cases at CI size: the cantilever's energy-norm error and tip deflection
// against the exact solution, sigma_xx at the hole against Kirsch's 3 sigma0, the Mazars tension plate's peak
// against the homogeneous solution (lambda = 2.0), and a coarse L-panel (probes load and node_A_uy, the limit point
// passed), plus a bad-input check.
#include "case_runner.hpp"
#include "process.hpp"

#include <algorithm>
#include <cmath>

using namespace lagfsi::testing;

TEST(EfgCases, TimoshenkoCantileverConvergesInEnergyNorm) {
  // Two refinements, bilinear basis, rho = 2h: error falls at the observed order ~1 (h^p, p = 1 for a linear basis).
  double e[2];
  int k = 0;
  for (const char* div : {"[8,2]", "[16,4]"}) {
    const RunResult r = run_case_file("cases/efg_timoshenko_cantilever/case.json", std::string("efg_cant_") + div[1],
                                      {std::string("bodies.0.domain.divisions=") + div});
    ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
    const auto s = summary_of(r);
    e[k++] = s["bodies"][0]["energy_error_relative"].get<double>();
    const Csv c = read_csv(r.out_dir / "probes.csv");
    const double tip = c["tip_uy"].back();
    std::printf("divisions %s: tip u_y %.6e (exact 8.9000e-03), relative energy error %.4e\n", div, tip, e[k - 1]);
    EXPECT_NEAR(tip / 0.0089, 1.0, 0.03);
  }
  const double order = std::log(e[0] / e[1]) / std::log(2.0);
  std::printf("observed order %.2f\n", order);
  EXPECT_GT(order, 0.8);
  EXPECT_LT(e[1], 0.08);
}

TEST(EfgCases, PlateWithHoleStressConcentration) {
  const RunResult r = run_case_file("cases/efg_plate_hole/case.json", "efg_plate_hole");
  const Csv c = probes_of(r);
  const double sA = c["sxx_A"].back(), sB = c["syy_B"].back();
  std::printf("sigma_xx(0,1) = %.4f (Kirsch 3), sigma_yy(1,0) = %.4f (Kirsch -1)\n", sA, sB);
  EXPECT_NEAR(sA / 3.0, 1.0, 0.02);
  EXPECT_NEAR(sB, -1.0, 0.1);
  EXPECT_LT(summary_of(r)["bodies"][0]["energy_error_relative"].get<double>(), 0.05);
}

TEST(EfgCases, TensionPlateMazarsPeak) {
  // CI size: 4 x 4 cells, 6 x 6 Gauss, secant operator, CDG initial load factor 0.2 (the peak at step 10).
  const RunResult r = run_case_file("cases/efg_tension_plate/case.json", "efg_tension_plate",
                                    {"bodies.0.domain.divisions=[4,4]", "bodies.0.efg.gauss=6",
                                     "analysis.load_steps=30", "bodies.0.control.increment=0.2"});
  const Csv c = probes_of(r);
  const auto& lam = c["lambda"];
  const double peak = *std::max_element(lam.begin(), lam.end());
  std::printf("peak lambda %.4f (homogeneous solution 2.0), last %.4f, max damage %.3f\n", peak, lam.back(),
              c["damage_max"].back());
  EXPECT_NEAR(peak, 2.0, 0.02);
  EXPECT_LT(lam.back(), 0.8 * peak);  // the limit point was passed
  // The Gauss points' output carries the law's declared state variables (Mazars: kappa; damage as for every law).
  fs::path last;
  for (const auto& e : fs::directory_iterator(r.out_dir / "plate_gauss"))
    if (e.path().extension() == ".vtp" && e.path() > last) last = e.path();
  ASSERT_FALSE(last.empty());
  const std::string vtp = file_text(last);
  EXPECT_NE(vtp.find("Name=\"kappa\""), std::string::npos) << last;
  EXPECT_NE(vtp.find("Name=\"damage\""), std::string::npos) << last;
}

TEST(EfgCases, LPanelCoarse) {
  const RunResult r = run_case_file("cases/efg_L_panel/case.json", "efg_L_panel",
                                    {"bodies.0.domain.divisions=[10,10]", "bodies.0.efg.gauss=3",
                                     "analysis.load_steps=60", "bodies.0.control.increment=0.05", "output.vtk=false"});
  const Csv c = probes_of(r);
  const auto& load = c["load"];
  const double peak = *std::max_element(load.begin(), load.end());
  std::printf("coarse L-panel: peak load %.0f N, last %.0f N at node_A_uy %.4f mm\n", peak, load.back(),
              c["node_A_uy"].back());
  EXPECT_GT(peak, 3000.0);
  EXPECT_LT(peak, 20000.0);
  EXPECT_LT(load.back(), peak);
}

TEST(EfgCases, LPanelPathFollowingMethodsAgreeAndLoadControlFailsAtTheLimit) {
  // Coarse L-panel: arc length (V form) and displacement control of node A (U form) pass the limit point with the
  // peak of generalized displacement control; load control cannot pass it: the step is cut back, then the run fails
  // with a message naming the control.
  std::string err;  // the last run's stderr
  auto peak_of = [&err](const std::string& tag, const std::vector<std::string>& extra, int* code) {
    std::vector<std::string> sets = {"bodies.0.domain.divisions=[10,10]", "bodies.0.efg.gauss=3",
                                     "analysis.load_steps=60", "output.vtk=false"};
    sets.insert(sets.end(), extra.begin(), extra.end());
    const RunResult r = run_case_file("cases/efg_L_panel/case.json", tag, sets);
    *code = r.exit_code;
    err = r.stderr_text;
    const Csv c = read_csv(r.out_dir / "probes.csv");
    const auto& load = c["load"];
    std::printf("%s: peak %.1f N, last %.1f N, exit %d\n", tag.c_str(), *std::max_element(load.begin(), load.end()),
                load.back(), r.exit_code);
    return std::make_pair(*std::max_element(load.begin(), load.end()), load.back());
  };
  int code;
  const auto cdg = peak_of("efg_lp_cdg", {"bodies.0.control.increment=0.05"}, &code);
  EXPECT_EQ(code, 0);
  const auto arc =
      peak_of("efg_lp_arc", {"bodies.0.control.type=arc_length", "bodies.0.control.increment=0.05"}, &code);
  EXPECT_EQ(code, 0);
  const auto cdd = peak_of("efg_lp_cdd",
                           {"bodies.0.control.type=displacement", "bodies.0.control.form=U",
                            "bodies.0.control.at=[500,500]", "bodies.0.control.increment=0.01"},
                           &code);
  EXPECT_EQ(code, 0);
  EXPECT_NEAR(arc.first / cdg.first, 1.0, 0.01);
  EXPECT_NEAR(cdd.first / cdg.first, 1.0, 0.01);
  EXPECT_LT(arc.second, 0.9 * arc.first);
  EXPECT_LT(cdd.second, 0.9 * cdd.first);
  const auto lc = peak_of("efg_lp_load", {"bodies.0.control.type=load", "bodies.0.control.increment=0.02"}, &code);
  EXPECT_EQ(code, 3);  // solver error after the step halvings
  EXPECT_NEAR(lc.second / cdg.first, 1.0, 0.02);
  // The message names the control and the reason (the tangent operator: no equilibrium beyond the peak).
  EXPECT_NE(err.find("case.json: /bodies/0/control: load control found no equilibrium"), std::string::npos) << err;
}

TEST(EfgCases, LPanelDisplacementControlUAndVFormsObeyTheLinearIdentity) {
  // Thesis §5.4, Tables 5.1-5.2 (digest 003_efg.md §3.1.6): displacement control of the vertical dof of the
  // interior particle B = (450, 400), in the U form (u_B imposed, u = f(v)) and the V form (the parameter v_B
  // imposed). In the linear regime the response is proportional to lambda, so lambda(V) / lambda(U) = u_B / v_B at
  // every step, to round-off; the parameter of a particle differs from its displacement (v_B != u_B), so the
  // identity fails if the U form acted on the parameters (or the V form on the displacements).
  auto run = [](const std::string& form) {
    const RunResult r =
        run_case_file("cases/efg_L_panel/case.json", "efg_lp_cdd_" + form,
                      {"bodies.0.domain.divisions=[10,10]", "bodies.0.efg.gauss=3", "bodies.0.efg.alpha=3",
                       "analysis.load_steps=4", "bodies.0.control.type=displacement", "bodies.0.control.at=[450,400]",
                       "bodies.0.control.form=" + form, "bodies.0.control.increment=0.0012", "output.vtk=false"});
    EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
    return read_csv(r.out_dir / "probes.csv");
  };
  const Csv u = run("U"), v = run("V");
  ASSERT_EQ(u["lambda"].size(), 5u);
  ASSERT_EQ(v["lambda"].size(), 5u);
  for (size_t j = 1; j < 5; ++j) {
    EXPECT_NEAR(u["node_B_uy"][j], 0.0012 * j, 1e-12);  // the controlled quantity of each form
    EXPECT_NEAR(v["node_B_vy"][j], 0.0012 * j, 1e-12);
    const double ratio = v["lambda"][j] / u["lambda"][j], uv = v["node_B_uy"][j] / v["node_B_vy"][j];
    std::printf("step %zu: lambda U %.12f V %.12f, lambda(V)/lambda(U) %.12f, u_B/v_B %.12f\n", j, u["lambda"][j],
                v["lambda"][j], ratio, uv);
    EXPECT_NEAR(ratio, uv, 1e-9);
    EXPECT_GT(std::abs(uv - 1), 1e-5);  // B is a particle: the forms differ
  }
}

TEST(EfgCases, LPanelEveryNodeFeIsTheQ4Element) {
  // The FEM Q4 reference of the thesis two ways on the coarse panel: EFG with rho = h and the bilinear basis (the Q4
  // functions on a regular grid), and every node an active FE node (essential.fe_nodes = [all], rho = 2h: the
  // corrected MLS functions vanish). Both with 2 x 2 Gauss; the same curve up to round-off.
  auto run = [](const std::string& tag, const std::vector<std::string>& extra) {
    std::vector<std::string> sets = {"bodies.0.domain.divisions=[10,10]", "bodies.0.efg.gauss=2",
                                     "analysis.load_steps=30", "bodies.0.control.increment=0.05", "output.vtk=false"};
    sets.insert(sets.end(), extra.begin(), extra.end());
    const RunResult r = run_case_file("cases/efg_L_panel/case.json", tag, sets);
    EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
    return read_csv(r.out_dir / "probes.csv");
  };
  const Csv h = run("efg_lp_q4_rho_h", {"bodies.0.efg.alpha=1"});
  const Csv fe = run("efg_lp_q4_fe", {"bodies.0.essential.fe_nodes=[{\"type\":\"all\"}]"});
  const Csv efg = run("efg_lp_q4_rho_2h", {});
  ASSERT_EQ(h["load"].size(), fe["load"].size());
  double d = 0, d_efg = 0;
  for (size_t j = 0; j < h["load"].size(); ++j) {
    d = std::max(d, std::abs(fe["load"][j] - h["load"][j]) + std::abs(fe["node_A_uy"][j] - h["node_A_uy"][j]) * 1e4);
    if (j < efg["load"].size()) d_efg = std::max(d_efg, std::abs(efg["load"][j] - h["load"][j]));
  }
  const double peak = *std::max_element(h["load"].begin(), h["load"].end());
  std::printf(
      "Q4 (rho = h) peak %.3f N; every node FE: largest difference %.3e (load N + 1e4 u_A mm); EFG rho = 2h: "
      "%.1f N\n",
      peak, d, d_efg);
  EXPECT_LT(d, 1e-6 * peak);
  EXPECT_GT(d_efg, 1e-3 * peak);  // EFG with rho = 2h is not the Q4 element
}

TEST(EfgCases, BadInputIsOneLineWithThePath) {
  const RunResult r =
      run_case_file("cases/efg_timoshenko_cantilever/case.json", "efg_bad", {"bodies.0.efg.basis=cubic"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("/bodies/0/efg/basis"), std::string::npos) << r.stderr_text;
  const RunResult r2 =
      run_case_file("cases/efg_timoshenko_cantilever/case.json", "efg_bad2", {"bodies.0.efg.alpha=0.4"});
  EXPECT_NE(r2.exit_code, 0);
  EXPECT_NE(r2.stderr_text.find("MLS at ("), std::string::npos) << r2.stderr_text;
}
