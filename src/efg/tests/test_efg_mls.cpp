// EFG moving-least-squares shape functions: partition of unity, reproduction of the basis and of its derivatives
// to round-off, derivatives against finite differences, the FE-EFG coupled correction, the Q4 limit (rho = h,
// bilinear basis) and the ill-conditioning report.
#include <lagfsi/efg/discretization.hpp>
#include <lagfsi/efg/mls.hpp>
#include <lagfsi/error.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

using namespace lagfsi;
using namespace lagfsi::efg;

namespace {

struct Cloud {
  std::vector<Vec2> nodes;
  std::vector<Vec2> rho;
  std::vector<Index> all;
};

/// (n+1)^2 nodes on [0,1]^2, interior nodes perturbed by up to `jitter` h.
Cloud grid(int n, double alpha, double jitter, DomainShape shape) {
  Cloud c;
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1, 1);
  const double h = 1.0 / n;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      Vec2 p(i * h, j * h);
      if (i > 0 && i < n && j > 0 && j < n) p += jitter * h * Vec2(u(rng), u(rng));
      c.nodes.push_back(p);
      c.rho.push_back(Vec2::Constant(alpha * h));
      c.all.push_back(static_cast<Index>(c.nodes.size() - 1));
    }
  (void)shape;
  return c;
}

struct Combo {
  BasisType basis;
  WeightType weight;
  DomainShape shape;
  double alpha;
};

std::string label(const Combo& k) {
  return std::to_string(static_cast<int>(k.basis)) + "/" + std::to_string(static_cast<int>(k.weight)) + "/" +
         std::to_string(static_cast<int>(k.shape)) + "/" + std::to_string(k.alpha);
}

std::vector<Combo> combos() {
  std::vector<Combo> out;
  for (BasisType b : {BasisType::linear, BasisType::bilinear, BasisType::quadratic, BasisType::biquadratic})
    for (WeightType w : {WeightType::cubic_spline, WeightType::quartic_spline})
      for (DomainShape s : {DomainShape::rectangular, DomainShape::circular}) {
        const bool q = b == BasisType::quadratic || b == BasisType::biquadratic;
        out.push_back({b, w, s, q ? 3.0 : 2.0});
      }
  return out;
}

MlsShape make(const Combo& k) {
  Basis b;
  b.type = k.basis;
  InfluenceDomain d;
  d.shape = k.shape;
  d.weight.type = k.weight;
  return MlsShape(b, d);
}

}  // namespace

TEST(EfgWeight, DerivativeMatchesFiniteDifference) {
  for (WeightType t :
       {WeightType::cubic_spline, WeightType::quartic_spline, WeightType::exponential, WeightType::quartic_alt}) {
    Weight w;
    w.type = t;
    for (double r : {0.1, 0.3, 0.49, 0.51, 0.7, 0.95}) {
      double a, da, ap, am, d;
      w.eval(r, a, da);
      w.eval(r + 1e-6, ap, d);
      w.eval(r - 1e-6, am, d);
      EXPECT_NEAR(da, (ap - am) / 2e-6, 1e-6) << static_cast<int>(t) << " r " << r;
    }
    double a, da;
    w.eval(1.0, a, da);
    EXPECT_EQ(a, 0.0);
  }
  // The cubic spline is C1 at r = 1/2 and vanishes with its slope at r = 1.
  Weight w;
  double a1, d1, a2, d2;
  w.eval(0.5 - 1e-12, a1, d1);
  w.eval(0.5 + 1e-12, a2, d2);
  EXPECT_NEAR(a1, a2, 1e-10);
  EXPECT_NEAR(d1, d2, 1e-10);
  w.eval(1 - 1e-9, a1, d1);
  EXPECT_NEAR(a1, 0, 1e-12);
  EXPECT_NEAR(d1, 0, 1e-8);
}

TEST(EfgMls, PartitionOfUnityAndReproductionToRoundOff) {
  for (const Combo& k : combos()) {
    const MlsShape mls = make(k);
    const Cloud c = grid(6, k.alpha, 0.2, k.shape);
    const int l = mls.basis().size();
    for (const Vec2& x : {Vec2(0.31, 0.47), Vec2(0.05, 0.93), Vec2(0.77, 0.12), Vec2(0.5, 0.5)}) {
      ShapeValues s;
      mls.compute(x, c.nodes, c.rho, c.all, s);
      ASSERT_GE(static_cast<int>(s.nodes.size()), l) << label(k);
      // sum_j N_j p(x_j) = p(x), sum_j N_j,k p(x_j) = p_,k(x), for every basis term (the basis itself).
      std::vector<double> p(l), px(l), py(l), pj(l);
      mls.basis().eval(x.x(), x.y(), p.data(), px.data(), py.data());
      for (int t = 0; t < l; ++t) {
        double r = 0, rx = 0, ry = 0;
        for (size_t j = 0; j < s.nodes.size(); ++j) {
          const Vec2& xj = c.nodes[s.nodes[j]];
          mls.basis().eval(xj.x(), xj.y(), pj.data(), nullptr, nullptr);
          r += s.N[j] * pj[t];
          rx += s.Nx[j] * pj[t];
          ry += s.Ny[j] * pj[t];
        }
        EXPECT_NEAR(r, p[t], 1e-12) << label(k) << " term " << t;
        EXPECT_NEAR(rx, px[t], 1e-10) << label(k) << " term " << t;
        EXPECT_NEAR(ry, py[t], 1e-10) << label(k) << " term " << t;
      }
    }
  }
}

TEST(EfgMls, DerivativesMatchFiniteDifferences) {
  for (const Combo& k : combos()) {
    const MlsShape mls = make(k);
    const Cloud c = grid(5, k.alpha, 0.15, k.shape);
    const Vec2 x(0.437, 0.281);
    const double e = 1e-6;
    ShapeValues s, sxp, sxm, syp, sym;
    mls.compute(x, c.nodes, c.rho, c.all, s);
    mls.compute(x + Vec2(e, 0), c.nodes, c.rho, c.all, sxp);
    mls.compute(x - Vec2(e, 0), c.nodes, c.rho, c.all, sxm);
    mls.compute(x + Vec2(0, e), c.nodes, c.rho, c.all, syp);
    mls.compute(x - Vec2(0, e), c.nodes, c.rho, c.all, sym);
    auto value = [](const ShapeValues& v, Index n) {
      for (size_t j = 0; j < v.nodes.size(); ++j)
        if (v.nodes[j] == n) return v.N[j];
      return 0.0;
    };
    for (size_t j = 0; j < s.nodes.size(); ++j) {
      const Index n = s.nodes[j];
      EXPECT_NEAR(s.Nx[j], (value(sxp, n) - value(sxm, n)) / (2 * e), 1e-5) << label(k) << " node " << n;
      EXPECT_NEAR(s.Ny[j], (value(syp, n) - value(sym, n)) / (2 * e), 1e-5) << label(k) << " node " << n;
    }
  }
}

TEST(EfgMls, BilinearWithRhoEqualHIsTheQ4Interpolation) {
  Basis b;
  b.type = BasisType::bilinear;
  InfluenceDomain d;
  const MlsShape mls(b, d);
  const Cloud c = grid(4, 1.0, 0.0, DomainShape::rectangular);
  const Vec2 x(0.3, 0.6);  // in the cell [0.25, 0.5] x [0.5, 0.75]
  ShapeValues s;
  mls.compute(x, c.nodes, c.rho, c.all, s);
  ASSERT_EQ(s.nodes.size(), 4u);
  double N[4], dxi[4], deta[4];
  const double xi = (0.3 - 0.375) / 0.125, eta = (0.6 - 0.625) / 0.125;
  q4_shape(xi, eta, N, dxi, deta);
  const Vec2 corner[4] = {{0.25, 0.5}, {0.5, 0.5}, {0.5, 0.75}, {0.25, 0.75}};
  for (int a = 0; a < 4; ++a)
    for (size_t j = 0; j < 4; ++j)
      if ((c.nodes[s.nodes[j]] - corner[a]).norm() < 1e-12) {
        EXPECT_NEAR(s.N[j], N[a], 1e-13);
        EXPECT_NEAR(s.Nx[j], dxi[a] / 0.125, 1e-11);
        EXPECT_NEAR(s.Ny[j], deta[a] / 0.125, 1e-11);
      }
}

TEST(EfgMls, CoupledCorrectionReproducesTheBasisWithTheFeFunctions) {
  // Active FE nodes on the edge y = 0 of the cell [0.25,0.5]x[0,0.25]; the combined FE + corrected MLS
  // approximation must reproduce the bilinear basis and its derivatives; on the edge the particles vanish.
  Basis b;
  b.type = BasisType::bilinear;
  InfluenceDomain d;
  const MlsShape mls(b, d);
  const Cloud c = grid(4, 2.0, 0.0, DomainShape::rectangular);
  for (const Vec2& x : {Vec2(0.31, 0.07), Vec2(0.4, 0.0)}) {
    const double xi = (x.x() - 0.375) / 0.125, eta = (x.y() - 0.125) / 0.125;
    double N[4], dxi[4], deta[4];
    q4_shape(xi, eta, N, dxi, deta);
    FeCorrection fe;
    const Vec2 corner[2] = {{0.25, 0.0}, {0.5, 0.0}};
    for (int a = 0; a < 2; ++a) {
      fe.x[a] = corner[a];
      fe.N[a] = N[a];
      fe.Nx[a] = dxi[a] / 0.125;
      fe.Ny[a] = deta[a] / 0.125;
    }
    fe.n = 2;
    ShapeValues s;
    mls.compute(x, c.nodes, c.rho, c.all, s, &fe);
    double p[4], px[4], py[4], pj[4];
    b.eval(x.x(), x.y(), p, px, py);
    for (int t = 0; t < 4; ++t) {
      double r = 0, rx = 0, ry = 0;
      for (size_t j = 0; j < s.nodes.size(); ++j) {
        b.eval(c.nodes[s.nodes[j]].x(), c.nodes[s.nodes[j]].y(), pj, nullptr, nullptr);
        r += s.N[j] * pj[t];
        rx += s.Nx[j] * pj[t];
        ry += s.Ny[j] * pj[t];
      }
      for (int a = 0; a < 2; ++a) {
        b.eval(fe.x[a].x(), fe.x[a].y(), pj, nullptr, nullptr);
        r += fe.N[a] * pj[t];
        rx += fe.Nx[a] * pj[t];
        ry += fe.Ny[a] * pj[t];
      }
      EXPECT_NEAR(r, p[t], 1e-12) << t;
      EXPECT_NEAR(rx, px[t], 1e-10) << t;
      EXPECT_NEAR(ry, py[t], 1e-10) << t;
    }
    if (x.y() == 0.0) {
      for (double v : s.N) EXPECT_NEAR(v, 0.0, 1e-13);  // u = FE interpolation of the active nodes on the edge
    }
  }
}

TEST(EfgMls, IllConditionedMomentMatrixNamesThePoint) {
  // Collinear nodes with a 2-D basis: M is singular; the error names the point and the support size.
  Basis b;
  b.type = BasisType::linear;
  InfluenceDomain d;
  const MlsShape mls(b, d);
  std::vector<Vec2> nodes, rho;
  std::vector<Index> all;
  for (int i = 0; i < 100; ++i) {
    nodes.emplace_back(0.01 * i, 0.0);
    rho.emplace_back(0.05, 0.05);
    all.push_back(i);
  }
  ShapeValues s;
  try {
    mls.compute(Vec2(0.503, 0.01), nodes, rho, all, s, nullptr, "cell 7");
    FAIL() << "expected a SolverError";
  } catch (const SolverError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("MLS at (0.503, 0.01) [cell 7]"), std::string::npos) << m;
    EXPECT_NE(m.find("ill-conditioned"), std::string::npos) << m;
  }
  // Too few nodes: no node's domain contains the point.
  EXPECT_THROW(mls.compute(Vec2(3.0, 3.0), nodes, rho, all, s), SolverError);
}

TEST(EfgDiscretization, GaussLegendreIsExactToDegree2nMinus1) {
  for (int n = 1; n <= 10; ++n) {
    std::vector<double> x, w;
    gauss_legendre(n, x, w);
    for (int deg = 0; deg <= 2 * n - 1; ++deg) {
      double s = 0;
      for (int i = 0; i < n; ++i) s += w[i] * std::pow(x[i], deg);
      const double exact = deg % 2 ? 0.0 : 2.0 / (deg + 1);
      EXPECT_NEAR(s, exact, 1e-13) << "n " << n << " degree " << deg;
    }
  }
}

TEST(EfgDiscretization, VisibilityAndGrids) {
  Visibility v;
  v.segments.push_back({Vec2(0, 0), Vec2(0, 1)});
  EXPECT_FALSE(v.visible(Vec2(-0.5, 0.5), Vec2(0.5, 0.5)));
  EXPECT_TRUE(v.visible(Vec2(-0.5, 1.5), Vec2(0.5, 1.5)));
  EXPECT_TRUE(v.visible(Vec2(0.1, 0.5), Vec2(0.5, 0.5)));
  // L-shaped panel: 4x4 cells minus the top-right 2x2 block: 12 cells, 21 nodes.
  const QuadMesh m = rectangle_grid(Vec2(0, 0), Vec2(4, 4), 4, 4, {{Vec2(2, 2), Vec2(4, 4)}});
  EXPECT_EQ(m.num_cells(), 12);
  EXPECT_EQ(m.num_nodes(), 21);
  const QuadMesh ph = plate_with_hole(1.0, 5.0, 3, 4, 2.0);
  EXPECT_EQ(ph.num_cells(), 24);
  double area = 0;
  for (const auto& c : ph.cells) {
    const Vec2 a = ph.nodes[c[0]], b = ph.nodes[c[1]], cc = ph.nodes[c[2]], d = ph.nodes[c[3]];
    area += 0.5 * ((cc - a).x() * (d - b).y() - (cc - a).y() * (d - b).x());
  }
  // Polygonal hole: area a bit larger than 25 - pi/4.
  EXPECT_GT(area, 25 - M_PI / 4);
  EXPECT_LT(area, 25 - M_PI / 4 + 0.05);
}

TEST(EfgDiscretization, Q9CellsAndShapeFunctions) {
  // Q9 grid: (2 nx + 1)(2 ny + 1) nodes, local nodes at their natural coordinates (Kronecker delta), and the Q9
  // functions reproduce x^2 y^2 (biquadratic) with exact derivatives.
  const QuadMesh m = rectangle_grid(Vec2(0, 0), Vec2(4, 2), 2, 1, {}, 2);
  ASSERT_TRUE(m.quadratic());
  EXPECT_EQ(m.num_nodes(), 5 * 3);
  EXPECT_EQ(m.num_cells(), 2);
  for (int a = 0; a < 9; ++a) {
    double xi, eta, N[9], dx[9], dy[9];
    cell_node_natural(a, xi, eta);
    q9_shape(xi, eta, N, dx, dy);
    for (int b = 0; b < 9; ++b) EXPECT_NEAR(N[b], a == b ? 1.0 : 0.0, 1e-14);
    // The node's position is the bilinear map of the corners at (xi, eta).
    double Nq[4], qx[4], qy[4];
    q4_shape(xi, eta, Nq, qx, qy);
    Vec2 x = Vec2::Zero();
    for (int c = 0; c < 4; ++c) x += Nq[c] * m.nodes[m.cells[1][c]];
    EXPECT_NEAR((x - m.nodes[m.cell_node(1, a)]).norm(), 0.0, 1e-14);
  }
  double xi = 0.3, eta = -0.7, N[9], dx[9], dy[9], f = 0, fx = 0, fy = 0;
  q9_shape(xi, eta, N, dx, dy);
  for (int a = 0; a < 9; ++a) {
    double s, t;
    cell_node_natural(a, s, t);
    f += N[a] * s * s * t * t;
    fx += dx[a] * s * s * t * t;
    fy += dy[a] * s * s * t * t;
  }
  EXPECT_NEAR(f, xi * xi * eta * eta, 1e-14);
  EXPECT_NEAR(fx, 2 * xi * eta * eta, 1e-14);
  EXPECT_NEAR(fy, 2 * xi * xi * eta, 1e-14);
  EXPECT_THROW(rectangle_grid(Vec2(0, 0), Vec2(1, 1), 1, 1, {}, 3), std::invalid_argument);
}
