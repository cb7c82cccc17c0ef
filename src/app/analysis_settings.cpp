// The case's "analysis" object (analysis_settings.hpp).
#include "analysis_settings.hpp"

#include "input_checks.hpp"

#include <lagfsi/linear_solver.hpp>
#include <lagfsi/time_integrator.hpp>

namespace lagfsi {

AnalysisSettings read_analysis(Params a, std::vector<std::string>& warnings, const Json& default_integrator) {
  a.validate({{"type", nullptr},
              {"dt", 0.0},
              {"end_time", 0.0},
              {"load_steps", 10},
              {"max_step_halvings", 4},
              {"integrator", default_integrator},
              {"newton", Json::object()},
              {"linear_solver", Json{{"type", "cholmod"}}}});
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
  Params it = a.at("integrator");
  if (!it.json().is_object() || !it.has("type")) it.fail("type", "required key is missing");
  const std::string itype = it.choice("type", time_integrator_types());
  if (itype == "newmark") {
    it.validate({{"type", "newmark"}, {"beta", 0.25}, {"gamma", 0.5}, {"allow_conditionally_stable", false}});
  } else if (itype == "generalized_alpha") {
    it.validate({{"type", "generalized_alpha"}, {"rho_inf", 0.8}});
  } else {
    it.validate({{"type", "central_difference"}});
    it.fail("type",
            "central_difference needs a lumped-mass explicit model; solids in this version are implicit "
            "(use newmark or generalized_alpha)");
  }
  warnings = check_integrator_stability(it);
  s.integrator = read_integrator(it);
  Params nw = a.at("newton");
  nw.validate({{"max_iterations", 25}, {"residual_tolerance", 1e-6}, {"position_tolerance", 1e-9}});
  s.newton.max_iterations = nw.integer("max_iterations", 1);
  s.newton.residual_tolerance = nw.positive("residual_tolerance");
  s.newton.position_tolerance = nw.positive("position_tolerance");
  Params ls = a.at("linear_solver");
  ls.validate({{"type", "cholmod"}});
  s.linear_solver = ls.choice("type", linear_solver_types());
  return s;
}

}  // namespace lagfsi
