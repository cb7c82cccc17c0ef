// The case's "analysis" object (analysis_settings.hpp).
#include "analysis_settings.hpp"

#include "input_checks.hpp"

#include <lagfsi/linear_solver_input.hpp>
#include <lagfsi/time_integrator.hpp>

namespace lagfsi {

namespace {

const KeyTable kAnalysisKeys(
    "/analysis", "How time (or load) advances: a static or a dynamic analysis and its solver settings.",
    {{"type", nullptr, "`static` (load steps, no inertia) or `dynamic` (time steps)."},
     {"dt", 0.0, "Time step (s) of a dynamic analysis; must be positive there."},
     {"end_time", 0.0, "End time (s) of a dynamic analysis; must be positive there."},
     {"load_steps", 10, "Number of load steps of a static analysis (the loads' functions see t = k / load_steps)."},
     {"max_step_halvings", 4, "How many times a step that fails (Newton, inverted elements) is retried at half dt."},
     {"time_step", Json{{"type", "fixed"}},
      "How the step is chosen: {\"type\": \"fixed\"} (dt; halved only to retry a failed step) or adaptive (see "
      "/analysis/time_step (type adaptive))."},
     {"integrator", Json::object(),
      "Time integrator (see /analysis/integrator (type newmark) and others); default: {\"type\": \"newmark\"}, or "
      "generalized_alpha with "
      "rho_inf 0.8 when a fluid body of the monolithic scheme has walls as constraints and the Robin free-surface "
      "pressure or an inflow or outflow.",
      kDerived},
     {"newton", Json::object(), "Newton iteration settings (see /analysis/newton)."},
     {"linear_solver", Json{{"type", "cholmod"}},
      "Sparse linear solver of the solids, shells and EFG bodies: {\"type\": ...} with the keys of linear solver "
      "(object form) (petsc: CG + GAMG with the rigid-body modes; mumps: MUMPS's LU)."}});

const KeyTable kNewmarkKeys(
    "/analysis/integrator (type newmark)", "Newmark's method (beta = 1/4, gamma = 1/2: the trapezoidal rule).",
    {{"type", "newmark", "`newmark`."},
     {"beta", 0.25, "Newmark's beta (> 0); unconditionally stable when beta >= gamma / 2."},
     {"gamma", 0.5, "Newmark's gamma (>= 0); unconditionally stable when gamma >= 1/2."},
     {"allow_conditionally_stable", false,
      "Run a conditionally stable choice (beta < gamma / 2) with a warning instead of an error."}});

const KeyTable kGeneralizedAlphaKeys("/analysis/integrator (type generalized_alpha)",
                                     "The generalized-alpha method (Chung and Hulbert), second order, with "
                                     "numerical damping of the high frequencies.",
                                     {{"type", "generalized_alpha", "`generalized_alpha`."},
                                      {"rho_inf", 0.8,
                                       "Spectral radius at infinite frequency, in [0, 1] (1: no damping, 0: "
                                       "the most)."}});

const KeyTable kCentralDifferenceKeys("/analysis/integrator (type central_difference)",
                                      "The explicit central difference: needs a lumped-mass explicit model, "
                                      "and is rejected in this version (the solids are implicit).",
                                      {{"type", "central_difference", "`central_difference`."}});

const KeyTable kFixedStepKeys("/analysis/time_step (type fixed)",
                              "Every step is dt (a failed one is retried at dt / 2).", {{"type", "fixed", "`fixed`."}});

const KeyTable kAdaptiveStepKeys(
    "/analysis/time_step (type adaptive)",
    "Each step is the smallest of the ceiling `max`, `growth` times the last step and every body's stable step for "
    "the Courant number (a fluid, at the step's start: C |x_a - x_b| / |v_a - v_b| over its mesh's edges, which a "
    "step may deform by at most C of themselves, C h / |v| over its particles outside the mesh, drops in flight, "
    "and C sqrt(h / |a|) over all its particles); the first step is dt; a failed step is still retried at half its "
    "size. "
    "log.csv records each step's limit (dt_limit) and what set it (dt_by: max, growth, end, or the body's reason); "
    "summary.json counts them.",
    {{"type", "adaptive", "`adaptive`."},
     {"courant", 0.5, "The Courant number C, in (0, 1]."},
     {"max", 0.0, "The largest step (s); default: the analysis' dt.", kDerived},
     {"growth", 1.25, "The largest ratio of a step to the one before (> 1)."}});

const KeyTable kNewtonKeys(
    "/analysis/newton", "Newton iterations of the implicit solids (each step or load step).",
    {{"max_iterations", 25, "Iterations before the step fails (and is retried at half dt)."},
     {"residual_tolerance", 1e-6,
      "Relative residual (to the step's reference) below which, with a small update, a step has converged."},
     {"position_tolerance", 1e-9,
      "Largest position update, relative to the body's size, for a step to have converged."}});

}  // namespace

AnalysisSettings read_analysis(Params a, std::vector<std::string>& warnings, const Json& default_integrator) {
  expand_linear_solver(a, "linear_solver");
  a.validate(kAnalysisKeys, {{"integrator", default_integrator}});
  AnalysisSettings s;
  s.type = a.choice("type", {"static", "dynamic"});
  if (s.type == "static") {
    const int n = a.integer("load_steps", 1);
    s.dt = 1.0 / n;
    s.end_time = 1.0;
  } else {
    s.dt = a.positive("dt");
    s.end_time = a.positive("end_time");
    if (s.end_time / s.dt > 1e8) a.fail("dt", "more than 1e8 steps requested");
  }
  s.max_step_halvings = a.integer("max_step_halvings", 0);
  Params ts = a.at("time_step");
  if (!ts.json().is_object() || !ts.has("type")) ts.fail("type", "required key is missing");
  if (ts.choice("type", {"fixed", "adaptive"}) == "adaptive") {
    ts.validate(kAdaptiveStepKeys, {{"max", s.dt}});
    if (s.type != "dynamic") ts.fail("type", "an adaptive step is for a dynamic analysis");
    s.time_step.adaptive = true;
    s.time_step.courant = ts.positive("courant");
    if (s.time_step.courant > 1) ts.fail("courant", "must lie in (0, 1]");
    s.time_step.max = ts.positive("max");
    s.time_step.growth = ts.positive("growth");
    if (!(s.time_step.growth > 1)) ts.fail("growth", "must be above 1");
  } else {
    ts.validate(kFixedStepKeys);
  }
  Params it = a.at("integrator");
  if (!it.json().is_object() || !it.has("type")) it.fail("type", "required key is missing");
  const std::string itype = it.choice("type", time_integrator_types());
  if (itype == "newmark") {
    it.validate(kNewmarkKeys);
  } else if (itype == "generalized_alpha") {
    it.validate(kGeneralizedAlphaKeys);
  } else {
    it.validate(kCentralDifferenceKeys);
    it.fail("type",
            "central_difference needs a lumped-mass explicit model; solids in this version are implicit "
            "(use newmark or generalized_alpha)");
  }
  warnings = check_integrator_stability(it);
  s.integrator = read_integrator(it);
  Params nw = a.at("newton");
  nw.validate(kNewtonKeys);
  s.newton.max_iterations = nw.integer("max_iterations", 1);
  s.newton.residual_tolerance = nw.positive("residual_tolerance");
  s.newton.position_tolerance = nw.positive("position_tolerance");
  LinearSolverSettings ls;
  ls.type = ls.direct = "cholmod";
  ls.kind = SystemKind::elasticity;
  ls.block_size = 2;
  s.linear_solver = read_linear_solver(a, "linear_solver", ls, direct_solver_types());
  return s;
}

}  // namespace lagfsi
