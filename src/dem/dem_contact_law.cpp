// Contact laws of the DEM body (src/dem/include/lagfsi/dem/dem_contact_law.hpp): constructors, the critical
// frequencies, Tsuji's damping constant from a restitution coefficient, and reading a law from the case file.
#include <lagfsi/dem/dem_contact_law.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace lagfsi::dem {

namespace {

const char* const kFrictionDoc = "Friction coefficient mu of the tangential force (|ft| <= mu |fn|).";
const char* const kTangentialDoc =
    "Tangential model: coulomb (a spring with history, limited by friction), haff_werner (viscous, limited by "
    "friction) or none; with friction 0 the default model is off.";
const char* const kHaffWernerDoc = "Viscous coefficient of the haff_werner tangential model (1/s).";
const char* const kNoAttractionDoc = "Clamp the normal force at 0 (the dashpot does not pull).";
const char* const kRollingDoc = "Rolling friction coefficient (0: none).";

const KeyTable kLinearKeys("/bodies/*/contact (dem body, law linear)",
                           "Linear spring-dashpot (Cundall and Strack): fn = kn x + cn dx/dt.",
                           {{"law", "linear", "`linear`."},
                            {"kn", nullptr, "Normal stiffness (N/m per m of depth)."},
                            {"damping", "ratio",
                             "How cn is given: ratio (damping_ratio), restitution or viscous (gamma_n)."},
                            {"damping_ratio", 0.0, "Normal damping ratio zeta, below 1."},
                            {"restitution", 1.0, "Restitution coefficient e, in (0, 1]."},
                            {"gamma_n", 0.0, "Viscous damping: cn = m_eff gamma_n (1/s)."},
                            {"kt_ratio", 2.0 / 7.0, "Tangential stiffness over normal stiffness."},
                            {"tangential_damping_ratio", 0.0, "Tangential damping ratio."},
                            {"gamma_t", 0.0, "Tangential viscous damping: ct = m_eff gamma_t (1/s)."},
                            {"friction", 0.0, kFrictionDoc},
                            {"tangential", "coulomb", kTangentialDoc},
                            {"haff_werner_gamma", 100.0, kHaffWernerDoc},
                            {"no_attraction", false, kNoAttractionDoc},
                            {"rolling_friction", 0.0, kRollingDoc}});

const KeyTable kHertzMindlinKeys(
    "/bodies/*/contact (dem body, law hertz_mindlin)",
    "Hertz normal force with Mindlin tangential stiffness and Tsuji damping (needs material.young).",
    {{"law", "hertz_mindlin", "`hertz_mindlin`."},
     {"restitution", 1.0, "Restitution coefficient e, in (0.01, 1]."},
     {"friction", 0.0, kFrictionDoc},
     {"tangential", "coulomb", kTangentialDoc},
     {"haff_werner_gamma", 100.0, kHaffWernerDoc},
     {"no_attraction", false, kNoAttractionDoc},
     {"rolling_friction", 0.0, kRollingDoc}});

const KeyTable kSabatucciKeys(
    "/bodies/*/contact (dem body, law sabatucci)",
    "The banded normal law of Sabatucci et al. (2013) with rupture, Haff-Werner tangential force.",
    {{"law", "sabatucci", "`sabatucci`."},
     {"kn", nullptr, "Base normal stiffness (N/m per m of depth)."},
     {"damping_ratio", 0.01, "Normal damping ratio zeta."},
     {"lambda", 50.0, "Stiffness factor of the bands: lambda kn, then lambda^2 kn."},
     {"bands", Json::array({0.1, 0.7}), "Relative overlaps [b1, b2] where the lambda and lambda^2 branches start."},
     {"rupture", 0.7, "Relative overlap at which both discs are marked ruptured (no force when unloading)."},
     {"continuous", false, "A continuous piecewise linear loading curve instead of the literal bands."},
     {"friction", 0.2, kFrictionDoc},
     {"tangential", "haff_werner", kTangentialDoc},
     {"haff_werner_gamma", 100.0, kHaffWernerDoc}});

}  // namespace

namespace {

/// zeta of a linear spring-dashpot whose restitution (unclamped contact) is e.
double zeta_from_restitution(double e) {
  if (e >= 1.0) return 0.0;
  const double l = std::log(e);
  return -l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
}

/// Restitution of the dimensionless Hertz impact X'' = -X^(3/2) - alpha X^(1/4) X', X(0) = 0, X'(0) = 1,
/// integrated with RK4 until X returns to 0 (the contact ends; the force is not clamped).
double tsuji_restitution(double alpha) {
  auto acc = [alpha](double x, double v) {
    const double xp = std::max(x, 0.0);
    return -xp * std::sqrt(xp) - alpha * std::sqrt(std::sqrt(xp)) * v;
  };
  const double h = 2e-4;
  double x = 0, v = 1;
  for (int n = 0; n < 1000000; ++n) {
    const double k1x = v, k1v = acc(x, v);
    const double k2x = v + 0.5 * h * k1v, k2v = acc(x + 0.5 * h * k1x, v + 0.5 * h * k1v);
    const double k3x = v + 0.5 * h * k2v, k3v = acc(x + 0.5 * h * k2x, v + 0.5 * h * k2v);
    const double k4x = v + h * k3v, k4v = acc(x + h * k3x, v + h * k3v);
    const double xn = x + h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    const double vn = v + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    if (n > 0 && xn <= 0) {
      // linear interpolation of the velocity at the crossing
      const double s = x / (x - xn);
      return -(v + s * (vn - v));
    }
    if (vn >= 0 && xn <= 0) return 0.0;
    x = xn;
    v = vn;
  }
  return 0.0;
}

}  // namespace

LinearSpringDashpot::LinearSpringDashpot(double kn, double zeta, double gamma_n, double kt_ratio, double zeta_t,
                                         double gamma_t, Tangential tangential, bool no_attraction)
    : kn_(kn),
      kt_(kt_ratio * kn),
      gamma_n_(gamma_n),
      gamma_t_(gamma_t),
      two_zeta_sqrt_kn_(2 * zeta * std::sqrt(kn)),
      two_zeta_t_sqrt_kt_(2 * zeta_t * std::sqrt(kt_ratio * kn)),
      no_attraction_(no_attraction) {
  tangential_ = tangential;
}

double LinearSpringDashpot::max_frequency(double m, double, double inertia_factor, bool rotation) const {
  // two equal discs: the relative motion has m_eff = m/2; sliding with rotation has 1/m_t = (1 + 1/f)/m_eff
  double k = kn_;
  if (tangential_.model == TangentialModel::Coulomb)
    k = std::max(k, kt_ * (rotation ? 1.0 + 1.0 / inertia_factor : 1.0));
  return std::sqrt(k / (0.5 * m));
}

HertzMindlin::HertzMindlin(double young, double poisson, double density, double restitution, Tangential tangential,
                           bool no_attraction)
    : density_(density), poisson_(poisson), no_attraction_(no_attraction) {
  const double g = young / (2 * (1 + poisson));
  shear_ = g;
  e_wall_ = young / (1 - poisson * poisson);
  e_pair_ = 0.5 * e_wall_;
  g_wall_ = g / (2 - poisson);
  g_pair_ = 0.5 * g_wall_;
  alpha_ = tsuji_alpha(restitution);
  tangential_ = tangential;
}

double HertzMindlin::tsuji_alpha(double e) {
  if (e >= 1.0) return 0.0;
  double lo = 0, hi = 1;
  while (tsuji_restitution(hi) > e && hi < 1e3) hi *= 2;
  for (int it = 0; it < 60 && hi - lo > 1e-10 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (tsuji_restitution(mid) > e ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double HertzMindlin::max_frequency(double, double r, double, bool) const {
  const double dt_rayleigh = std::numbers::pi * r * std::sqrt(density_ / shear_) / (0.1631 * poisson_ + 0.8766);
  return 2.0 / dt_rayleigh;
}

Sabatucci::Sabatucci(double kn, double zeta, double lambda, double band1, double band2, double rupture, bool continuous,
                     Tangential tangential)
    : kn_(kn),
      two_zeta_sqrt_kn_(2 * zeta * std::sqrt(kn)),
      lambda_(lambda),
      lambda2_(lambda * lambda),
      band1_(band1),
      band2_(band2),
      rupture_(rupture),
      continuous_(continuous) {
  tangential_ = tangential;
}

double Sabatucci::max_frequency(double m, double, double, bool) const {
  return std::sqrt(std::max(lambda2_, 1.0) * kn_ / (0.5 * m));
}

namespace {

Tangential read_tangential(Params c, const std::string& deflt) {
  Tangential t;
  const std::string m = c.choice("tangential", {"coulomb", "haff_werner", "none"});
  t.mu = c.non_negative("friction");
  t.haff_werner = c.non_negative("haff_werner_gamma");
  t.model = m == "coulomb"       ? TangentialModel::Coulomb
            : m == "haff_werner" ? TangentialModel::HaffWerner
                                 : TangentialModel::None;
  if (t.mu == 0 && m != "none" && c.json().at("tangential") == deflt) t.model = TangentialModel::None;
  return t;
}

}  // namespace

std::unique_ptr<ContactLaw> make_contact_law(Params c, double young, double poisson, double density) {
  if (!c.json().is_object()) c.fail("expected an object");
  if (!c.has("law")) c.fail("law", "required key is missing");
  const std::string law = c.choice("law", {"linear", "hertz_mindlin", "sabatucci"});
  if (law == "linear") {
    c.validate(kLinearKeys);
    const double kn = c.positive("kn");
    const std::string d = c.choice("damping", {"ratio", "restitution", "viscous"});
    double zeta = 0, gamma_n = 0;
    if (d == "ratio") {
      zeta = c.non_negative("damping_ratio");
      if (zeta >= 1) c.fail("damping_ratio", "must be below 1 (critical damping)");
    } else if (d == "restitution") {
      const double e = c.number("restitution");
      if (!(e > 0 && e <= 1)) c.fail("restitution", "must lie in (0, 1]");
      zeta = zeta_from_restitution(e);
    } else {
      gamma_n = c.positive("gamma_n");
    }
    const double ztr = c.non_negative("tangential_damping_ratio");
    const double gt = c.non_negative("gamma_t");
    auto law = std::make_unique<LinearSpringDashpot>(kn, zeta, gamma_n, c.non_negative("kt_ratio"), ztr, gt,
                                                     read_tangential(c, "coulomb"), c.boolean("no_attraction"));
    law->set_rolling(c.non_negative("rolling_friction"));
    return law;
  }
  if (law == "hertz_mindlin") {
    c.validate(kHertzMindlinKeys);
    const double e = c.number("restitution");
    if (!(e > 0.01 && e <= 1)) c.fail("restitution", "must lie in (0.01, 1]");
    if (!(young > 0)) c.fail("law", "hertz_mindlin needs the body's material.young > 0");
    auto law = std::make_unique<HertzMindlin>(young, poisson, density, e, read_tangential(c, "coulomb"),
                                              c.boolean("no_attraction"));
    law->set_rolling(c.non_negative("rolling_friction"));
    return law;
  }
  c.validate(kSabatucciKeys);
  const auto bands = c.numbers("bands");
  if (bands.size() != 2 || !(bands[0] > 0 && bands[1] > bands[0]))
    c.fail("bands", "expected [b1, b2] with 0 < b1 < b2");
  const double zeta = c.non_negative("damping_ratio");
  if (zeta >= 1) c.fail("damping_ratio", "must be below 1 (critical damping)");
  Tangential t = read_tangential(c, "haff_werner");
  if (t.model == TangentialModel::Coulomb)
    c.fail("tangential", "the sabatucci law has no tangential spring: haff_werner or none");
  return std::make_unique<Sabatucci>(c.positive("kn"), zeta, c.positive("lambda"), bands[0], bands[1],
                                     c.positive("rupture"), c.boolean("continuous"), t);
}

}  // namespace lagfsi::dem
