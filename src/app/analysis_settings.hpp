#pragma once
// The case's "analysis" object (analysis_settings.cpp): static or dynamic, time step and end, step halvings,
// integrator (checked for unconditional stability), Newton settings and linear solver.
#include <lagfsi/case.hpp>

#include <string>
#include <vector>

namespace lagfsi {

/// Validates /analysis (defaults filled in) and reads it; `warnings` receives what was chosen on purpose (a
/// conditionally stable integrator), for stderr and summary.json. `default_integrator` is the integrator when the
/// case names none: what the bodies ask for (integrator_preferences, model_registry.hpp), else Newmark's
/// trapezoidal rule.
AnalysisSettings read_analysis(Params analysis, std::vector<std::string>& warnings,
                               const Json& default_integrator = Json{{"type", "newmark"}});

}  // namespace lagfsi
