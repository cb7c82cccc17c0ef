// Analytical solutions of the EFG benchmarks: Timoshenko & Goodier's cantilever with a parabolic end shear
// (as in Belytschko, Lu & Gu 1994) and Kirsch's plate with a circular hole (the formulas of
// shared/reference/efg_timoshenko_cantilever_exact.csv and efg_plate_hole_kirsch.csv). Plane stress.
#include <lagfsi/efg/efg_model.hpp>

#include <cmath>

namespace lagfsi::efg {

namespace {
Mat3 plane_stress(double E, double nu) {
  Mat3 D;
  const double c = E / (1 - nu * nu);
  D << c, c * nu, 0, c * nu, c, 0, 0, 0, c * (1 - nu) / 2;
  return D;
}
// Gradient of 1, x, y, x^2, xy, y^2.
Vec2 grad(const double* c, const Vec2& p) {
  return Vec2(c[1] + 2 * c[3] * p.x() + c[4] * p.y(), c[2] + c[4] * p.x() + 2 * c[5] * p.y());
}
}  // namespace

Vec2 ExactSolution::body_force(const Vec2&) const {
  if (type != "polynomial") return Vec2::Zero();
  const Mat3 Dm = plane_stress(E, nu);
  const Vec3 dex(2 * cx[3], cy[4], cx[4] + 2 * cy[3]), dey(cx[4], 2 * cy[5], 2 * cx[5] + cy[4]);
  const Vec3 sx = Dm * dex, sy = Dm * dey;
  return -Vec2(sx[0] + sy[2], sx[2] + sy[1]);
}

Vec3 ExactSolution::stress(const Vec2& p) const {
  if (type == "polynomial") {
    const Vec2 gx = grad(cx, p), gy = grad(cy, p);
    return plane_stress(E, nu) * Vec3(gx.x(), gy.y(), gx.y() + gy.x());
  }
  if (type == "timoshenko") {
    const double I = D * D * D / 12.0, x = p.x(), y = p.y();
    return Vec3(-P * (L - x) * y / I, 0.0, P / (2 * I) * (D * D / 4 - y * y));
  }
  if (type == "kirsch") {
    const double r = p.norm(), t = std::atan2(p.y(), p.x()), s0 = sigma0;
    const double a2 = a * a / (r * r), a4 = a2 * a2, c2 = std::cos(2 * t), s2 = std::sin(2 * t);
    const double srr = s0 / 2 * (1 - a2) + s0 / 2 * (1 - 4 * a2 + 3 * a4) * c2;
    const double stt = s0 / 2 * (1 + a2) - s0 / 2 * (1 + 3 * a4) * c2;
    const double srt = -s0 / 2 * (1 + 2 * a2 - 3 * a4) * s2;
    const double c = std::cos(t), s = std::sin(t);
    return Vec3(srr * c * c + stt * s * s - 2 * srt * s * c, srr * s * s + stt * c * c + 2 * srt * s * c,
                (srr - stt) * s * c + srt * (c * c - s * s));
  }
  return Vec3::Zero();
}

Vec2 ExactSolution::displacement(const Vec2& p) const {
  if (type == "polynomial") {
    const double m[6] = {1, p.x(), p.y(), p.x() * p.x(), p.x() * p.y(), p.y() * p.y()};
    double ux = 0, uy = 0;
    for (int k = 0; k < 6; ++k) {
      ux += cx[k] * m[k];
      uy += cy[k] * m[k];
    }
    return Vec2(ux, uy);
  }
  if (type != "timoshenko") return Vec2::Zero();
  const double I = D * D * D / 12.0, x = p.x(), y = p.y();
  const double ux = -P * y / (6 * E * I) * ((6 * L - 3 * x) * x + (2 + nu) * (y * y - D * D / 4));
  const double uy = P / (6 * E * I) * (3 * nu * y * y * (L - x) + (4 + 5 * nu) * D * D * x / 4 + (3 * L - x) * x * x);
  return Vec2(ux, uy);
}

}  // namespace lagfsi::efg
