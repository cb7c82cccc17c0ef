#include <lagfsi/error.hpp>
#include <lagfsi/model.hpp>

#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace lagfsi {

namespace {
std::string fmt(double x, int prec = 6) {
  std::ostringstream o;
  o << std::setprecision(prec) << x;
  return o.str();
}
}  // namespace

std::vector<KeyDecl> probe_keys(const std::vector<std::string>& types, std::vector<KeyDecl> own) {
  std::string names;
  for (size_t i = 0; i < types.size(); ++i)
    names += (i == 0 ? "`" : i + 1 == types.size() ? " or `" : ", `") + types[i] + "`";
  std::vector<KeyDecl> keys = {
      {"name", nullptr, "Column name in probes.csv (1-64 letters, digits, '_', '-', '.', '+')."},
      {"type", types.size() == 1 ? Json(types[0]) : Json(nullptr), names + "."},
      {"body", nullptr, "Name of the body (or coupling) probed."}};
  for (auto& k : own) keys.push_back(std::move(k));
  return keys;
}

void PhysicsModel::serialize(StateArchive&) {
  throw std::logic_error("body '" + name() + "' (" + type() + "): checkpoints are not implemented for this type");
}

int iterate_to_convergence(PhysicsModel& m, int max_iterations, double t_new, double* relative) {
  int iterations = 0;
  double last = 0.0;
  for (int it = 1; it <= max_iterations; ++it) {
    const IterationReport r = m.solve_iteration();
    iterations += std::max(1, r.inner_iterations);
    last = r.residual / std::max(r.residual_ref, 1e-300);
    if (relative) *relative = last;
    if (!std::isfinite(last) || last > 1e12)
      throw SolverError("body '" + m.name() + "': Newton diverged at t = " + fmt(t_new) + " (relative residual " +
                        fmt(last, 3) + ")");
    if (r.converged) return iterations;
  }
  throw SolverError("body '" + m.name() + "': Newton did not converge in " + std::to_string(max_iterations) +
                    " iterations at t = " + fmt(t_new) + " (relative residual " + fmt(last, 3) + ")");
}

}  // namespace lagfsi
