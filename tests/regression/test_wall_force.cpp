// The wall_force probe of the fluid (FluidModel::wall_force): the force the fluid applies to a wall, from the
// reactions of the wall's constraints ("wall_model": "constraints") or of its wall particles.
//  - water at rest in a tank (0.4 x 0.2 m, h = 0.02 m): the floor carries the water's weight rho g A (measured:
//    exact to round-off with the constraints, each scheme) and each side wall the hydrostatic thrust rho g d^2 / 2;
//    with wall particles the walls together carry the weight of the meshed water (the alpha shape leaves out
//    the corners' triangles of wall particles only: the floor alone carries 0.974 of it, the rest goes to the
//    side walls' last particles);
//  - plane Poiseuille flow (the set-up of cases/channel_poiseuille at H/h = 10): the middle of each wall, away
//    from the inlet and the outlet, carries the wall shear tau_w = 6 mu U / H over its length (measured, mean over
//    1-2 s: 0.978 of it with the fractional step, 0.915 with the monolithic scheme, whose flow rate is 0.91 of the
//    inflow's at this size: cases/channel_poiseuille), and the floor and the ceiling the pressure in opposite
//    directions;
//  - the load sensor (a pressure probe with "method": "load"): water at rest, a sensor on each side wall and on the
//    floor reads the hydrostatic pressure at its centre, rho g (d - y_c) (measured: exact to the printed digits with
//    either wall model and scheme; the particles' mean on the same segment of wall particles reads 0.91 of it); a
//    sensor above the water reads 0;
//  - a probe naming a wall the body does not have is an input error naming the key, as is a load sensor whose
//    segment's ends coincide or whose segment is not on a wall.
#include "case_runner.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace {

using namespace lagfsi::testing;

std::string tank(const std::string& scheme, const std::string& wall_model, const std::string& detection) {
  return R"({
    "name": "tank",
    "analysis": {"type": "dynamic", "dt": 0.005, "end_time": 0.2},
    "gravity": [0.0, -9.81],
    "bodies": [{
      "name": "water", "type": "fluid", "density": 1000.0, "viscosity": 0.001, "spacing": 0.02,
      "regions": [{"type": "rectangle", "origin": [0, 0], "size": [0.4, 0.2]}],
      "walls": [{"name": "left", "points": [[0, 0.3], [0, 0]]}, {"name": "bottom", "points": [[0, 0], [0.4, 0]]},
                {"name": "right", "points": [[0.4, 0], [0.4, 0.3]]}],
      "initial_pressure": {"type": "hydrostatic", "level": 0.2},
      "domain_detection": ")" +
         detection + R"(", "wall_model": ")" + wall_model + R"(",
      "scheme": {"type": ")" +
         scheme + R"("}
    }],
    "probes": [
      {"name": "Fy_bottom", "type": "wall_force", "body": "water", "wall": "bottom", "component": "y"},
      {"name": "Fx_bottom", "type": "wall_force", "body": "water", "wall": "bottom", "component": "x"},
      {"name": "Fx_left", "type": "wall_force", "body": "water", "wall": "left", "component": "x"},
      {"name": "Fy_left", "type": "wall_force", "body": "water", "wall": "left", "component": "y"},
      {"name": "Fx_right", "type": "wall_force", "body": "water", "wall": "right", "component": "x"},
      {"name": "Fy_right", "type": "wall_force", "body": "water", "wall": "right", "component": "y"},
      {"name": "area", "type": "fluid_area", "body": "water"}],
    "output": {"every": 100000, "vtk": false}
  })";
}

constexpr double kRhoG = 1000.0 * 9.81;

TEST(WallForce, TheFloorCarriesTheWeightOfWaterAtRest) {
  for (const std::string scheme : {"fractional_step", "monolithic_pspg"}) {
    const RunResult r = run_case_text(fresh_dir("wall_force_tank_" + scheme), tank(scheme, "constraints", "advected"));
    ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
    const Csv p = read_csv(r.out_dir / "probes.csv");
    for (size_t k = 0; k < p.rows(); ++k) {
      if (!(p["time"][k] > 0)) continue;  // no step yet: zero
      const double weight = kRhoG * p["area"][k];
      EXPECT_NEAR(p["Fy_bottom"][k], -weight, 0.01 * weight) << scheme << " at " << p["time"][k];
      EXPECT_NEAR(p["Fx_bottom"][k], 0.0, 1e-6 * weight) << scheme;
      // The side walls: the hydrostatic thrust rho g d^2 / 2 outwards, no shear at rest.
      const double thrust = 0.5 * kRhoG * 0.2 * 0.2;
      EXPECT_NEAR(p["Fx_left"][k], -thrust, 0.01 * thrust) << scheme;
      EXPECT_NEAR(p["Fx_right"][k], thrust, 0.01 * thrust) << scheme;
      EXPECT_NEAR(p["Fy_left"][k], 0.0, 1e-6 * weight) << scheme;
    }
  }
}

TEST(WallForce, WallParticlesCarryTheWeightOfTheMeshedWater) {
  for (const std::string scheme : {"fractional_step", "monolithic_pspg"}) {
    const RunResult r =
        run_case_text(fresh_dir("wall_force_tank_particles_" + scheme), tank(scheme, "particles", "alpha"));
    ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
    const Csv p = read_csv(r.out_dir / "probes.csv");
    for (size_t k = 0; k < p.rows(); ++k) {
      if (!(p["time"][k] > 0)) continue;  // no step yet: zero
      const double weight = kRhoG * p["area"][k];
      const double fy = p["Fy_bottom"][k] + p["Fy_left"][k] + p["Fy_right"][k];
      EXPECT_NEAR(fy, -weight, 0.01 * weight) << scheme << " at " << p["time"][k];
      EXPECT_NEAR(p["Fy_bottom"][k], -weight, 0.04 * weight) << scheme;
      // The horizontal forces balance.
      EXPECT_NEAR(p["Fx_bottom"][k] + p["Fx_left"][k] + p["Fx_right"][k], 0.0, 1e-6 * weight) << scheme;
    }
  }
}

/// cases/channel_poiseuille at H/h = 10, its floor cut into three walls (the middle one from x = 0.1 to 0.4 m).
std::string channel(const std::string& scheme) {
  return R"({
    "name": "channel",
    "analysis": {"type": "dynamic", "dt": 0.01, "end_time": 2.0},
    "gravity": [0.0, 0.0],
    "bodies": [{
      "name": "water", "type": "fluid", "density": 1000.0, "viscosity": 1.0, "spacing": 0.01,
      "regions": [{"type": "rectangle", "origin": [0, 0], "size": [0.5, 0.1]}],
      "walls": [{"name": "inlet_floor", "points": [[0, 0], [0.1, 0]]}, {"name": "floor", "points": [[0.1, 0], [0.4, 0]]},
                {"name": "outlet_floor", "points": [[0.4, 0], [0.5, 0]]}, {"name": "top", "points": [[0, 0.1], [0.5, 0.1]]}],
      "wall_friction": "held", "domain_detection": "advected", "wall_model": "constraints",
      "boundaries": [
        {"type": "inflow", "name": "inlet", "segment": [[0, 0], [0, 0.1]], "velocity": [0.05, 0],
         "profile": "parabolic"},
        {"type": "outflow", "name": "outlet", "segment": [[0.5, 0], [0.5, 0.1]]}],
      "scheme": {"type": ")" +
         scheme + R"("}
    }],
    "probes": [
      {"name": "Fx_floor", "type": "wall_force", "body": "water", "wall": "floor", "component": "x"},
      {"name": "Fy_floor", "type": "wall_force", "body": "water", "wall": "floor", "component": "y"},
      {"name": "Fx_in", "type": "wall_force", "body": "water", "wall": "inlet_floor", "component": "x"},
      {"name": "Fy_in", "type": "wall_force", "body": "water", "wall": "inlet_floor", "component": "y"},
      {"name": "Fx_out", "type": "wall_force", "body": "water", "wall": "outlet_floor", "component": "x"},
      {"name": "Fy_out", "type": "wall_force", "body": "water", "wall": "outlet_floor", "component": "y"},
      {"name": "Fx_top", "type": "wall_force", "body": "water", "wall": "top", "component": "x"},
      {"name": "Fy_top", "type": "wall_force", "body": "water", "wall": "top", "component": "y"}],
    "output": {"every": 100000, "vtk": false}
  })";
}

double mean_after(const Csv& p, const std::string& column, double t0) {
  double sum = 0;
  int n = 0;
  for (size_t k = 0; k < p.rows(); ++k)
    if (p["time"][k] >= t0 - 1e-9) {
      sum += p[column][k];
      ++n;
    }
  return n > 0 ? sum / n : 0.0;
}

void expect_wall_shear(const std::string& scheme, double tolerance) {
  const RunResult r = run_case_text(fresh_dir("wall_force_channel_" + scheme), channel(scheme));
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  const Csv p = read_csv(r.out_dir / "probes.csv");
  const double tau_w = 6.0 * 1.0 * 0.05 / 0.1;  // 6 mu U / H = 3 Pa
  // The floor's middle 0.3 m: the fluid drags it downstream.
  EXPECT_NEAR(mean_after(p, "Fx_floor", 1.0), tau_w * 0.3, tolerance * tau_w * 0.3) << scheme;
  // The whole ceiling: its ends carry less, within about 2 h of the inlet and of the outlet (measured 0.914 of
  // tau_w L with the fractional step, 0.831 with the monolithic scheme).
  EXPECT_NEAR(mean_after(p, "Fx_top", 1.0), tau_w * 0.5, (tolerance + 0.1) * tau_w * 0.5) << scheme;
  // The pressure pushes the floor down and the ceiling up, equally.
  const double floor_y = mean_after(p, "Fy_floor", 1.0) + mean_after(p, "Fy_in", 1.0) + mean_after(p, "Fy_out", 1.0);
  EXPECT_LT(floor_y, 0.0) << scheme;
  EXPECT_NEAR(floor_y, -mean_after(p, "Fy_top", 1.0), 0.02 * std::abs(floor_y)) << scheme;
}

TEST(WallForce, ChannelWallsCarryThePoiseuilleShearWithTheFractionalStep) {
  expect_wall_shear("fractional_step", 0.05);
}

TEST(WallForce, ChannelWallsCarryThePoiseuilleShearWithTheMonolithicScheme) {
  expect_wall_shear("monolithic_pspg", 0.12);
}

/// The tank at rest with load sensors: on the right wall centred at y = 0.09 m, 0.08 m long; on the left wall the
/// same, from top to bottom; on the floor over 0.1-0.27 m; above the water; and one a twentieth of a spacing long.
std::string tank_with_load_sensors(const std::string& scheme, const std::string& wall_model,
                                   const std::string& detection) {
  std::string text = tank(scheme, wall_model, detection);
  const std::string probes = R"("probes": [)";
  text.replace(text.find(probes), probes.size(), R"("probes": [
      {"name": "right", "type": "pressure", "body": "water", "from": [0.4, 0.05], "to": [0.4, 0.13], "method": "load"},
      {"name": "left", "type": "pressure", "body": "water", "from": [0.0, 0.13], "to": [0.0, 0.05], "method": "load"},
      {"name": "floor", "type": "pressure", "body": "water", "from": [0.1, 0.0], "to": [0.27, 0.0], "method": "load"},
      {"name": "dry", "type": "pressure", "body": "water", "from": [0.4, 0.24], "to": [0.4, 0.29], "method": "load"},
      {"name": "short", "type": "pressure", "body": "water", "from": [0.4, 0.0895], "to": [0.4, 0.0905],
       "method": "load"},)");
  return text;
}

TEST(WallForce, ALoadSensorOnAWallReadsTheHydrostaticPressureAtItsCentre) {
  struct Setting {
    std::string scheme, wall_model, detection;
  };
  for (const Setting& s :
       {Setting{"fractional_step", "constraints", "advected"}, Setting{"monolithic_pspg", "constraints", "advected"},
        Setting{"fractional_step", "particles", "alpha"}}) {
    const std::string tag = s.scheme + " " + s.wall_model;
    const RunResult r = run_case_text(fresh_dir("wall_load_" + s.scheme + "_" + s.wall_model),
                                      tank_with_load_sensors(s.scheme, s.wall_model, s.detection));
    ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
    const Csv p = read_csv(r.out_dir / "probes.csv");
    for (size_t k = 0; k < p.rows(); ++k) {
      if (!(p["time"][k] > 0)) {  // no step yet: no load
        EXPECT_EQ(p["right"][k], 0.0) << tag;
        continue;
      }
      const double side = kRhoG * (0.2 - 0.09), floor = kRhoG * 0.2;
      EXPECT_NEAR(p["right"][k], side, 0.005 * side) << tag << " at " << p["time"][k];
      EXPECT_NEAR(p["left"][k], side, 0.005 * side) << tag;
      EXPECT_NEAR(p["floor"][k], floor, 0.005 * floor) << tag;
      EXPECT_NEAR(p["short"][k], side, 0.005 * side) << tag;
      EXPECT_EQ(p["dry"][k], 0.0) << tag;
    }
  }
}

TEST(WallForce, ALoadSensorWithoutLengthOrOffTheWallsIsAnErrorNamingTheKey) {
  std::string text = tank("fractional_step", "constraints", "advected");
  const std::string probes = R"("probes": [)";
  text.replace(text.find(probes), probes.size(), R"("probes": [
      {"name": "p", "type": "pressure", "body": "water", "from": [0.4, 0.1], "to": [0.4, 0.1], "method": "load"},)");
  const RunResult r = run_case_text(fresh_dir("wall_load_no_length"), text);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("/probes/0/to"), std::string::npos) << r.stderr_text;
  // A segment in the water, away from every wall.
  const std::string point = R"("from": [0.4, 0.1], "to": [0.4, 0.1])";
  text.replace(text.find(point), point.size(), R"("from": [0.2, 0.05], "to": [0.2, 0.15])");
  const RunResult off = run_case_text(fresh_dir("wall_load_off_the_wall"), text);
  EXPECT_EQ(off.exit_code, 2);
  EXPECT_NE(off.stderr_text.find("/probes/0/from"), std::string::npos) << off.stderr_text;
}

TEST(WallForce, AProbeOfAWallTheBodyDoesNotHaveIsAnErrorNamingTheKey) {
  std::string text = tank("fractional_step", "constraints", "advected");
  const std::string wall = R"("wall": "bottom", "component": "y")";
  text.replace(text.find(wall), wall.size(), R"("wall": "floor", "component": "y")");
  const RunResult r = run_case_text(fresh_dir("wall_force_unknown_wall"), text);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("/probes/0/wall"), std::string::npos) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("floor"), std::string::npos) << r.stderr_text;
}

}  // namespace
