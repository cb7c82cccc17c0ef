#pragma once
/// @file time_integrator.hpp
/// Time integrators for second-order systems written in positions (positional FEM, PFEM, MPM),
///
///   M a + C v + f_int(x) = f_ext(t),
///
/// where the unknown of every implicit step is the new position x_{n+1} (not an increment).
///
/// The contract (in the spirit of MFEM's SecondOrderODESolver / NewmarkSolver). Every member is built by
/// make_time_integrator() from the case's integrator object; a model never constructs one by name.
///
/// Rules for every member:
///  - The state (x_n, v_n, a_n, t_n) of a KinematicState is consistent at entry to a step: a_n is the
///    acceleration of the equation of motion at (x_n, v_n, t_n), not a leftover of a failed attempt.
///  - A step can be abandoned and taken again with another dt from the same state: nothing a step computes
///    is kept by the integrator beyond the stored start of the step, so a model that keeps its own copy of
///    the state (the snapshot of PhysicsModel::predict) retries by calling begin_step() again.
///  - dt > 0 and finite; t_{n+1} = t_n + dt.
///
/// Implicit members (Newmark, generalized-alpha; is_explicit() false):
///  - begin_step(state, dt) stores the old state; predictor() gives the first Newton guess for x_{n+1}.
///  - For a trial x_{n+1}, kinematics(x_{n+1}) returns the quantities at which the residual is evaluated:
///    x_eval, v_eval, a_eval and t_eval (for Newmark these are x_{n+1}, v_{n+1}, a_{n+1}, t_{n+1}; for
///    generalized-alpha the intermediate points x_{n+1-af}, v_{n+1-af}, a_{n+1-am}, t_{n+1-af}).
///    The model assembles r = M a_eval + C v_eval + f_int(x_eval) - f_ext(t_eval).
///  - Prescribed dofs (moving walls, a structure's ghost particles) are taken to the same point: the model writes
///    their v and a at t_{n+1} into end_step()'s state of the trial x_{n+1} and calls evaluation() on it (under
///    generalized-alpha, rates written unchanged into kinematics()' point make the step first order).
///  - coefficients() gives the derivatives of those quantities with respect to x_{n+1}:
///    d a_eval/dx = c_m, d v_eval/dx = c_c, d x_eval/dx = c_k, so the consistent tangent is
///    H = c_m M + c_c C + c_k K(x_eval) (system_assembly.hpp: combine_tangent()).
///  - end_step(x_{n+1}, state) writes (x_{n+1}, v_{n+1}, a_{n+1}) into the state; it is const and may be
///    called on a scratch state for any trial x_{n+1} (the integrator's own v_{n+1}(x), a_{n+1}(x): what an
///    energy account or a coupling's interface kinematics use, never a formula of one particular rule).
///
/// Explicit members (central difference; is_explicit() true): Newmark with beta = 0, gamma = 1/2 in
/// velocity-Verlet form, with a lumped (diagonal) mass; the model calls explicit_step() or its
/// non-allocating form explicit_step_into() instead of the Newton loop:
///   x_{n+1} = x_n + dt v_n + dt^2/2 a_n,  a_{n+1} = M_L^{-1} F(x_{n+1}, v_n + dt a_n, t_{n+1}),
///   v_{n+1} = v_n + dt/2 (a_n + a_{n+1}).
///  - Conditionally stable: dt <= 2 / omega_max. The model's driver step is its step-size control: it splits
///    the analysis' dt into n equal sub-steps below its stable step (the DEM's critical step, the MPM's
///    cfl h / c) and calls the member once per sub-step.
///  - Prescribed dofs have inv_mass 0 (no acceleration from the force); the caller imposes their motion.
///  - explicit_step_into() works in place on the state; the caller owns the force vector, and the force
///    callback receives the half-step velocity v_{n+1/2} = v_n + dt/2 a_n (what a dashpot or a tangential
///    spring history uses). It equals explicit_step() up to rounding (v_{n+1} is formed as
///    v_{n+1/2} + dt/2 a_{n+1}).
///  - Leapfrog form: with v_n = v_{n-1/2} + dt/2 a_n the step gives v_{n+1/2} = v_{n-1/2} + dt a_n and
///    x_{n+1} = x_n + dt v_{n+1/2}, the symplectic update of a model whose velocities live at half steps
///    (the explicit MPM's grid, whose force is that of the sub-step's start: mpm_scheme_explicit.cpp).
///
/// References: Newmark (1959); Chung & Hulbert (1993), J. Appl. Mech. 60:371 (generalized-alpha with
/// am = (2 rho - 1)/(rho + 1), af = rho/(rho + 1), gamma = 1/2 - am + af, beta = (1 - am + af)^2 / 4);
/// Hughes (1987), The Finite Element Method, ch. 9 (central difference).
#include <lagfsi/types.hpp>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace lagfsi {

class Params;

/// Positions, velocities and accelerations of all dofs at one time.
struct KinematicState {
  double t = 0.0;
  Vec x, v, a;
};

/// What the residual is evaluated with, for a trial x_{n+1}.
struct EvalPoint {
  double t;
  Vec x, v, a;
};

/// Derivatives of the evaluation point with respect to x_{n+1}: H = c_m M + c_c C + c_k K.
struct TangentCoefficients {
  double c_m, c_c, c_k;
};

class TimeIntegrator {
 public:
  virtual ~TimeIntegrator() = default;
  virtual std::string type() const = 0;
  virtual bool is_explicit() const { return false; }

  /// Stores (x_n, v_n, a_n, t_n) and dt for the step to come.
  virtual void begin_step(const KinematicState& s, double dt) = 0;
  /// First guess for x_{n+1} (the "constant position" or the "constant acceleration" predictor).
  virtual Vec predictor() const = 0;
  /// Evaluation point for a trial x_{n+1}: evaluation(end) of the end state end_step(x_{n+1}) writes.
  virtual EvalPoint kinematics(const Vec& x_new) const = 0;
  /// Evaluation point of a given end state (x_{n+1}, v_{n+1}, a_{n+1}) from the stored start. A model whose dofs
  /// include a prescribed motion (moving walls, a coupled structure's ghost particles) takes end_step()'s state
  /// of its trial x_{n+1}, writes the prescribed v and a at t_{n+1} into those dofs and evaluates here, so that
  /// every dof is taken at the same level (t_{n+1-af} under generalized-alpha; the end state itself under
  /// Newmark). Writing the prescribed rates into kinematics()'s point instead puts those dofs at t_{n+1} and the
  /// others at t_{n+1-af}: first order (TimeIntegratorContract test), and the coupled flexible_tank blew up.
  virtual EvalPoint evaluation(const KinematicState& end) const = 0;
  virtual TangentCoefficients coefficients() const = 0;
  /// v_{n+1}, a_{n+1} from the converged x_{n+1}; writes the new state (t_{n+1} = t_n + dt).
  virtual void end_step(const Vec& x_new, KinematicState& s) const = 0;

  /// Explicit integrators only: one step of central difference with a lumped (diagonal) mass.
  /// force(x, v, t) returns f_ext - f_int - C v (the out-of-balance force); inv_mass is 1/M_ii
  /// (0 for prescribed dofs, whose motion the caller imposes afterwards).
  using ForceFunction = std::function<Vec(const Vec& x, const Vec& v, double t)>;
  virtual void explicit_step(const ForceFunction& force, const Vec& inv_mass, double dt, KinematicState& s) const;

  /// Explicit integrators only: the non-allocating form of explicit_step(). force(x_{n+1}, v_{n+1/2},
  /// t_{n+1}, f) writes the out-of-balance force into f (sized like x by the step, reused from call to
  /// call: no allocation once the size is set). In place: x_{n+1} = x_n + dt v_n + dt^2/2 a_n,
  /// v_{n+1/2} = v_n + dt/2 a_n, a_{n+1} = inv_mass f, v_{n+1} = v_{n+1/2} + dt/2 a_{n+1}.
  using ForceIntoFunction = std::function<void(const Vec& x, const Vec& v, double t, Vec& f)>;
  virtual void explicit_step_into(const ForceIntoFunction& force, const Vec& inv_mass, double dt, KinematicState& s,
                                  Vec& f) const;
};

/// The analysis' integrator as the case names it, read once (read_integrator) and handed to every implicit model,
/// which builds its own from it (make_time_integrator); explicit models take the central difference.
struct IntegratorSpec {
  std::string type = "newmark";     ///< "newmark" | "generalized_alpha" | "central_difference"
  double beta = 0.25, gamma = 0.5;  ///< newmark
  double rho_inf = 0.8;             ///< generalized_alpha
  bool implicit() const { return type != "central_difference"; }
};

/// Reads an integrator: {"type": "newmark", "beta": 0.25, "gamma": 0.5} | {"type": "generalized_alpha", "rho_inf":
/// 0.8} | {"type": "central_difference"} (missing parameters take these defaults). A bad type or parameter fails
/// with InputError naming the file and JSON path.
IntegratorSpec read_integrator(const Params& integrator);
/// The integrator of a spec: the one place that turns a name into an integrator.
std::unique_ptr<TimeIntegrator> make_time_integrator(const IntegratorSpec& spec);
/// read_integrator, then make_time_integrator.
std::unique_ptr<TimeIntegrator> make_time_integrator(const Params& integrator);
/// The "type" names make_time_integrator() accepts.
const std::vector<std::string>& time_integrator_types();

/// Newmark-beta (beta, gamma); beta = 1/4, gamma = 1/2 is the average-acceleration rule.
std::unique_ptr<TimeIntegrator> make_newmark(double beta = 0.25, double gamma = 0.5);
/// Generalized-alpha of Chung & Hulbert with spectral radius at infinity rho_inf in [0, 1].
std::unique_ptr<TimeIntegrator> make_generalized_alpha(double rho_inf);
/// Explicit central difference (velocity-Verlet form; conditionally stable, dt < 2/omega_max).
std::unique_ptr<TimeIntegrator> make_central_difference();

/// Symplectic (semi-implicit) Euler, the update of the models whose new velocity comes before the new position
/// (the fractional-step fluid, whose v_{n+1} is the projection's; the two-phase MPM, whose particles take the
/// grid's accelerations): v_{n+1} = v_n + dt a_n (kick), then x_{n+1} = x_n + dt v_{n+1} (drift). First order,
/// symplectic (no numerical damping of an undamped oscillator), conditionally stable: dt <= 2 / omega_max
/// (Hairer, Lubich & Wanner, Geometric Numerical Integration, 2006, sec. I.1.2). The stages are static so that a
/// model applies them to its own storage (a particle's 2-vector or a whole state); make_symplectic_euler() is the
/// same update behind the TimeIntegrator contract (explicit_step: a_n = inv_mass f(x_n, v_n, t_n)).
struct SymplecticEuler {
  template <class V, class A>
  static void kick(V&& v, const A& a, double dt) {
    v += dt * a;
  }
  template <class X, class V>
  static void drift(X&& x, const V& v, double dt) {
    x += dt * v;
  }
};
std::unique_ptr<TimeIntegrator> make_symplectic_euler();

}  // namespace lagfsi
