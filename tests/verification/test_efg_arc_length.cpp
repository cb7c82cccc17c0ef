// Cylindrical arc length through a sharp snap-back: two springs in series, the model of the EFG defect
// beam's localisation in two dofs. Spring 1 (ground - dof 0) is a damage spring, stiffness K, exponential softening
// after e0: on loading its force is F(e) = K e (e <= e0), F(e) = K e0 exp(-(e - e0)/ef) (e > e0); it unloads with
// the secant stiffness (1 - d)K of its largest strain so far. Spring 2 (dof 0 - dof 1) is elastic, stiffness k; the
// load lambda P acts on dof 1. The loading path is known in closed form, parameterised by the strain e of spring 1:
//   lambda = F(e) / P,  u0 = e,  u1 = e + F(e) / k.
// Past the peak du1/de = 1 - F/(ef k): with ef k < K e0 the path snaps back, u1 falls from 11 (the peak) to its
// minimum 6.22 at F = ef k (K = e0 = P = 1, ef = 2, k = 0.1). The iterations use the secant operator, as the defect
// beam does; the driver below is EfgModel's step (predictor, corrector iterations, residual test) with the analysis
// driver's cut-back (the step retried from the converged state with half the increment, at most 4 times).
// Without a remedy the arc-length constraint has complex roots at the peak at every step length ("cut_back", the
// behaviour before the option existed): the run stops there. Taking the real part of the roots (the default)
// crosses the snap-back in one step that converges off the constraint sphere and lands on the analytic path past
// it; every other step lies on the constraint and every point on the analytic path.
#include <lagfsi/efg/path_following.hpp>
#include <lagfsi/error.hpp>

#include <gtest/gtest.h>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace lagfsi;
using namespace lagfsi::efg;

namespace {

constexpr double K = 1.0, e0 = 1.0, ef = 2.0, k = 0.1, P = 1.0;

double force(double e) { return e <= e0 ? K * e : K * e0 * std::exp(-(e - e0) / ef); }

struct Point {
  double lambda, u0, u1;
};

/// Internal forces and secant stiffness at u with the committed largest strain kappa0; kappa: the trial one.
void state(const Vec& u, double kappa0, Vec& f, Eigen::MatrixXd& Ks, double& kappa) {
  kappa = std::max(kappa0, u[0]);
  const double ks = kappa > 0 ? force(kappa) / kappa : K;  // secant stiffness (1 - d) K
  const double f2 = k * (u[1] - u[0]);
  f.resize(2);
  f << ks * u[0] - f2, f2;
  Ks.resize(2, 2);
  Ks << ks + k, -k, -k, k;
}

/// Runs `steps` arc-length steps of initial load factor 0.1; returns the committed points (the origin first) and
/// whether every step converged.
bool trace(ComplexRoots remedy, int steps, std::vector<Point>& path, PathFollowing& pf) {
  pf = PathFollowing(ControlType::arc_length, 0.1, -1, remedy);
  Vec u = Vec::Zero(2), Pv(2);
  Pv << 0.0, P;
  double lambda = 0, kappa = 0;
  path = {{0, 0, 0}};
  for (int s = 0; s < steps; ++s) {
    bool done = false;
    for (int halving = 0; halving <= 4 && !done; ++halving) {
      const double scale = std::ldexp(1.0, -halving);
      Vec x = u, DU = Vec::Zero(2), f;
      Eigen::MatrixXd Ks;
      double l = lambda, kappa1 = kappa;
      try {
        for (int it = 0; it < 100; ++it) {
          state(x, kappa, f, Ks, kappa1);
          const Vec Q = l * Pv - f;
          if (it > 0 && Q.norm() <= 1e-10 * std::max({(l * Pv).norm(), f.norm(), 1e-300})) {
            done = true;
            break;
          }
          const Vec dUP = Ks.lu().solve(Pv);
          double dl;
          Vec dx;
          if (it == 0) {
            dl = pf.predictor(dUP, scale);
            dx = dl * dUP;
          } else {
            const Vec dUQ = Ks.lu().solve(Q);
            dl = pf.corrector(dUP, dUQ, DU);
            dx = dl * dUP + dUQ;
          }
          x += dx;
          l += dl;
          DU += dx;
        }
      } catch (const SolverError&) {
      }
      if (done) {
        pf.commit(DU);
        u = x;
        lambda = l;
        kappa = kappa1;
        path.push_back({lambda, u[0], u[1]});
      }
    }
    if (!done) return false;
  }
  return true;
}

}  // namespace

TEST(EfgArcLength, WithoutARemedyTheSnapBackStopsTheRun) {
  std::vector<Point> path;
  PathFollowing pf;
  EXPECT_FALSE(trace(ComplexRoots::cut_back, 30, path, pf));
  // It stops at the peak (lambda = 1, u1 = 11: ten steps up the elastic branch), before any softening.
  ASSERT_FALSE(path.empty());
  EXPECT_NEAR(path.back().lambda, 1.0, 1e-9);
  EXPECT_NEAR(path.back().u1, 11.0, 1e-8);
}

TEST(EfgArcLength, RealPartOfTheRootsCrossesTheSnapBackOntoTheAnalyticPath) {
  std::vector<Point> path, stopped;
  PathFollowing pf, pf_cut;
  ASSERT_TRUE(trace(ComplexRoots::real_part, 30, path, pf));
  trace(ComplexRoots::cut_back, 30, stopped, pf_cut);
  // Up to the peak both remedies are the same computation, bit for bit.
  ASSERT_LE(stopped.size(), path.size());
  for (size_t i = 0; i < stopped.size(); ++i) {
    EXPECT_EQ(path[i].lambda, stopped[i].lambda) << i;
    EXPECT_EQ(path[i].u1, stopped[i].u1) << i;
  }
  // Every point is on the analytic loading path (spring 1 never unloads on this path).
  for (size_t i = 1; i < path.size(); ++i) {
    EXPECT_NEAR(path[i].lambda, force(path[i].u0) / P, 1e-8) << "step " << i;
    EXPECT_NEAR(path[i].u1, path[i].u0 + force(path[i].u0) / k, 1e-7) << "step " << i;
  }
  // The path passes the snap-back: a point past its end (F < ef k, u1 rising again from below the peak's 11).
  const double e_end = e0 + ef * std::log(K * e0 / (ef * k));  // F(e_end) = ef k: minimum of u1
  const auto past = std::find_if(path.begin(), path.end(), [&](const Point& p) { return p.u0 > e_end; });
  ASSERT_NE(past, path.end());
  EXPECT_LT(past->u1, 11.0);
  EXPECT_LT(past->lambda, ef * k / P);
  EXPECT_GT(path.back().u1, past->u1);  // and goes on along the descending branch
  // One step crossed it off the constraint; the remedy was used, and every other step lies on the sphere.
  EXPECT_GT(pf.stats().complex_root_iterations, 0);
  EXPECT_EQ(pf.stats().steps_off_constraint, 1);
  EXPECT_GT(pf.stats().max_increment_ratio, 1.5);
}

TEST(EfgArcLength, ComplexRootsRemedies) {
  // A corrector whose line DU + dUQ + dl dUP misses the sphere |.| = Dl: DU = (1, 0) on the sphere (Dl = 1 from the
  // predictor), dUQ = (0, 1) pushes outside, dUP = (0, 1) is parallel to it.
  Vec dUP(2);
  dUP << 1.0, 0.0;
  for (ComplexRoots r : {ComplexRoots::real_part, ComplexRoots::normal_plane, ComplexRoots::cut_back}) {
    PathFollowing pf(ControlType::arc_length, 1.0, -1, r);
    ASSERT_DOUBLE_EQ(pf.predictor(dUP, 1.0), 1.0);  // Dl = 1
    Vec up(2), q(2), d(2);
    up << 0.0, 1.0;
    q << 0.5, 2.0;
    d << 1.0, 0.0;
    // a = 1, b = 2 (2 + 0) = 4, c = |(1.5, 2)|^2 - 1 = 5.25: disc = 16 - 21 < 0.
    if (r == ComplexRoots::cut_back) {
      EXPECT_THROW(pf.corrector(up, q, d), SolverError);
    } else if (r == ComplexRoots::real_part) {
      EXPECT_DOUBLE_EQ(pf.corrector(up, q, d), -2.0);  // -b / 2a
      EXPECT_EQ(pf.stats().complex_root_iterations, 1);
    } else {
      // DU . (dl dUP + dUQ) = 0 has no solution with dUP normal to DU: the remedy says so.
      EXPECT_THROW(pf.corrector(up, q, d), SolverError);
      Vec up2(2);
      up2 << 1.0, 1.0;  // a = 2, b = 2 (1.5 + 2) = 7, c = 5.25: disc = 49 - 42 > 0, a real root: no remedy
      EXPECT_NO_THROW(pf.corrector(up2, q, d));
      Vec q2(2);
      q2 << 0.5, 6.0;  // b = 2 (1.5 + 6) = 15, c = 1.5^2 + 36 - 1 = 37.25: disc = 225 - 298 < 0
      EXPECT_DOUBLE_EQ(pf.corrector(up2, q2, d), -0.5);  // -(DU . dUQ)/(DU . dUP)
    }
  }
}
