#include <lagfsi/error.hpp>
#include <lagfsi/fsi/coupling.hpp>

#include <algorithm>
#include <cmath>

namespace lagfsi::fsi {

CouplingReport dirichlet_neumann_step(const DirichletSide& dirichlet, const NeumannSide& neumann,
                                      Acceleration& acceleration, Vec& x, const CouplingSettings& settings,
                                      double reference) {
  CouplingReport rep;
  const Vec x0 = x;
  acceleration.begin_step();
  for (int k = 0; k < settings.max_iterations; ++k) {
    const Vec f = dirichlet(x);
    const Vec xt = neumann(f);
    if (xt.size() != x.size())
      throw SolverError("coupling: the Neumann side returned " + std::to_string(xt.size()) +
                        " interface values, expected " + std::to_string(x.size()));
    ++rep.iterations;
    rep.residual = (xt - x).norm();
    const Vec& origin = settings.origin.size() == x.size() ? settings.origin : x0;
    rep.reference = reference > 0 ? reference : std::max((xt - origin).norm(), settings.reference_floor);
    if (!std::isfinite(rep.residual)) {
      x = xt;
      return rep;
    }
    if (rep.residual <= settings.tolerance * rep.reference) {
      x = xt;
      rep.converged = true;
      acceleration.end_step();
      return rep;
    }
    x = acceleration.update(x, xt);
  }
  return rep;
}

}  // namespace lagfsi::fsi
