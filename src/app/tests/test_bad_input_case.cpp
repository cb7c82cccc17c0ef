// Whole-case checks at input: body names against the run's output files,
// overlapping bodies, MPM regions outside their grid and MPM bodies leaving it, and time integrators that are
// only conditionally stable.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "case_runner.hpp"
#include "process.hpp"

namespace {

using namespace lagfsi::testing;
using nlohmann::json;

json fluid_body() {
  return json::parse(R"({
    "name": "water", "type": "fluid", "density": 1000, "viscosity": 1e-3, "spacing": 0.05,
    "regions": [{"type": "rectangle", "origin": [0, 0], "size": [0.4, 0.2]}],
    "walls": [{"name": "tank", "points": [[0, 0.6], [0, 0], [1.0, 0], [1.0, 0.6]]}],
    "scheme": {"type": "fractional_step"}
  })");
}

json plate_body(double x0, double y0, double w, double h) {
  json p = json::parse(R"({
    "name": "plate", "type": "solid",
    "material": {"type": "svk", "young": 1e6, "poisson": 0.0, "density": 2500},
    "mesh": {"type": "structured", "size": 0.05, "order": 1}
  })");
  p["geometry"] = {{"type", "rectangle"}, {"origin", {x0, y0}}, {"size", {w, h}}};
  p["boundary_conditions"] =
      json::array({{{"type", "fixed"}, {"select", {{"type", "segment"}, {"from", {x0, y0}}, {"to", {x0 + w, y0}}}}}});
  return p;
}

json case_of(const std::vector<json>& bodies) {
  json j = {{"name", "case_checks"},
            {"analysis", {{"type", "dynamic"}, {"dt", 1e-3}, {"end_time", 2e-3}}},
            {"gravity", {0, -9.81}},
            {"bodies", bodies},
            {"output", {{"vtk", false}}}};
  return j;
}

json mpm_body(const std::string& name, double x0, double y0) {
  json m = json::parse(R"({
    "type": "mpm",
    "material": {"type": "linear_elastic", "young": 1e6, "poisson": 0.3, "density": 1000},
    "grid": {"origin": [0, 0], "size": [1.0, 1.0], "cell": 0.1}
  })");
  m["name"] = name;
  m["regions"] = json::array({{{"type", "rectangle"}, {"origin", {x0, y0}}, {"size", {0.4, 0.4}}}});
  m["boundary_conditions"] =
      json::array({{{"type", "fixed"}, {"select", {{"type", "segment"}, {"from", {0, 0}}, {"to", {1, 0}}}}}});
  return m;
}

Finished check(const std::string& tag, const json& j) {
  const fs::path dir = fresh_dir("case_checks_" + tag);
  write_text(dir / "case.json", j.dump(2));
  return run_args({"check", (dir / "case.json").string()}, dir);
}

Finished run(const std::string& tag, const json& j, std::vector<std::string> extra = {"--quiet"}) {
  const fs::path dir = fresh_dir("case_checks_" + tag);
  write_text(dir / "case.json", j.dump(2));
  std::vector<std::string> args{"run", (dir / "case.json").string(), "-o", (dir / "out").string()};
  args.insert(args.end(), extra.begin(), extra.end());
  return run_args(args, dir);
}

void expect_input_error(const Finished& r, const std::string& part) {
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(part), std::string::npos) << r.err;
}

TEST(BadInputCase, BodyNamesAgainstOutputFiles) {
  EXPECT_EQ(check("names_ok", case_of({fluid_body(), plate_body(0.6, 0, 0.05, 0.3)})).code, 0);
  // A fluid "water" writes water_walls.pvd: a solid "water_walls" would write its series into the same file.
  json plate = plate_body(0.6, 0, 0.05, 0.3);
  plate["name"] = "water_walls";
  expect_input_error(check("names_walls", case_of({fluid_body(), plate})),
                     "/bodies/1/name: its output 'water_walls.pvd' is also written by body 'water'");
  // The other order too.
  expect_input_error(check("names_walls_first", case_of({plate, fluid_body()})),
                     "/bodies/1/name: its output 'water_walls");
  // Names of the run's own files, and folders that would take a file's place; case is ignored.
  for (const std::string name : {"log", "summary", "probes", "resolved_case", "Log", "summary.json", "log.csv"}) {
    plate["name"] = name;
    expect_input_error(check("names_run_files", case_of({fluid_body(), plate})), "/bodies/1/name: ");
  }
  plate["name"] = "Water";
  expect_input_error(check("names_case", case_of({fluid_body(), plate})), "ignoring case");
  // MPM bodies write NAME_grid.pvd and NAME_particles.csv.
  expect_input_error(check("names_mpm", case_of({mpm_body("soil", 0.2, 0), mpm_body("soil_grid", 0.2, 0.5)})),
                     "/bodies/1/name: its output 'soil_grid.pvd'");
}

TEST(BadInputCase, OverlappingBodies) {
  // A fluid region filling a solid plate, in either order: the later body is named.
  expect_input_error(check("overlap_plate_first", case_of({plate_body(0.1, 0, 0.05, 0.3), fluid_body()})),
                     "/bodies/1/regions/0: overlaps body 'plate'");
  expect_input_error(check("overlap_fluid_first", case_of({fluid_body(), plate_body(0.1, 0, 0.05, 0.3)})),
                     "/bodies/1/geometry: overlaps body 'water'");
  // A plate beside the water, touching it, is not an overlap; nor one standing on the tank's floor.
  EXPECT_EQ(check("overlap_touching", case_of({fluid_body(), plate_body(0.4, 0, 0.05, 0.3)})).code, 0);
  // A polygon region (non-convex, an L) that reaches into the plate.
  json l = fluid_body();
  l["particles"] = "unstructured";
  l["regions"][0] =
      json::parse(R"({"type": "polygon", "points": [[0, 0], [0.8, 0], [0.8, 0.1], [0.3, 0.1], [0.3, 0.2], [0, 0.2]]})");
  expect_input_error(check("overlap_polygon", case_of({l, plate_body(0.6, 0.05, 0.05, 0.3)})),
                     "/bodies/1/geometry: overlaps body 'water'");
  EXPECT_EQ(check("overlap_polygon_notch", case_of({l, plate_body(0.45, 0.1, 0.05, 0.3)})).code, 0)
      << "the plate stands in the L's notch";
  // A solid crossed by the tank's wall (a plate through the floor).
  expect_input_error(check("overlap_wall", case_of({fluid_body(), plate_body(0.6, -0.1, 0.05, 0.3)})),
                     "/bodies/1/geometry: is crossed by the wall 'tank' of body 'water'");
  // Two MPM bodies in one place.
  expect_input_error(check("overlap_mpm", case_of({mpm_body("a", 0.2, 0), mpm_body("b", 0.4, 0.2)})),
                     "/bodies/1/regions/0: overlaps body 'a'");
  EXPECT_EQ(check("overlap_mpm_apart", case_of({mpm_body("a", 0.0, 0), mpm_body("b", 0.5, 0.0)})).code, 0);
}

json shell_body(double x0, double y0, double x1, double y1, double thickness) {
  json s = json::parse(R"({
    "name": "gate", "type": "shell",
    "material": {"type": "svk", "young": 1e7, "poisson": 0.0, "density": 1100},
    "mesh": {"order": 2, "elements": 4}
  })");
  s["thickness"] = thickness;
  s["geometry"] = {{"type", "line"}, {"from", {x0, y0}}, {"to", {x1, y1}}};
  s["boundary_conditions"] = json::array({{{"type", "fixed"}, {"select", {{"type", "point"}, {"at", {x0, y0}}}}}});
  return s;
}

TEST(BadInputCase, OverlappingShellsAndCircleCuts) {
  // A shell standing in the water (its mid-line widened to its thickness), in either order; a shell whose face
  // touches the water is not an overlap.
  expect_input_error(check("overlap_shell", case_of({fluid_body(), shell_body(0.2, 0.0, 0.2, 0.3, 0.02)})),
                     "/bodies/1/geometry: overlaps body 'water'");
  expect_input_error(check("overlap_shell_first", case_of({shell_body(0.2, 0.0, 0.2, 0.3, 0.02), fluid_body()})),
                     "/bodies/1/regions/0: overlaps body 'gate'");
  EXPECT_EQ(check("overlap_shell_touching", case_of({fluid_body(), shell_body(0.41, 0.0, 0.41, 0.3, 0.02)})).code, 0);
  // A shell through the tank's wall.
  expect_input_error(check("overlap_shell_wall", case_of({fluid_body(), shell_body(0.8, 0.3, 1.2, 0.3, 0.02)})),
                     "/bodies/1/geometry: is crossed by the wall 'tank' of body 'water'");
  // A flag clamped on a cylinder (circle_cut) in the water; beside a plate that sits in the disc cut out of
  // its polygon, which it does not overlap.
  json flag = plate_body(0, 0, 1, 1);
  flag["name"] = "flag";
  flag["mesh"] = {{"size", 0.01}, {"order", 1}};
  flag["geometry"] =
      json::parse(R"({"type": "circle_cut", "points": [[0.1, 0.05], [0.35, 0.05], [0.35, 0.07], [0.1, 0.07]],
                                     "centre": [0.1, 0.06], "radius": 0.02})");
  flag["boundary_conditions"][0]["select"] = {{"type", "circle"}, {"centre", {0.1, 0.06}}, {"radius", 0.02}};
  expect_input_error(check("overlap_circle_cut", case_of({fluid_body(), flag})),
                     "/bodies/1/geometry: overlaps body 'water'");
  flag["geometry"]["points"] = json::parse("[[0.5, 0.3], [0.9, 0.3], [0.9, 0.32], [0.5, 0.32]]");
  flag["geometry"]["centre"] = {0.5, 0.31};
  flag["geometry"]["radius"] = 0.05;
  flag["boundary_conditions"][0]["select"] = {{"type", "circle"}, {"centre", {0.5, 0.31}}, {"radius", 0.05}};
  json plate = plate_body(0.5, 0.3, 0.03, 0.02);
  EXPECT_EQ(check("overlap_circle_cut_disc", case_of({flag, plate})).code, 0) << "the plate is in the cut-out disc";
  json wide = plate_body(0.5, 0.3, 0.2, 0.02);
  expect_input_error(check("overlap_circle_cut_plate", case_of({flag, wide})),
                     "/bodies/1/geometry: overlaps body 'flag'");
}

TEST(BadInputCase, MpmRegionOutsideItsGridAndLeavingIt) {
  // Partly outside: the region was cut silently.
  json m = mpm_body("block", 0.8, 0.0);
  expect_input_error(check("mpm_cut", case_of({m})), "/bodies/0/regions/0/size: reaches (1.2, 0), outside the grid");
  m["regions"][0] = json::parse(R"({"type": "polygon", "points": [[0.2, 0.2], [0.6, 0.2], [0.4, -0.3]]})");
  expect_input_error(check("mpm_cut_polygon", case_of({m})), "/bodies/0/regions/0/points/2: reaches");
  // No supports: the block falls out of its grid; the run stops with "left the grid" (exit 3), the output valid.
  m = mpm_body("block", 0.3, 0.5);
  m["boundary_conditions"] = json::array();
  json j = case_of({m});
  j["analysis"]["end_time"] = 0.6;
  const Finished r = run("mpm_falls_out", j);
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("left the grid"), std::string::npos) << r.err;
  const auto s = json::parse(std::ifstream(fs::path(LAGFSI_BINARY_DIR) / "test_output" / "case_checks_mpm_falls_out" /
                                           "out" / "summary.json"));
  EXPECT_EQ(s["status"], "failed");
  EXPECT_LT(s["time"].get<double>(), 0.6);
}

TEST(BadInputCase, IntegratorStability) {
  json j = case_of({plate_body(0, 0, 0.05, 0.3)});
  auto with = [&](json it) {
    json k = j;
    k["analysis"]["integrator"] = it;
    return k;
  };
  EXPECT_EQ(check("newmark_ok", with({{"type", "newmark"}, {"beta", 0.3025}, {"gamma", 0.6}})).code, 0);
  EXPECT_EQ(check("newmark_edge", with({{"type", "newmark"}, {"beta", 0.3}, {"gamma", 0.6}})).code, 0);
  // gamma > 2 beta: stable only below a critical step (it blew up).
  expect_input_error(check("newmark_conditional", with({{"type", "newmark"}, {"beta", 0.25}, {"gamma", 0.6}})),
                     "/analysis/integrator/beta: beta = 0.25 < gamma / 2 = 0.3: conditionally stable");
  expect_input_error(check("newmark_fox_goodwin", with({{"type", "newmark"}, {"beta", 1.0 / 12}, {"gamma", 0.5}})),
                     "allow_conditionally_stable");
  expect_input_error(check("newmark_gamma", with({{"type", "newmark"}, {"beta", 0.25}, {"gamma", 0.4}})),
                     "/analysis/integrator/gamma: must be at least 1/2");
  expect_input_error(check("alpha_rho", with({{"type", "generalized_alpha"}, {"rho_inf", 1.2}})),
                     "/analysis/integrator/rho_inf: must lie in [0, 1]");
  // Chosen on purpose: a warning on stderr and in summary.json.
  const Finished r =
      run("newmark_allowed",
          with({{"type", "newmark"}, {"beta", 1.0 / 12}, {"gamma", 0.5}, {"allow_conditionally_stable", true}}),
          {"--progress", "none"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("lagfsi: warning: /analysis/integrator: beta = 0.08333 < gamma / 2 = 0.25"), std::string::npos)
      << r.err;
  const auto s = json::parse(std::ifstream(fs::path(LAGFSI_BINARY_DIR) / "test_output" / "case_checks_newmark_allowed" /
                                           "out" / "summary.json"));
  ASSERT_EQ(s["warnings"].size(), 1u) << s.dump();
  EXPECT_NE(s["warnings"][0].get<std::string>().find("conditionally stable"), std::string::npos);
}

TEST(CaseDefaults, FluidDefaultsFollowTheSchemeAndTheDetection) {
  // `check` prints the case with every default filled in. With the monolithic scheme and remeshing the defaults
  // are the conservative ones (docs/decisions/0001-0006); the fractional step, a fixed mesh and a chosen "alpha" keep
  // the classic PFEM's (src/fluid/fluid_input.cpp). Walls as constraints with a Robin free surface, or with an
  // inflow or outflow, make generalized-alpha the analysis' default integrator (fluid_preferred_integrator); any
  // other case, wall particles with a Robin surface included, gets Newmark. An inflow or outflow takes p = 0 on the
  // free surface and the surface correction (the source correction with the fractional step).
  struct Expected {
    std::string detection, wall_model, wall_friction, free_surface_pressure, volume_correction;
    double contact_gap, relaxation_time;
    bool open = false;  // an inflow or outflow
  };
  auto resolved = [](const std::string& tag, const json& body, const Expected& e) {
    const Finished r = check(tag, case_of({body}));
    ASSERT_EQ(r.code, 0) << tag << ": " << r.err;
    const size_t start = r.out.find('{');
    ASSERT_NE(start, std::string::npos) << r.out;
    const json root = json::parse(r.out.substr(start));
    const bool generalized_alpha = (e.free_surface_pressure == "robin" || e.open) && e.wall_model == "constraints";
    EXPECT_EQ(root["analysis"]["integrator"]["type"], generalized_alpha ? "generalized_alpha" : "newmark") << tag;
    if (generalized_alpha) {
      EXPECT_EQ(root["analysis"]["integrator"]["rho_inf"].get<double>(), 0.8) << tag;
    }
    const json b = root["bodies"][0];
    EXPECT_EQ(b["domain_detection"], e.detection) << tag;
    EXPECT_EQ(b["wall_model"], e.wall_model) << tag;
    EXPECT_EQ(b["wall_friction"], e.wall_friction) << tag;
    EXPECT_EQ(b["contact_gap"].get<double>(), e.contact_gap) << tag;
    EXPECT_EQ(b["scheme"]["volume_correction"], e.volume_correction) << tag;
    EXPECT_EQ(b["scheme"]["volume_relaxation_time"].get<double>(), e.relaxation_time) << tag;
    if (e.free_surface_pressure.empty())
      EXPECT_FALSE(b["scheme"].contains("free_surface_pressure")) << tag;
    else
      EXPECT_EQ(b["scheme"]["free_surface_pressure"], e.free_surface_pressure) << tag;
  };
  json mono = fluid_body();
  mono["scheme"] = json::object();
  resolved("defaults_monolithic", mono, {"advected", "constraints", "navier", "robin", "particle", 0.3, 0.01});
  resolved("defaults_fractional", fluid_body(), {"alpha", "particles", "held", "", "surface", 0.0, 0.1});
  json alpha = mono;
  alpha["domain_detection"] = "alpha";
  resolved("defaults_alpha", alpha, {"alpha", "particles", "held", "dirichlet", "surface", 0.0, 0.1});
  json fixed = mono;
  fixed["remesh"] = false;
  resolved("defaults_fixed_mesh", fixed, {"alpha", "particles", "held", "dirichlet", "surface", 0.0, 0.1});
  json particles = mono;
  particles["wall_model"] = "particles";
  resolved("defaults_wall_particles", particles, {"advected", "particles", "held", "robin", "particle", 0.3, 0.01});
  json level_set = mono;
  level_set["domain_detection"] = "level_set";
  level_set["scheme"]["volume_correction"] = "none";
  resolved("defaults_level_set", level_set, {"level_set", "constraints", "navier", "robin", "none", 0.0, 0.1});
  json dirichlet = mono;
  dirichlet["scheme"]["free_surface_pressure"] = "dirichlet";
  resolved("defaults_dirichlet", dirichlet, {"advected", "constraints", "navier", "dirichlet", "particle", 0.3, 0.01});
  json open = mono;
  open["walls"] = json::parse(R"([{"name": "floor", "points": [[0, 0], [1.0, 0]]}])");
  open["boundaries"] = json::parse(R"([{"type": "inflow", "name": "inlet", "segment": [[0, 0], [0, 0.2]],
                                        "velocity": [0.1, 0]},
                                       {"type": "outflow", "name": "outlet", "segment": [[1.0, 0], [1.0, 0.3]]}])");
  resolved("defaults_open", open, {"advected", "constraints", "navier", "dirichlet", "surface", 0.3, 0.1, true});
  open["wall_model"] = "particles";
  resolved("defaults_open_wall_particles", open,
           {"advected", "particles", "held", "dirichlet", "surface", 0.3, 0.1, true});
  // The fractional step with the advected domain and open boundaries takes the source correction, but not behind an
  // inflow that holds a layer (its jitter would kick the confined water).
  json open_fractional = open;
  open_fractional["scheme"] = {{"type", "fractional_step"}};
  open_fractional["domain_detection"] = "advected";
  resolved("defaults_open_fractional", open_fractional,
           {"advected", "particles", "held", "", "source", 0.3, 0.1, true});
  open_fractional["boundaries"][0]["hold"] = "layer";
  resolved("defaults_open_fractional_layer", open_fractional,
           {"advected", "particles", "held", "", "none", 0.3, 0.1, true});
  // An integrator the case names is kept.
  json c = case_of({mono});
  c["analysis"]["integrator"] = {{"type", "newmark"}};
  const Finished r = check("defaults_named_integrator", c);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(json::parse(r.out.substr(r.out.find('{')))["analysis"]["integrator"]["type"], "newmark");
}

}  // namespace
