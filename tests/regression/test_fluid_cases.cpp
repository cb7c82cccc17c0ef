// Regression: the PFEM fluid cases of cases/ at CI size. Tolerances: hydrostatic as its README states; for the
// dam break, the values this code reaches (see cases/dam_break_tank/README.md), not the original targets, which
// are not met yet (front RMS 0.10, impact 0.30 +- 0.02 s). These are physical sanity bounds
// at a reduced size; the numbers the READMEs state are checked at full size, against their references and
// against the recorded values, by the `cases` tier (cases/<case>/expected.json, scripts/claims.py).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "fluid_checks.hpp"

namespace {

using namespace lagfsi::testing;

TEST(Hydrostatic, PressureStaysHydrostaticAndFluidAtRest) {
  check_hydrostatic(probes_of(run_case_file("cases/hydrostatic/case.json", "hydrostatic")));
}

TEST(DamBreakTank, FrontReachesTheWallAndAreaIsKept) {
  // Koshizuka & Oka (1996): column L = 0.146 m, 2L high, tank 4L. CI size: the default resolution over
  // 0.35 s (through the wall impact). Measured: front RMS 0.348, impact 0.249 s (the alpha shape with wall
  // particles: 0.270, 0.266 s). The front leads the experiment by its unmodelled release (so the 0.10 target
  // was retired): delayed by the best-fitting 31 ms it is 0.113 (cases/dam_break_tank, plot.py).
  const Csv c =
      probes_of(run_case_file("cases/dam_break_tank/case.json", "dam_break_tank", {"analysis.end_time=0.35"}));
  const auto [rms, t_impact] = dam_break_tank_front(c);
  EXPECT_LT(rms, 0.40) << "front RMS in Z";
  EXPECT_GT(t_impact, 0.23);
  EXPECT_LT(t_impact, 0.32);
  const double a0 = c["fluid_area"].front();
  for (size_t i = 0; i < c.rows(); ++i) EXPECT_NEAR(c["fluid_area"][i], a0, 0.005 * a0) << "t " << c["time"][i];
  std::printf("dam break: front RMS %.3f, impact %.4f s, area drift at 0.35 s %.3f %%\n", rms, t_impact,
              100 * (c["fluid_area"].back() / a0 - 1));
}

TEST(DamBreakTank, WaterAndEnergyAreKeptThroughTheSplash) {
  // The whole second of the default case (the monolithic scheme's conservative defaults: advected domain, no-slip
  // walls as constraints sliding against their Navier friction, Robin free-surface pressure, particle volumes).
  // Checks (docs/decisions/0005-particle-volumes.md): the energy above the rest state at 0.25 s, before the wall
  // impact, keeps at least 97 % of the initial (measured 0.998; the alpha shape with its surface correction, the
  // default before, 0.896), and the water, the mesh plus the drops in flight that carry their own area, stays within
  // 0.5 % through the impact, the run-up and the plunging wave (measured 0.275 %, target 0.3 %, with the tuned
  // relaxation time of the particle volumes and generalized-alpha; 0.32 % at dt = 1.1 ms, README). The mesh's own area
  // drifts by what is in flight (2.3 %). A change that lets particles through the walls gives several %.
  const RunResult r = run_case_1thread("cases/dam_break_tank/case.json", "dam_break_tank_1s", {"output.every=1000"});
  const Csv c = probes_of(r);
  ASSERT_GT(c.rows(), 900u);
  const auto area = summary_of(r)["bodies"][0]["fluid_area"];
  ASSERT_TRUE(area.contains("water_drift_max")) << "the default keeps particle volumes";
  EXPECT_LT(area["water_drift_max"].get<double>(), 0.005);
  EXPECT_LT(max_area_drift(c), 0.04) << "the mesh's area: the water less what is in flight";
  const double rho_g = 1000.0 * 9.81, width = 4 * 0.146;
  auto energy = [&](size_t i) {
    const double a = c["fluid_area"][i];
    return c["kinetic_energy"][i] + c["potential_energy"][i] - rho_g * a * a / (2 * width);
  };
  size_t i25 = 0;
  while (i25 + 1 < c.rows() && c["time"][i25] < 0.25 - 1e-9) ++i25;
  EXPECT_GT(energy(i25) / energy(0), 0.97) << "energy above the rest state at t = " << c["time"][i25];
  std::printf("dam break, 1 s: water drift %.3f %%, mesh %.2f %%, energy at 0.25 s %.4f\n",
              100 * area["water_drift_max"].get<double>(), 100 * max_area_drift(c), energy(i25) / energy(0));
}

TEST(SloshingFree, PeriodWithinTwoPercentOfLinearTheory) {
  // First sloshing mode of a 1 m tank with 0.5 m of water: omega^2 = g k tanh(k d), k = pi / L.
  const RunResult r = run_case_file("cases/sloshing_free/case.json", "sloshing_free", {"analysis.end_time=3.6"});
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  const Csv c = read_csv(r.out_dir / "probes.csv");
  const auto& e = c["eta_left"];
  const double d = 0.5, T = sloshing_period(c, "eta_left", d), T1 = linear_sloshing_period(1.0, d);
  EXPECT_NEAR(T, T1, 0.02 * T1) << "period " << T;
  // Bounded: the amplitude never exceeds the initial one by more than 2 %.
  for (double v : e) EXPECT_LT(std::abs(v - d), 1.02 * 0.005);
  // Energy of the wave: KE + PE above the flat surface of the same area, rho g A^2 / (2 L); linear theory
  // rho g a^2 L / 4 = 0.0613 J/m. On the fixed mesh it is conserved but for viscosity and the PSPG terms
  // (measured: 0.0613 J at the start, at most +0.2 %, -0.2 % after 3 periods); a growth is energy fed by the
  // scheme (in the remeshed twin, case_remesh.json, the largest kinetic energy of a period reaches 16 times
  // the wave's energy within 10 periods: README).
  const double rho_g = 1000.0 * 9.81, L = 1.0;
  auto wave_energy = [&](size_t i) {
    const double A = c["fluid_area"][i];
    return c["kinetic_energy"][i] + c["potential_energy"][i] - rho_g * A * A / (2 * L);
  };
  const double E0 = wave_energy(0);
  EXPECT_NEAR(E0, rho_g * 0.005 * 0.005 * L / 4, 0.03 * E0) << "initial wave energy";
  for (size_t i = 0; i < c.rows(); ++i) EXPECT_LT(wave_energy(i), 1.005 * E0) << "t " << c["time"][i];
  EXPECT_GT(wave_energy(c.rows() - 1), 0.95 * E0) << "no more than 5 % lost in 3 periods";
}

TEST(SolitaryWave, CrestReachesTheRightWall) {
  const RunResult r = run_case_file("cases/solitary_wave/case.json", "solitary_wave", {"analysis.end_time=2.7"});
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  const Csv c = read_csv(r.out_dir / "probes.csv");
  const auto& e = c["eta_right"];
  const size_t i = std::max_element(e.begin(), e.end()) - e.begin();
  // Seed: 2.3 +- 0.1 s (an inferred value, see the case README); this model gives 2.43 s.
  EXPECT_GT(c["time"][i], 2.3);
  EXPECT_LT(c["time"][i], 2.55);
  // Run-up on a vertical wall: about twice the wave height (1.45 m here for H = 0.2 m on d = 1 m).
  EXPECT_GT(e[i], 1.35);
  EXPECT_LT(e[i], 1.5);
  const double a0 = c["fluid_area"].front();
  for (double a : c["fluid_area"]) EXPECT_NEAR(a, a0, 1e-3 * a0);
}

// ------------------------------------------------------------------------------------------------------------
// More fluid cases: dam_break_floor (Avancini 2018, 6.9.1), dam_break_obstacle (6.9.4), sloshing_viscous
// (6.9.5). Tolerances: the original targets where the code meets them, otherwise the values reached (each case's
// README says which). These runs pass --threads 1 (as ctest's OMP_NUM_THREADS=1, but also when the test binary
// is run by hand): one thread is faster on this shared two-core machine, and the remeshed dam break's front is
// sensitive to round-off, which a fixed summation order keeps reproducible.

TEST(DamBreakFloor, FixedConnectivitySlipWalls) {
  // Avancini (2018) sec. 6.9.1 as there: fixed mesh, slip left wall and floor, natural free-surface pressure (with
  // p = 0 imposed the toe tangles at T = 1.8). CI size h = a/15 through T = 4.1. Measured: front RMS 0.355
  // (target 0.10: not met, converged in h), height RMS 0.012, area drift 0.001 %.
  const Csv c = probes_of(
      run_case_1thread("cases/dam_break_floor/case.json", "dam_break_floor_fixed", {"bodies.0.spacing=0.00381"}));
  EXPECT_NEAR(c["time"].back(), 0.22, 1e-9) << "the fixed mesh must stay valid to T = 4";
  const MartinMoyceErrors e = martin_moyce_errors(c);
  EXPECT_EQ(e.front_points, 13);
  EXPECT_LT(e.front_rms, 0.40) << "front RMS in Z for T <= 3";
  EXPECT_GE(e.height_points, 10);
  EXPECT_LT(e.height_rms, 0.02) << "column height RMS in H";
  EXPECT_LT(max_area_drift(c), 1e-4);
  std::printf(
      "dam break on a floor, fixed mesh: front RMS %.3f (%d points), height RMS %.4f (%d points), "
      "max area drift %.4f %%\n",
      e.front_rms, e.front_points, e.height_rms, e.height_points, 100 * max_area_drift(c));
}

TEST(DamBreakFloor, RemeshedNoSlipWalls) {
  // The same column with PFEM remeshing and no-slip walls (the default package: sliding against their Navier
  // friction), default size, to T = 3.15. Measured: front RMS 0.315, 0.038 with the best-fitting release delay
  // (the classic alpha shape with held wall particles: 0.211 and 0.061; the front is sensitive to a
  // one-particle film on the floor: 0.16-0.52 with dt, alpha, h), height RMS 0.011, area drift 0.02 % by then.
  const Csv c = probes_of(
      run_case_1thread("cases/dam_break_floor/case_remesh.json", "dam_break_floor_remesh", {"analysis.end_time=0.17"}));
  EXPECT_NEAR(c["time"].back(), 0.17, 1e-9);
  const MartinMoyceErrors e = martin_moyce_errors(c);
  EXPECT_EQ(e.front_points, 13);
  EXPECT_LT(e.front_rms, 0.36) << "front RMS in Z for T <= 3";
  EXPECT_GE(e.height_points, 9);
  EXPECT_LT(e.height_rms, 0.03) << "column height RMS in H";
  EXPECT_LT(max_area_drift(c), 0.005);
  std::printf(
      "dam break on a floor, remeshed: front RMS %.3f (%d points), height RMS %.4f (%d points), "
      "max area drift %.3f %%\n",
      e.front_rms, e.front_points, e.height_rms, e.height_points, 100 * max_area_drift(c));
}

TEST(DamBreakObstacle, StableToOneSecondJetReachesTheWall) {
  // Avancini (2018) sec. 6.9.4, the full case (1 s). The jet is at the right wall when the largest x of meshed fluid is
  // within 1.5 h of it (target: 0.30-0.35 s; measured 0.298 s); the wall pressure sensor (y < 0.2 m) gets
  // wet within the target window (measured 0.307 s). The jet's tip is a film a few particles thick and its
  // arrival scatters by about 5 ms with small changes (0.298-0.308 s over recent versions), so the jet is
  // checked within 0.29-0.35 s. Measured with the conservative defaults (walls as constraints sliding against their
  // Navier friction, particle volumes, generalized-alpha): jet 0.318 s, sensor 0.336 s; the alpha shape with wall
  // particles: 0.304 and 0.305 s. The water (mesh + drops in flight): within the 1 % target (measured 0.39 %,
  // 0.31-0.70 % around its settings; under Newmark 0.65 %; 1.58 % while particles sliding along the floor went through
  // the obstacle's downstream face, whose fluid side was taken from the water facing it through the obstacle); the
  // mesh's own area drifts by what is in flight (2.35 %).
  const RunResult r = run_case_1thread("cases/dam_break_obstacle/case.json", "dam_break_obstacle");
  const Csv c = probes_of(r);
  EXPECT_NEAR(c["time"].back(), 1.0, 1e-9) << "stable to 1 s";
  const double W = 0.584, h = 0.0073;
  double t_jet = -1, t_wet = -1;
  for (size_t i = 0; i < c.rows(); ++i) {
    if (t_jet < 0 && c["reach_x"][i] >= W - 1.5 * h) t_jet = c["time"][i];
    if (t_wet < 0 && c["p_right_wall"][i] != 0.0) t_wet = c["time"][i];
  }
  EXPECT_GE(t_jet, 0.29);
  EXPECT_LE(t_jet, 0.35);
  EXPECT_GE(t_wet, 0.30);
  EXPECT_LE(t_wet, 0.35);
  const auto area = summary_of(r)["bodies"][0]["fluid_area"];
  ASSERT_TRUE(area.contains("water_drift_max")) << "the default keeps particle volumes";
  EXPECT_LT(area["water_drift_max"].get<double>(), 0.01);
  EXPECT_LT(max_area_drift(c), 0.05) << "the mesh's area: the water less what is in flight";
  for (size_t i = 0; i < c.rows(); ++i) EXPECT_TRUE(std::isfinite(c["kinetic_energy"][i])) << "t " << c["time"][i];
  std::printf(
      "dam break with obstacle: jet at the right wall %.4f s, wall sensor wet %.4f s, water drift %.2f %%, "
      "mesh %.2f %%\n",
      t_jet, t_wet, 100 * area["water_drift_max"].get<double>(), 100 * max_area_drift(c));
}

TEST(SloshingViscous, DecaysAndKeepsArea) {
  // Avancini (2018) sec. 6.9.5 at CI size (dt = 2 ms, 2 s; the full case is h = 0.01 m, 1 ms, 10 s, 3 min).
  // Targets: stable, kinetic energy decays, area drift <= 1 % (measured 0.06 %). Also the first sloshing period
  // against linear theory, omega^2 = g k tanh(k d), k = pi/L: 0.836 s (measured 0.838 s).
  const Csv c = probes_of(run_case_1thread("cases/sloshing_viscous/case.json", "sloshing_viscous",
                                           {"analysis.dt=2e-3", "analysis.end_time=2.0"}));
  const auto [ke_ratio, period, T_lin] = check_sloshing_viscous(c);
  std::printf(
      "viscous sloshing: max area drift %.3f %%, kinetic energy 1.5-2 s / 0-0.5 s %.3f, period %.4f s "
      "(linear %.4f s)\n",
      100 * max_area_drift(c), ke_ratio, period, T_lin);
}

TEST(SloshingForced, ShakenTankFollowsLinearTheory) {
  // A 1 m tank with 0.5 m of water shaken by 0.01 sin(0.7 omega_1 t) m from rest, CI size: the case's
  // resolution over 3 s (advected domain, slip walls as constraints, no volume correction). Measured over
  // 0-3 s: RMS error / linear peak 0.029 (left) and 0.032 (right) (with wall particles and the alpha shape:
  // 0.148, 0.168); area drift below 1e-6. Target: 0.05.
  const Csv c =
      probes_of(run_case_1thread("cases/sloshing_forced/case.json", "sloshing_forced", {"analysis.end_time=3.0"}));
  EXPECT_NEAR(c["time"].back(), 3.0, 1e-9);
  const double el = shaken_tank_error(c, "eta_left", 3.0), er = shaken_tank_error(c, "eta_right", 3.0);
  EXPECT_LT(el, 0.05);
  EXPECT_LT(er, 0.05);
  EXPECT_LT(max_area_drift(c), 1e-4);
  std::printf("shaken tank: elevation RMS error / linear peak %.3f (left), %.3f (right), max area drift %.3f %%\n", el,
              er, 100 * max_area_drift(c));
}

}  // namespace
