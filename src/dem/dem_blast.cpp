// Air-blast load with shadowing (include/lagfsi/dem/dem_blast.hpp): Henrych overpressure, Wu-Hao duration,
// Rankine-Hugoniot arrival, Friedlander decay, and the angular sweep of Sabatucci et al. (2013), Sec. 4.1.
#include <lagfsi/dem/dem_blast.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

namespace lagfsi::dem {

double henrych_overpressure_kpa(double z) {
  z = std::clamp(z, 0.05, 10.0);
  const double z2 = z * z, z3 = z2 * z;
  if (z < 0.3) return 1407.2 / z + 554.0 / z2 - 35.7 / z3 + 0.625 / (z2 * z2);
  if (z < 1.0) return 619.4 / z - 326.0 / z2 + 213.2 / z3;
  return 66.2 / z + 405.0 / z2 + 328.8 / z3;
}

double wu_hao_duration(double r, double w) { return 0.5e-3 * std::pow(r, 0.72) * std::pow(w, 0.16); }

double shock_speed(double ps, double p0, double a0) { return a0 * std::sqrt(1.0 + 6.0 * ps / (7.0 * p0)); }

Blast::Blast(Params p) {
  p.validate({{"charge_mass", nullptr}, {"position", nullptr}, {"t_end", 2.5e-3}, {"beta", 1.0},
              {"arrival", "direct"}, {"area", "arc"}, {"ambient_pressure", 101325.0}, {"sound_speed", 340.0},
              {"exposure_every", 1}});
  w_ = p.positive("charge_mass");
  w13_ = std::cbrt(w_);
  g_ = p.vec2("position");
  t_end_ = p.non_negative("t_end");
  beta_ = p.non_negative("beta");
  integrated_ = p.choice("arrival", {"direct", "integrated"}) == "integrated";
  projected_ = p.choice("area", {"arc", "projected"}) == "projected";
  p0_ = p.positive("ambient_pressure");
  a0_ = p.positive("sound_speed");
  every_ = p.integer("exposure_every", 1);
}

double Blast::arrival(double r) const {
  auto us = [&](double s) { return shock_speed(1e3 * henrych_overpressure_kpa(s / w13_), p0_, a0_); };
  if (!integrated_) return r / us(r);
  // midpoint rule over 200 intervals (the speed is smooth within a Henrych branch)
  const int n = 200;
  double ta = 0;
  for (int k = 0; k < n; ++k) ta += (r / n) / us((k + 0.5) * r / n);
  return ta;
}

double Blast::pressure(double r, double t) const {
  const double ta = arrival(r);
  if (t < ta) return 0.0;
  const double td = wu_hao_duration(r, w_);
  const double s = (t - ta) / td;
  if (s > 1.0) return 0.0;
  return 1e3 * henrych_overpressure_kpa(r / w13_) * (1.0 - s) * std::exp(-beta_ * s);
}

void Blast::update_exposure(const double* x, int stride, const double* r, int n) {
  exposed_.assign(n, 0.0);
  key_.resize(n);
  for (int p = 0; p < n; ++p) key_[p] = {std::hypot(x[stride * p] - g_.x(), x[stride * p + 1] - g_.y()), p};
  std::sort(key_.begin(), key_.end());
  std::map<double, double> occ;  // blocked directions: disjoint [start, end]
  const double pi = std::numbers::pi;
  for (const auto& [d, pp] : key_) {
    const int p = static_cast<int>(pp);
    const double rp = r[p];
    if (d <= rp) continue;  // the charge inside a disc: refused when the body is read
    const double alpha = std::asin(rp / d);
    const double phi = std::atan2(x[stride * p + 1] - g_.y(), x[stride * p] - g_.x());
    auto theta = [&](double psi) { return std::asin(std::clamp(d / rp * std::sin(psi), -1.0, 1.0)) - psi; };
    auto loaded = [&](double psi1, double psi2) {
      const double t1 = theta(psi1), t2 = theta(psi2);
      return projected_ ? rp * std::abs(std::sin(t2) - std::sin(t1)) : rp * std::abs(t2 - t1);
    };
    double length = 0;
    // the interval [phi - alpha, phi + alpha], split where it crosses +-pi; shift maps back to phi's frame
    std::vector<std::pair<double, double>> parts;
    std::vector<double> shifts;
    double lo = phi - alpha, hi = phi + alpha;
    if (lo < -pi) {
      parts.push_back({lo + 2 * pi, pi});
      shifts.push_back(-2 * pi);
      lo = -pi;
    }
    if (hi > pi) {
      parts.push_back({-pi, hi - 2 * pi});
      shifts.push_back(2 * pi);
      hi = pi;
    }
    parts.push_back({lo, hi});
    shifts.push_back(0.0);
    for (size_t q = 0; q < parts.size(); ++q) {
      const auto [a, b] = parts[q];
      const double sh = shifts[q];
      // free parts of [a, b]
      double cur = a;
      auto it = occ.upper_bound(a);
      if (it != occ.begin()) {
        auto prev = std::prev(it);
        if (prev->second > cur) cur = prev->second;
      }
      for (; it != occ.end() && it->first < b && cur < b; ++it) {
        if (it->first > cur) length += loaded(cur + sh - phi, it->first + sh - phi);
        cur = std::max(cur, it->second);
      }
      if (cur < b) length += loaded(cur + sh - phi, b + sh - phi);
      // block [a, b]
      double na = a, nb = b;
      auto jt = occ.upper_bound(a);
      if (jt != occ.begin() && std::prev(jt)->second >= a) --jt;
      while (jt != occ.end() && jt->first <= b) {
        na = std::min(na, jt->first);
        nb = std::max(nb, jt->second);
        jt = occ.erase(jt);
      }
      occ[na] = nb;
    }
    exposed_[p] = length;
  }
}

int Blast::apply(const double* x, int stride, const double* r, int n, double t, std::vector<double>& f) {
  if (!active(t)) return 0;
  if (static_cast<int>(exposed_.size()) != n || calls_ % every_ == 0) update_exposure(x, stride, r, n);
  ++calls_;
  int loaded = 0;
  for (int p = 0; p < n; ++p) {
    if (!(exposed_[p] > 0)) continue;
    const double dx = x[stride * p] - g_.x(), dy = x[stride * p + 1] - g_.y();
    const double d = std::hypot(dx, dy);
    const double pe = pressure(d, t);
    if (pe <= 0) continue;
    const double fm = pe * exposed_[p];  // times 1 m depth
    f[2 * p] += fm * dx / d;
    f[2 * p + 1] += fm * dy / d;
    ++loaded;
  }
  return loaded;
}

}  // namespace lagfsi::dem
