/// @file linear_solver_input.cpp
/// Reading a `linear_solver` value (linear_solver_input.hpp).
#include <lagfsi/linear_solver_input.hpp>

#include <algorithm>

namespace lagfsi {

namespace {

const KeyTable kLinearSolverObjectKeys(
    "linear solver (object form)",
    "A linear solver with its settings; the string form \"petsc\" is this object with its defaults.",
    {{"type", nullptr, "A direct type the system accepts, petsc or auto."},
     {"direct", "klu",
      "auto: the direct solver below auto_threshold unknowns (default: the system's own direct default).", kDerived},
     {"auto_threshold", 40000,
      "auto: unknowns from which the Krylov solver is used (default: the system's measured crossover: 6000 for the "
      "monolithic fluid, 20000 for the fractional step's Poisson, 40000 for the solids).",
      kDerived},
     {"rtol", 1e-8, "Krylov: relative residual ||b - A x|| / ||b|| a solve must reach, else the step fails."},
     {"max_iterations", 1000, "Krylov: iterations before the solve fails (the step is then retried)."},
     {"ksp", "", "Krylov: PETSc KSP type (cg, gmres, fgmres, bcgs, preonly, ...); empty: the system's default."},
     {"pc", "", "Krylov: PETSc PC type (hypre, gamg, jacobi, ilu, fieldsplit, lu, ...); empty: the system's default."},
     {"options", "",
      "Krylov: raw PETSc options for this solver alone, read last (e.g. \"-ksp_monitor -pc_hypre_boomeramg_"
      "strong_threshold 0.5\")."}});

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + v[i];
  return s;
}

}  // namespace

Json solver_summary(const LinearSolver& solver) {
  const SolverStatistics& st = solver.statistics();
  Json j = {{"type", solver.type()},
            {"method", solver.report().method},
            {"setups", st.setups},
            {"pattern_setups", st.pattern_setups},
            {"solves", st.solves},
            {"failures", st.failures},
            {"setup_seconds", st.setup_seconds},
            {"solve_seconds", st.solve_seconds}};
  if (st.iterative_solves > 0) {
    j["krylov_solves"] = st.iterative_solves;
    j["iterations_per_solve"] = static_cast<double>(st.iterations) / static_cast<double>(st.iterative_solves);
    j["iterations_max"] = st.max_iterations;
  }
  return j;
}

std::string linear_solver_doc(const std::vector<std::string>& direct_types) {
  return join(direct_types) +
         ", petsc (Krylov) or auto (direct below a size, Krylov above), or an object (see "
         "linear solver (object form)).";
}

void expand_linear_solver(Params& parent, const std::string& key) {
  Json& j = parent.json();
  if (j.is_object() && j.contains(key) && j.at(key).is_string()) j[key] = Json{{"type", j.at(key)}};
}

LinearSolverSettings read_linear_solver(const Params& parent, const std::string& key, LinearSolverSettings defaults,
                                        const std::vector<std::string>& direct_types) {
  std::vector<std::string> types = direct_types;
  types.push_back("petsc");
  types.push_back("auto");
  LinearSolverSettings s = std::move(defaults);
  if (parent.json().is_object() && parent.json().contains(key) && parent.json().at(key).is_string()) {
    s.type = parent.choice(key, types);
    return s;
  }
  Params p = parent.at(key);
  if (!p.json().is_object()) p.fail("expected a type string or an object");
  p.validate(kLinearSolverObjectKeys, {{"direct", s.direct}, {"auto_threshold", s.auto_threshold}});
  s.type = p.choice("type", types);
  s.direct = p.choice("direct", direct_types);
  s.auto_threshold = p.integer("auto_threshold", 1);
  s.rtol = p.positive("rtol");
  if (s.rtol >= 1.0) p.fail("rtol", "must be below 1");
  s.max_iterations = p.integer("max_iterations", 1);
  s.ksp = p.string("ksp");
  s.pc = p.string("pc");
  s.options = p.string("options");
  return s;
}

}  // namespace lagfsi
