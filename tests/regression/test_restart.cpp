// Interrupt and resume: a run with "output": {"checkpoint": ...} stopped part way
// (--stop-after-step, or Ctrl-C) and continued with `lagfsi run CASE --restart OUTDIR` ends with the probes.csv of
// the run that was not stopped, to the last digit (one thread), for a solid, a remeshed PFEM fluid (with wall
// particles, and with the walls as constraints), an FSI case
// with a quasi-Newton coupling that keeps its Jacobian between steps, an MPM body with plastic history, DEM
// bodies (a blast on a bed with tangential springs; a moving wall after a settling stage), and EFG bodies past
// their limit point (damage history, path-following memory);
// log.csv's rows (but for the wall times) and the ParaView series are the same too. A restart of another case,
// or without a checkpoint, is refused in one line and leaves the earlier run's files as they are.
#include <gtest/gtest.h>

#include <csignal>

#include <nlohmann/json.hpp>

#include "case_runner.hpp"
#include "process.hpp"
#include "strip_case.hpp"

namespace {

using namespace lagfsi::testing;
using nlohmann::json;

std::string case_path(const std::string& rel) { return (fs::path(LAGFSI_SOURCE_DIR) / rel).string(); }

std::vector<std::string> with_sets(std::vector<std::string> args, const std::vector<std::string>& sets) {
  for (const auto& s : sets) {
    args.push_back("--set");
    args.push_back(s);
  }
  return args;
}

/// log.csv without the wall-time columns (t_remesh .. t_step: those whose header starts with "t_").
std::string log_without_times(const fs::path& f) {
  std::istringstream in(file_text(f));
  std::string line, out;
  std::vector<bool> timed;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) cells.push_back(cell);
    if (timed.empty())
      for (const auto& c : cells) timed.push_back(c.rfind("t_", 0) == 0);
    for (size_t i = 0; i < cells.size(); ++i)
      if (i >= timed.size() || !timed[i]) out += cells[i] + ",";
    out += "\n";
  }
  return out;
}

json summary_in(const fs::path& out) { return json::parse(file_text(out / "summary.json")); }

/// Runs `case_rel` with `sets` to the end, then again stopped after step `stop` (checkpoints every
/// `every` steps) and restarted; the two probes.csv, log.csv and .pvd files must be the same.
void expect_restart_is_seamless(const std::string& tag, const std::string& case_rel, std::vector<std::string> sets,
                                int every, int stop, const std::vector<std::string>& series) {
  const fs::path dir = fresh_dir("restart_" + tag);
  const fs::path full = dir / "full", part = dir / "part";
  sets.push_back("output.checkpoint.every_steps=" + std::to_string(every));
  const std::vector<std::string> base{"run", case_path(case_rel), "--quiet", "--threads", "1"};
  auto args = [&](std::vector<std::string> extra) {
    std::vector<std::string> a = base;
    a.insert(a.end(), extra.begin(), extra.end());
    return with_sets(a, sets);
  };
  Finished r = run_args(args({"-o", full.string()}), dir);
  ASSERT_EQ(r.code, 0) << r.err;
  r = run_args(args({"-o", part.string(), "--stop-after-step", std::to_string(stop)}), dir);
  ASSERT_EQ(r.code, 0) << r.err;
  json s = summary_in(part);
  EXPECT_EQ(s["status"], "stopped");
  EXPECT_EQ(s["steps"], stop);
  EXPECT_EQ(s["checkpoint"]["step"], stop);
  EXPECT_TRUE(fs::exists(part / "checkpoint.bin"));
  EXPECT_TRUE(fs::exists(part / "checkpoint.prev.bin"));  // keep: 2 (the default)
  EXPECT_FALSE(fs::exists(part / ".lagfsi.lock"));
  // The stopped run wrote its last state into the series (stop is not a multiple of output.every).
  r = run_args(args({"--restart", part.string()}), dir);
  ASSERT_EQ(r.code, 0) << r.err;
  s = summary_in(part);
  EXPECT_EQ(s["status"], "completed");
  EXPECT_EQ(s["restarted_from_step"], stop);
  EXPECT_EQ(s["steps"], summary_in(full)["steps"]);
  EXPECT_EQ(s["newton_iterations"]["total"], summary_in(full)["newton_iterations"]["total"]);
  const std::string p_full = file_text(full / "probes.csv"), p_part = file_text(part / "probes.csv");
  EXPECT_GT(count_lines(p_full), stop + 2);
  EXPECT_EQ(p_part, p_full) << "probes.csv of the restarted run differs from the uninterrupted one's";
  EXPECT_EQ(log_without_times(part / "log.csv"), log_without_times(full / "log.csv"));
  for (const auto& name : series)
    EXPECT_EQ(file_text(part / (name + ".pvd")), file_text(full / (name + ".pvd"))) << name << ".pvd";
  EXPECT_FALSE(fs::exists(part / ".lagfsi.lock"));
}

TEST(Restart, SolidContinuesBitForBit) {
  // The cantilever under a step load (Newmark), 40 steps; stopped after 25, checkpoints every 10.
  expect_restart_is_seamless("solid", "cases/cantilever_step_load/case.json", {"analysis.end_time=0.005"}, 10, 25,
                             {"beam"});
}

TEST(Restart, RemeshedFluidContinuesBitForBit) {
  // The dam break in a tank (PFEM, remeshed every step, monolithic PSPG): 40 steps, stopped after 23.
  expect_restart_is_seamless("fluid", "cases/dam_break_tank/case.json", {"analysis.end_time=0.04", "output.every=4"},
                             10, 23, {"water", "water_walls"});
}

TEST(Restart, FluidWithWallConstraintsContinuesBitForBit) {
  // The shaken tank (advected domain, moving slip walls as constraints on the particles on them, found again
  // at every step): 20 steps, stopped after 11.
  expect_restart_is_seamless("fluid_constraints", "cases/sloshing_forced/case.json",
                             {"analysis.end_time=0.05", "output.every=4"}, 5, 11, {"water", "water_walls"});
}

TEST(Restart, FluidWithParticleVolumesContinuesBitForBit) {
  // The dam break with particle volumes (advected domain, walls as constraints, Robin free surface): the owed
  // areas and the step's starting shares are in the checkpoint; 40 steps, stopped after 23.
  expect_restart_is_seamless("fluid_particle_volumes", "cases/dam_break_tank/case.json",
                             {"analysis.end_time=0.04", "output.every=4", "bodies.0.domain_detection=advected",
                              "bodies.0.wall_model=constraints", "bodies.0.scheme.free_surface_pressure=robin",
                              "bodies.0.scheme.volume_correction=particle"},
                             10, 23, {"water", "water_walls"});
}

TEST(Restart, FsiContinuesBitForBit) {
  // The flexible tank wall (Dirichlet-Neumann with IQN-IMVJ, whose Jacobian carries over from step to step):
  // 20 coupled steps, stopped after 11.
  expect_restart_is_seamless("fsi", "cases/flexible_tank/case.json", {"analysis.end_time=0.02", "output.every=5"}, 5,
                             11, {"water", "water_walls", "plate"});
}

TEST(Restart, MpmContinuesBitForBit) {
  // The granular column collapse (Mohr-Coulomb: plastic multipliers, stresses; explicit sub-steps) on a
  // coarser grid: 20 steps, stopped after 11.
  expect_restart_is_seamless("mpm", "cases/mpm_granular_collapse/case.json",
                             {"analysis.end_time=0.1", "bodies.0.grid.cell=0.005", "output.every=4"}, 5, 11, {"bars"});
}

TEST(Restart, EfgLPanelPastTheLimitPointContinuesBitForBit) {
  // The L-panel (smeared crack, tangent operator, generalized displacement control) on the CI's coarse
  // discretisation: 60 steps, the limit point at step 31; stopped after 37, on the descending branch, so that the
  // restart reads the control's sign and previous tangent response and the cracks' history.
  expect_restart_is_seamless("efg_L_panel", "cases/efg_L_panel/case.json",
                             {"bodies.0.domain.divisions=[10,10]", "bodies.0.efg.gauss=3", "analysis.load_steps=60",
                              "bodies.0.control.increment=0.05", "output.every=7"},
                             10, 37, {"panel", "panel_gauss"});
}

TEST(Restart, EfgDefectBeamThroughTheSnapBackContinuesBitForBit) {
  // The beam with a weakened zone (exponential damage, secant operator, generalized displacement control): the
  // first 64 steps of the case, the limit point at step 58, stopped after 60; the restart passes the snap-back
  // (step 62, where the damage reaches 1).
  expect_restart_is_seamless("efg_defect_beam", "cases/efg_defect_beam/case.json",
                             {"analysis.load_steps=64", "output.every=8"}, 20, 60, {"beam", "beam_gauss"});
}

TEST(Restart, DemRestartBlastBedWithFrictionContinuesBitForBit) {
  // cases/dem_blast_crater on a 0.3 m x 0.1 m bed of 4 mm discs in a box, with a linear law whose Coulomb
  // tangential springs keep a history, rolling resistance, the 1 kg charge 0.5 m above the bed with the shadowing
  // recomputed every 3 sub-steps (so the exposure of the last update carries over), energy probes (the
  // dissipated and blast-work sums, the balance), the KE peaks near the axis, the contacts and the largest force:
  // 200 steps of 10 sub-steps (2 ms; the shock reaches the bed at 0.38 ms), lists rebuilt and discs reordered on
  // the way; stopped after 61 (within the blast's positive phase, after the KE peak 1 cm deep, and after 611 blast
  // calls: the restart's first sub-step uses the exposure of the update before the stop), checkpoints every 20.
  const json contact = {{"law", "linear"},         {"kn", 2.75e6},    {"damping_ratio", 0.05},
                        {"friction", 0.3},         {"kt_ratio", 0.5}, {"tangential_damping_ratio", 0.05},
                        {"rolling_friction", 0.05}};
  const json discs = json::array({{{"type", "hex_lattice"},
                                   {"region", {{"type", "rectangle"}, {"origin", {0.0, 0.0}}, {"size", {0.3, 0.1}}}},
                                   {"radius", 0.002}}});
  const json walls = json::array({{{"name", "box"}, {"points", {{0.0, 0.2}, {0.0, 0.0}, {0.3, 0.0}, {0.3, 0.2}}}}});
  json probes = json::array();
  for (double d : {0.01, 0.03})
    probes.push_back({{"name", "ke_" + std::to_string(int(1000 * d))},
                      {"type", "ke_near"},
                      {"body", "bed"},
                      {"at", {0.15, 0.0996 - d}},
                      {"count", 6}});
  for (const char* k : {"kinetic", "elastic", "dissipated", "blast_work", "balance"})
    probes.push_back({{"name", std::string("e_") + k}, {"type", "energy"}, {"body", "bed"}, {"kind", k}});
  probes.push_back({{"name", "contacts"}, {"type", "contacts"}, {"body", "bed"}});
  probes.push_back({{"name", "fmax"}, {"type", "max_contact_force"}, {"body", "bed"}});
  probes.push_back({{"name", "omega"}, {"type", "disc"}, {"body", "bed"}, {"id", 1900}, {"quantity", "omega"}});
  expect_restart_is_seamless(
      "dem_blast", "cases/dem_blast_crater/case.json",
      {"analysis.end_time=0.002", "bodies.0.time_step.dt=1e-6", "bodies.0.contact=" + contact.dump(),
       "bodies.0.discs=" + discs.dump(), "bodies.0.walls=" + walls.dump(), "bodies.0.blast.position=[0.15,0.5996]",
       "bodies.0.blast.exposure_every=3", "probes=" + probes.dump(), "output.every=40"},
      20, 61, {"bed", "bed_walls"});
}

TEST(Restart, DemRestartMovingWallContinuesBitForBit) {
  // A random pack of discs (r 1-1.5 mm) settled under gravity behind a gate (the settling stage runs again at the
  // restart and removes the gate), then pushed along the floor by a piston that starts after a ramp, with
  // Coulomb friction and rolling resistance: 100 steps, stopped after 47, checkpoints every 10.
  const fs::path dir = fresh_dir("restart_dem_wall_case");
  write_text(dir / "case.json", R"({
    "name": "dem_piston",
    "analysis": {"type": "dynamic", "dt": 1e-3, "end_time": 0.1},
    "gravity": [0.0, -9.81],
    "bodies": [{
      "name": "pack", "type": "dem", "material": {"density": 2650},
      "contact": {"law": "linear", "kn": 2e5, "damping": "restitution", "restitution": 0.5, "friction": 0.5,
                  "tangential_damping_ratio": 0.2, "rolling_friction": 0.1},
      "discs": [{"type": "random", "region": {"type": "rectangle", "origin": [0.004, 0.0], "size": [0.046, 0.05]},
                 "radius": [0.001, 0.0015], "fraction": 0.5, "seed": 3}],
      "walls": [{"name": "box", "points": [[0.0, 0.1], [0.0, 0.0], [0.12, 0.0], [0.12, 0.1]]},
                {"name": "gate", "points": [[0.05, 0.0], [0.05, 0.1]]},
                {"name": "piston", "points": [[0.002, 0.0012], [0.002, 0.08]], "velocity": [0.25, 0.0],
                 "function": {"type": "ramp", "t0": 0.0, "t1": 0.02}}],
      "settle": {"time": 0.03, "remove_walls": ["gate"]},
      "neighbour": {"skin": 0.001}
    }],
    "probes": [
      {"name": "runout", "type": "front", "body": "pack", "skip": 2},
      {"name": "height", "type": "height", "body": "pack", "x": 0.01},
      {"name": "x7", "type": "disc", "body": "pack", "id": 7, "quantity": "x"},
      {"name": "theta7", "type": "disc", "body": "pack", "id": 7, "quantity": "theta"},
      {"name": "kinetic", "type": "energy", "body": "pack", "kind": "kinetic"},
      {"name": "dissipated", "type": "energy", "body": "pack", "kind": "dissipated"},
      {"name": "balance", "type": "energy", "body": "pack", "kind": "balance"},
      {"name": "contacts", "type": "contacts", "body": "pack"},
      {"name": "fmax", "type": "max_contact_force", "body": "pack"}
    ],
    "output": {"every": 20}
  })");
  expect_restart_is_seamless("dem_wall", (dir / "case.json").string(), {}, 10, 47, {"pack", "pack_walls"});
}

/// The shared strip (tests/support/strip_case.hpp) with quadratic elements and checkpoints, `steps` steps of 1 ms.
json strip_case(long steps) {
  return lagfsi::testing::strip_case("restart_strip", steps, 2,
                                     {{"every", 7}, {"checkpoint", {{"every_steps", 1000}}}});
}

TEST(Restart, AfterCtrlC) {
  // Ctrl-C wherever it lands: the interrupted run writes a checkpoint of its last step, and the restart ends
  // with the probes of the run that was not interrupted.
  const fs::path dir = fresh_dir("restart_sigint");
  const long steps = 600;
  write_text(dir / "case.json", strip_case(steps).dump(2));
  const std::string c = (dir / "case.json").string();
  Finished r = run_args({"run", c, "-o", (dir / "full").string(), "--quiet", "--threads", "1"}, dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const fs::path out = dir / "part";
  const Spawned s = spawn_lagfsi({"run", c, "-o", out.string(), "--threads", "1", "--progress", "none"},
                                 dir / "stdout.txt", dir / "stderr.txt");
  // Waiting for the run to be under way (not a timing assertion: only how long to wait at most).
  for (int i = 0; i < 6000; ++i) {
    if (fs::exists(out / "log.csv") && count_lines(file_text(out / "log.csv")) > 20) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ::kill(s.pid, SIGINT);
  ASSERT_EQ(wait_exit(s), 130) << file_text(dir / "stderr.txt");
  const json stopped = summary_in(out);
  EXPECT_EQ(stopped["status"], "interrupted");
  const long at = stopped["steps"].get<long>();
  ASSERT_LT(at, steps);
  EXPECT_EQ(stopped["checkpoint"]["step"], at);
  EXPECT_NE(file_text(dir / "stderr.txt").find("continue it with --restart " + out.string()), std::string::npos)
      << file_text(dir / "stderr.txt");
  EXPECT_FALSE(fs::exists(out / ".lagfsi.lock"));
  r = run_args({"run", c, "--restart", out.string(), "--quiet", "--threads", "1"}, dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(file_text(out / "probes.csv"), file_text(dir / "full" / "probes.csv"));
  EXPECT_EQ(file_text(out / "strip.pvd"), file_text(dir / "full" / "strip.pvd"));
}

TEST(Restart, RefusedInOneLine) {
  const fs::path dir = fresh_dir("restart_refused");
  write_text(dir / "case.json", strip_case(30).dump(2));
  const std::string c = (dir / "case.json").string(), out = (dir / "out").string();
  // No run yet: no folder.
  Finished r = run_args({"run", c, "--restart", out, "--quiet"}, dir);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("is not a folder of an earlier run"), std::string::npos) << r.err;
  // A run without checkpoints: nothing to continue from.
  json plain = strip_case(30);
  plain["output"].erase("checkpoint");
  write_text(dir / "plain.json", plain.dump(2));
  r = run_args({"run", (dir / "plain.json").string(), "-o", out, "--quiet", "--stop-after-step", "10"}, dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(summary_in(dir / "out")["status"], "stopped");
  r = run_args({"run", (dir / "plain.json").string(), "--restart", out, "--quiet"}, dir);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("--restart: no checkpoint in"), std::string::npos) << r.err;
  // Another case (a changed value) than the checkpoint's: refused, the files stay as they were.
  r = run_args({"run", c, "-o", out, "--quiet", "--stop-after-step", "10"}, dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string probes = file_text(dir / "out" / "probes.csv"), summary = file_text(dir / "out" / "summary.json");
  r = run_args({"run", c, "--restart", out, "--quiet", "--set", "bodies.0.material.young=2e6"}, dir);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("the case differs from the checkpointed one"), std::string::npos) << r.err;
  EXPECT_EQ(file_text(dir / "out" / "probes.csv"), probes);
  EXPECT_EQ(file_text(dir / "out" / "summary.json"), summary);
  EXPECT_FALSE(fs::exists(dir / "out" / ".lagfsi.lock"));
  // Another checkpoint interval is the same case.
  r = run_args({"run", c, "--restart", out, "--quiet", "--set", "output.checkpoint.every_steps=5"}, dir);
  EXPECT_EQ(r.code, 0) << r.err;
  // A damaged checkpoint.bin: the one before (checkpoint.prev.bin) is used.
  r = run_args({"run", c, "-o", out, "--quiet", "--stop-after-step", "12", "--set", "output.checkpoint.every_steps=5"},
               dir);
  ASSERT_EQ(r.code, 0) << r.err;
  {
    std::string bytes = file_text(dir / "out" / "checkpoint.bin");
    bytes[bytes.size() / 2] ^= 0x55;
    write_text(dir / "out" / "checkpoint.bin", bytes);
  }
  r = run_args({"run", c, "--restart", out, "--quiet", "--set", "output.checkpoint.every_steps=5"}, dir);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(summary_in(dir / "out")["restarted_from_step"], 10);
  EXPECT_EQ(summary_in(dir / "out")["status"], "completed");
  // -o and --restart naming two folders; --restart for check.
  r = run_args({"run", c, "-o", (dir / "other").string(), "--restart", out}, dir);
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  r = run_args({"check", c, "--restart", out}, dir);
  EXPECT_EQ(r.code, 1) << r.err;
}

TEST(Restart, ABadCheckpointObjectNamesItsKey) {
  const fs::path dir = fresh_dir("restart_bad_key");
  json j = json::parse(file_text(case_path("cases/efg_tension_plate/case.json")), nullptr, true, true);
  j["output"]["checkpoint"] = {{"every_step", 10}};
  write_text(dir / "case.json", j.dump(2));
  Finished r = run_args({"check", (dir / "case.json").string()}, dir);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(r.err.find("lagfsi: error"), r.err.rfind("lagfsi: error")) << r.err;
  EXPECT_NE(r.err.find("/output/checkpoint/every_step"), std::string::npos) << r.err;
}

}  // namespace
