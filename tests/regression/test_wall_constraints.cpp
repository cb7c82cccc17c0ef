// Walls as constraints on the fluid particles on them ("wall_model": "constraints",
// docs/decisions/0002-walls-as-constraints.md): the PFEM wall
// particles have zero velocity, and fluid sliding past them has a discrete divergence that the continuity
// equation resists, a numerical friction that drained 1.2 % of a standing wave's energy a period. With the
// particles on a slip wall held in the normal direction only, the wave keeps its energy as a fixed mesh does.
//  - the first sloshing mode, remeshed every step with the advected domain (cases/sloshing_free/
//    case_advected.json), 3 periods: measured 0.9981 of the wave's energy kept (0.9655 with wall particles),
//    area drift 8e-8;
//  - a blob dropped into a tank lands on the floor and stays in the tank (each scheme): the particles that reach
//    a wall are put on it (wall_snaps) or back from beyond it (wall_crossings), none falls through, and one that
//    lands where another particle sits (a corner) is merged with it;
//  - water hanging from a ceiling falls (each scheme): a wall that pulls lets go of its particles (measured: the
//    blob's top at 0.311 and 0.306 m after 0.2 s, free fall 0.304 m; held, it would stay at 0.5 m);
//  - a block of viscous fluid sliding on a no-slip floor: with "wall_friction": "navier" the
//    particles on the floor slide against the friction (mu / s)(v_t - v_wall,t), whose dissipation the energy
//    balance counts; held ("held"), a layer one spacing thick stops, and the block loses more of its energy
//    (each scheme: the fractional step's friction acts in its viscous predictor, explicit or implicit);
//  - beside a structure (FSI, ghost particles): water pressed against a plate that bends 23 mm away stays in
//    the domain (the box follows the structure; it lost 6e-6 m² by 0.2 s before), and a particle put on the
//    end of a floor where an obstacle's ghost stands goes to the ghost (before, the next remesh stopped on a
//    duplicate point at 0.213 s);
//  - inclined walls (each particle on one solved in the wall's frame): water at rest in a tank with 45-degree
//    slip sides stays at rest (measured: largest speed 2e-14 m/s over 1 s), a wave sloshing in it keeps its
//    energy (measured 0.9966 of it after 2 s, its area to 3e-7), and a block sliding down a 30-degree slip
//    slope moves as the same block on a floor under gravity turned by 30 degrees (kinetic energy within 0.2 %
//    at 0.1 s), and so does a viscous one on a no-slip slope, sliding against its Navier friction or held;
//  - a step retried after a remesh that failed once its particle management had changed the cloud keeps the
//    cloud's own pressures (the last step's, of the old cloud's size, were put back, and the next remesh read
//    past their end: under the sanitizers, scripts/developer_check.sh -R WallConstraints, a heap overflow at
//    0.22 s of this run);
//  - the "surface" volume correction leaves the particles on the walls where the walls hold them (moved along the
//    area's gradient, a particle at the water's edge left the wall's line, the step put it back, and the two undid
//    each other at every step: the dam break with the fractional step lost 57 % of its water by 0.3 s through
//    30 000 wall crossings; measured now -0.7 % and 4 crossings).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "case_runner.hpp"

namespace {

using namespace lagfsi::testing;

/// The wave's energy: kinetic + potential above the still water of the same area (a 1 m tank) + dissipated.
double wave_energy(const Csv& c, size_t i) {
  const double rho = 1000.0, g = 9.81, W = 1.0, A = c["fluid_area"][i];
  return c["kinetic_energy"][i] + c["potential_energy"][i] - rho * g * A * A / (2 * W) + c["viscous_dissipation"][i];
}

TEST(WallConstraints, StandingWaveKeepsItsEnergy) {
  const double T = 1.18182;  // the first mode's linear period
  const RunResult r = run_case_file("cases/sloshing_free/case_advected.json", "wall_constraints_sloshing",
                                    {"analysis.end_time=" + std::to_string(3 * T), "output.vtk=false"});
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  const Csv c = probes_of(r);
  const auto s = summary_of(r);
  ASSERT_EQ(s["bodies"][0]["wall_model"].get<std::string>(), "constraints");
  const double e0 = wave_energy(c, 0);
  size_t k = 0;
  for (size_t i = 0; i < c.rows(); ++i)
    if (std::abs(c["time"][i] - 3 * T) < std::abs(c["time"][k] - 3 * T)) k = i;
  const double kept = wave_energy(c, k) / e0;
  double drift = 0;
  for (double a : c["fluid_area"]) drift = std::max(drift, std::abs(a / c["fluid_area"][0] - 1));
  std::printf("standing wave, walls as constraints: energy kept after 3 periods %.4f, area drift %.1e\n", kept, drift);
  EXPECT_GT(kept, 0.995) << "the wall-particle layer lost 3.5 % in 3 periods";
  EXPECT_LT(kept, 1.001);
  EXPECT_LT(drift, 1e-5);
}

/// A 5 x 5 particle blob thrown into a tank with slip walls as constraints. With the monolithic scheme it keeps
/// the settings it was measured with, p = 0 on the free surface and no correction (the default package's particle
/// volumes throw a drop of this unresolved splash out over the walls at 5 m/s, 0.4 % of the area).
std::string blob_in_tank(const std::string& scheme) {
  const std::string settings =
      scheme == "monolithic_pspg" ? R"(, "free_surface_pressure": "dirichlet", "volume_correction": "none")" : "";
  return R"({
    "name": "blob_in_tank",
    "analysis": {"type": "dynamic", "dt": 2e-3, "end_time": 0.5},
    "gravity": [0.0, -9.81],
    "bodies": [{
      "name": "water", "type": "fluid", "density": 1000.0, "viscosity": 1e-3, "spacing": 0.02,
      "domain_detection": "advected", "wall_model": "constraints",
      "regions": [{"type": "rectangle", "origin": [0.1, 0.1], "size": [0.1, 0.1]}],
      "walls": [{"points": [[0, 0.4], [0, 0], [0.3, 0], [0.3, 0.4]], "slip": true}],
      "initial_velocity": [1.0, 0.0],
      "scheme": {"type": ")" +
         scheme + "\"" + settings + R"(}
    }],
    "probes": [{"name": "area", "type": "fluid_area", "body": "water"}],
    "output": {"every": 50}
  })";
}

TEST(WallConstraints, ABlobLandsAndStaysInTheTank) {
  for (const std::string scheme : {"monolithic_pspg", "fractional_step"}) {
    const RunResult r = run_case_text(fresh_dir("wall_constraints_blob_" + scheme), blob_in_tank(scheme));
    ASSERT_EQ(r.exit_code, 0) << scheme << ": " << r.stderr_text;
    const auto s = summary_of(r);
    const auto& b = s["bodies"][0];
    EXPECT_GT(b["wall_snaps"].get<long>() + b["wall_crossings"].get<long>(), 0) << scheme << ": it reached the floor";
    EXPECT_EQ(b["fluid_area"]["left_domain"].get<double>(), 0.0) << scheme << ": none fell through a wall";
    const Csv c = probes_of(r);
    double drift = 0;
    for (double a : c["area"]) drift = std::max(drift, std::abs(a / c["area"][0] - 1));
    // A sanity bound only: the impact of a 5 x 5 particle blob is not resolved (measured 49.0 % and 31.6 %; with
    // wall particles, monolithic scheme, 85 % of the blob's area is lost by 0.5 s). With "contact_gap": 0 (the
    // advected detection's default before its contact gap, docs/decisions/0001) 35.4 % and 18.4 %: pieces of the film
    // that separate rejoin it with a gap element of up to 1.5 h, which gave back some of what the steps lose.
    EXPECT_LT(drift, 0.55) << scheme;
    std::printf("%s: %ld put on a wall, %ld put back from beyond one, largest area drift %.2f %%\n", scheme.c_str(),
                b["wall_snaps"].get<long>(), b["wall_crossings"].get<long>(), 100 * drift);
  }
}

std::string blob_under_ceiling(const std::string& scheme) {
  return R"({
    "name": "blob_under_ceiling",
    "analysis": {"type": "dynamic", "dt": 2e-3, "end_time": 0.2},
    "gravity": [0.0, -9.81],
    "bodies": [{
      "name": "water", "type": "fluid", "density": 1000.0, "viscosity": 1e-3, "spacing": 0.02,
      "domain_detection": "advected", "wall_model": "constraints",
      "regions": [{"type": "rectangle", "origin": [0.1, 0.4], "size": [0.1, 0.1]}],
      "walls": [{"name": "tank", "points": [[0, 0.6], [0, 0], [0.3, 0], [0.3, 0.6]], "slip": true},
                {"name": "ceiling", "points": [[0, 0.5], [0.3, 0.5]], "slip": true}],
      "scheme": {"type": ")" +
         scheme + R"("}
    }],
    "probes": [{"name": "top", "type": "column_height", "body": "water", "wall": 0.15, "band": 0.3}],
    "output": {"every": 50}
  })";
}

TEST(WallConstraints, WaterUnderACeilingFalls) {
  for (const std::string scheme : {"monolithic_pspg", "fractional_step"}) {
    const RunResult r = run_case_text(fresh_dir("wall_constraints_ceiling_" + scheme), blob_under_ceiling(scheme));
    ASSERT_EQ(r.exit_code, 0) << scheme << ": " << r.stderr_text;
    const Csv c = probes_of(r);
    const double top = c["top"].back(), free_fall = 0.5 - 0.5 * 9.81 * 0.2 * 0.2;
    EXPECT_NEAR(top, free_fall, 0.02) << scheme << ": the blob's top after 0.2 s of free fall";
    EXPECT_GT(summary_of(r)["bodies"][0]["wall_releases"].get<long>(), 0) << scheme;
  }
}

/// `scheme`: the body's "scheme" object ("" the default, the monolithic scheme).
std::string block_on_floor(const std::string& friction, bool slip, const std::string& scheme = "") {
  return R"({
    "name": "block_on_floor",
    "analysis": {"type": "dynamic", "dt": 1e-3, "end_time": 0.1},
    "gravity": [0.0, -9.81],
    "bodies": [{
      "name": "water", "type": "fluid", "density": 1000.0, "viscosity": 1.0, "spacing": 0.0125,
      "domain_detection": "advected", "wall_model": "constraints", "wall_friction": ")" +
         friction + R"(",
      "regions": [{"type": "rectangle", "origin": [0.1, 0], "size": [0.2, 0.05]}],
      "walls": [{"name": "floor", "points": [[0, 0], [1, 0]], "slip": )" +
         (slip ? "true" : "false") + R"(}],
      "initial_velocity": [1.0, 0.0],)" +
         (scheme.empty() ? std::string() : R"("scheme": )" + scheme + ",") + R"(
      "initial_pressure": {"type": "hydrostatic", "level": 0.05}
    }],
    "probes": [{"name": "ke", "type": "kinetic_energy", "body": "water"},
               {"name": "dissipated", "type": "viscous_dissipation", "body": "water"},
               {"name": "total", "type": "total_energy", "body": "water"}],
    "output": {"vtk": false}
  })";
}

TEST(WallConstraints, NoSlipWallsSlideAgainstTheirNavierFriction) {
  struct Outcome {
    double ke_lost, dissipated, balance;
  };
  const auto run = [](const std::string& friction, bool slip, const std::string& scheme = "",
                      const std::string& scheme_tag = "") {
    const std::string tag = "wall_constraints_block_" + friction + (slip ? "_slip" : "") + scheme_tag;
    const RunResult r = run_case_text(fresh_dir(tag), block_on_floor(friction, slip, scheme));
    EXPECT_EQ(r.exit_code, 0) << tag << ": " << r.stderr_text;
    if (r.exit_code != 0) return Outcome{0, 0, 1e300};
    const auto s = summary_of(r);
    EXPECT_EQ(s["bodies"][0]["wall_friction"].get<std::string>(), friction) << tag;
    const Csv c = probes_of(r);
    const double ke0 = c["ke"][0];
    // KE + PE + dissipated at the end against the start, less what the remeshing changed (the lumped masses
    // a re-triangulation moves: summary.json's remeshing.kinetic_energy_change), over the initial KE.
    const double remesh = s["bodies"][0]["remeshing"]["kinetic_energy_change"].get<double>();
    const double balance = std::abs(c["total"].back() - c["total"][0] - remesh) / ke0;
    const Outcome o{1 - c["ke"].back() / ke0, c["dissipated"].back() / ke0, balance};
    std::printf("block on a floor, %s: kinetic energy lost %.4f, dissipated %.4f, balance %.1e\n", tag.c_str(),
                o.ke_lost, o.dissipated, o.balance);
    return o;
  };
  const Outcome slip = run("navier", true), navier = run("navier", false), held = run("held", false);
  // The block slides and spreads (its ends are free); on the slip floor only the fluid's own viscosity
  // dissipates (measured 0.02 of the initial kinetic energy, and 0.32 on the no-slip floor).
  EXPECT_LT(slip.dissipated, 0.05);
  // On the no-slip floor the friction takes energy (17 particles on the floor, (mu / s) v^2 = 2 W/m each at
  // 1 m/s: at most 0.7 of the initial 5 J/m over 0.1 s, less as the floor layer slows), and the balance
  // counts it (measured 2e-3).
  EXPECT_GT(navier.dissipated, 0.2);
  EXPECT_GT(navier.ke_lost, slip.ke_lost + 0.2);
  EXPECT_LT(navier.balance, 0.01);
  EXPECT_LT(slip.balance, 0.01);
  // Held, the floor layer stops at once: more is lost.
  EXPECT_GT(held.ke_lost, navier.ke_lost);

  // The fractional step: the friction in its viscous predictor, explicit and implicit. It slides as the
  // monolithic scheme's block does (measured: kinetic energy lost 0.2231 and 0.2238 against 0.2213), and the
  // balance holds to 2 % (measured 9e-3; on the slip floor 4e-3: the symplectic Euler's own error, and the
  // friction acts on u* where the dissipation counts it at u^{n+1}). Held, the fractional step's block loses
  // 0.295.
  for (const auto& [scheme, tag] :
       {std::pair<std::string, std::string>{R"({"type": "fractional_step", "viscous_step": "explicit"})", "_fs"},
        {R"({"type": "fractional_step", "viscous_step": "implicit"})", "_fs_implicit"}}) {
    const Outcome fs_navier = run("navier", false, scheme, tag), fs_held = run("held", false, scheme, tag);
    EXPECT_GT(fs_navier.dissipated, 0.2) << tag;
    EXPECT_NEAR(fs_navier.ke_lost, navier.ke_lost, 0.05) << tag;
    EXPECT_LT(fs_navier.balance, 0.02) << tag;
    EXPECT_GT(fs_held.ke_lost, fs_navier.ke_lost + 0.05) << tag;
  }
}

TEST(WallConstraints, BesideAStructure) {
  const std::vector<std::string> conservative = {"bodies.0.domain_detection=advected",
                                                 "bodies.0.wall_model=constraints", "output.vtk=false"};
  std::vector<std::string> sets = conservative;
  sets.push_back("analysis.end_time=0.2");
  RunResult r = run_case_file("cases/flexible_tank/case.json", "wall_constraints_flexible_tank", sets);
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_EQ(summary_of(r)["bodies"][0]["fluid_area"]["left_domain"].get<double>(), 0.0)
      << "the water held by the bent plate is in the domain";
  sets = conservative;
  sets.push_back("analysis.end_time=0.25");
  r = run_case_file("cases/elastic_obstacle_walhorn/case.json", "wall_constraints_walhorn", sets);
  EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
}

/// A tank whose sides are slip walls inclined at 45 degrees (floor 0.4 m wide from x = 0.2 to 0.6), its water
/// a polygon from the floor up to (-0.02, y_left) and (0.78, 0.18) on the sides; unstructured particles (the
/// mesh's boundary nodes lie on the sides).
std::string sloped_tank(double y_left, const std::string& scheme_keys, double end_time) {
  const std::string x_left = std::to_string(0.2 - y_left), y = std::to_string(y_left);
  return R"({
    "name": "sloped_tank",
    "analysis": {"type": "dynamic", "dt": 2e-3, "end_time": )" +
         std::to_string(end_time) + R"(},
    "gravity": [0.0, -9.81],
    "bodies": [{
      "name": "water", "type": "fluid", "density": 1000.0, "viscosity": 1e-3, "spacing": 0.02,
      "particles": "unstructured", "domain_detection": "advected", "wall_model": "constraints",
      "regions": [{"type": "polygon", "points": [[0.2, 0], [0.6, 0], [0.78, 0.18], [)" +
         x_left + ", " + y + R"(]]}],
      "walls": [{"points": [[-0.1, 0.3], [0.2, 0], [0.6, 0], [0.9, 0.3]], "slip": true}],
      "initial_pressure": {"type": "hydrostatic", "level": 0.18},
      "scheme": {)" +
         scheme_keys + R"(}
    }],
    "probes": [{"name": "vmax", "type": "max_speed", "body": "water"},
               {"name": "area", "type": "fluid_area", "body": "water"},
               {"name": "total", "type": "total_energy", "body": "water"}],
    "output": {"vtk": false}
  })";
}

/// A block of water 0.2 x 0.1 m resting on a slip floor: inclined down at 30 degrees (the block's sides along and
/// across it), or horizontal with gravity turned by 30 degrees (the same flow in the floor's frame). With a
/// `friction` ("navier", "held") the floor is a no-slip one.
std::string block_on_slope(bool inclined, double viscosity = 1e-3, const std::string& friction = "") {
  const double th = M_PI / 6, c = std::cos(th), s = std::sin(th);
  const auto pair = [](double x, double y) {  // in full (the block's corners on the slope to round-off)
    char buf[64];
    std::snprintf(buf, sizeof buf, "[%.17g, %.17g]", x, y);
    return std::string(buf);
  };
  const auto pt = [&](double along, double across) {
    return inclined ? pair(along * c + across * s, -along * s + across * c) : pair(along, across);
  };
  const std::string floor_end = pt(2.0, 0.0);
  const std::string gravity = inclined ? "[0.0, -9.81]" : pair(9.81 * s, -9.81 * c);
  return R"({
    "name": "block_on_slope",
    "analysis": {"type": "dynamic", "dt": 1e-3, "end_time": 0.1},
    "gravity": )" +
         gravity + R"(,
    "bodies": [{
      "name": "water", "type": "fluid", "density": 1000.0, "spacing": 0.0125,
      "particles": "unstructured", "domain_detection": "advected", "wall_model": "constraints",)" +
         "\"viscosity\": " + std::to_string(viscosity) + "," +
         (friction.empty() ? std::string() : "\"wall_friction\": \"" + friction + "\",") +
         // Held walls: measured with the particle volumes' relaxation time then 0.02 s. The held slope against
         // the turned floor is 0.992 / 0.954 / 0.982 at T = 0.005 / 0.01 / 0.02 s: scatter of the held layer,
         // not a trend (the Navier friction's pair agrees within 0.1 % at the default 0.01 s).
         (friction == "held" ? std::string(R"("scheme": {"volume_relaxation_time": 0.02},)") : std::string()) +
         R"(
      "regions": [{"type": "polygon", "points": [)" +
         pt(0.2, 0) + ", " + pt(0.4, 0) + ", " + pt(0.4, 0.1) + ", " + pt(0.2, 0.1) + R"(]}],
      "walls": [{"points": [[0, 0.5], [0, 0], )" +
         floor_end + R"(], "slip": )" + (friction.empty() ? "true" : "false") + R"(}]
    }],
    "probes": [{"name": "ke", "type": "kinetic_energy", "body": "water"}],
    "output": {"vtk": false}
  })";
}

TEST(WallConstraints, InclinedWallsHoldTheFluidInTheirFrames) {
  // Water at rest between 45-degree sides (hydrostatic start, the default scheme keys): it stays at rest.
  RunResult r = run_case_text(fresh_dir("wall_constraints_sloped_still"), sloped_tank(0.18, "", 1.0));
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  Csv c = probes_of(r);
  double vmax = 0;
  for (double v : c["vmax"]) vmax = std::max(vmax, v);
  std::printf("still water between inclined walls: largest speed %.1e m/s over 1 s\n", vmax);
  EXPECT_LT(vmax, 1e-6 * std::sqrt(9.81 * 0.18));
  EXPECT_EQ(summary_of(r)["bodies"][0]["wall_crossings"].get<long>(), 0);

  // Its surface tilted (0.22 m on the left, 0.18 m on the right), with the conservative package: the wave
  // keeps its energy (total = kinetic + potential + dissipated, over that of the still water of the same area).
  r = run_case_text(fresh_dir("wall_constraints_sloped_wave"),
                    sloped_tank(0.22, R"("free_surface_pressure": "robin", "volume_correction": "particle")", 2.0));
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  c = probes_of(r);
  const auto rest = [](double area) {  // potential energy of the still water of that area, A = 0.4 d + d^2
    const double depth = (-0.4 + std::sqrt(0.16 + 4 * area)) / 2;
    return 1000 * 9.81 * (0.2 * depth * depth + 2.0 / 3.0 * depth * depth * depth);
  };
  const double A = c["area"][0];
  const double kept = (c["total"].back() - rest(c["area"].back())) / (c["total"][0] - rest(A));
  double drift = 0;
  for (double a : c["area"]) drift = std::max(drift, std::abs(a / A - 1));
  std::printf("wave between inclined walls: energy kept after 2 s %.4f, area drift %.1e\n", kept, drift);
  EXPECT_GT(kept, 0.99);
  EXPECT_LT(kept, 1.001);
  EXPECT_LT(drift, 1e-4);

  // A block sliding down a 30-degree slope, against the same block on a floor under turned gravity.
  const RunResult slope = run_case_text(fresh_dir("wall_constraints_slope"), block_on_slope(true));
  const RunResult flat = run_case_text(fresh_dir("wall_constraints_slope_flat"), block_on_slope(false));
  ASSERT_EQ(slope.exit_code, 0) << slope.stderr_text;
  ASSERT_EQ(flat.exit_code, 0) << flat.stderr_text;
  const double ke_slope = probes_of(slope)["ke"].back(), ke_flat = probes_of(flat)["ke"].back();
  std::printf("block on a 30-degree slope: kinetic energy at 0.1 s %.4f J/m, on the turned floor %.4f\n", ke_slope,
              ke_flat);
  EXPECT_NEAR(ke_slope / ke_flat, 1.0, 0.01);
  // Free sliding alone: 0.5 m (g sin 30 t)^2 = 2.4 J/m for the 20 kg/m block; its spreading adds to it.
  EXPECT_GT(ke_slope, 2.4);
  // A viscous block (1 Pa s) on a no-slip slope: the Navier friction acts along the slope (measured: the turned
  // floor's kinetic energy within 1.4 %); held, the floor layer stops (1.5 %).
  const RunResult viscous = run_case_text(fresh_dir("wall_constraints_slope_viscous"), block_on_slope(true, 1.0));
  ASSERT_EQ(viscous.exit_code, 0) << viscous.stderr_text;
  const double ke_viscous = probes_of(viscous)["ke"].back();
  for (const std::string friction : {"navier", "held"}) {
    const RunResult a =
        run_case_text(fresh_dir("wall_constraints_slope_" + friction), block_on_slope(true, 1.0, friction));
    const RunResult b =
        run_case_text(fresh_dir("wall_constraints_slope_flat_" + friction), block_on_slope(false, 1.0, friction));
    ASSERT_EQ(a.exit_code, 0) << a.stderr_text;
    ASSERT_EQ(b.exit_code, 0) << b.stderr_text;
    const double ka = probes_of(a)["ke"].back(), kb = probes_of(b)["ke"].back();
    std::printf("viscous block on a no-slip 30-degree slope, %s: kinetic energy %.4f J/m, on the turned floor %.4f\n",
                friction.c_str(), ka, kb);
    EXPECT_NEAR(ka / kb, 1.0, 0.02) << friction;
    EXPECT_LT(ka, 0.95 * ke_viscous) << friction << ": the friction takes energy";
  }
}

TEST(WallConstraints, ARetryAfterAFailedRemeshKeepsTheCloudsPressures) {
  const RunResult r = run_case_file(
      "cases/dam_break_obstacle/case.json", "wall_constraints_obstacle_retry",
      {"bodies.0.domain_detection=advected", "bodies.0.wall_model=constraints", "bodies.0.wall_friction=navier",
       "bodies.0.scheme.free_surface_pressure=robin", "bodies.0.scheme.volume_correction=particle",
       "bodies.0.scheme.volume_relaxation_time=0.01", "analysis.end_time=0.25", "output.vtk=false",
       // Newmark's trapezoidal rule retries steps in this splash; generalized-alpha, the default with the
       // Robin surface, does not before 0.25 s.
       "analysis.integrator.type=newmark"},
      "--threads 1");
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_GT(summary_of(r)["step_retries"].get<long>(), 0) << "the splash retries steps";
}

TEST(WallConstraints, TheSurfaceCorrectionLeavesTheParticlesOnTheWallsThere) {
  const RunResult r = run_case_file(
      "cases/dam_break_tank/case.json", "wall_constraints_surface_correction",
      {"bodies.0.scheme.type=fractional_step", "bodies.0.domain_detection=advected", "bodies.0.wall_model=constraints",
       "bodies.0.scheme.volume_correction=surface", "analysis.end_time=0.3", "output.vtk=false"},
      "--threads 1");
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  const auto s = summary_of(r);
  const auto& fluid = s["bodies"][0];
  const double drift =
      fluid["fluid_area"]["drift_without_left"].get<double>() / fluid["fluid_area"]["initial"].get<double>();
  const double churn =
      std::abs(fluid["fluid_area"]["change_in_steps"].get<double>()) / fluid["fluid_area"]["initial"].get<double>();
  std::printf(
      "surface correction on walls as constraints: water drift %.4f, steps' change %.4f of the water, "
      "%ld wall crossings\n",
      drift, churn, fluid["wall_crossings"].get<long>());
  EXPECT_LT(std::abs(drift), 0.02);
  EXPECT_LT(churn, 0.05) << "the steps take back what the correction moved";
  EXPECT_LT(fluid["wall_crossings"].get<long>(), 200);
}

}  // namespace
