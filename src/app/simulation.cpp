#include "simulation.hpp"

#include <lagfsi/error.hpp>
#include <lagfsi/stopwatch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

namespace lagfsi {

Simulation::Simulation(const AnalysisSettings& analysis, std::vector<PhysicsModel*> bodies,
                       std::vector<PhysicsModel*> couplings, std::vector<PhysicsModel*> steppers)
    : analysis_(analysis),
      bodies_(std::move(bodies)),
      couplings_(std::move(couplings)),
      steppers_(std::move(steppers)) {}

long Simulation::planned_steps() const {
  return std::lround(std::ceil(analysis_.end_time / analysis_.dt * (1 - 1e-9)));
}

void Simulation::initialize() {
  for (PhysicsModel* m : bodies_) m->initialize();
  for (PhysicsModel* m : couplings_) m->initialize();
  columns_.clear();
  for (const auto* list : {&bodies_, &couplings_})
    for (const PhysicsModel* m : *list)
      for (const Metric& x : m->step_metrics())
        if (std::none_of(columns_.begin(), columns_.end(), [&](const Metric& c) { return c.name == x.name; }))
          columns_.push_back(x);
  totals_.labelled.assign(columns_.size(), 0.0);
}

void Simulation::start() {
  for (StepObserver* o : observers_) o->started(*this);
}

void Simulation::resume(const RunPosition& pos, const RunTotals& totals) {
  totals_ = totals;
  totals_.labelled.resize(columns_.size(), 0.0);
  step_ = pos.step;
  t_ = pos.t;
  for (StepObserver* o : observers_) o->resumed(*this, pos);
}

std::vector<double> Simulation::combined_metrics() const {
  std::vector<double> v(columns_.size(), 0.0);
  std::vector<bool> seen(columns_.size(), false);
  for (const auto* list : {&bodies_, &couplings_})
    for (const PhysicsModel* m : *list)
      for (const Metric& x : m->step_metrics()) {
        const auto it =
            std::find_if(columns_.begin(), columns_.end(), [&](const Metric& c) { return c.name == x.name; });
        if (it == columns_.end()) continue;  // a name the model did not report at the start: no column for it
        const size_t k = static_cast<size_t>(it - columns_.begin());
        v[k] = !seen[k] ? x.value : it->combine == Metric::Combine::max ? std::max(v[k], x.value) : v[k] + x.value;
        seen[k] = true;
      }
  return v;
}

double Simulation::choose_step(std::string& by) const {
  const TimeStepControl& c = analysis_.time_step;
  double dt = analysis_.dt;
  by = "fixed";
  if (c.adaptive) {
    // The first step is dt; then the smallest of the ceiling, the growth limit and the bodies' stable steps.
    by = totals_.last_dt > 0 ? "max" : "first";
    dt = totals_.last_dt > 0 ? c.max : std::min(analysis_.dt, c.max);
    if (totals_.last_dt > 0 && c.growth * totals_.last_dt < dt) {
      dt = c.growth * totals_.last_dt;
      by = "growth";
    }
    for (const PhysicsModel* m : bodies_) {
      const StepLimit l = m->stable_step(c.courant);
      if (l.dt < dt) {
        dt = l.dt;
        by = m->name() + ": " + l.by;
      }
    }
  }
  if (analysis_.end_time - t_ < dt) {
    dt = analysis_.end_time - t_;
    by = "end";
  }
  // A remainder shorter than 1e-6 dt is taken with this step.
  if (analysis_.end_time - (t_ + dt) < 1e-6 * analysis_.dt) dt = analysis_.end_time - t_;
  return dt;
}

StepRecord Simulation::advance() {
  StepRecord r;
  r.step = step_ + 1;
  double dt = choose_step(r.dt_by);
  r.dt_limit = dt;
  for (PhysicsModel* m : couplings_) m->times() = PhaseTimes{};
  for (PhysicsModel* m : bodies_) m->times() = PhaseTimes{};
  for (int halving = 0;; ++halving) {
    const double t_new = t_ + dt;
    try {
      for (PhysicsModel* m : steppers_) {
        m->predict(t_new, dt);
        r.iterations += iterate_to_convergence(*m, analysis_.newton.max_iterations, t_new, &r.residual);
      }
      break;
    } catch (const SolverError& e) {
      if (halving >= analysis_.max_step_halvings) throw;
      char note[512];
      std::snprintf(note, sizeof note, "step at t=%.6g failed (%s); retrying with dt=%.3g", t_new, e.what(), dt / 2);
      for (StepObserver* o : observers_) o->retried(*this, note);
      dt /= 2;
      ++totals_.retries;
    }
  }
  for (PhysicsModel* m : steppers_) m->finalize_step();
  r.dt = dt;
  r.t = t_ + dt;
  r.metrics = combined_metrics();
  return r;
}

void Simulation::record(StepRecord& r) {
  r.phases = PhaseTimes{};
  r.nodes = r.elements = r.particles = 0;
  for (const PhysicsModel* m : bodies_) {
    r.phases += m->times();
    r.nodes += m->num_nodes();
    r.elements += m->num_elements();
    r.particles += m->num_particles();
  }
}

void Simulation::account(const StepRecord& r) {
  ++totals_.steps;
  if (analysis_.time_step.adaptive) {
    totals_.dt_min = totals_.last_dt > 0 ? std::min(totals_.dt_min, r.dt) : r.dt;
    totals_.dt_max = std::max(totals_.dt_max, r.dt);
    totals_.last_dt = r.dt;
    const auto it = std::find(totals_.dt_by.begin(), totals_.dt_by.end(), r.dt_by);
    if (it == totals_.dt_by.end()) {
      totals_.dt_by.push_back(r.dt_by);
      totals_.dt_by_steps.push_back(1);
    } else {
      ++totals_.dt_by_steps[static_cast<size_t>(it - totals_.dt_by.begin())];
    }
  }
  totals_.iterations += r.iterations;
  totals_.max_iterations = std::max(totals_.max_iterations, r.iterations);
  totals_.phases += r.phases;
  totals_.body_phases.resize(bodies_.size());
  for (size_t i = 0; i < bodies_.size(); ++i) totals_.body_phases[i] += bodies_[i]->times();
  for (size_t k = 0; k < columns_.size(); ++k)
    if (!columns_[k].progress_label.empty()) totals_.labelled[k] += r.metrics[k];
}

void Simulation::run(const std::function<bool(const Simulation&)>& stop) {
  while (!finished() && !stop(*this)) {
    const auto t_step = SteadyClock::now();
    StepRecord r = advance();
    step_ = r.step;
    t_ = r.t;
    for (StepObserver* o : observers_) o->output(*this, r);
    record(r);
    r.wall = seconds_since(t_step);
    account(r);
    for (StepObserver* o : observers_) o->stepped(*this, r);
  }
  if (!finished())
    for (StepObserver* o : observers_) o->stopped_early(*this);
}

void Simulation::end(RunEnd how) {
  for (StepObserver* o : observers_) o->ended(*this, how);
}

std::vector<std::pair<std::string, double>> Simulation::labelled(const StepRecord& r) const {
  std::vector<std::pair<std::string, double>> v;
  for (size_t k = 0; k < columns_.size(); ++k)
    if (!columns_[k].progress_label.empty()) v.emplace_back(columns_[k].progress_label, r.metrics[k]);
  return v;
}

std::vector<std::pair<std::string, double>> Simulation::labelled_totals() const {
  std::vector<std::pair<std::string, double>> v;
  for (size_t k = 0; k < columns_.size(); ++k)
    if (!columns_[k].progress_label.empty()) v.emplace_back(columns_[k].progress_label, totals_.labelled[k]);
  return v;
}

}  // namespace lagfsi
