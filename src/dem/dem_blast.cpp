// Air-blast load with shadowing (src/dem/include/lagfsi/dem/dem_blast.hpp): Henrych overpressure, Wu-Hao duration,
// Rankine-Hugoniot arrival, Friedlander decay, and the angular sweep of Sabatucci et al. (2013), Sec. 4.1.
#include <lagfsi/dem/dem_blast.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <numeric>

namespace lagfsi::dem {

namespace {

const KeyTable kBlastKeys(
    "/bodies/*/blast (dem body)",
    "An air blast: Henrych overpressure, Wu-Hao duration, Friedlander decay, loaded on the exposed arcs of the discs.",
    {{"charge_mass", nullptr, "Charge mass W (kg of TNT)."},
     {"position", nullptr, "Position of the charge [x, y] (m)."},
     {"t_end", 2.5e-3, "The load acts until this time (s)."},
     {"beta", 1.0, "Decay coefficient of the Friedlander pulse."},
     {"arrival", "direct", "Arrival time: direct (R / Us) or integrated (the integral of dr / Us(r))."},
     {"area", "arc", "Loaded length of a disc: arc (the exposed arc) or projected (its projected width)."},
     {"ambient_pressure", 101325.0, "Ambient pressure (Pa)."},
     {"sound_speed", 340.0, "Speed of sound of the air (m/s)."},
     {"exposure_every", 1, "Recompute which arcs are exposed every this many steps."}});

}  // namespace

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
  p.validate(kBlastKeys);
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

namespace {

/// A monotone stand-in for the angle atan2(y, x) in (-pi, pi]: values in (-2, 2], no trigonometry.
inline double pseudo_angle(double x, double y) {
  const double s = x / (std::abs(x) + std::abs(y));
  return y >= 0 ? 1.0 - s : s - 1.0;
}

/// The angle of a pseudo-angle p (its inverse).
inline double angle_of(double p) {
  if (p >= 0) {
    const double s = 1.0 - p;
    return std::atan2(1.0 - std::abs(s), s);
  }
  const double s = 1.0 + p;
  return -std::atan2(1.0 - std::abs(s), s);
}

}  // namespace

void Blast::update_exposure(const double* x, int stride, const double* r, int n) {
  exposed_.assign(n, 0.0);
  dist_.resize(n);
  lo_.resize(n);
  hi_.resize(n);
  const double gx = g_.x(), gy = g_.y();
  // per disc: distance from G and the directions of its two tangents (as pseudo-angles; see the header)
#pragma omp parallel for schedule(static) if (n >= 20000)
  for (int p = 0; p < n; ++p) {
    const double cx = x[stride * p] - gx, cy = x[stride * p + 1] - gy, rp = r[p];
    const double d2 = cx * cx + cy * cy;
    dist_[p] = std::sqrt(d2);
    if (d2 <= rp * rp) {  // the charge inside a disc: refused when the body is read
      lo_[p] = hi_[p] = 0;
      continue;
    }
    const double q = std::sqrt(d2 - rp * rp);                   // |tangent| = d cos(alpha); r = d sin(alpha)
    lo_[p] = pseudo_angle(cx * q + cy * rp, cy * q - cx * rp);  // the centre direction turned by -alpha
    hi_[p] = pseudo_angle(cx * q - cy * rp, cy * q + cx * rp);  // by +alpha
  }
  // discs by increasing distance (ties by index): the order of the last update, repaired by insertion sort
  // (discs move little between updates), or a full sort when the disc order changed
  auto before = [this](int a, int b) { return dist_[a] < dist_[b] || (dist_[a] == dist_[b] && a < b); };
  if (!order_valid_ || static_cast<int>(order_.size()) != n) {
    order_.resize(n);
    std::iota(order_.begin(), order_.end(), 0);
    std::sort(order_.begin(), order_.end(), before);
    order_valid_ = true;
  } else {
    for (int k = 1; k < n; ++k) {
      const int v = order_[k];
      int m = k;
      while (m > 0 && before(v, order_[m - 1])) {
        order_[m] = order_[m - 1];
        --m;
      }
      order_[m] = v;
    }
  }
  std::map<double, double>& occ = occupied_;  // blocked directions: disjoint [start, end] in pseudo-angle
  occ.clear();
  for (const int p : order_) {
    const double rp = r[p], d = dist_[p];
    if (d <= rp) continue;
    const double lo = lo_[p], hi = hi_[p];
    // the interval [lo, hi], split where it crosses the direction -x (pseudo-angle +-2)
    std::pair<double, double> parts[2];
    int np = 0;
    if (lo <= hi) {
      parts[np++] = {lo, hi};
    } else {
      parts[np++] = {lo, 2.0};
      parts[np++] = {-2.0, hi};
    }
    double length = 0;
    bool free = false;
    double phi = 0;
    auto loaded = [&](double p1, double p2) {
      if (!free) phi = std::atan2(x[stride * p + 1] - gy, x[stride * p] - gx);
      free = true;
      auto psi = [&](double pa) {
        double s = angle_of(pa) - phi;
        if (s > std::numbers::pi) s -= 2 * std::numbers::pi;
        if (s < -std::numbers::pi) s += 2 * std::numbers::pi;
        return s;
      };
      auto theta = [&](double s) { return std::asin(std::clamp(d / rp * std::sin(s), -1.0, 1.0)) - s; };
      const double t1 = theta(psi(p1)), t2 = theta(psi(p2));
      length += projected_ ? rp * std::abs(std::sin(t2) - std::sin(t1)) : rp * std::abs(t2 - t1);
    };
    for (int q = 0; q < np; ++q) {
      const auto [a, b] = parts[q];
      // the free parts of [a, b]
      double cur = a;
      auto it = occ.upper_bound(a);
      if (it != occ.begin()) {
        auto prev = std::prev(it);
        if (prev->second > cur) cur = prev->second;
      }
      for (; it != occ.end() && it->first < b && cur < b; ++it) {
        if (it->first > cur) loaded(cur, it->first);
        cur = std::max(cur, it->second);
      }
      if (cur < b) loaded(cur, b);
    }
    if (!free) continue;  // wholly in the shadow: the blocked set does not change
    for (int q = 0; q < np; ++q) {
      const auto [a, b] = parts[q];
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
