#include <lagfsi/element.hpp>

#include <array>
#include <stdexcept>
#include <string>
#include <utility>

namespace lagfsi {

namespace {

// A symmetric orbit of points given by barycentric coordinates (a, b, 1 - a - b):
//  - kind 1: the centroid (a = b = 1/3);
//  - kind 3: the 3 distinct permutations of (a, b, b), b = (1 - a) / 2;
//  - kind 6: the 6 permutations of (a, b, c), c = 1 - a - b.
// `weight` is the weight of each point of the orbit, already scaled to the parent area 1/2.
struct Orbit {
  int kind;
  double weight, a, b;
};

std::vector<QuadraturePoint> expand(std::initializer_list<Orbit> orbits) {
  std::vector<QuadraturePoint> rule;
  for (const Orbit& o : orbits) {
    const double w = o.weight;
    if (o.kind == 1) {
      rule.push_back({1.0 / 3.0, 1.0 / 3.0, w});
    } else if (o.kind == 3) {
      const double a = o.a, b = 0.5 * (1.0 - o.a);
      rule.push_back({a, b, w});
      rule.push_back({b, a, w});
      rule.push_back({b, b, w});
    } else {
      const double a = o.a, b = o.b, c = 1.0 - o.a - o.b;
      for (const auto& [x, y] :
           std::array<std::pair<double, double>, 6>{{{a, b}, {b, a}, {a, c}, {c, a}, {b, c}, {c, b}}})
        rule.push_back({x, y, w});
    }
  }
  return rule;
}

// Orbit parameters: Dunavant (1985) rules of degree 1, 2, 4, 5, 6 and 8, and a 15-point fully
// symmetric degree-7 rule with positive weights and interior points (same orbit structure as the
// Lyness-Jespersen / Taylor-Wingate-Bos rules). All values were re-solved from the moment equations
// in 50-digit arithmetic (Newton on the symmetric moment system, starting from the published
// 15-digit values) and rounded to 21 significant digits.

const std::vector<QuadraturePoint>& rule_d1() {
  static const std::vector<QuadraturePoint> r = expand({{1, 0.5, 0.0, 0.0}});
  return r;
}

const std::vector<QuadraturePoint>& rule_d2() {
  static const std::vector<QuadraturePoint> r = expand({{3, 1.0 / 6.0, 2.0 / 3.0, 0.0}});
  return r;
}

const std::vector<QuadraturePoint>& rule_d4() {
  static const std::vector<QuadraturePoint> r = expand({
      {3, 0.111690794839005732848, 0.108103018168070227363, 0.0},
      {3, 0.0549758718276609338192, 0.816847572980458513081, 0.0},
  });
  return r;
}

const std::vector<QuadraturePoint>& rule_d5() {
  static const std::vector<QuadraturePoint> r = expand({
      {1, 0.1125, 0.0, 0.0},
      {3, 0.0661970763942530903688, 0.0597158717897698204591, 0.0},
      {3, 0.0629695902724135762978, 0.797426985353087322398, 0.0},
  });
  return r;
}

const std::vector<QuadraturePoint>& rule_d6() {
  static const std::vector<QuadraturePoint> r = expand({
      {3, 0.0583931378631896830126, 0.501426509658179157417, 0.0},
      {3, 0.0254224531851034084605, 0.873821971016995543319, 0.0},
      {6, 0.0414255378091867875968, 0.0531450498448169473533, 0.310352451033784405417},
  });
  return r;
}

const std::vector<QuadraturePoint>& rule_d7() {
  static const std::vector<QuadraturePoint> r = expand({
      {3, 0.0265389008951162058360, 0.870138973681670273843, 0.0},
      {6, 0.0354265418460667836592, 0.284575584249170335197, 0.198384476681506719180},
      {6, 0.0346373410397084467561, 0.313559184384931507956, 0.642577343822696020532},
  });
  return r;
}

const std::vector<QuadraturePoint>& rule_d8() {
  static const std::vector<QuadraturePoint> r = expand({
      {1, 0.0721578038388935841256, 0.0, 0.0},
      {3, 0.0475458171336423123970, 0.0814148234145536879424, 0.0},
      {3, 0.0516086852673591251409, 0.658861384496479586755, 0.0},
      {3, 0.0162292488115990401555, 0.898905543365938049083, 0.0},
      {6, 0.0136151570872174971324, 0.00839477740995760533721, 0.263112829634638113422},
  });
  return r;
}

// Gauss-Legendre on [0, 1]: the nodes s <= 1/2 with their weights (the rest by symmetry s -> 1 - s),
// computed by Newton on P_n in 40-digit arithmetic.
std::vector<std::pair<double, double>> gauss_legendre(std::initializer_list<std::pair<double, double>> half) {
  std::vector<std::pair<double, double>> lower(half), rule;
  for (const auto& p : lower) rule.push_back(p);
  for (auto it = lower.rbegin(); it != lower.rend(); ++it)
    if (it->first < 0.5) rule.push_back({1.0 - it->first, it->second});
  return rule;
}

}  // namespace

const std::vector<QuadraturePoint>& triangle_quadrature(int degree) {
  switch (degree) {
    case 0:
    case 1:
      return rule_d1();
    case 2:
      return rule_d2();
    case 3:
    case 4:
      return rule_d4();
    case 5:
      return rule_d5();
    case 6:
      return rule_d6();
    case 7:
      return rule_d7();
    case 8:
      return rule_d8();
    default:
      throw std::invalid_argument("triangle_quadrature: unsupported degree " + std::to_string(degree) +
                                  " (supported: 1 to 8)");
  }
}

const std::vector<std::pair<double, double>>& line_quadrature(int n_points) {
  static const std::array<std::vector<std::pair<double, double>>, 6> rules{
      gauss_legendre({{0.5, 1.0}}),
      gauss_legendre({{0.211324865405187117745, 0.5}}),
      gauss_legendre({{0.112701665379258311482, 0.277777777777777777778}, {0.5, 0.444444444444444444444}}),
      gauss_legendre(
          {{0.0694318442029737123880, 0.173927422568726928687}, {0.330009478207571867599, 0.326072577431273071313}}),
      gauss_legendre({{0.0469100770306680036012, 0.118463442528094543757},
                      {0.230765344947158454482, 0.239314335249683234021},
                      {0.5, 0.284444444444444444444}}),
      gauss_legendre({{0.0337652428984239860938, 0.0856622461895851725201},
                      {0.169395306766867743169, 0.180380786524069303785},
                      {0.380690406958401545685, 0.233956967286345523695}}),
  };
  if (n_points < 1 || n_points > 6)
    throw std::invalid_argument("line_quadrature: unsupported number of points " + std::to_string(n_points) +
                                " (supported: 1 to 6)");
  return rules[static_cast<size_t>(n_points - 1)];
}

void triangle_shape(int order, double xi1, double xi2, Eigen::VectorXd& N, Eigen::MatrixX2d& dN) {
  if (order < 1 || order > 3)
    throw std::invalid_argument("triangle_shape: unsupported order " + std::to_string(order) + " (supported: 1 to 3)");
  // Area coordinates and their (constant) derivatives with respect to (xi1, xi2).
  const double L[3] = {xi1, xi2, 1.0 - xi1 - xi2};
  const double dL[3][2] = {{1.0, 0.0}, {0.0, 1.0}, {-1.0, -1.0}};
  const int n = (order + 1) * (order + 2) / 2;
  N.resize(n);
  dN.resize(n, 2);

  if (order == 1) {
    for (int i = 0; i < 3; ++i) {
      N(i) = L[i];
      dN(i, 0) = dL[i][0];
      dN(i, 1) = dL[i][1];
    }
    return;
  }

  if (order == 2) {
    for (int i = 0; i < 3; ++i) {  // vertices: L (2L - 1)
      N(i) = L[i] * (2.0 * L[i] - 1.0);
      const double f = 4.0 * L[i] - 1.0;
      dN(i, 0) = f * dL[i][0];
      dN(i, 1) = f * dL[i][1];
    }
    for (int k = 0; k < 3; ++k) {  // mid-node of edge k (vertices k, k+1): 4 Li Lj
      const int i = k, j = (k + 1) % 3, m = 3 + k;
      N(m) = 4.0 * L[i] * L[j];
      for (int d = 0; d < 2; ++d) dN(m, d) = 4.0 * (dL[i][d] * L[j] + L[i] * dL[j][d]);
    }
    return;
  }

  // order 3
  for (int i = 0; i < 3; ++i) {  // vertices: L (3L - 1)(3L - 2) / 2
    const double l = L[i];
    N(i) = 0.5 * l * (3.0 * l - 1.0) * (3.0 * l - 2.0);
    const double f = 0.5 * (27.0 * l * l - 18.0 * l + 2.0);
    dN(i, 0) = f * dL[i][0];
    dN(i, 1) = f * dL[i][1];
  }
  for (int k = 0; k < 3; ++k) {  // edge k from vertex i = k to vertex j = k+1: nodes nearer i, then j
    const int i = k, j = (k + 1) % 3;
    const int pair[2][2] = {{i, j}, {j, i}};
    for (int s = 0; s < 2; ++s) {
      const int p = pair[s][0], q = pair[s][1], m = 3 + 2 * k + s;
      // 9/2 Lp Lq (3 Lp - 1), the node nearer vertex p
      const double lp = L[p], lq = L[q];
      N(m) = 4.5 * lp * lq * (3.0 * lp - 1.0);
      const double dfp = 4.5 * lq * (6.0 * lp - 1.0);  // d/dLp
      const double dfq = 4.5 * lp * (3.0 * lp - 1.0);  // d/dLq
      for (int d = 0; d < 2; ++d) dN(m, d) = dfp * dL[p][d] + dfq * dL[q][d];
    }
  }
  N(9) = 27.0 * L[0] * L[1] * L[2];
  for (int d = 0; d < 2; ++d)
    dN(9, d) = 27.0 * (dL[0][d] * L[1] * L[2] + L[0] * dL[1][d] * L[2] + L[0] * L[1] * dL[2][d]);
}

void line_shape(int order, double s, Eigen::VectorXd& N, Eigen::VectorXd& dN) {
  if (order < 1 || order > 3)
    throw std::invalid_argument("line_shape: unsupported order " + std::to_string(order) + " (supported: 1 to 3)");
  N.resize(order + 1);
  dN.resize(order + 1);
  const double t = 1.0 - s;  // area coordinate of the first vertex; s is that of the second
  switch (order) {
    case 1:
      N << t, s;
      dN << -1.0, 1.0;
      break;
    case 2:
      N << t * (2.0 * t - 1.0), 4.0 * t * s, s * (2.0 * s - 1.0);
      dN << -(4.0 * t - 1.0), 4.0 * (t - s), 4.0 * s - 1.0;
      break;
    default:
      N << 0.5 * t * (3.0 * t - 1.0) * (3.0 * t - 2.0), 4.5 * t * s * (3.0 * t - 1.0), 4.5 * t * s * (3.0 * s - 1.0),
          0.5 * s * (3.0 * s - 1.0) * (3.0 * s - 2.0);
      dN << -0.5 * (27.0 * t * t - 18.0 * t + 2.0), 4.5 * (t * (3.0 * t - 1.0) - s * (3.0 * t - 1.0) - 3.0 * t * s),
          4.5 * (t * (3.0 * s - 1.0) + 3.0 * t * s - s * (3.0 * s - 1.0)), 0.5 * (27.0 * s * s - 18.0 * s + 2.0);
      break;
  }
}

std::vector<std::pair<double, double>> triangle_node_coordinates(int order) {
  if (order < 1 || order > 3)
    throw std::invalid_argument("triangle_node_coordinates: unsupported order " + std::to_string(order) +
                                " (supported: 1 to 3)");
  // (xi1, xi2) = (L1, L2): vertex 0 at (1, 0), vertex 1 at (0, 1), vertex 2 at (0, 0).
  const std::pair<double, double> v[3] = {{1.0, 0.0}, {0.0, 1.0}, {0.0, 0.0}};
  std::vector<std::pair<double, double>> out(v, v + 3);
  for (int k = 0; k < 3; ++k) {  // edge nodes from vertex k towards vertex k+1
    const auto& a = v[k];
    const auto& b = v[(k + 1) % 3];
    for (int i = 1; i < order; ++i) {
      const double f = static_cast<double>(i) / order;
      out.push_back({a.first + f * (b.first - a.first), a.second + f * (b.second - a.second)});
    }
  }
  if (order == 3) out.push_back({1.0 / 3.0, 1.0 / 3.0});
  return out;
}

}  // namespace lagfsi
