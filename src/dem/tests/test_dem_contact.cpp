// Unit tests of the DEM contact laws (src/dem/include/lagfsi/dem/dem_contact_law.hpp), the neighbour grid against a
// brute-force search, the disc generators and the blast load formulas.
#include <gtest/gtest.h>

#include <lagfsi/dem/dem_blast.hpp>
#include <lagfsi/dem/dem_contact_law.hpp>
#include <lagfsi/dem/dem_neighbour_grid.hpp>
#include <lagfsi/dem/dem_particles.hpp>
#include <lagfsi/time_integrator.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <set>

namespace {

using namespace lagfsi;
using namespace lagfsi::dem;

Tangential coulomb(double mu) {
  Tangential t;
  t.model = TangentialModel::Coulomb;
  t.mu = mu;
  return t;
}

ContactKinematics kin(double x, double rate, double vt = 0, double m_eff = 0.5, double r = 0.01) {
  ContactKinematics k;
  k.overlap = x;
  k.rate = rate;
  k.vt = vt;
  k.m_eff = m_eff;
  k.r_eff = r / 2;
  k.r_min = r;
  k.dt = 1e-6;
  return k;
}

/// Rebound speed / impact speed of one contact (a mass m_eff on a spring), integrated with velocity Verlet
/// (the damping with the half-step velocity, as the model does) in steps of t_ref / 2000.
double restitution(const ContactLaw& law, double m, double v0, double t_ref) {
  const double h = t_ref / 2000;
  double x = 0, v = v0, hist = 0;  // x: overlap, v: its rate
  auto acc = [&](double xx, double vv) {
    ContactKinematics k = kin(xx, vv, 0, m);
    k.dt = h;
    return xx > 0 ? -law.evaluate(k, hist).fn / m : 0.0;
  };
  double a = 0;
  for (int n = 0; n < 1000000; ++n) {
    x += h * v + 0.5 * h * h * a;
    const double vh = v + 0.5 * h * a;
    const double an = acc(x, vh);
    v = vh + 0.5 * h * an;
    a = an;
    if (x <= 0 && n > 0) return -v / v0;
  }
  return -1;
}

TEST(DemContact, LinearForceOverlapAndDamping) {
  const double kn = 1e5, zeta = 0.2;
  LinearSpringDashpot law(kn, zeta, 0, 2.0 / 7.0, 0, 0, Tangential{}, false);
  double h = 0;
  const auto k = kin(1e-4, 0.3, 0, 0.5);
  const ContactForce f = law.evaluate(k, h);
  EXPECT_NEAR(f.fn, kn * 1e-4 + 2 * zeta * std::sqrt(0.5 * kn) * 0.3, 1e-9);
  EXPECT_EQ(f.ft, 0.0);
  // unclamped: attraction allowed while separating fast; clamped: none
  EXPECT_LT(law.evaluate(kin(1e-6, -1.0), h).fn, 0.0);
  LinearSpringDashpot clamped(kn, zeta, 0, 2.0 / 7.0, 0, 0, Tangential{}, true);
  EXPECT_EQ(clamped.evaluate(kin(1e-6, -1.0), h).fn, 0.0);
}

TEST(DemContact, LinearRestitutionFromCoefficient) {
  for (double e : {0.2, 0.5, 0.9}) {
    const double l = std::log(e), zeta = -l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
    LinearSpringDashpot law(1e5, zeta, 0, 0, 0, 0, Tangential{}, false);
    const double m = 0.1, t_ref = std::numbers::pi * std::sqrt(m / 1e5);
    for (double v : {0.01, 1.0}) EXPECT_NEAR(restitution(law, m, v, t_ref), e, 2e-3 * e) << "e " << e << " v " << v;
  }
}

TEST(DemContact, CoulombSpringSticksThenSlides) {
  LinearSpringDashpot law(1e5, 0, 0, 0.5, 0, 0, coulomb(0.3), false);
  double xi = 0;
  auto k = kin(1e-4, 0, 0.01);  // fn = 10 N, sliding 0.01 m/s
  k.dt = 1e-4;
  ContactForce f = law.evaluate(k, xi);
  EXPECT_NEAR(xi, 1e-6, 1e-18);             // stick: the spring stretched by vt dt
  EXPECT_NEAR(f.ft, -0.5e5 * 1e-6, 1e-12);  // -kt xi
  for (int n = 0; n < 100; ++n) f = law.evaluate(k, xi);
  EXPECT_NEAR(f.ft, -0.3 * 10.0, 1e-9);  // slide: the Coulomb limit
  EXPECT_NEAR(xi, 3.0 / 0.5e5, 1e-15);   // the spring reset to the limit
}

TEST(DemContact, HertzForceOverlapAndRestitution) {
  const double E = 7e10, nu = 0.3, rho = 2700;
  HertzMindlin elastic(E, nu, rho, 1.0, Tangential{}, false);
  double h = 0;
  auto k = kin(1e-5, 0, 0, 1.0, 0.01);
  k.r_eff = 0.005;
  const double estar = E / (2 * (1 - nu * nu));
  EXPECT_NEAR(elastic.evaluate(k, h).fn, 4.0 / 3.0 * estar * std::sqrt(0.005) * std::pow(1e-5, 1.5), 1e-6);
  k.wall = true;
  EXPECT_NEAR(elastic.evaluate(k, h).fn, 4.0 / 3.0 * 2 * estar * std::sqrt(0.005) * std::pow(1e-5, 1.5), 1e-6);
  EXPECT_EQ(HertzMindlin::tsuji_alpha(1.0), 0.0);
  for (double e : {0.3, 0.7}) {
    HertzMindlin law(E, nu, rho, e, Tangential{}, false);
    // contact time scale at 1 m/s for m = 1 kg, K = 4/3 E* sqrt(R)
    for (double v : {0.02, 2.0}) {
      const double K = 4.0 / 3.0 * estar * std::sqrt(0.005);
      const double dmax = std::pow(5.0 * v * v / (4.0 * K), 0.4);  // m = 1 kg
      const double tc = 3 * dmax / v;
      const double r = [&] {
        const double hh = tc / 4000;
        double x = 0, vel = v, a = 0, hist = 0;
        for (int n = 0; n < 100000; ++n) {
          x += hh * vel + 0.5 * hh * hh * a;
          const double vh = vel + 0.5 * hh * a;
          ContactKinematics c = kin(x, vh, 0, 1.0, 0.01);
          c.r_eff = 0.005;
          const double an = x > 0 ? -law.evaluate(c, hist).fn : 0.0;
          vel = vh + 0.5 * hh * an;
          a = an;
          if (x <= 0 && n > 0) return -vel / v;
        }
        return -1.0;
      }();
      EXPECT_NEAR(r, e, 5e-3 * e) << "e " << e << " v " << v;
    }
  }
}

TEST(DemContact, SabatucciBandsRuptureAndUnloading) {
  const double kn = 2.75e4, lambda = 50;
  Sabatucci law(kn, 0.0, lambda, 0.1, 0.7, 0.7, false, Tangential{});
  double h = 0;
  const double r = 0.002;
  auto f = [&](double delta, double rate, bool marked) {
    ContactKinematics k = kin(delta * r, rate, 0, 0.0078, r);
    k.marked = marked;
    return law.evaluate(k, h);
  };
  EXPECT_NEAR(f(0.05, 1, false).fn, kn * 0.05 * r, 1e-12);
  EXPECT_NEAR(f(0.3, 1, false).fn, lambda * kn * 0.3 * r, 1e-9);
  EXPECT_NEAR(f(0.8, 1, false).fn, lambda * lambda * kn * 0.8 * r, 1e-6);
  EXPECT_NEAR(f(0.95, 1, false).fn, lambda * lambda * kn * 0.95 * r, 1e-6);  // beyond 0.9: the lambda^2 branch
  EXPECT_FALSE(f(0.69, 1, false).rupture);
  EXPECT_TRUE(f(0.7, 1, false).rupture);
  EXPECT_NEAR(f(0.3, -1, false).fn, kn * 0.3 * r, 1e-12);        // unloading: no lambda
  EXPECT_EQ(f(0.3, -1, true).fn, 0.0);                           // marked: no unloading force
  EXPECT_NEAR(f(0.3, 1, true).fn, lambda * kn * 0.3 * r, 1e-9);  // compression ignores the marks
  // the continuous variant: no jump at the band limits, slopes kn, lambda kn, lambda^2 kn
  Sabatucci cont(kn, 0.0, lambda, 0.1, 0.7, 0.7, true, Tangential{});
  auto g = [&](double delta) {
    ContactKinematics k = kin(delta * r, 1, 0, 0.0078, r);
    return cont.evaluate(k, h).fn;
  };
  for (double b : {0.1, 0.7}) EXPECT_NEAR(g(b - 1e-9), g(b + 1e-9), 1e-6 * g(b));
  EXPECT_NEAR((g(0.5) - g(0.4)) / (0.1 * r), lambda * kn, 1e-6 * lambda * kn);
}

TEST(DemContact, HaffWernerFriction) {
  Tangential t;
  t.model = TangentialModel::HaffWerner;
  t.mu = 0.2;
  t.haff_werner = 100;
  Sabatucci law(1e4, 0.0, 50, 0.1, 0.7, 0.7, false, t);
  double h = 0;
  ContactKinematics k = kin(1e-4, 1, 1e-3, 0.01, 0.002);          // delta 0.05: fn = 1 N
  EXPECT_NEAR(law.evaluate(k, h).ft, -100 * 0.01 * 1e-3, 1e-12);  // the viscous branch
  k.vt = -10;
  EXPECT_NEAR(law.evaluate(k, h).ft, 0.2 * 1.0, 1e-12);  // the Coulomb limit, against the sliding
}

TEST(DemNeighbourGrid, MatchesBruteForce) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1), ur(0.005, 0.02);
  for (int trial = 0; trial < 3; ++trial) {
    const int n = 1500;
    std::vector<double> x(3 * n), r(n);
    for (int p = 0; p < n; ++p) {
      x[3 * p] = u(rng) * (trial == 2 ? 3.0 : 1.0);
      x[3 * p + 1] = u(rng);
      r[p] = ur(rng);
    }
    const double skin = 0.004;
    NeighbourGrid g;
    g.bin(x.data(), 3, n, 2 * 0.02 + skin);
    PairList l;
    g.build(x.data(), 3, r.data(), n, skin, l);
    std::set<std::pair<Index, Index>> got;
    for (size_t k = 0; k < l.size(); ++k) got.insert({std::min(l.i[k], l.j[k]), std::max(l.i[k], l.j[k])});
    EXPECT_EQ(got.size(), l.size()) << "a pair listed twice";
    const auto ref = brute_force_pairs(x.data(), 3, r.data(), n, skin);
    const std::set<std::pair<Index, Index>> want(ref.begin(), ref.end());
    EXPECT_EQ(got, want);
    // incidence: every pair appears once for each of its discs
    EXPECT_EQ(l.inc.size(), 2 * l.size());
    for (Index p = 0; p < n; ++p)
      for (Index e = l.inc_row[p]; e < l.inc_row[p + 1]; ++e) {
        const Index k = l.inc[e] >> 1;
        EXPECT_EQ((l.inc[e] & 1) ? l.j[k] : l.i[k], p);
      }
  }
}

TEST(DemParticles, HexLatticeOfThePaperBed) {
  const std::vector<Vec2> box = {{0, 0}, {1.2, 0}, {1.2, 0.427}, {0, 0.427}};
  const auto d = hex_lattice(box, 0.002, 0.0);
  EXPECT_EQ(d.size(), 36839u);  // 62 rows of 300 and 61 of 299 (shared/spec/004_dem.md, Sec. 2.1)
  const auto rnd = random_pack(box, 0.002, 0.003, 0.3, 0, 3, 2000);
  double area = 0;
  for (size_t a = 0; a < rnd.size(); ++a) {
    area += std::numbers::pi * rnd[a].r * rnd[a].r;
    for (size_t b = a + 1; b < std::min(rnd.size(), a + 50); ++b)
      EXPECT_GE((rnd[a].x - rnd[b].x).norm(), rnd[a].r + rnd[b].r);
  }
  EXPECT_GE(area / (1.2 * 0.427), 0.3);
}

TEST(DemBlast, HenrychWuHaoAndArrival) {
  // shared/spec/004_dem.md Sec. 2.5: reference values
  EXPECT_NEAR(henrych_overpressure_kpa(0.5), 1640.4, 0.1);
  EXPECT_NEAR(henrych_overpressure_kpa(0.7), 841.1, 0.1);
  EXPECT_NEAR(henrych_overpressure_kpa(2.0), 175.4, 0.1);
  EXPECT_NEAR(henrych_overpressure_kpa(10.0), 11.0, 0.05);
  EXPECT_NEAR(wu_hao_duration(0.5, 1.0), 0.304e-3, 0.001e-3);
  EXPECT_NEAR(wu_hao_duration(0.781, 1.0), 0.418e-3, 0.001e-3);
  Blast b(Params(Json{{"charge_mass", 1.0}, {"position", {0.0, 0.5}}}, "test"));
  EXPECT_NEAR(b.arrival(0.5), 0.381e-3, 0.002e-3);
  EXPECT_NEAR(b.arrival(0.781), 0.870e-3, 0.005e-3);
}

TEST(DemBlast, ShadowingLoadsTheNearestDiscOnly) {
  Blast b(Params(Json{{"charge_mass", 1.0}, {"position", {0.0, 0.5}}}, "test"));
  // a disc below the charge, one hidden right behind it, one off to the side
  const double r = 0.002;
  std::vector<double> x = {0.0, 0.0, 0, 0.0, -0.01, 0, 0.3, 0.0, 0};
  std::vector<double> rad = {r, r, r};
  std::vector<double> f(6, 0.0);
  const double t = b.arrival(0.5) + 1e-6;
  b.apply(x.data(), 3, rad.data(), 3, t, f);
  const double alpha = std::asin(r / 0.5);
  EXPECT_NEAR(b.exposed()[0], r * (std::numbers::pi - 2 * alpha), 1e-12);  // the whole visible arc
  EXPECT_EQ(b.exposed()[1], 0.0);                                          // in the shadow
  EXPECT_GT(b.exposed()[2], 0.0);
  EXPECT_LT(f[1], 0.0);  // pushed down, away from the charge
  EXPECT_EQ(f[2], 0.0);
  EXPECT_EQ(f[3], 0.0);
  EXPECT_NEAR(f[1], -b.pressure(0.5, t) * b.exposed()[0], 1e-9);
}

// The exposure of the shadowing sweep against brute-force ray casting on a random loose pack: 200 000 rays from the
// charge; two consecutive rays that first meet the same disc load the width between their hit points, measured
// across the line from the charge to the disc's centre ("area": "projected", whose width has no singularity at
// the tangent points, unlike the arc).
TEST(DemBlast, ExposureMatchesRayCasting) {
  const Vec2 g(0.3, 0.5);
  Blast b(Params(Json{{"charge_mass", 1.0}, {"position", {g.x(), g.y()}}, {"area", "projected"}}, "test"));
  std::vector<double> rmin_rmax = {0.004, 0.012};
  const auto pack =
      random_pack({{0.0, 0.0}, {0.6, 0.0}, {0.6, 0.2}, {0.0, 0.2}}, rmin_rmax[0], rmin_rmax[1], 0.5, 0, 7, 2000);
  const int n = static_cast<int>(pack.size());
  ASSERT_GT(n, 100);
  std::vector<double> x(3 * n, 0.0), rad(n), f(2 * n, 0.0);
  for (int p = 0; p < n; ++p) {
    x[3 * p] = pack[p].x.x();
    x[3 * p + 1] = pack[p].x.y();
    rad[p] = pack[p].r;
  }
  b.apply(x.data(), 3, rad.data(), n, 0.0, f);
  // rays over the directions that can meet the pack (below the charge), each hitting its nearest disc at the
  // point P(phi); the loaded arc of a disc is the sum of the arcs between the hit points of consecutive rays
  std::vector<double> brute(n, 0.0);
  const int rays = 200000;
  const double a0 = -std::numbers::pi + 1e-6, a1 = -1e-6;
  int prev = -1;
  double prev_w = 0;  // offset of the previous hit point across the charge-centre line of its disc
  for (int k = 0; k <= rays; ++k) {
    const double a = a0 + (a1 - a0) * k / rays;
    const Vec2 u(std::cos(a), std::sin(a));
    int hit = -1;
    double best = 1e300;
    for (int p = 0; p < n; ++p) {
      const Vec2 c = Vec2(x[3 * p], x[3 * p + 1]) - g;
      const double proj = c.dot(u), perp2 = c.squaredNorm() - proj * proj, r2 = rad[p] * rad[p];
      if (perp2 >= r2 || proj <= 0) continue;
      const double s = proj - std::sqrt(r2 - perp2);
      if (s < best) {
        best = s;
        hit = p;
      }
    }
    double w = 0;
    if (hit >= 0) {
      const Vec2 c(x[3 * hit], x[3 * hit + 1]);
      const Vec2 e = (g - c).normalized();
      w = (g + best * u - c).dot(Vec2(-e.y(), e.x()));
      if (hit == prev) brute[hit] += std::abs(w - prev_w);
    }
    prev = hit;
    prev_w = w;
  }
  int exposed = 0;
  double total = 0, err = 0;
  for (int p = 0; p < n; ++p) {
    if (b.exposed()[p] > 0) ++exposed;
    total += brute[p];
    err += std::abs(b.exposed()[p] - brute[p]);
    EXPECT_NEAR(b.exposed()[p], brute[p], 0.01 * rad[p]) << "disc " << p;
  }
  EXPECT_GT(exposed, 10);
  EXPECT_LT(err, 3e-3 * total);  // each change of disc between two rays loses up to one ray spacing
}

// The non-allocating step of the shared central difference (time_integrator.hpp) that the DEM body uses equals
// explicit_step() up to rounding, with the half-step velocity handed to the force.
TEST(DemIntegrator, ExplicitStepIntoMatchesExplicitStep) {
  const auto cd = make_central_difference();
  const Vec k = (Vec(3) << 4.0, 9.0, 1.0).finished(), c = (Vec(3) << 0.1, 0.0, 0.2).finished();
  const Vec inv_mass = (Vec(3) << 1.0, 0.5, 2.0).finished();
  KinematicState a, b;
  a.x = b.x = (Vec(3) << 1.0, -0.5, 0.2).finished();
  a.v = b.v = (Vec(3) << 0.0, 0.3, -1.0).finished();
  a.a = b.a = inv_mass.cwiseProduct(-k.cwiseProduct(a.x));
  Vec f;
  Vec v_seen;
  for (int n = 0; n < 2000; ++n) {
    cd->explicit_step(
        [&](const Vec& x, const Vec& v, double) -> Vec { return Vec(-k.cwiseProduct(x) - c.cwiseProduct(v)); },
        inv_mass, 1e-3, a);
    const Vec v_half = b.v + 0.5e-3 * b.a;
    cd->explicit_step_into(
        [&](const Vec& x, const Vec& v, double, Vec& out) {
          v_seen = v;
          out = -k.cwiseProduct(x) - c.cwiseProduct(v);
        },
        inv_mass, 1e-3, b, f);
    ASSERT_LT((v_seen - v_half).norm(), 1e-14);
  }
  EXPECT_LT((a.x - b.x).norm(), 1e-12);
  EXPECT_LT((a.v - b.v).norm(), 1e-12);
  EXPECT_NEAR(a.t, b.t, 1e-12);
  EXPECT_THROW(make_newmark()->explicit_step_into([](const Vec&, const Vec&, double, Vec&) {}, inv_mass, 1e-3, b, f),
               std::logic_error);
}

}  // namespace
