#pragma once
/// @file dem/dem_contact_law.hpp
/// Contact laws of the DEM body: one interface (ContactLaw), one class per law. A law turns the kinematics of
/// one contact (disc-disc, or disc-wall with the wall of infinite mass) into a normal and a tangential force.
///
/// Conventions (2D, discs i and j, or disc i and a wall point):
///   n = (c_i - c_j)/|c_i - c_j|, t = (-n_y, n_x), overlap x = r_i + r_j - |c_i - c_j| > 0,
///   rate  dx/dt = -(v_i - v_j).n,
///   vt = (v_i - v_j).t - (r_i w_i + r_j w_j)   (relative sliding velocity at the contact point),
///   force on i: F = fn n + ft t (fn > 0 repulsive), on j: -F; torques: T_i = -r_i ft, T_j = -r_j ft.
/// m_eff = m_i m_j/(m_i + m_j) (m_i on a wall), r_eff = r_i r_j/(r_i + r_j) (r_i on a wall).
///
/// Laws:
///  - LinearSpringDashpot: fn = kn x + cn dx/dt (Cundall & Strack 1979), cn = 2 zeta sqrt(m_eff kn); zeta from a
///    damping ratio, or from a restitution coefficient e: zeta = -ln e / sqrt(pi^2 + ln^2 e) (then e is exact
///    for an unclamped contact: e = exp(-zeta pi / sqrt(1 - zeta^2))), or cn = m_eff gamma_n (LAMMPS gran/hooke).
///  - HertzMindlin: fn = 4/3 E* sqrt(R*) x^(3/2) + alpha sqrt(m_eff 4/3 E* sqrt(R*)) x^(1/4) dx/dt (Hertz 1882;
///    damping of Tsuji, Tanaka & Ishida 1992, whose restitution does not depend on the impact speed; alpha(e) is
///    found here by integrating the dimensionless impact X'' = -X^(3/2) - alpha X^(1/4) X' and bisection);
///    tangential stiffness kt = 8 G* sqrt(R* x) (Mindlin 1949), tangential damping alpha sqrt(m_eff kt).
///    E* = E/(2(1 - nu^2)) between equal discs, E/(1 - nu^2) on a rigid wall; G* = G/(2(2 - nu)), G/(2 - nu).
///  - Sabatucci: the normal model proposed by Sabatucci et al. (CILAMCE 2013, Eq. 8): delta = x / min(r_i, r_j);
///    loading (dx/dt >= 0): kn x (delta < 0.1), lambda kn x (0.1 <= delta < 0.7), lambda^2 kn x (delta >= 0.7,
///    the lambda^2 branch kept beyond 0.9), plus cn dx/dt, cn = 2 zeta sqrt(m_eff kn) (zeta = 0.01, base kn);
///    unloading: kn x + cn dx/dt, and 0 when either disc is marked "ruptured" (marked once a contact of it reached
///    delta >= 0.7). "continuous": true replaces the literal bands (force jumps x50 at 0.1 and 0.7) by a
///    continuous piecewise linear loading curve with the same slopes (a deviation from the paper, flagged).
///    fn >= 0 (no attraction). Tangential: Haff & Werner (1986).
/// Tangential models (shared by the laws):
///  - "coulomb": a tangential spring with history xi (xi += vt dt), ft = -kt xi - ct vt, limited to mu |fn|
///    (then xi is reset to the spring length that gives the limit, as LAMMPS gran/*/history does);
///  - "haff_werner": ft = -min(mu |fn|, gamma_t m_eff |vt|) sign(vt), no history (Haff & Werner 1986);
///  - "none".
/// Rolling resistance (optional, linear and Hertz-Mindlin laws, "rolling_friction" mu_r > 0; a constant-torque
/// model, Ai, Chen, Rotter & Ooi 2011 type A): a torque M = -min(mu_r r_eff |fn|, I_eff |w_rel| / (2 dt))
/// sign(w_rel) on i and -M on j, w_rel = w_i - w_j (w_i on a wall), I_eff = I_i I_j / (I_i + I_j); the cap keeps
/// the torque from reversing w_rel within one step (no chatter at rest).
#include <lagfsi/params.hpp>

#include <cmath>
#include <memory>
#include <string>

namespace lagfsi::dem {

/// The kinematics of one contact at the force evaluation (see the conventions above).
struct ContactKinematics {
  double overlap = 0;  ///< x > 0
  double rate = 0;     ///< dx/dt
  double vt = 0;       ///< sliding velocity at the contact point
  double m_eff = 0, r_eff = 0, r_min = 0;
  double dt = 0;        ///< the time step (the tangential history advances by vt dt)
  bool wall = false;    ///< j is a rigid wall
  bool marked = false;  ///< either disc is marked ruptured (Sabatucci law)
};

/// What a law returns: forces, and for the energy balance the elastic energy stored in the contact after the
/// step and the energy dissipated during it.
struct ContactForce {
  double fn = 0, ft = 0;
  bool rupture = false;  ///< the contact reached the rupture overlap (Sabatucci law): mark both discs
  double elastic = 0, dissipated = 0;
};

enum class TangentialModel { None, Coulomb, HaffWerner };

/// The tangential part shared by the laws.
struct Tangential {
  TangentialModel model = TangentialModel::None;
  double mu = 0;             ///< Coulomb friction coefficient
  double haff_werner = 100;  ///< gamma_t [1/s] of Haff & Werner

  /// Tangential force for the normal force fn, stiffness kt and damping ct (coulomb), history xi (in/out).
  inline double force(double fn, double kt, double ct, const ContactKinematics& k, double& xi, double& elastic,
                      double& dissipated) const {
    if (model == TangentialModel::Coulomb) {
      xi += k.vt * k.dt;
      double ft = -kt * xi - ct * k.vt;
      const double limit = mu * std::abs(fn);
      dissipated += ct * k.vt * k.vt * k.dt;
      if (std::abs(ft) > limit) {
        const double e0 = 0.5 * kt * xi * xi;
        ft = std::copysign(limit, ft);
        xi = kt > 0 ? -(ft + ct * k.vt) / kt : 0.0;
        dissipated += e0 - 0.5 * kt * xi * xi;
      }
      elastic += 0.5 * kt * xi * xi;
      return ft;
    }
    if (model == TangentialModel::HaffWerner) {
      const double a = std::abs(k.vt);
      const double ft = std::min(mu * std::abs(fn), haff_werner * k.m_eff * a);
      dissipated += ft * a * k.dt;
      return k.vt > 0 ? -ft : (k.vt < 0 ? ft : 0.0);
    }
    return 0.0;
  }
  bool has_history() const { return model == TangentialModel::Coulomb; }
};

/// What every law offers.
class ContactLaw {
 public:
  virtual ~ContactLaw() = default;
  virtual std::string type() const = 0;
  /// Forces of one contact; `history` is the contact's tangential spring length (kept between steps).
  virtual ContactForce evaluate(const ContactKinematics& k, double& history) const = 0;
  /// The largest angular frequency sqrt(k/m) a contact of two discs of mass m and radius r (or of such a disc
  /// on a wall) can have, with rotation (inertia I = inertia_factor m r^2) or without; the critical step of the
  /// central difference is 2/omega.
  virtual double max_frequency(double m, double r, double inertia_factor, bool rotation) const = 0;
  const Tangential& tangential() const { return tangential_; }
  bool has_history() const { return tangential_.has_history(); }
  /// Rolling friction coefficient mu_r (0: none).
  double rolling() const { return rolling_; }
  void set_rolling(double mu_r) { rolling_ = mu_r; }
  /// The rolling-resistance torque on i for w_rel, normal force fn, effective inertia and step h.
  inline double rolling_torque(double w_rel, double fn, double r_eff, double i_eff, double h) const {
    if (w_rel == 0.0 || !(h > 0)) return 0.0;
    const double m = std::min(rolling_ * r_eff * std::abs(fn), 0.5 * i_eff * std::abs(w_rel) / h);
    return w_rel > 0 ? -m : m;
  }

 protected:
  Tangential tangential_;
  double rolling_ = 0;
};

/// Linear spring-dashpot with a Coulomb tangential spring (or Haff-Werner).
class LinearSpringDashpot final : public ContactLaw {
 public:
  /// damping: cn = 2 zeta sqrt(m_eff kn) (gamma_n = 0) or cn = m_eff gamma_n (gamma_n > 0; zeta ignored);
  /// tangential: kt = kt_ratio kn, ct = 2 zeta_t sqrt(m_eff kt) or m_eff gamma_t.
  LinearSpringDashpot(double kn, double zeta, double gamma_n, double kt_ratio, double zeta_t, double gamma_t,
                      Tangential tangential, bool no_attraction);
  std::string type() const override { return "linear"; }
  ContactForce evaluate(const ContactKinematics& k, double& history) const override { return compute(k, history); }
  double max_frequency(double m, double r, double inertia_factor, bool rotation) const override;

  inline ContactForce compute(const ContactKinematics& k, double& xi) const {
    ContactForce f;
    const double sm = std::sqrt(k.m_eff);
    const double cn = gamma_n_ > 0 ? k.m_eff * gamma_n_ : two_zeta_sqrt_kn_ * sm;
    f.fn = kn_ * k.overlap + cn * k.rate;
    if (no_attraction_ && f.fn < 0) f.fn = 0;
    f.elastic = 0.5 * kn_ * k.overlap * k.overlap;
    f.dissipated = cn * k.rate * k.rate * k.dt;
    if (tangential_.model != TangentialModel::None) {
      const double ct = gamma_t_ > 0 ? k.m_eff * gamma_t_ : two_zeta_t_sqrt_kt_ * sm;
      f.ft = tangential_.force(f.fn, kt_, ct, k, xi, f.elastic, f.dissipated);
    }
    return f;
  }
  double kn() const { return kn_; }

 private:
  double kn_, kt_, gamma_n_, gamma_t_, two_zeta_sqrt_kn_, two_zeta_t_sqrt_kt_;
  bool no_attraction_;
};

/// Hertz-Mindlin with Tsuji damping and a Coulomb tangential spring.
class HertzMindlin final : public ContactLaw {
 public:
  /// young, poisson, density of the discs (walls rigid); restitution e in (0, 1] (1: no damping).
  HertzMindlin(double young, double poisson, double density, double restitution, Tangential tangential,
               bool no_attraction);
  std::string type() const override { return "hertz_mindlin"; }
  ContactForce evaluate(const ContactKinematics& k, double& history) const override { return compute(k, history); }
  /// 2 / (the Rayleigh time step pi r sqrt(rho/G) / (0.1631 nu + 0.8766)) (Thornton 2015); the Hertz stiffness
  /// grows with the overlap, so sqrt(k/m) has no fixed value.
  double max_frequency(double m, double r, double inertia_factor, bool rotation) const override;
  /// The dimensionless damping alpha of Tsuji et al. for a restitution e (0 < e <= 1).
  static double tsuji_alpha(double restitution);

  inline ContactForce compute(const ContactKinematics& k, double& xi) const {
    ContactForce f;
    const double es = k.wall ? e_wall_ : e_pair_, gs = k.wall ? g_wall_ : g_pair_;
    const double a = std::sqrt(k.r_eff * k.overlap);   // contact radius
    const double kn_t = 2.0 * es * a;                  // dF/dx = 2 E* sqrt(R* x)
    const double fe = (2.0 / 3.0) * kn_t * k.overlap;  // 4/3 E* sqrt(R*) x^(3/2)
    // Tsuji: alpha sqrt(m K) x^(1/4) = alpha sqrt(m_eff fe / x)
    const double cn = alpha_ > 0 ? alpha_ * std::sqrt(k.m_eff * fe / k.overlap) : 0.0;
    f.fn = fe + cn * k.rate;
    if (no_attraction_ && f.fn < 0) f.fn = 0;
    f.elastic = 0.4 * fe * k.overlap;
    f.dissipated = cn * k.rate * k.rate * k.dt;
    if (tangential_.model != TangentialModel::None) {
      const double kt = 8.0 * gs * a;
      const double ct = alpha_ > 0 ? alpha_ * std::sqrt(k.m_eff * kt) : 0.0;
      f.ft = tangential_.force(f.fn, kt, ct, k, xi, f.elastic, f.dissipated);
    }
    return f;
  }
  double alpha() const { return alpha_; }

 private:
  double e_pair_, e_wall_, g_pair_, g_wall_, alpha_, density_, shear_, poisson_;
  bool no_attraction_;
};

/// The normal model of Sabatucci et al. (2013) with Haff-Werner friction.
class Sabatucci final : public ContactLaw {
 public:
  /// bands: delta limits (0.1, 0.7) of the lambda and lambda^2 branches; rupture at delta >= rupture (0.7).
  Sabatucci(double kn, double zeta, double lambda, double band1, double band2, double rupture, bool continuous,
            Tangential tangential);
  std::string type() const override { return "sabatucci"; }
  ContactForce evaluate(const ContactKinematics& k, double& history) const override { return compute(k, history); }
  /// With the stiffest branch lambda^2 kn.
  double max_frequency(double m, double r, double inertia_factor, bool rotation) const override;

  inline ContactForce compute(const ContactKinematics& k, double& xi) const {
    ContactForce f;
    const double cn = two_zeta_sqrt_kn_ * std::sqrt(k.m_eff);
    const double x = k.overlap, delta = x / k.r_min;
    if (k.rate >= 0) {  // loading
      double fe;
      if (!continuous_) {
        fe = (delta < band1_ ? kn_ : delta < band2_ ? lambda_ * kn_ : lambda2_ * kn_) * x;
      } else {
        const double x1 = band1_ * k.r_min, x2 = band2_ * k.r_min;
        fe = x < x1   ? kn_ * x
             : x < x2 ? kn_ * x1 + lambda_ * kn_ * (x - x1)
                      : kn_ * x1 + lambda_ * kn_ * (x2 - x1) + lambda2_ * kn_ * (x - x2);
      }
      f.fn = fe + cn * k.rate;
      f.rupture = delta >= rupture_;
    } else {
      f.fn = k.marked ? 0.0 : kn_ * x + cn * k.rate;
    }
    if (f.fn < 0) f.fn = 0;
    f.elastic = k.marked ? 0.0 : 0.5 * kn_ * x * x;  // what unloading can give back
    f.dissipated = cn * k.rate * k.rate * k.dt;
    f.ft = tangential_.force(f.fn, 0.0, 0.0, k, xi, f.elastic, f.dissipated);
    return f;
  }

 private:
  double kn_, two_zeta_sqrt_kn_, lambda_, lambda2_, band1_, band2_, rupture_;
  bool continuous_;
};

/// Builds the law of a body from its "contact" object (validated here; JSON-path errors). young, poisson and
/// density come from the body's "material".
std::unique_ptr<ContactLaw> make_contact_law(Params contact, double young, double poisson, double density);

}  // namespace lagfsi::dem
