// Quadrature rules and Lagrange shape functions of element.hpp, checked against exact integrals,
// finite differences and the node layout described in mesh.hpp.
#include <lagfsi/element.hpp>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <random>
#include <stdexcept>
#include <vector>

using namespace lagfsi;

namespace {

double factorial(int n) {
  double f = 1.0;
  for (int i = 2; i <= n; ++i) f *= i;
  return f;
}

// Exact integral of xi1^a xi2^b over the parent triangle.
double exact_monomial(int a, int b) { return factorial(a) * factorial(b) / factorial(a + b + 2); }

double quad_monomial(const std::vector<QuadraturePoint>& rule, int a, int b) {
  double s = 0.0;
  for (const auto& q : rule) s += q.weight * std::pow(q.xi1, a) * std::pow(q.xi2, b);
  return s;
}

int num_nodes(int order) { return (order + 1) * (order + 2) / 2; }

// Node positions as described in mesh.hpp / element.hpp, built independently of the library:
// vertex i at L_i = 1 with (xi1, xi2) = (L1, L2); edge k from vertex k to vertex k+1, order-1 equally
// spaced nodes from vertex k; T10 centroid last.
std::vector<std::array<double, 2>> expected_nodes(int order) {
  const std::array<double, 2> v[3] = {{1.0, 0.0}, {0.0, 1.0}, {0.0, 0.0}};
  std::vector<std::array<double, 2>> out{v[0], v[1], v[2]};
  if (order == 2) {
    out.push_back({0.5, 0.5});  // 3: edge 0-1
    out.push_back({0.0, 0.5});  // 4: edge 1-2
    out.push_back({0.5, 0.0});  // 5: edge 2-0
  } else if (order == 3) {
    out.push_back({2.0 / 3, 1.0 / 3});  // 3: edge 0-1, 1/3 from vertex 0
    out.push_back({1.0 / 3, 2.0 / 3});  // 4
    out.push_back({0.0, 2.0 / 3});      // 5: edge 1-2, 1/3 from vertex 1
    out.push_back({0.0, 1.0 / 3});      // 6
    out.push_back({1.0 / 3, 0.0});      // 7: edge 2-0, 1/3 from vertex 2
    out.push_back({2.0 / 3, 0.0});      // 8
    out.push_back({1.0 / 3, 1.0 / 3});  // 9: centroid
  }
  return out;
}

// Local nodes of edge k (0: 0-1, 1: 1-2, 2: 2-0), from its first vertex to its second (mesh.hpp).
std::vector<int> edge_nodes(int order, int k) {
  std::vector<int> out{k};
  for (int i = 0; i < order - 1; ++i) out.push_back(3 + k * (order - 1) + i);
  out.push_back((k + 1) % 3);
  return out;
}

std::vector<std::array<double, 2>> random_points(int n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<std::array<double, 2>> pts;
  while (static_cast<int>(pts.size()) < n) {
    double a = u(gen), b = u(gen);
    if (a + b > 1.0) {
      a = 1.0 - a;
      b = 1.0 - b;
    }
    pts.push_back({a, b});
  }
  // Also some points outside the triangle: polynomial identities hold everywhere.
  pts.push_back({-0.3, 1.4});
  pts.push_back({0.7, 0.9});
  return pts;
}

}  // namespace

// ------------------------------------------------------------------ triangle quadrature

TEST(TriangleQuadrature, IntegratesMonomialsExactly) {
  for (int degree = 1; degree <= 8; ++degree) {
    const auto& rule = triangle_quadrature(degree);
    for (int a = 0; a <= degree; ++a)
      for (int b = 0; a + b <= degree; ++b) {
        const double exact = exact_monomial(a, b), q = quad_monomial(rule, a, b);
        EXPECT_NEAR(q, exact, 1e-13) << "degree " << degree << " monomial xi1^" << a << " xi2^" << b;
        EXPECT_LT(std::abs(q - exact), 1e-14 * exact) << "degree " << degree << " monomial xi1^" << a << " xi2^" << b;
      }
  }
}

TEST(TriangleQuadrature, WeightsSumToParentAreaAndPointsInside) {
  for (int degree = 1; degree <= 8; ++degree) {
    const auto& rule = triangle_quadrature(degree);
    double sum = 0.0;
    for (const auto& q : rule) {
      sum += q.weight;
      EXPECT_GT(q.weight, 0.0) << "degree " << degree;
      EXPECT_GT(q.xi1, 0.0) << "degree " << degree;
      EXPECT_GT(q.xi2, 0.0) << "degree " << degree;
      EXPECT_LT(q.xi1 + q.xi2, 1.0) << "degree " << degree;
    }
    EXPECT_NEAR(sum, 0.5, 1e-15) << "degree " << degree;
  }
}

TEST(TriangleQuadrature, ExpectedPointCountsAndSymmetry) {
  const int expected[9] = {0, 1, 3, 6, 6, 7, 12, 15, 16};
  for (int degree = 1; degree <= 8; ++degree) {
    const auto& rule = triangle_quadrature(degree);
    EXPECT_EQ(static_cast<int>(rule.size()), expected[degree]) << "degree " << degree;
    // Fully symmetric rules: swapping xi1 and xi2 maps the rule onto itself.
    for (const auto& q : rule) {
      bool found = false;
      for (const auto& r : rule)
        found = found || (std::abs(r.xi1 - q.xi2) < 1e-15 && std::abs(r.xi2 - q.xi1) < 1e-15 &&
                          std::abs(r.weight - q.weight) < 1e-15);
      EXPECT_TRUE(found) << "degree " << degree;
    }
  }
}

TEST(TriangleQuadrature, SameObjectOnEveryCall) {
  EXPECT_EQ(&triangle_quadrature(4), &triangle_quadrature(4));
  EXPECT_EQ(&triangle_quadrature(3), &triangle_quadrature(4));  // degree 3 uses the degree-4 rule
}

TEST(TriangleQuadrature, IntegratesSmoothFunctionAccurately) {
  // Integral of exp(xi1 + 2 xi2) over the parent triangle:
  // int_0^1 int_0^{1-x} e^{x+2y} dy dx = int_0^1 (e^{2-x} - e^x)/2 dx = (e^2 - e - e + 1) / 2.
  const double exact = 0.5 * (std::exp(2.0) - 2.0 * std::exp(1.0) + 1.0);
  double prev_err = 1.0;
  for (int degree : {2, 4, 6, 8}) {
    double s = 0.0;
    for (const auto& q : triangle_quadrature(degree)) s += q.weight * std::exp(q.xi1 + 2.0 * q.xi2);
    const double err = std::abs(s - exact);
    EXPECT_LT(err, prev_err) << "degree " << degree;
    prev_err = err;
  }
  EXPECT_LT(prev_err, 1e-7);
}

TEST(TriangleQuadrature, UnsupportedDegreeThrows) {
  EXPECT_THROW(triangle_quadrature(9), std::invalid_argument);
  EXPECT_THROW(triangle_quadrature(-1), std::invalid_argument);
}

// ------------------------------------------------------------------ line quadrature

TEST(LineQuadrature, GaussLegendreExactness) {
  for (int n = 1; n <= 6; ++n) {
    const auto& rule = line_quadrature(n);
    ASSERT_EQ(static_cast<int>(rule.size()), n);
    double sum = 0.0;
    for (const auto& [s, w] : rule) {
      sum += w;
      EXPECT_GT(w, 0.0);
      EXPECT_GT(s, 0.0);
      EXPECT_LT(s, 1.0);
    }
    EXPECT_NEAR(sum, 1.0, 1e-15);
    for (int k = 0; k <= 2 * n - 1; ++k) {
      double q = 0.0;
      for (const auto& [s, w] : rule) q += w * std::pow(s, k);
      EXPECT_NEAR(q, 1.0 / (k + 1), 1e-14) << "n " << n << " s^" << k;
    }
    // Gauss rules are exact to degree 2n-1 and no further: s^(2n) is not integrated exactly.
    double q = 0.0;
    for (const auto& [s, w] : rule) q += w * std::pow(s, 2 * n);
    EXPECT_GT(std::abs(q - 1.0 / (2 * n + 1)), 1e-9) << "n " << n;
  }
}

TEST(LineQuadrature, UnsupportedThrows) {
  EXPECT_THROW(line_quadrature(0), std::invalid_argument);
  EXPECT_THROW(line_quadrature(7), std::invalid_argument);
}

// ------------------------------------------------------------------ triangle shape functions

TEST(TriangleShape, NodeCoordinatesFollowMeshNumbering) {
  for (int order = 1; order <= 3; ++order) {
    const auto nodes = triangle_node_coordinates(order);
    const auto expected = expected_nodes(order);
    ASSERT_EQ(nodes.size(), expected.size());
    ASSERT_EQ(static_cast<int>(nodes.size()), num_nodes(order));
    for (size_t i = 0; i < nodes.size(); ++i) {
      EXPECT_NEAR(nodes[i].first, expected[i][0], 1e-15) << "order " << order << " node " << i;
      EXPECT_NEAR(nodes[i].second, expected[i][1], 1e-15) << "order " << order << " node " << i;
    }
  }
}

TEST(TriangleShape, KroneckerAtNodes) {
  Eigen::VectorXd N;
  Eigen::MatrixX2d dN;
  for (int order = 1; order <= 3; ++order) {
    const auto nodes = expected_nodes(order);
    for (size_t j = 0; j < nodes.size(); ++j) {
      triangle_shape(order, nodes[j][0], nodes[j][1], N, dN);
      ASSERT_EQ(N.size(), num_nodes(order));
      ASSERT_EQ(dN.rows(), num_nodes(order));
      for (int i = 0; i < N.size(); ++i)
        EXPECT_NEAR(N(i), i == static_cast<int>(j) ? 1.0 : 0.0, 1e-14)
            << "order " << order << " N" << i << " at node " << j;
    }
  }
}

TEST(TriangleShape, PartitionOfUnityAndZeroDerivativeSum) {
  Eigen::VectorXd N;
  Eigen::MatrixX2d dN;
  for (int order = 1; order <= 3; ++order)
    for (const auto& p : random_points(20, 11u + order)) {
      triangle_shape(order, p[0], p[1], N, dN);
      EXPECT_NEAR(N.sum(), 1.0, 1e-13);
      EXPECT_NEAR(dN.col(0).sum(), 0.0, 1e-12);
      EXPECT_NEAR(dN.col(1).sum(), 0.0, 1e-12);
    }
}

TEST(TriangleShape, DerivativesMatchCentralDifferences) {
  Eigen::VectorXd N, Np, Nm;
  Eigen::MatrixX2d dN, tmp;
  const double h = 1e-6;
  for (int order = 1; order <= 3; ++order)
    for (const auto& p : random_points(20, 23u + order)) {
      triangle_shape(order, p[0], p[1], N, dN);
      for (int d = 0; d < 2; ++d) {
        const double dx = d == 0 ? h : 0.0, dy = d == 1 ? h : 0.0;
        triangle_shape(order, p[0] + dx, p[1] + dy, Np, tmp);
        triangle_shape(order, p[0] - dx, p[1] - dy, Nm, tmp);
        const Eigen::VectorXd fd = (Np - Nm) / (2.0 * h);
        for (int i = 0; i < N.size(); ++i)
          EXPECT_NEAR(dN(i, d), fd(i), 1e-7) << "order " << order << " N" << i << " d/dxi" << d + 1;
      }
    }
}

TEST(TriangleShape, ReproducesCompletePolynomials) {
  // p(x, y) = sum c_ab x^a y^b over a + b <= order with random coefficients: interpolation at the
  // nodes reproduces p and its gradient exactly.
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd N;
  Eigen::MatrixX2d dN;
  for (int order = 1; order <= 3; ++order) {
    std::vector<std::array<double, 3>> terms;  // a, b, coefficient
    for (int a = 0; a <= order; ++a)
      for (int b = 0; a + b <= order; ++b) terms.push_back({double(a), double(b), u(gen)});
    auto p = [&](double x, double y) {
      double s = 0.0;
      for (const auto& t : terms) s += t[2] * std::pow(x, t[0]) * std::pow(y, t[1]);
      return s;
    };
    auto grad = [&](double x, double y) {
      double gx = 0.0, gy = 0.0;
      for (const auto& t : terms) {
        if (t[0] > 0) gx += t[2] * t[0] * std::pow(x, t[0] - 1) * std::pow(y, t[1]);
        if (t[1] > 0) gy += t[2] * t[1] * std::pow(x, t[0]) * std::pow(y, t[1] - 1);
      }
      return std::array<double, 2>{gx, gy};
    };
    const auto nodes = expected_nodes(order);
    Eigen::VectorXd pn(nodes.size());
    for (size_t i = 0; i < nodes.size(); ++i) pn(static_cast<int>(i)) = p(nodes[i][0], nodes[i][1]);
    for (const auto& x : random_points(20, 31u + order)) {
      triangle_shape(order, x[0], x[1], N, dN);
      EXPECT_NEAR(N.dot(pn), p(x[0], x[1]), 1e-12) << "order " << order;
      const auto g = grad(x[0], x[1]);
      EXPECT_NEAR(dN.col(0).dot(pn), g[0], 1e-11) << "order " << order;
      EXPECT_NEAR(dN.col(1).dot(pn), g[1], 1e-11) << "order " << order;
    }
  }
}

TEST(TriangleShape, DoesNotReproduceHigherDegree) {
  // The element is of degree `order` exactly: x^(order+1) is not interpolated exactly.
  Eigen::VectorXd N;
  Eigen::MatrixX2d dN;
  for (int order = 1; order <= 3; ++order) {
    const auto nodes = expected_nodes(order);
    Eigen::VectorXd pn(nodes.size());
    for (size_t i = 0; i < nodes.size(); ++i) pn(static_cast<int>(i)) = std::pow(nodes[i][0], order + 1);
    triangle_shape(order, 0.2, 0.3, N, dN);
    EXPECT_GT(std::abs(N.dot(pn) - std::pow(0.2, order + 1)), 1e-4) << "order " << order;
  }
}

TEST(TriangleShape, UnsupportedOrderThrows) {
  Eigen::VectorXd N, dNl;
  Eigen::MatrixX2d dN;
  EXPECT_THROW(triangle_shape(0, 0.2, 0.2, N, dN), std::invalid_argument);
  EXPECT_THROW(triangle_shape(4, 0.2, 0.2, N, dN), std::invalid_argument);
  EXPECT_THROW(line_shape(0, 0.5, N, dNl), std::invalid_argument);
  EXPECT_THROW(line_shape(4, 0.5, N, dNl), std::invalid_argument);
  EXPECT_THROW(triangle_node_coordinates(0), std::invalid_argument);
  EXPECT_THROW(triangle_node_coordinates(4), std::invalid_argument);
}

// ------------------------------------------------------------------ line shape functions

TEST(LineShape, KroneckerUnityDerivativesAndReproduction) {
  Eigen::VectorXd N, dN, Np, Nm, tmp;
  const double h = 1e-6;
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int order = 1; order <= 3; ++order) {
    for (int j = 0; j <= order; ++j) {
      line_shape(order, static_cast<double>(j) / order, N, dN);
      ASSERT_EQ(N.size(), order + 1);
      ASSERT_EQ(dN.size(), order + 1);
      for (int i = 0; i <= order; ++i) EXPECT_NEAR(N(i), i == j ? 1.0 : 0.0, 1e-14);
    }
    std::vector<double> c(order + 1);
    for (auto& ci : c) ci = u(gen);
    auto p = [&](double s) {
      double v = 0.0;
      for (int k = 0; k <= order; ++k) v += c[k] * std::pow(s, k);
      return v;
    };
    auto dp = [&](double s) {
      double v = 0.0;
      for (int k = 1; k <= order; ++k) v += c[k] * k * std::pow(s, k - 1);
      return v;
    };
    Eigen::VectorXd pn(order + 1);
    for (int i = 0; i <= order; ++i) pn(i) = p(static_cast<double>(i) / order);
    for (double s : {-0.2, 0.0, 0.13, 0.5, 0.77, 1.0, 1.3}) {
      line_shape(order, s, N, dN);
      EXPECT_NEAR(N.sum(), 1.0, 1e-13);
      EXPECT_NEAR(dN.sum(), 0.0, 1e-12);
      EXPECT_NEAR(N.dot(pn), p(s), 1e-13);
      EXPECT_NEAR(dN.dot(pn), dp(s), 1e-12);
      line_shape(order, s + h, Np, tmp);
      line_shape(order, s - h, Nm, tmp);
      for (int i = 0; i <= order; ++i) EXPECT_NEAR(dN(i), (Np(i) - Nm(i)) / (2 * h), 1e-7);
    }
  }
}

TEST(LineShape, ConsistentWithTriangleOnEveryEdge) {
  // On edge k (from vertex k to vertex k+1), the triangle functions of the edge nodes equal the line
  // functions, the other functions vanish, and the tangential derivative matches d/ds.
  const double v[3][2] = {{1.0, 0.0}, {0.0, 1.0}, {0.0, 0.0}};
  Eigen::VectorXd N, Nl, dNl;
  Eigen::MatrixX2d dN;
  for (int order = 1; order <= 3; ++order)
    for (int k = 0; k < 3; ++k) {
      const auto en = edge_nodes(order, k);
      const int a = k, b = (k + 1) % 3;
      const double tx = v[b][0] - v[a][0], ty = v[b][1] - v[a][1];
      for (double s : {0.0, 0.1, 0.35, 0.5, 0.8, 1.0}) {
        triangle_shape(order, v[a][0] + s * tx, v[a][1] + s * ty, N, dN);
        line_shape(order, s, Nl, dNl);
        std::vector<bool> on_edge(N.size(), false);
        for (int i = 0; i <= order; ++i) {
          on_edge[en[i]] = true;
          EXPECT_NEAR(N(en[i]), Nl(i), 1e-13) << "order " << order << " edge " << k << " s " << s;
          EXPECT_NEAR(dN(en[i], 0) * tx + dN(en[i], 1) * ty, dNl(i), 1e-12)
              << "order " << order << " edge " << k << " s " << s;
        }
        for (int i = 0; i < N.size(); ++i) {
          if (!on_edge[i]) {
            EXPECT_NEAR(N(i), 0.0, 1e-13) << "order " << order << " edge " << k;
          }
        }
      }
    }
}
