#include <lagfsi/time_integrator.hpp>

#include <lagfsi/params.hpp>

#include <cmath>
#include <stdexcept>

namespace lagfsi {

void TimeIntegrator::explicit_step(const ForceFunction&, const Vec&, double, KinematicState&) const {
  throw std::logic_error("explicit_step called on the implicit integrator '" + type() + "'");
}

void TimeIntegrator::explicit_step_into(const ForceIntoFunction&, const Vec&, double, KinematicState&, Vec&) const {
  throw std::logic_error("explicit_step_into called on the implicit integrator '" + type() + "'");
}

namespace {

/// Newmark-type family in position form; generalized-alpha adds the intermediate evaluation points.
///   a_{n+1} = (x_{n+1} - x_n - dt v_n - dt^2 (1/2 - beta) a_n) / (beta dt^2)
///   v_{n+1} = v_n + dt ((1 - gamma) a_n + gamma a_{n+1})
///   x_e = (1 - af) x_{n+1} + af x_n, v_e likewise, a_e = (1 - am) a_{n+1} + am a_n, t_e = t_n + (1 - af) dt
class AlphaNewmark final : public TimeIntegrator {
 public:
  AlphaNewmark(std::string name, double beta, double gamma, double am, double af)
      : name_(std::move(name)), beta_(beta), gamma_(gamma), am_(am), af_(af) {
    if (!(beta > 0.0) || !(gamma >= 0.0) || !std::isfinite(beta) || !std::isfinite(gamma))
      throw std::invalid_argument("Newmark needs beta > 0 and gamma >= 0");
  }
  std::string type() const override { return name_; }

  void begin_step(const KinematicState& s, double dt) override {
    if (!(dt > 0.0) || !std::isfinite(dt)) throw std::invalid_argument("time step must be positive and finite");
    old_ = s;
    dt_ = dt;
  }

  Vec predictor() const override { return old_.x; }

  EvalPoint kinematics(const Vec& x_new) const override {
    KinematicState end;
    end_step(x_new, end);
    return evaluation(end);
  }

  EvalPoint evaluation(const KinematicState& end) const override {
    EvalPoint p;
    p.t = old_.t + (1.0 - af_) * dt_;
    p.x = (1.0 - af_) * end.x + af_ * old_.x;
    p.v = (1.0 - af_) * end.v + af_ * old_.v;
    p.a = (1.0 - am_) * end.a + am_ * old_.a;
    return p;
  }

  TangentCoefficients coefficients() const override {
    const double da = 1.0 / (beta_ * dt_ * dt_);
    const double dv = gamma_ / (beta_ * dt_);
    return {(1.0 - am_) * da, (1.0 - af_) * dv, 1.0 - af_};
  }

  void end_step(const Vec& x_new, KinematicState& s) const override {
    const Vec a_new = acceleration(x_new);
    s.v = old_.v + dt_ * ((1.0 - gamma_) * old_.a + gamma_ * a_new);
    s.a = a_new;
    s.x = x_new;
    s.t = old_.t + dt_;
  }

 private:
  Vec acceleration(const Vec& x_new) const {
    return (x_new - old_.x - dt_ * old_.v - dt_ * dt_ * (0.5 - beta_) * old_.a) / (beta_ * dt_ * dt_);
  }

  std::string name_;
  double beta_, gamma_, am_, af_;
  KinematicState old_;
  double dt_ = 0.0;
};

class CentralDifference final : public TimeIntegrator {
 public:
  std::string type() const override { return "central_difference"; }
  bool is_explicit() const override { return true; }
  void begin_step(const KinematicState& s, double dt) override {
    old_ = s;
    dt_ = dt;
  }
  Vec predictor() const override { return old_.x + dt_ * old_.v + 0.5 * dt_ * dt_ * old_.a; }
  EvalPoint kinematics(const Vec& x_new) const override { return {old_.t + dt_, x_new, old_.v, old_.a}; }
  EvalPoint evaluation(const KinematicState& end) const override { return {old_.t + dt_, end.x, old_.v, old_.a}; }
  TangentCoefficients coefficients() const override { return {0.0, 0.0, 0.0}; }
  void end_step(const Vec& x_new, KinematicState& s) const override {
    s.x = x_new;
    s.t = old_.t + dt_;
  }

  void explicit_step(const ForceFunction& force, const Vec& inv_mass, double dt, KinematicState& s) const override {
    if (!(dt > 0.0) || !std::isfinite(dt)) throw std::invalid_argument("time step must be positive and finite");
    const Vec x_new = s.x + dt * s.v + 0.5 * dt * dt * s.a;
    const Vec v_pred = s.v + 0.5 * dt * s.a;  // half-step velocity, used for the damping force
    const Vec a_new = inv_mass.cwiseProduct(force(x_new, v_pred, s.t + dt));
    s.v += 0.5 * dt * (s.a + a_new);
    s.a = a_new;
    s.x = x_new;
    s.t += dt;
  }

  void explicit_step_into(const ForceIntoFunction& force, const Vec& inv_mass, double dt, KinematicState& s,
                          Vec& f) const override {
    if (!(dt > 0.0) || !std::isfinite(dt)) throw std::invalid_argument("time step must be positive and finite");
    const Eigen::Index n = s.x.size();
    if (f.size() != n) f.resize(n);
    const double h = 0.5 * dt, h2 = 0.5 * dt * dt;
    double* x = s.x.data();
    double* v = s.v.data();
    double* a = s.a.data();
    const double* im = inv_mass.data();
    // Element-wise loops: the same result for any thread count.
#pragma omp parallel for schedule(static) if (n >= 60000)
    for (Eigen::Index i = 0; i < n; ++i) {
      x[i] = x[i] + dt * v[i] + h2 * a[i];
      v[i] += h * a[i];  // v_{n+1/2}
    }
    force(s.x, s.v, s.t + dt, f);
    const double* fp = f.data();
#pragma omp parallel for schedule(static) if (n >= 60000)
    for (Eigen::Index i = 0; i < n; ++i) {
      a[i] = im[i] * fp[i];
      v[i] += h * a[i];
    }
    s.t += dt;
  }

 private:
  KinematicState old_;
  double dt_ = 0.0;
};

}  // namespace

std::unique_ptr<TimeIntegrator> make_newmark(double beta, double gamma) {
  return std::make_unique<AlphaNewmark>("newmark", beta, gamma, 0.0, 0.0);
}

std::unique_ptr<TimeIntegrator> make_generalized_alpha(double rho_inf) {
  if (!(rho_inf >= 0.0 && rho_inf <= 1.0)) throw std::invalid_argument("generalized-alpha needs 0 <= rho_inf <= 1");
  const double am = (2.0 * rho_inf - 1.0) / (rho_inf + 1.0);
  const double af = rho_inf / (rho_inf + 1.0);
  const double gamma = 0.5 - am + af;
  const double beta = 0.25 * (1.0 - am + af) * (1.0 - am + af);
  return std::make_unique<AlphaNewmark>("generalized_alpha", beta, gamma, am, af);
}

std::unique_ptr<TimeIntegrator> make_central_difference() { return std::make_unique<CentralDifference>(); }

namespace {
class SymplecticEulerIntegrator final : public TimeIntegrator {
 public:
  std::string type() const override { return "symplectic_euler"; }
  bool is_explicit() const override { return true; }
  void begin_step(const KinematicState& s, double dt) override {
    old_ = s;
    dt_ = dt;
  }
  Vec predictor() const override { return old_.x + dt_ * (old_.v + dt_ * old_.a); }
  EvalPoint kinematics(const Vec& x_new) const override { return {old_.t, x_new, old_.v, old_.a}; }
  EvalPoint evaluation(const KinematicState& end) const override { return {old_.t, end.x, old_.v, old_.a}; }
  TangentCoefficients coefficients() const override { return {0.0, 0.0, 0.0}; }
  void end_step(const Vec& x_new, KinematicState& s) const override {
    s.x = x_new;
    s.t = old_.t + dt_;
  }
  void explicit_step(const ForceFunction& force, const Vec& inv_mass, double dt, KinematicState& s) const override {
    if (!(dt > 0.0) || !std::isfinite(dt)) throw std::invalid_argument("time step must be positive and finite");
    s.a = inv_mass.cwiseProduct(force(s.x, s.v, s.t));
    SymplecticEuler::kick(s.v, s.a, dt);
    SymplecticEuler::drift(s.x, s.v, dt);
    s.t += dt;
  }

 private:
  KinematicState old_;
  double dt_ = 0.0;
};
}  // namespace

std::unique_ptr<TimeIntegrator> make_symplectic_euler() { return std::make_unique<SymplecticEulerIntegrator>(); }

const std::vector<std::string>& time_integrator_types() {
  static const std::vector<std::string> types = {"newmark", "generalized_alpha", "central_difference"};
  return types;
}

IntegratorSpec read_integrator(const Params& p) {
  IntegratorSpec s;
  s.type = p.choice("type", time_integrator_types());
  auto number = [&](const char* key, double fallback) { return p.has(key) ? p.number(key) : fallback; };
  if (s.type == "newmark") {
    s.beta = number("beta", 0.25);
    s.gamma = number("gamma", 0.5);
    if (!(s.beta > 0.0)) p.fail("beta", "must be positive (beta = 0 is the explicit central_difference)");
    if (!(s.gamma >= 0.0)) p.fail("gamma", "must not be negative");
  } else if (s.type == "generalized_alpha") {
    s.rho_inf = number("rho_inf", 0.8);
    if (!(s.rho_inf >= 0.0 && s.rho_inf <= 1.0)) p.fail("rho_inf", "must lie in [0, 1]");
  }
  return s;
}

std::unique_ptr<TimeIntegrator> make_time_integrator(const IntegratorSpec& s) {
  if (s.type == "newmark") return make_newmark(s.beta, s.gamma);
  if (s.type == "generalized_alpha") return make_generalized_alpha(s.rho_inf);
  return make_central_difference();
}

std::unique_ptr<TimeIntegrator> make_time_integrator(const Params& p) {
  return make_time_integrator(read_integrator(p));
}

}  // namespace lagfsi
