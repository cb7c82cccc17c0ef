#pragma once
// The case's "analysis" object (analysis_settings.cpp): static or dynamic, time step and end, step halvings,
// integrator (checked for unconditional stability), Newton settings and linear solver.
#include <lagfsi/case.hpp>

#include <string>
#include <vector>

namespace lagfsi {

/// Validates /analysis (defaults filled in) and reads it; `warnings` receives what was chosen on purpose (a
/// conditionally stable integrator), for stderr and summary.json. `bodies` (the case's "bodies" array) gives the
/// integrator when the case names none: Newmark's trapezoidal rule, or what a body asks for (a fluid whose
/// free-surface pressure is Robin, with walls as constraints: generalized-alpha; fluid_preferred_integrator).
AnalysisSettings read_analysis(Params analysis, std::vector<std::string>& warnings, const Json& bodies = nullptr);

}  // namespace lagfsi
