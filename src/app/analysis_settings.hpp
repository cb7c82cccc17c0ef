#pragma once
// The case's "analysis" object (analysis_settings.cpp): static or dynamic, time step and end, step halvings,
// integrator (checked for unconditional stability), Newton settings and linear solver.
#include <lagfsi/case.hpp>

#include <string>
#include <vector>

namespace lagfsi {

/// Validates /analysis (defaults filled in) and reads it; `warnings` receives what was chosen on purpose (a
/// conditionally stable integrator), for stderr and summary.json.
AnalysisSettings read_analysis(Params analysis, std::vector<std::string>& warnings);

}  // namespace lagfsi
