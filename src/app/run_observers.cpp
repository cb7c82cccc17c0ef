#include "run_observers.hpp"

#include "interrupt.hpp"

#include <lagfsi/mpi_run.hpp>
#include <lagfsi/stopwatch.hpp>

#include <iomanip>
#include <sstream>

namespace lagfsi {

namespace fs = std::filesystem;

std::string json_text(const Json& j) { return j.dump(2, ' ', false, Json::error_handler_t::replace) + "\n"; }

void ProbesCsv::started(const Simulation& s) {
  csv_.open(file_);
  std::string header = "time";
  for (const Probe* p : probes_)
    for (const auto& col : p->columns()) header += "," + col;
  csv_.write(header + "\n");
  sample(s.time());
}

void ProbesCsv::sample(double t) {
  std::ostringstream row;
  row << std::setprecision(12) << t;
  for (const Probe* p : probes_)
    for (double v : p->sample()) row << "," << v;
  row << "\n";
  csv_.write(row.str());
}

void RunLog::started(const Simulation& s) {
  csv_.open(file_);
  std::string header = "step,time,dt,iterations,residual,nodes,elements";
  if (s.analysis().time_step.adaptive) header += ",dt_limit,dt_by";
  for (const Metric& m : s.metric_columns()) header += "," + m.name;
  header += ",t_remesh,t_assembly,t_factorization,t_solve,t_output,t_step";
  if (mpi_run::size() > 1) header += ",t_comm,comm_MB,t_halo,petsc_MB";
  csv_.write(header + "\n");
  traffic_ = mpi_run::traffic();
}

void RunLog::stepped(const Simulation& s, const StepRecord& r) {
  std::ostringstream row;
  row << std::setprecision(10) << r.step << "," << r.t << "," << r.dt << "," << r.iterations << "," << r.residual << ","
      << r.nodes << "," << r.elements;
  if (s.analysis().time_step.adaptive) row << "," << r.dt_limit << "," << r.dt_by;
  for (double v : r.metrics) row << "," << v;
  const PhaseTimes& ph = r.phases;
  row << "," << ph.remesh << "," << ph.assembly << "," << ph.factorization << "," << ph.solve << "," << ph.output << ","
      << r.wall;
  if (mpi_run::size() > 1) {
    const mpi_run::Traffic now = mpi_run::traffic();
    row << "," << now.seconds - traffic_.seconds << "," << (now.bytes - traffic_.bytes) / 1e6 << ","
        << now.halo_seconds - traffic_.halo_seconds << "," << (now.petsc_bytes - traffic_.petsc_bytes) / 1e6;
    traffic_ = now;
  }
  row << "\n";
  csv_.write(row.str());
}

void VtkSeries::write(const Simulation& s) {
  if (!enabled_ || s.time() == last_t_) return;
  last_t_ = s.time();
  for (PhysicsModel* m : s.bodies())
    if (!pieces_only_ || m->writes_pieces()) m->write_output(s.time());
}

void VtkSeries::ended(const Simulation& s, RunEnd how) {
  // A failed run: its last converged state, so that the series ends where the run did (not after a failed
  // write: the disk that refused it would refuse this one too).
  if (how != RunEnd::failed) return;
  try {
    write(s);
  } catch (const std::exception&) {
  }
}

Checkpointer::Checkpointer(Parts parts) : p_(std::move(parts)) {}

void Checkpointer::save(const Simulation& s) {
  RunPosition& pos = p_.position;
  pos.step = s.step();
  pos.t = s.time();
  pos.last_output_t = p_.series->last_output_time();
  pos.probes_bytes = p_.probes_csv->size();
  pos.log_bytes = p_.log->size();
  RunTotals saved = s.totals();
  saved.wall_before += seconds_since(p_.start);
  save_checkpoint(p_.dir, p_.settings.keep, pos, saved, p_.models, p_.probes, p_.case_file);
  last_step_ = s.step();
  last_wall_ = seconds_since(p_.start);
}

void Checkpointer::stepped(const Simulation& s, const StepRecord& r) {
  const CheckpointSettings& ck = p_.settings;
  if ((ck.every_steps > 0 && r.step % ck.every_steps == 0) ||
      (ck.every_minutes > 0 && seconds_since(p_.start) - last_wall_ >= 60 * ck.every_minutes))
    if (!s.finished()) save(s);
}

void Checkpointer::stopped_early(const Simulation& s) {
  // Before the series gets the state where the run stopped (VtkSeries::ended), so that a restart continues the
  // series as if the run had not stopped.
  if (p_.settings.active() && last_step_ != s.step()) save(s);
}

void ProgressReport::stepped(const Simulation& s, const StepRecord& r) {
  StepStatus st;
  st.step = r.step;
  st.t = r.t;
  st.t_end = s.analysis().end_time;
  st.dt = r.dt;
  st.iterations = r.iterations;
  st.shown = s.labelled(r);
  st.particles = r.particles;
  st.nodes = r.nodes;
  st.wall = seconds_since(start_);
  progress_.step(st);
}

namespace {
Json timing(const PhaseTimes& p) {
  return Json{{"remesh", p.remesh},
              {"assembly", p.assembly},
              {"factorization", p.factorization},
              {"solve", p.solve},
              {"output", p.output},
              {"total", p.remesh + p.assembly + p.factorization + p.solve + p.output}};
}
}  // namespace

Json process_report(const PhaseTimes& p, double wall) {
  if (mpi_run::size() <= 1) return nullptr;
  const mpi_run::Traffic t = mpi_run::traffic();
  const std::vector<double> mine{
      p.remesh,       p.assembly,          p.factorization,          p.solve, p.output, wall, t.seconds, t.bytes / 1e6,
      t.halo_seconds, t.petsc_bytes / 1e6, mpi_run::peak_memory_mb()};
  const std::vector<double> all = mpi_run::gather_to_writer(mine);
  if (all.empty()) return nullptr;
  const char* names[] = {"remesh", "assembly", "factorization", "solve",    "output", "wall",
                         "comm",   "comm_MB",  "halo",          "petsc_MB", "peak_MB"};
  Json out = Json::array();
  for (size_t r = 0; r * mine.size() < all.size(); ++r) {
    Json e{{"rank", r}};
    for (size_t k = 0; k < mine.size(); ++k) e[names[k]] = all[r * mine.size() + k];
    out.push_back(std::move(e));
  }
  return out;
}

void SummaryWriter::write(const Simulation& sim) const {
  const RunTotals& tot = sim.totals();
  Json s;
  s["case"] = p_.case_name;
  s["case_file"] = p_.case_file.string();
  s["status"] = status_.value;
  s["message"] = status_.message;
  if (InterruptGuard::received()) s["signal"] = signal_name(InterruptGuard::received());
  s["warnings"] = p_.warnings;
  s["analysis"] = sim.analysis().type;
  s["steps"] = tot.steps;
  s["steps_planned"] = sim.planned_steps();
  s["step_retries"] = tot.retries;
  if (sim.analysis().time_step.adaptive) {
    Json by = Json::object();
    for (size_t k = 0; k < tot.dt_by.size(); ++k) by[tot.dt_by[k]] = tot.dt_by_steps[k];
    const TimeStepControl& c = sim.analysis().time_step;
    s["time_step"] = {{"type", "adaptive"},
                      {"courant", c.courant},
                      {"max", c.max},
                      {"growth", c.growth},
                      {"dt_min", tot.dt_min},
                      {"dt_max", tot.dt_max},
                      {"dt_mean", tot.steps ? sim.time() / tot.steps : 0.0},
                      {"steps_set_by", by}};
  }
  s["time"] = sim.time();
  s["wall_time"] = tot.wall_before + seconds_since(p_.start);
  if (p_.restarted_step >= 0) s["restarted_from_step"] = p_.restarted_step;
  if (p_.checkpointer && p_.checkpointer->last_step() >= 0)
    s["checkpoint"] = {{"file", kCheckpointFile}, {"step", p_.checkpointer->last_step()}};
  s["newton_iterations"] = {{"total", tot.iterations},
                            {"mean", tot.steps ? double(tot.iterations) / tot.steps : 0.0},
                            {"max", tot.max_iterations}};
  s["timing"] = timing(tot.phases);
  Json bodies = Json::array();
  for (size_t i = 0; i < sim.bodies().size(); ++i) {
    const PhysicsModel& m = *sim.bodies()[i];
    Json b{{"name", m.name()},
           {"type", m.type()},
           {"nodes", m.num_nodes()},
           {"elements", m.num_elements()},
           {"timing", timing(i < tot.body_phases.size() ? tot.body_phases[i] : PhaseTimes{})}};
    b.update(m.summary());
    bodies.push_back(std::move(b));
  }
  s["bodies"] = bodies;
  // Couplings: each its own entry; a case with one coupling also has it as "coupling".
  Json couplings = Json::array();
  for (const PhysicsModel* m : sim.couplings()) {
    Json c{{"name", m->name()}, {"type", m->type()}};
    c.update(m->summary());
    couplings.push_back(std::move(c));
  }
  if (!couplings.empty()) s["couplings"] = couplings;
  if (couplings.size() == 1) s["coupling"] = couplings[0];
  s["threads"] = p_.threads;
  if (mpi_run::size() > 1) s["mpi_processes"] = mpi_run::size();  // mpi_run.hpp: replicated data, distributed solves
  if (!processes.is_null()) s["processes"] = processes;
  write_file_atomic(p_.file, json_text(s));
}

}  // namespace lagfsi
