#include "analysis_settings.hpp"
#include "checkpoint.hpp"
#include "input_checks.hpp"
#include "interrupt.hpp"
#include "output_lock.hpp"
#include "progress.hpp"

#include <lagfsi/analysis.hpp>
#include <lagfsi/case.hpp>
#include <lagfsi/error.hpp>
#include <lagfsi/fsi/dirichlet_neumann.hpp>
#include <lagfsi/linear_solver.hpp>
#include <lagfsi/model_registry.hpp>
#include <lagfsi/output_file.hpp>
#include <lagfsi/text.hpp>
#include <lagfsi/time_integrator.hpp>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <new>
#include <sstream>

#ifdef LAGFSI_HAVE_OPENMP
#include <omp.h>
#endif

namespace lagfsi {

namespace fs = std::filesystem;

const Json& case_defaults() {
  static const Json d = {
      {"name", ""},
      {"description", ""},
      {"analysis", nullptr},
      {"gravity", Json::array({0.0, 0.0})},
      {"bodies", nullptr},
      {"couplings", Json::array()},
      {"probes", Json::array()},
      {"output", Json::object()},
  };
  return d;
}

const std::map<std::string, ModelBuilder>& model_registry() {
  static const std::map<std::string, ModelBuilder> r = {
      {"solid", make_solid_model}, {"shell", make_solid_model}, {"fluid", make_fluid_model},
      {"mpm", make_mpm_model},     {"dem", make_dem_model},     {"efg", make_efg_model},
  };
  return r;
}

namespace {

/// Registry of coupling types (fsi/): the "type" string of an entry of "couplings" to its builder, which
/// gets the two bodies it couples.
using CouplingBuilder = std::function<std::unique_ptr<PhysicsModel>(Params, const CaseContext&, PhysicsModel& fluid,
                                                                    PhysicsModel& structure)>;
const std::map<std::string, CouplingBuilder>& coupling_registry() {
  static const std::map<std::string, CouplingBuilder> r = {{"dirichlet_neumann", fsi::make_dirichlet_neumann}};
  return r;
}

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// Everything built from the case file.
struct Case {
  Params root;
  CaseContext ctx;
  std::string name;
  std::vector<std::unique_ptr<PhysicsModel>> models;     ///< the bodies (output, probes, sizes, timing)
  std::vector<std::unique_ptr<PhysicsModel>> couplings;  ///< each steps the bodies it couples
  std::vector<PhysicsModel*> steppers;                   ///< what the driver steps: uncoupled bodies, couplings
  std::vector<std::unique_ptr<Probe>> probes;
  int output_every = 1;
  bool vtk = true;
  CheckpointSettings checkpoint;
  std::vector<std::string>
      warnings;  ///< chosen on purpose (a conditionally stable integrator): stderr and summary.json
};

Case build_case(const RunOptions& opt, bool for_check) {
  Case c;
  c.root = Params::load(opt.case_file);
  for (const auto& o : opt.overrides) apply_override(c.root.json(), o);
  c.root.validate(case_defaults());
  c.name = c.root.string("name").empty() ? opt.case_file.stem().string() : c.root.identifier("name");
  c.ctx.case_file = opt.case_file;
  c.ctx.quiet = opt.quiet;
  c.ctx.base_dir = opt.case_file.parent_path();
  c.ctx.out_dir = opt.out_dir.empty() ? fs::path("out") / c.name : opt.out_dir;
  c.ctx.analysis = read_analysis(c.root.at("analysis"), c.warnings, c.root.json().at("bodies"));
  c.ctx.gravity = c.root.vec2("gravity");
  Params out = c.root.at("output");
  out.validate({{"every", 1}, {"vtk", true}, {"checkpoint", Json::object()}});
  c.output_every = out.integer("every", 1);
  c.vtk = out.boolean("vtk");
  c.checkpoint = read_checkpoint_settings(out.at("checkpoint"));
  (void)for_check;

  Params bodies = c.root.at("bodies");
  if (bodies.size() == 0) bodies.fail("at least one body is needed");
  std::vector<std::string> types;
  for (const auto& [k, v] : model_registry()) types.push_back(k);
  for (size_t i = 0; i < bodies.size(); ++i) {
    Params b = bodies.at(i);
    if (!b.json().is_object()) b.fail("expected an object");
    if (!b.has("type")) b.fail("type", "required key is missing");
    const std::string type = b.choice("type", types);
    c.models.push_back(model_registry().at(type)(b, c.ctx));
    for (size_t j = 0; j + 1 < c.models.size(); ++j)
      if (c.models[j]->name() == c.models.back()->name()) b.fail("name", "duplicate body name");
  }
  // Couplings: each takes two bodies out of the driver's hands.
  Params couplings = c.root.at("couplings");
  std::vector<std::string> coupling_types;
  for (const auto& [k, v] : coupling_registry()) coupling_types.push_back(k);
  std::vector<PhysicsModel*> coupled;
  auto body_named = [&](Params q, const std::string& key) -> PhysicsModel& {
    if (!q.has(key)) q.fail(key, "required key is missing");
    const std::string nm = q.string(key);
    for (auto& m : c.models)
      if (m->name() == nm) {
        if (std::find(coupled.begin(), coupled.end(), m.get()) != coupled.end())
          q.fail(key, "body '" + nm + "' is already coupled");
        coupled.push_back(m.get());
        return *m;
      }
    q.fail(key, "no body named '" + nm + "'");
  };
  for (size_t i = 0; i < couplings.size(); ++i) {
    Params q = couplings.at(i);
    if (!q.json().is_object()) q.fail("expected an object");
    if (!q.has("type")) q.fail("type", "required key is missing");
    const std::string type = q.choice("type", coupling_types);
    PhysicsModel& fluid = body_named(q, "fluid");
    PhysicsModel& structure = body_named(q, "structure");
    c.couplings.push_back(coupling_registry().at(type)(q, c.ctx, fluid, structure));
    for (const auto& m : c.models)
      if (m->name() == c.couplings.back()->name()) q.fail("name", "a body has the same name");
  }
  for (auto& m : c.models)
    if (std::find(coupled.begin(), coupled.end(), m.get()) == coupled.end()) c.steppers.push_back(m.get());
  if (c.checkpoint.active() || opt.restart) {
    std::vector<PhysicsModel*> all;
    for (const auto* list : {&c.models, &c.couplings})
      for (const auto& m : *list) all.push_back(m.get());
    check_checkpointable(all, out, opt.restart, opt.case_file);
  }
  for (auto& m : c.couplings) c.steppers.push_back(m.get());

  Params probes = c.root.at("probes");
  std::vector<std::string> names;
  for (size_t i = 0; i < probes.size(); ++i) {
    Params p = probes.at(i);
    if (!p.json().is_object()) p.fail("expected an object");
    if (!p.has("name")) p.fail("name", "required key is missing");
    if (!p.has("type")) p.fail("type", "required key is missing");
    if (!p.has("body")) p.fail("body", "required key is missing");
    (void)p.identifier("name");  // a column of probes.csv: no commas, quotes or line breaks
    const std::string body = p.string("body");
    PhysicsModel* m = nullptr;
    for (auto& mm : c.models)
      if (mm->name() == body) m = mm.get();
    for (auto& mm : c.couplings)
      if (mm->name() == body) m = mm.get();
    if (!m) p.fail("body", "no body named '" + body + "'");
    auto probe = m->make_probe(p);
    for (const auto& col : probe->columns()) {
      if (col == "time" || std::find(names.begin(), names.end(), col) != names.end())
        p.fail("name", "duplicate probe column '" + col + "'");
      names.push_back(col);
    }
    c.probes.push_back(std::move(probe));
  }
  // What no single body can see: output names shared by two bodies, bodies that overlap.
  check_output_names(c.root);
  check_overlaps(c.root);
  return c;
}

/// JSON text for a file: never throws (every string is UTF-8 since the input is checked; any other byte
/// would be replaced).
std::string json_text(const Json& j) { return j.dump(2, ' ', false, Json::error_handler_t::replace) + "\n"; }

}  // namespace

namespace {
/// Builds the case; on bad input prints the one-line error and returns null.
std::unique_ptr<Case> build_case_or_report(const RunOptions& opt, bool for_check) {
  try {
    return std::make_unique<Case>(build_case(opt, for_check));
  } catch (const InputError& e) {
    std::cerr << "lagfsi: error: " << e.what() << "\n";
  } catch (const std::bad_alloc&) {
    std::cerr << "lagfsi: error: " << opt.case_file.string()
              << ": out of memory while building the case (a mesh size, spacing or length far from the others?)\n";
  } catch (const std::exception& e) {
    std::cerr << "lagfsi: error: " << opt.case_file.string() << ": " << e.what() << "\n";
  }
  return nullptr;
}
}  // namespace

int check_case(const RunOptions& opt) {
  const auto c = build_case_or_report(opt, true);
  if (!c) return kInputError;
  for (const auto& w : c->warnings) std::cerr << "lagfsi: warning: " << w << "\n";
  std::cout << json_text(c->root.json()) << std::flush;
  if (!std::cout) {
    std::cerr << "lagfsi: error: stdout: cannot write (" << errno_reason(errno) << ")\n";
    return kOutputError;
  }
  return kOk;
}

int run_case(const RunOptions& opt) {
  const auto t_start = Clock::now();
#ifdef LAGFSI_HAVE_OPENMP
  if (opt.threads > 0) omp_set_num_threads(opt.threads);
  const int threads = omp_get_max_threads();
#else
  const int threads = 1;
#endif
  // From here on Ctrl-C ends the run at the next step (a second one stops at once); while the case is built
  // (meshes), as soon as it is.
  const InterruptGuard interrupt_guard;
  const std::unique_ptr<Case> cp = build_case_or_report(opt, false);
  if (!cp) return kInputError;
  if (const int sig = InterruptGuard::received()) {
    std::cerr << "lagfsi: interrupted by " << signal_name(sig) << " while the case was being built; nothing written\n";
    return 128 + sig;
  }
  Case& c = *cp;
  const fs::path out = c.ctx.out_dir;
  AppendFile probes_csv, log_csv;
  RunTotals tot;
  std::string status = "running", message;
  int code = kOk;
  double t = 0.0, last_output_t = -1.0;
  const AnalysisSettings& an = c.ctx.analysis;
  const long nsteps = std::lround(std::ceil(an.end_time / an.dt * (1 - 1e-9)));
  ProgressMode mode = ProgressMode::none;
  parse_progress_mode(opt.progress, opt.quiet, mode);
  Progress progress(mode, c.name, !opt.quiet);
  // Checkpoints: every model (bodies, then couplings) and probe, where the run is.
  std::vector<PhysicsModel*> all_models;
  for (const auto* list : {&c.models, &c.couplings})
    for (const auto& m : *list) all_models.push_back(m.get());
  std::vector<Probe*> all_probes;
  for (const auto& p : c.probes) all_probes.push_back(p.get());
  RunPosition pos;
  pos.case_hash = case_hash(c.root.json());
  long restarted_step = -1, checkpoint_step = -1;
  double checkpoint_wall = 0;

  auto write_summary = [&]() {
    Json s;
    s["case"] = c.name;
    s["case_file"] = opt.case_file.string();
    s["status"] = status;
    s["message"] = message;
    if (InterruptGuard::received()) s["signal"] = signal_name(InterruptGuard::received());
    s["warnings"] = c.warnings;
    s["analysis"] = an.type;
    s["steps"] = tot.steps;
    s["steps_planned"] = nsteps;
    s["step_retries"] = tot.retries;
    s["time"] = t;
    s["wall_time"] = tot.wall_before + since(t_start);
    if (restarted_step >= 0) s["restarted_from_step"] = restarted_step;
    if (checkpoint_step >= 0) s["checkpoint"] = {{"file", kCheckpointFile}, {"step", checkpoint_step}};
    s["newton_iterations"] = {{"total", tot.iterations},
                              {"mean", tot.steps ? double(tot.iterations) / tot.steps : 0.0},
                              {"max", tot.max_iterations}};
    int restarts = 0;
    for (const auto& m : c.couplings) restarts += m->coupling_restarts();
    if (!c.couplings.empty())
      s["coupling"] = {
          {"coupled_steps", tot.coupled_steps},
          {"restarts", restarts},
          {"iterations_total", tot.coupling_iterations},
          {"iterations_mean", tot.coupled_steps ? double(tot.coupling_iterations) / tot.coupled_steps : 0.0},
          {"iterations_max", tot.coupling_max},
          {"residual_max", tot.coupling_residual_max}};
    auto timing = [](const PhaseTimes& p) {
      return Json{{"remesh", p.remesh},
                  {"assembly", p.assembly},
                  {"factorization", p.factorization},
                  {"solve", p.solve},
                  {"output", p.output},
                  {"total", p.remesh + p.assembly + p.factorization + p.solve + p.output}};
    };
    s["timing"] = timing(tot.phases);
    Json bodies = Json::array();
    for (size_t i = 0; i < c.models.size(); ++i) {
      const auto& m = c.models[i];
      Json b{{"name", m->name()},
             {"type", m->type()},
             {"nodes", m->num_nodes()},
             {"elements", m->num_elements()},
             {"timing", timing(i < tot.body_phases.size() ? tot.body_phases[i] : PhaseTimes{})}};
      b.update(m->summary());
      bodies.push_back(std::move(b));
    }
    s["bodies"] = bodies;
    s["threads"] = threads;
    write_file_atomic(out / "summary.json", json_text(s));
  };

  // The output folder first: not the case file's own, not in use by another run; if it cannot be written,
  // say so once and write nothing else.
  OutputLock lock;
  try {
    check_output_folder(opt.case_file, out);
  } catch (const InputError& e) {
    std::cerr << "lagfsi: error: " << e.what() << "\n";
    return kInputError;
  }
  if (opt.restart && !fs::is_directory(out)) {
    std::cerr << "lagfsi: error: " << opt.case_file.string() << ": --restart: " << out.string()
              << " is not a folder of an earlier run\n";
    return kInputError;
  }
  try {
    fs::create_directories(out);
    if (!fs::is_directory(out)) throw std::runtime_error("it is not a folder");
  } catch (const std::exception& e) {
    const auto* fe = dynamic_cast<const fs::filesystem_error*>(&e);
    std::cerr << "lagfsi: error: " << opt.case_file.string() << ": cannot write the output folder " << out.string()
              << " (" << (fe ? fe->code().message() : std::string(e.what())) << ")\n";
    return kInputError;
  }
  if (const std::string why = lock.acquire(out); !why.empty()) {
    std::cerr << "lagfsi: error: " << opt.case_file.string() << ": the output folder " << out.string() << " is "
              << (why.rfind("in use", 0) == 0 ? why : "not usable: " + why) << "\n";
    return kInputError;
  }
  // A restart: the checkpoint must be of this case and the CSV files at least as long as it says; otherwise
  // one line, and the earlier run's files stay as they are.
  std::unique_ptr<StateArchive> restart;
  if (opt.restart) {
    try {
      restart = std::make_unique<StateArchive>(open_restart(out, pos, tot, opt.case_file));
    } catch (const InputError& e) {
      std::cerr << "lagfsi: error: " << e.what() << "\n";
      return kInputError;
    }
    if (pos.threads != threads && !opt.quiet)
      std::cerr << "lagfsi: warning: the checkpoint was written with " << pos.threads << " threads, this run has "
                << threads << ": the results may differ from an uninterrupted run in the last digits\n";
  }
  for (const auto& w : c.warnings)
    if (!opt.quiet) std::cerr << "lagfsi: warning: " << w << "\n";
  long step = 0;
  try {
    auto sample = [&]() {
      std::ostringstream row;
      row << std::setprecision(12) << t;
      for (const auto& p : c.probes)
        for (double v : p->sample()) row << "," << v;
      row << "\n";
      probes_csv.write(row.str());
    };
    auto output = [&]() {
      if (!c.vtk || t == last_output_t) return;
      last_output_t = t;
      for (auto& m : c.models) m->write_output(t);
    };
    auto checkpoint = [&]() {
      pos = RunPosition{pos.case_hash, step, t, last_output_t, probes_csv.size(), log_csv.size(), threads};
      RunTotals saved = tot;
      saved.wall_before += since(t_start);
      save_checkpoint(out, c.checkpoint.keep, pos, saved, all_models, all_probes, opt.case_file);
      checkpoint_step = step;
      checkpoint_wall = since(t_start);
    };

    for (auto& m : c.models) m->initialize();
    for (auto& m : c.couplings) m->initialize();
    if (restart) {
      // The state of the checkpoint over the initial one; the CSV files cut back to its step.
      try {
        serialize_run_models(*restart, all_models, all_probes);
      } catch (const CheckpointError& e) {
        throw InputError(opt.case_file.string(), "",
                         std::string("--restart: the checkpoint does not fit the case (") + e.what() + ")");
      }
      restart.reset();
      probes_csv.resume(out / "probes.csv", pos.probes_bytes);
      log_csv.resume(out / "log.csv", pos.log_bytes);
      step = restarted_step = checkpoint_step = pos.step;
      t = pos.t;
      last_output_t = pos.last_output_t;
    } else {
      // A new run: the checkpoints of an earlier one in the folder are not its own.
      for (const char* f : {kCheckpointFile, kCheckpointPrevFile}) fs::remove(out / f);
      write_file_atomic(out / "resolved_case.json", json_text(c.root.json()));
      probes_csv.open(out / "probes.csv");
      log_csv.open(out / "log.csv");
      std::string header = "time";
      for (const auto& p : c.probes)
        for (const auto& col : p->columns()) header += "," + col;
      probes_csv.write(header + "\n");
      log_csv.write(
          "step,time,dt,iterations,residual,nodes,elements,fluid_area_remeshed,fluid_area,remesh_dA,remesh_dKE,"
          "t_remesh,t_assembly,t_factorization,t_solve,t_output,t_step,fsi_iterations,fsi_residual\n");
      output();
      sample();
    }
    write_summary();

    const NewtonSettings& nw = an.newton;
    auto stop_requested = [&]() {
      return InterruptGuard::received() || (opt.stop_after_step > 0 && step >= opt.stop_after_step);
    };
    // Step loop. A step whose Newton iterations fail (divergence, an element inverted, a singular
    // matrix) is retried from the same state with half the time step, up to max_step_halvings times;
    // the next step goes back to the nominal dt. A remainder shorter than 1e-6 dt at the end is dropped.
    // A signal (SIGINT, SIGTERM) is looked at between steps: the step under way ends first.
    while (an.end_time - t > 1e-6 * an.dt && !stop_requested()) {
      ++step;
      const auto t_step = Clock::now();
      double dt = std::min(an.dt, an.end_time - t);
      if (an.end_time - (t + dt) < 1e-6 * an.dt) dt = an.end_time - t;
      int iters_step = 0;
      double last_res = 0.0;
      for (auto& m : c.couplings) m->times() = PhaseTimes{};
      for (auto& m : c.models) m->times() = PhaseTimes{};
      for (int halving = 0;; ++halving) {
        const double t_new = t + dt;
        try {
          for (PhysicsModel* m : c.steppers) {
            m->predict(t_new, dt);
            iters_step += iterate_to_convergence(*m, nw.max_iterations, t_new, &last_res);
          }
          break;
        } catch (const SolverError& e) {
          if (halving >= an.max_step_halvings) throw;
          char note[512];
          std::snprintf(note, sizeof note, "[%s] step at t=%.6g failed (%s); retrying with dt=%.3g", c.name.c_str(),
                        t_new, e.what(), dt / 2);
          progress.note(note);
          dt /= 2;
          ++tot.retries;
        }
      }
      const double t_new = t + dt;
      for (PhysicsModel* m : c.steppers) m->finalize_step();
      int fsi_iterations = 0;
      double fsi_residual = 0;
      for (auto& m : c.couplings) {
        fsi_iterations += m->coupling_iterations();
        fsi_residual = std::max(fsi_residual, m->coupling_residual());
      }
      if (fsi_iterations > 0) {
        ++tot.coupled_steps;
        tot.coupling_iterations += fsi_iterations;
        tot.coupling_max = std::max(tot.coupling_max, fsi_iterations);
        tot.coupling_residual_max = std::max(tot.coupling_residual_max, fsi_residual);
      }
      t = t_new;
      ++tot.steps;
      tot.iterations += iters_step;
      tot.max_iterations = std::max(tot.max_iterations, iters_step);
      sample();
      if (step % c.output_every == 0 || an.end_time - t <= 1e-6 * an.dt) output();
      PhaseTimes ph;
      Index nn = 0, ne = 0;
      long particles = 0;
      double area = 0, area_remeshed = 0, remesh_dA = 0, remesh_dKE = 0;
      tot.body_phases.resize(c.models.size());
      for (size_t i = 0; i < c.models.size(); ++i) tot.body_phases[i] += c.models[i]->times();
      for (auto& m : c.models) {
        ph += m->times();
        nn += m->num_nodes();
        ne += m->num_elements();
        if (m->type() == "fluid" || m->type() == "mpm") particles += m->num_nodes();
        area += m->fluid_area();
        area_remeshed += m->fluid_area_remeshed();
        remesh_dA += m->remesh_area_change();
        remesh_dKE += m->remesh_kinetic_energy_change();
      }
      tot.phases += ph;
      const double wall_step = since(t_step);
      std::ostringstream row;
      row << std::setprecision(10) << step << "," << t << "," << dt << "," << iters_step << "," << last_res << "," << nn
          << "," << ne << "," << area_remeshed << "," << area << "," << remesh_dA << "," << remesh_dKE << ","
          << ph.remesh << "," << ph.assembly << "," << ph.factorization << "," << ph.solve << "," << ph.output << ","
          << wall_step << "," << fsi_iterations << "," << fsi_residual << "\n";
      log_csv.write(row.str());
      StepStatus st;
      st.step = step;
      st.t = t;
      st.t_end = an.end_time;
      st.dt = dt;
      st.iterations = iters_step;
      st.fsi_passes = fsi_iterations;
      st.particles = particles;
      st.nodes = nn;
      st.wall = since(t_start);
      progress.step(st);
      const CheckpointSettings& ck = c.checkpoint;
      if ((ck.every_steps > 0 && step % ck.every_steps == 0) ||
          (ck.every_minutes > 0 && since(t_start) - checkpoint_wall >= 60 * ck.every_minutes))
        if (an.end_time - t > 1e-6 * an.dt) checkpoint();
      if (step % 50 == 0) write_summary();
    }
    if (an.end_time - t > 1e-6 * an.dt) {
      // Ended early (a signal, --stop-after-step): a checkpoint of this step, then its state into the series
      // (after the checkpoint, so that a restart continues the series as if the run had not stopped).
      if (c.checkpoint.active() && checkpoint_step != step) checkpoint();
      output();
    }
  } catch (const OutputError& e) {
    status = "failed";
    message = e.what();
    code = kOutputError;
  } catch (const SolverError& e) {
    status = "failed";
    message = e.what();
    code = kSolverError;
  } catch (const InputError& e) {
    status = "failed";
    message = e.what();
    code = kInputError;
  } catch (const std::bad_alloc&) {
    status = "failed";
    message = "out of memory at t = " + std::to_string(t);
    code = kSolverError;
  } catch (const std::exception& e) {
    status = "failed";
    message = e.what();
    code = kInternalError;
  }
  progress.finish();
  if (code != kOk) {
    std::cerr << "lagfsi: error: " << opt.case_file.string() << ": " << message << "\n";
    // Last output: the last converged state, so that the series ends where the run did (not after a failed
    // write: the disk that refused it would refuse this one too).
    try {
      if (c.vtk && t != last_output_t && code != kOutputError)
        for (auto& m : c.models) m->write_output(t);
    } catch (const std::exception&) {
    }
  }
  const int sig = InterruptGuard::received();
  const bool early = an.end_time - t > 1e-6 * an.dt;
  if (code == kOk && sig != 0 && early) {
    status = "interrupted";
    message = std::string("interrupted by ") + signal_name(sig) + " after step " + std::to_string(step) +
              " at t = " + std::to_string(t);
    code = 128 + sig;
  } else if (code == kOk && early) {
    status = "stopped";
    message = "stopped after step " + std::to_string(step) + " at t = " + std::to_string(t) + " (--stop-after-step)";
  }
  if (code == kOk && !early) status = "completed";
  try {
    write_summary();
  } catch (const std::exception& e) {
    // After a failure its message has been printed: one line per run.
    if (code == kOk || code > 128) {
      std::cerr << "lagfsi: error: " << opt.case_file.string() << ": " << e.what() << "\n";
      code = dynamic_cast<const OutputError*>(&e) ? kOutputError : kInternalError;
    }
  }
  if (code == kOk || code > 128) {
    TimeTable table;
    table.phases = tot.phases;
    table.wall = tot.wall_before + since(t_start);
    table.steps = tot.steps;
    table.retries = tot.retries;
    table.iterations = tot.iterations;
    table.fsi_passes = tot.coupling_iterations;
    progress.table(table);
  }
  const std::string resume = checkpoint_step >= 0 && early ? "; continue it with --restart " + out.string() : "";
  if (code > 128 || (code == kOk && early)) {
    if (!opt.quiet || code > 128)
      std::cerr << "lagfsi: " << message << "; output written to " << out.string() << resume << "\n";
  } else if (code == kOk) {
    if (!opt.quiet)
      std::fprintf(stderr, "[%s] done: %d steps, %ld Newton iterations, %.2f s -> %s\n", c.name.c_str(), tot.steps,
                   tot.iterations, since(t_start), out.string().c_str());
  }
  return code;
}

}  // namespace lagfsi
