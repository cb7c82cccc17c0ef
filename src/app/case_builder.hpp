#pragma once
// The case of a run, built from its file (case_builder.cpp): the bodies through the model registry, the couplings
// through the coupling registry, the probes, the output settings; and what no single body can check (output names
// shared by two bodies, bodies that overlap).
#include "analysis_settings.hpp"
#include "checkpoint.hpp"

#include <lagfsi/app/analysis.hpp>
#include <lagfsi/case.hpp>
#include <lagfsi/model.hpp>

#include <memory>
#include <string>
#include <vector>

namespace lagfsi {

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
  std::vector<std::string> warnings;  ///< chosen on purpose (a conditionally stable integrator,
                                      ///< PhysicsModel::warnings): stderr and summary.json
};

/// Builds the case; on bad input prints the one-line error and returns null. `for_check`: for `lagfsi check`.
std::unique_ptr<Case> build_case_or_report(const RunOptions& opt, bool for_check);

/// Every model of the case, bodies then couplings (the order of checkpoints).
std::vector<PhysicsModel*> all_models(const Case& c);

}  // namespace lagfsi
