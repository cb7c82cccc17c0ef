// EFG materials and path following (docs/theory/efg.md): Mazars' uniaxial peak (E kappa0) and residual stress, the
// exponential damage law, the smeared crack's tensile strength and fracture energy per unit band, the tangent
// against central differences of the stress, rollback (the committed history is never changed by an evaluation),
// and the generalized-displacement direction flip at a limit point.
#include <lagfsi/efg/material.hpp>
#include <lagfsi/efg/path_following.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <type_traits>
#include <vector>

using namespace lagfsi;
using namespace lagfsi::efg;

namespace {
std::unique_ptr<Material> law(const Json& j) { return make_material(Params(j, "m.json", "/material")); }

/// Uniaxial stress path: eps_yy from sigma_yy = 0 by Newton (plane stress), returns sigma_xx at eps_xx.
double uniaxial(const Material& m, double exx, History& h0) {
  Vec3 e(exx, -m.poisson() * exx, 0), s;
  Mat3 E;
  History h1;
  for (int it = 0; it < 50; ++it) {
    m.evaluate(e, h0, h1, s, E, Operator::tangent);
    if (std::abs(s[1]) < 1e-12 * (1 + std::abs(s[0]))) break;
    e[1] -= s[1] / E(1, 1);
  }
  h0 = h1;
  return s[0];
}
}  // namespace

static_assert(std::is_base_of_v<MaterialLaw, Material>, "the EFG laws are material laws");

TEST(EfgMaterial, EachLawNamesTheEntriesOfItsHistory) {
  EXPECT_TRUE(law({{"type", "linear_elastic"}, {"young", 2e4}, {"poisson", 0.2}})->state_variables().empty());
  const auto m = law({{"type", "exponential_damage"},
                      {"young", 2e4},
                      {"poisson", 0.2},
                      {"kappa0", 1e-4},
                      {"alpha", 0.99},
                      {"beta", 1e4}});
  ASSERT_EQ(m->state_variables(), (std::vector<std::string>{"kappa", "damage"}));
  History h;
  uniaxial(*m, 3e-4, h);  // past the peak (kappa0 = 1e-4): kappa and the damage grew
  EXPECT_GT(h.h[0], 1e-4);
  EXPECT_EQ(h.h[1], m->damage(h));
  EXPECT_GT(h.h[1], 0.0);
  const auto c = law({{"type", "smeared_crack"},
                      {"young", 25850.0},
                      {"poisson", 0.18},
                      {"ft", 2.7},
                      {"fc", 31.0},
                      {"Gf", 0.065},
                      {"band_width", 28.0}});
  const std::vector<std::string> names = c->state_variables();
  ASSERT_EQ(names.size(), 3u);
  EXPECT_EQ(names[2], "tension_damage");
  History hc;
  uniaxial(*c, 5e-4, hc);  // cracked in tension
  EXPECT_EQ(hc.h[2], c->damage(hc));
  EXPECT_GT(hc.h[2], 0.0);
}

TEST(EfgMaterial, MazarsUniaxialPeakAndResidual) {
  const auto m = law({{"type", "mazars"},
                      {"young", 2e4},
                      {"poisson", 0.2},
                      {"At", 0.95},
                      {"Bt", 1e4},
                      {"Ac", 1.0},
                      {"Bc", 3e3},
                      {"kappa0", 1e-4}});
  History h;
  double peak = 0, e_peak = 0;
  for (int i = 1; i <= 400; ++i) {
    const double e = i * 2.5e-6, s = uniaxial(*m, e, h);
    if (s > peak) {
      peak = s;
      e_peak = e;
    }
  }
  EXPECT_NEAR(peak, 2.0, 1e-3);  // E kappa0 (B_t kappa0 = 1: horizontal tangent at the peak)
  EXPECT_NEAR(e_peak, 1e-4, 5e-6);
  History far;
  const double s_far = uniaxial(*m, 5e-2, far);
  EXPECT_NEAR(s_far, 0.1, 2e-3);  // residual E kappa0 (1 - A_t)
}

TEST(EfgMaterial, ExponentialDamageLaw) {
  const auto m = law({{"type", "exponential_damage"},
                      {"young", 2e4},
                      {"poisson", 0.0},
                      {"alpha", 1.0},
                      {"beta", 1500.0},
                      {"kappa0", 1e-4}});
  History h0, h1;
  Vec3 s;
  Mat3 E;
  const double k = 3e-4;
  m->evaluate(Vec3(k, 0, 0), h0, h1, s, E, Operator::secant);
  const double D = 1 - 1e-4 / k * std::exp(-1500 * (k - 1e-4));
  EXPECT_NEAR(m->damage(h1), D, 1e-12);
  EXPECT_NEAR(s[0], (1 - D) * 2e4 * k, 1e-10);
}

TEST(EfgMaterial, SmearedCrackStrengthAndFractureEnergy) {
  const double ft = 2.7, E = 25850, Gf = 0.065, h = 28;
  const auto m = law({{"type", "smeared_crack"},
                      {"young", E},
                      {"poisson", 0.0},
                      {"ft", ft},
                      {"fc", 31.0},
                      {"Gf", Gf},
                      {"band_width", h},
                      {"residual", 0.0}});
  History hist;
  double peak = 0, work = 0, e_prev = 0, s_prev = 0;
  for (int i = 1; i <= 20000; ++i) {
    const double e = i * 1e-6;
    Vec3 s;
    Mat3 Es;
    History h1;
    m->stress(Vec3(e, 0, 0), hist, h1, s, Es);
    hist = h1;
    peak = std::max(peak, s[0]);
    work += 0.5 * (s[0] + s_prev) * (e - e_prev);
    e_prev = e;
    s_prev = s[0];
  }
  EXPECT_NEAR(peak, ft, 5e-3);
  EXPECT_NEAR(work, Gf / h, 0.01 * Gf / h);  // energy per unit volume of the band = G_f / h (crack band)
}

TEST(EfgMaterial, TangentMatchesDifferencesAndEvaluationNeverChangesTheCommittedHistory) {
  for (const Json& j : {Json{{"type", "mazars"},
                             {"young", 2e4},
                             {"poisson", 0.2},
                             {"At", 0.95},
                             {"Bt", 1e4},
                             {"Ac", 1.0},
                             {"Bc", 3e3},
                             {"kappa0", 1e-4}},
                        Json{{"type", "smeared_crack"},
                             {"young", 25850.0},
                             {"poisson", 0.18},
                             {"ft", 2.7},
                             {"fc", 31.0},
                             {"Gf", 0.065},
                             {"band_width", 28.0}}}) {
    const auto m = law(j);
    History h0;
    h0.h = {1.5 * m->strain_scale(), 0.0, 0.0};
    if (m->type() == "mazars") h0.h[1] = 0.3;
    const History saved = h0;
    const Vec3 e(3.1 * m->strain_scale(), -0.4 * m->strain_scale(), 1.3 * m->strain_scale());
    History h1;
    Vec3 s;
    Mat3 Et;
    m->evaluate(e, h0, h1, s, Et, Operator::tangent);
    for (int k = 0; k < 3; ++k) {
      const double d = 1e-4 * m->strain_scale();
      Vec3 ep = e, em = e, sp, sm;
      ep[k] += d;
      em[k] -= d;
      Mat3 X;
      History t;
      m->stress(ep, h0, t, sp, X);
      m->stress(em, h0, t, sm, X);
      const Vec3 col = (sp - sm) / (2 * d);
      EXPECT_LT((Et.col(k) - col).norm(), 1e-3 * m->young()) << m->type() << " column " << k;
    }
    EXPECT_EQ(h0.h, saved.h) << m->type();
    EXPECT_GE(h1.h[0], h0.h[0]) << m->type();
  }
}

TEST(EfgPathFollowing, GeneralizedDisplacementFlipsAtALimitPoint) {
  PathFollowing pf(ControlType::generalized_displacement, 0.1, -1);
  Vec d(2);
  d << 1.0, 0.0;
  EXPECT_DOUBLE_EQ(pf.predictor(d, 1.0), 0.1);
  pf.commit(0.1 * d);
  Vec d2(2);
  d2 << 2.0, 0.0;  // softer: GSP = 1/2, smaller increment
  EXPECT_NEAR(pf.predictor(d2, 1.0), 0.1 * std::sqrt(0.5), 1e-15);
  pf.commit(d2);
  Vec d3(2);
  d3 << -4.0, 0.0;  // the tangent response reversed: past the limit point the load decreases
  EXPECT_LT(pf.predictor(d3, 1.0), 0.0);
  pf.commit(d3);
  Vec d4(2);
  d4 << -3.0, 0.0;  // still on the descending branch: keeps decreasing
  EXPECT_LT(pf.predictor(d4, 0.5), 0.0);
}
