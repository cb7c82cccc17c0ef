// MLS polynomial bases, weight functions and influence domains (thesis Eqs. 2.8-2.11, 2.32-2.36; digest
// shared/spec/003_efg.md §2.2.1). See src/efg/include/lagfsi/efg/mls.hpp.
#include <lagfsi/efg/mls.hpp>

#include <cmath>
#include <stdexcept>

namespace lagfsi::efg {

int Basis::size() const {
  switch (type) {
    case BasisType::linear:
      return 3;
    case BasisType::bilinear:
      return 4;
    case BasisType::quadratic:
      return 6;
    case BasisType::biquadratic:
      return 9;
  }
  return 0;
}

int Basis::complete_degree() const { return (type == BasisType::quadratic || type == BasisType::biquadratic) ? 2 : 1; }

void Basis::eval(double x, double y, double* p, double* px, double* py) const {
  // Monomials x^i y^j in the order of the thesis: 1, x, y, xy, x^2, (x^2 y), y^2, (x y^2), (x^2 y^2).
  static const int lin[3][2] = {{0, 0}, {1, 0}, {0, 1}};
  static const int bil[4][2] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  static const int quad[6][2] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}, {2, 0}, {0, 2}};
  static const int biq[9][2] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}, {2, 0}, {2, 1}, {0, 2}, {1, 2}, {2, 2}};
  const int(*e)[2] = type == BasisType::linear      ? lin
                     : type == BasisType::bilinear  ? bil
                     : type == BasisType::quadratic ? quad
                                                    : biq;
  const double xp[3] = {1.0, x, x * x}, yp[3] = {1.0, y, y * y};
  for (int k = 0, n = size(); k < n; ++k) {
    const int i = e[k][0], j = e[k][1];
    if (p) p[k] = xp[i] * yp[j];
    if (px) px[k] = i == 0 ? 0.0 : i * xp[i - 1] * yp[j];
    if (py) py[k] = j == 0 ? 0.0 : j * xp[i] * yp[j - 1];
  }
}

const std::vector<std::string>& Basis::names() {
  static const std::vector<std::string> n = {"linear", "bilinear", "quadratic", "biquadratic"};
  return n;
}

BasisType Basis::parse(const std::string& name) {
  if (name == "linear") return BasisType::linear;
  if (name == "bilinear") return BasisType::bilinear;
  if (name == "quadratic") return BasisType::quadratic;
  if (name == "biquadratic") return BasisType::biquadratic;
  throw std::invalid_argument("unknown basis '" + name + "'");
}

void Weight::eval(double r, double& w, double& dw) const {
  w = dw = 0.0;
  if (r >= 1.0) return;
  switch (type) {
    case WeightType::cubic_spline:
      if (r <= 0.5) {
        w = 2.0 / 3.0 - 4 * r * r + 4 * r * r * r;
        dw = -8 * r + 12 * r * r;
      } else {
        w = 4.0 / 3.0 - 4 * r + 4 * r * r - 4.0 / 3.0 * r * r * r;
        dw = -4 + 8 * r - 4 * r * r;
      }
      return;
    case WeightType::quartic_spline:
      w = 1 - 6 * r * r + 8 * r * r * r - 3 * r * r * r * r;
      dw = -12 * r + 24 * r * r - 12 * r * r * r;
      return;
    case WeightType::exponential: {
      const double a = exp_alpha;
      w = std::exp(-(r / a) * (r / a));
      dw = -2 * r / (a * a) * w;
      return;
    }
    case WeightType::quartic_alt:
      w = 2.0 / 3.0 - 4.5 * r * r + 19.0 / 3.0 * r * r * r - 2.5 * r * r * r * r;
      dw = -9 * r + 19 * r * r - 10 * r * r * r;
      return;
  }
}

const std::vector<std::string>& Weight::names() {
  static const std::vector<std::string> n = {"cubic_spline", "quartic_spline", "exponential", "quartic_alt"};
  return n;
}

WeightType Weight::parse(const std::string& name) {
  if (name == "cubic_spline") return WeightType::cubic_spline;
  if (name == "quartic_spline") return WeightType::quartic_spline;
  if (name == "exponential") return WeightType::exponential;
  if (name == "quartic_alt") return WeightType::quartic_alt;
  throw std::invalid_argument("unknown weight '" + name + "'");
}

bool InfluenceDomain::contains(const Vec2& x, const Vec2& xj, const Vec2& rho) const {
  const Vec2 d = x - xj;
  if (shape == DomainShape::circular) return d.squaredNorm() < rho.x() * rho.x();
  return std::abs(d.x()) < rho.x() && std::abs(d.y()) < rho.y();
}

void InfluenceDomain::eval(const Vec2& x, const Vec2& xj, const Vec2& rho, double& w, double& wx, double& wy) const {
  const Vec2 d = x - xj;
  if (shape == DomainShape::circular) {
    const double dist = d.norm(), r = dist / rho.x();
    double dw;
    weight.eval(r, w, dw);
    if (dist > 0) {
      wx = dw * d.x() / (dist * rho.x());
      wy = dw * d.y() / (dist * rho.x());
    } else {
      wx = wy = 0.0;
    }
    return;
  }
  double fx, dfx, fy, dfy;
  weight.eval(std::abs(d.x()) / rho.x(), fx, dfx);
  weight.eval(std::abs(d.y()) / rho.y(), fy, dfy);
  const double sx = d.x() > 0 ? 1.0 : (d.x() < 0 ? -1.0 : 0.0), sy = d.y() > 0 ? 1.0 : (d.y() < 0 ? -1.0 : 0.0);
  w = fx * fy;
  wx = dfx * sx / rho.x() * fy;
  wy = fx * dfy * sy / rho.y();
}

}  // namespace lagfsi::efg
